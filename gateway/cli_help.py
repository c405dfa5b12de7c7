"""The one-line help of each ``fleet-gateway`` command, and the parser of a command made with it.

Both sides read it from here: the top-level CLI (gateway/cli.py) for ``fleet-gateway --help``, which
imports no command's module, and each command's module when it registers its command.
"""

from __future__ import annotations

import argparse

COMMAND_HELP: dict[str, str] = {
    "serve": "run the gateway (REST API, /mcp, sidecars)",
    "demo": "run the gateway with simulated drones and print how to connect an MCP client",
    "drones": "register, list and remove drones",
    "db": "database maintenance",
    "sim": "run simulated ArduCopter drones (MAVLink 2 over TCP, like ArduPilot SITL)",
    "mcp-stdio": "serve MCP over stdio (for clients that launch the server as a process)",
    "agent": "let a chat model plan a flight and the host fly it through the gateway's MCP tools",
}

#: the longer description of a command's own ``--help`` (a command not named here has none, or gives its own)
COMMAND_DESCRIPTION: dict[str, str] = {
    "serve": "Serve the REST API, the MCP endpoint (/mcp) and the operator pages, and run one "
    "mavsdk_server per registered drone. The database schema is upgraded on start.",
    "demo": "Start simulated drones, the gateway serving them and its MCP endpoint on this machine, "
    "and print how to connect an MCP client. Ctrl-C stops everything.",
    "sim": "Run N simulated ArduCopter 4.x vehicles in one process. Vehicle i listens on TCP "
    "bind:tcp_base_port+10*i with system id sysid_base+i.",
}


def add_command(
    subparsers: argparse._SubParsersAction[argparse.ArgumentParser],
    name: str,
    description: str | None = None,
    formatter_class: type[argparse.HelpFormatter] = argparse.HelpFormatter,
    add_help: bool = True,
) -> argparse.ArgumentParser:
    """The parser of command ``name``, with its one-line help from `COMMAND_HELP` and its description
    (``description``, else from `COMMAND_DESCRIPTION`)."""
    return subparsers.add_parser(
        name,
        help=COMMAND_HELP[name],
        description=description or COMMAND_DESCRIPTION.get(name),
        formatter_class=formatter_class,
        add_help=add_help,
    )
