"""``fleet-gateway sim``: run N simulated ArduCopters until interrupted."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import signal
import sys

from gateway.cli_help import add_command
from gateway.sim.control import ControlServer
from gateway.sim.fleet import DEFAULT_HOME, SimFleet, parse_home
from gateway.sim.params import FIRMWARES


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = add_command(subparsers, "sim")
    add_sim_arguments(parser)
    parser.set_defaults(func=run)


def _home(text: str) -> tuple[float, float, float, float]:
    try:
        return parse_home(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text}")
    return value


def _port(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a port number: {text!r}") from None
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"port must be 0..65535, got {value}")
    return value


def add_sim_arguments(parser: argparse.ArgumentParser, default_count: int = 1) -> None:
    parser.add_argument("--count", type=int, default=default_count, help="number of vehicles")
    parser.add_argument("--tcp-base-port", type=_port, default=5760, help="TCP port of vehicle 0 (0 = any)")
    parser.add_argument("--udp-base-port", type=_port, default=None, help="also send UDP to 127.0.0.1:P+i")
    parser.add_argument(
        "--gcs-base-port",
        type=_port,
        default=None,
        help="a second MAVLink TCP port per vehicle, P+10*i (0 = any), for another ground station (as "
        "SITL's SERIAL1, 5762)",
    )
    parser.add_argument("--speedup", type=_positive_float, default=1.0, help="simulated time speed-up")
    parser.add_argument(
        "--home",
        type=_home,
        default=DEFAULT_HOME,
        help="LAT,LON,ALT_AMSL,HEADING of vehicle 0 (others 5 m apart eastwards)",
    )
    parser.add_argument("--bind", default="127.0.0.1", help="address the TCP ports listen on")
    parser.add_argument("--sysid-base", type=int, default=1, help="system id of vehicle 0")
    parser.add_argument("--seed", type=int, default=None, help="seed of the sensor-noise random source")
    parser.add_argument("--control-port", type=_port, default=None, help="serve the JSON control API here")
    parser.add_argument("--firmware", choices=FIRMWARES, default="4.7", help="parameter naming generation")
    parser.add_argument(
        "--autopilot", type=int, default=3, help="MAV_AUTOPILOT its HEARTBEAT names (3 ArduPilot, 0 generic)"
    )


def build_fleet(args: argparse.Namespace) -> SimFleet:
    fleet = SimFleet(
        args.count,
        tcp_base_port=args.tcp_base_port,
        udp_base_port=args.udp_base_port,
        gcs_base_port=getattr(args, "gcs_base_port", None),
        speedup=args.speedup,
        home=args.home,
        bind=args.bind,
        sysid_base=args.sysid_base,
        seed=args.seed,
        firmware=args.firmware,
    )
    for vehicle in fleet.vehicles:  # it still flies as ArduCopter: the announcement is what changes
        vehicle.autopilot = getattr(args, "autopilot", vehicle.autopilot)
    return fleet


async def serve(args: argparse.Namespace, banner: bool = True) -> None:
    fleet = build_fleet(args)
    control = ControlServer(fleet, "127.0.0.1", args.control_port) if args.control_port is not None else None
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        with contextlib.suppress(NotImplementedError):
            loop.add_signal_handler(sig, stop.set)
    await fleet.start()
    try:
        if control is not None:
            await control.start()
        if banner:
            for v in fleet.vehicles:
                extra = f" udp {v.udp_url}" if v.udp_url else ""
                extra += f" gcs {v.gcs_url}" if v.gcs_url else ""
                print(f"vehicle {v.index} sysid {v.sysid} {v.url}{extra}", flush=True)
            if control is not None:
                print(f"control {control.url}", flush=True)
            print("ready", flush=True)
        await stop.wait()
    finally:
        if control is not None:
            await control.stop()
        await fleet.stop()


def run(args: argparse.Namespace) -> int:
    try:
        build_fleet(args)  # validate before binding anything
    except ValueError as exc:
        print(f"fleet-gateway sim: error: {exc}", file=sys.stderr)
        return 2
    try:
        asyncio.run(serve(args))
    except OSError as exc:
        print(f"fleet-gateway sim: error: {exc}", file=sys.stderr)
        return 1
    return 0
