"""The link to one vehicle: its mavsdk_server sidecar (``sidecar``, ``confine``), the link and its
connection state machine (``session``), one MAVSDK session and its loops (``mavsdk_session``), what
the link shows its owner and is given by it (``contract``), raw MAVLink commands (``rawlink``), the
telemetry cache (``telemetry``) and the feed that fills it (``telemetry_feed``). Nothing here knows how
to fly: ``gateway.fleet`` sits above, and what differs between autopilots reaches the link through
``contract.LinkRules`` (implemented by ``gateway.fleet.dialects``). Imports nothing from
``gateway.fleet``, ``gateway.mcp`` or ``gateway.api``."""
