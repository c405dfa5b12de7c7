"""`fleet-gateway mcp-stdio`: the MCP server on stdin/stdout, for clients that launch servers as processes.

It runs a whole gateway (registry, sidecars, store) in this process; stdout carries only the protocol,
logs go to stderr.
"""

from __future__ import annotations

import argparse
import asyncio

from gateway.cli_help import add_command


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = add_command(subparsers, "mcp-stdio", __doc__, argparse.RawDescriptionHelpFormatter)
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from gateway.cli_support import fail
    from gateway.config import get_settings
    from gateway.startup import StartupError, prepare_database_location

    try:  # as `serve` does: a missing SQLite directory is created, anything else is one line
        prepare_database_location(get_settings().database_url)
    except StartupError as exc:
        return fail(str(exc), 2)
    asyncio.run(serve_stdio())
    return 0


async def serve_stdio() -> None:
    from gateway.config import get_settings
    from gateway.mcp.server import build_mcp
    from gateway.runtime import Gateway

    gateway = Gateway(get_settings())
    await gateway.start()
    try:
        server = build_mcp(gateway)
        await server.run_stdio_async()
    finally:
        await gateway.stop()
