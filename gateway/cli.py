"""`fleet-gateway` command line: each area of the gateway registers its own subcommands."""

from __future__ import annotations

import argparse
import importlib
import logging
import sys
from collections.abc import Sequence

# Modules exposing ``register(subparsers)``; each adds its subcommands with ``set_defaults(func=...)``.
COMMAND_MODULES: tuple[str, ...] = (
    "gateway.sim.cli",
    "gateway.demo",
    "gateway.server_cli",
    "gateway.mcp.cli",
    "gateway.agent.cli",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="fleet-gateway",
        description="MCP gateway that lets LLMs fly a fleet of MAVLink drones under operator control.",
    )
    parser.add_argument(
        "--log-level", default=None, help="Python log level (default: GATEWAY_LOG_LEVEL or INFO)"
    )
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module_name in COMMAND_MODULES:
        importlib.import_module(module_name).register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    from gateway.config import get_settings

    level = (args.log_level or get_settings().log_level).upper()
    logging.basicConfig(level=level, format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    try:
        result = args.func(args)
    except KeyboardInterrupt:
        return 130
    return int(result or 0)


if __name__ == "__main__":
    sys.exit(main())
