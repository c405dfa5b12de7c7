"""``fleet-gateway demo``: the gateway with three simulated drones, and how to connect an MCP client."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import os
import signal
import sys
from pathlib import Path

from gateway.cli_help import add_command
from gateway.localstack import LocalStack, StackError
from gateway.startup import StartupError, check_port_free

DRONE_NAMES = ("alpha", "bravo", "charlie", "delta", "echo", "foxtrot", "golf", "hotel", "india")

CONNECT_HELP = """\
fleet-gateway is running with {count} simulated drones: {drones}
  MCP endpoint (Streamable HTTP): {mcp_url}
  REST API for operators:         {api_url}/api/v1/vehicles   (OpenAPI docs: {api_url}/docs)
  operator console (browser):     {api_url}/console
  database and logs:              {workdir}  ({kept})

Connect an MCP client:
  Claude Code:    claude mcp add --transport http fleet-gateway {mcp_url}
  MCP Inspector:  npx @modelcontextprotocol/inspector   (Transport "Streamable HTTP", URL {mcp_url})
  any client:     point a Streamable HTTP MCP client at {mcp_url}
  an LLM here:    .venv/bin/fleet-gateway agent --mcp-url {mcp_url} --endpoint http://127.0.0.1:11434/v1 \\
                    --model qwen2.5:7b "take off alpha to 10 m, fly 100 m north, then land"

Try it: call list_drones, then takeoff(drone_id="alpha", alt_m=10). Operators can lock a drone:
  curl -X POST {api_url}/api/v1/vehicles/alpha/lock -H 'content-type: application/json' \\
       -d '{{"reason": "inspection"}}'
Ctrl-C stops the gateway, its sidecars and the simulator.
"""


DEFAULT_PORT = 8765


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = add_command(subparsers, "demo")
    parser.add_argument("--count", type=int, default=3, help="simulated drones (1-9, default 3)")
    parser.add_argument(
        "--port", type=int, default=None, help="HTTP port of REST and /mcp (default: GATEWAY_PORT, else 8765)"
    )
    parser.add_argument(
        "--speedup", type=float, default=1.0, help="simulator time factor (default 1: real time)"
    )
    parser.add_argument(
        "--workdir", type=Path, default=None, help="keep the database and logs here (default: a temp dir)"
    )
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if not 1 <= args.count <= len(DRONE_NAMES):
        print(f"fleet-gateway demo: error: --count must be 1-{len(DRONE_NAMES)}", file=sys.stderr)
        return 2
    if args.port is None:
        given = os.environ.get("GATEWAY_PORT", "").strip()
        if given and not given.isdigit():
            print(
                f"fleet-gateway demo: error: GATEWAY_PORT must be a port number 1-65535; got '{given[:40]}'",
                file=sys.stderr,
            )
            return 2
        args.port = int(given) if given else DEFAULT_PORT
    if not 1 <= args.port <= 65535:
        print(f"fleet-gateway demo: error: --port must be 1-65535; got {args.port}", file=sys.stderr)
        return 2
    if not 0.1 <= args.speedup <= 100:
        print("fleet-gateway demo: error: --speedup must be 0.1-100", file=sys.stderr)
        return 2
    try:
        check_port_free("127.0.0.1", args.port)
    except StartupError as exc:
        print(f"fleet-gateway demo: error: {exc}", file=sys.stderr)
        return 2
    if args.workdir is not None:
        args.workdir.mkdir(parents=True, exist_ok=True)
    # the banner is what a person reads: request lines of the stack's own HTTP calls go nowhere
    logging.getLogger("httpx").setLevel(logging.WARNING)
    try:
        return asyncio.run(_demo(args))
    except StackError as exc:
        print(f"fleet-gateway demo: error: {exc}", file=sys.stderr)
        return 1


async def _demo(args: argparse.Namespace) -> int:
    drones = list(DRONE_NAMES[: args.count])
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    boot_s = 20.0 / args.speedup
    print(
        f"Starting {len(drones)} simulated drones and the gateway; the drones need about {boot_s:.0f} s "
        "to get a GPS fix and a home position, as ArduPilot does...",
        flush=True,
    )
    stack = LocalStack(drones, speedup=args.speedup, port=args.port, auth=False, workdir=args.workdir)
    starting = asyncio.ensure_future(stack.__aenter__())
    stopping = asyncio.ensure_future(stop.wait())
    await asyncio.wait({starting, stopping}, return_when=asyncio.FIRST_COMPLETED)
    if not starting.done():
        starting.cancel()
        with contextlib.suppress(asyncio.CancelledError, StackError):
            await starting
        print("stopped before the drones were ready", flush=True)
        return 130
    starting.result()  # raises StackError if the stack did not come up
    try:
        print(
            CONNECT_HELP.format(
                count=len(drones),
                drones=", ".join(drones),
                mcp_url=stack.mcp_url,
                api_url=stack.api_url,
                workdir=stack.workdir,
                kept="kept" if args.workdir is not None else "deleted on exit; --workdir DIR keeps them",
            ),
            flush=True,
        )
        await stopping
    finally:
        print("stopping...", flush=True)
        await stack.__aexit__(None, None, None)
    print("stopped", flush=True)
    return 0
