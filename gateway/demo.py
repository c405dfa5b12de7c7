"""``fleet-gateway demo``: three simulated drones to fly with any MAVLink ground station or MAVSDK."""

from __future__ import annotations

import argparse
import asyncio
import sys

from gateway.sim.cli import add_sim_arguments, build_fleet, serve

HOW_TO = """\
Three simulated ArduCopters are running (Ctrl-C stops them). Fly one with MAVSDK, for example:
  .venv/lib/python3.11/site-packages/mavsdk_grpc/bin/mavsdk_server -p 50051 {url}
  then in Python:  from mavsdk_grpc import System; drone = System(mavsdk_server_address="127.0.0.1",
  port=50051); await drone.connect(); call drone.telemetry.set_rate_position(5), switch to GUIDED,
  wait for telemetry.health().is_armable, then action.arm() and action.takeoff().
Or connect QGroundControl / MAVProxy to the TCP ports above (one client per port at a time).
"""


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser("demo", help="start three simulated drones and print how to fly them")
    add_sim_arguments(parser, default_count=3)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    try:
        fleet = build_fleet(args)
    except ValueError as exc:
        print(f"fleet-gateway demo: error: {exc}", file=sys.stderr)
        return 2
    print(HOW_TO.format(url=fleet.vehicles[0].url), flush=True)
    try:
        asyncio.run(serve(args))
    except OSError as exc:
        print(f"fleet-gateway demo: error: {exc}", file=sys.stderr)
        return 1
    return 0
