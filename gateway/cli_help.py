"""The one-line help of each ``fleet-gateway`` command.

Both sides read it from here: the top-level CLI (gateway/cli.py) for ``fleet-gateway --help``, which
imports no command's module, and each command's module when it registers its command.
"""

COMMAND_HELP: dict[str, str] = {
    "serve": "run the gateway (REST API, /mcp, sidecars)",
    "demo": "run the gateway with simulated drones and print how to connect an MCP client",
    "drones": "register, list and remove drones",
    "db": "database maintenance",
    "sim": "run simulated ArduCopter drones (MAVLink 2 over TCP, like ArduPilot SITL)",
    "mcp-stdio": "serve MCP over stdio (for clients that launch the server as a process)",
    "agent": "let a chat model plan a flight and the host fly it through the gateway's MCP tools",
}
