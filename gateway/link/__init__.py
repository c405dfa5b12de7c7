"""The link to one vehicle: its mavsdk_server sidecar (``sidecar``, ``confine``), its MAVSDK session and
connection state machine (``session``), raw MAVLink commands (``rawlink``) and the telemetry cache
(``telemetry``). Nothing here knows how to fly: ``gateway.fleet`` sits above, and what differs between
autopilots reaches the link through ``contract.LinkRules`` (implemented by ``gateway.fleet.dialects``).
Imports nothing from ``gateway.fleet``, ``gateway.mcp`` or ``gateway.api``."""
