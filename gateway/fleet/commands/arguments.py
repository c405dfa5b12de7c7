"""The argument types the verbs declare and every door shares (an MCP tool's inputSchema is built from
them, `gateway.mcp.declared`): pydantic ``Annotated`` bounds, with short descriptions (the tool list's
size is paid on every turn of a model). fleet/ never imports the MCP layer; the MCP layer reuses these."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

DroneId = str
"""Checked by the MCP wrapper (length, then the registry names the known ids): keeps every schema small."""
AltFrame = Literal["home", "amsl"]
Lat = Annotated[float, Field(ge=-90, le=90, allow_inf_nan=False)]
Lon = Annotated[float, Field(ge=-180, le=180, allow_inf_nan=False)]
Metres = Annotated[float, Field(allow_inf_nan=False, ge=-10_000, le=10_000)]
FlightMode = Annotated[
    str,
    Field(
        description="HOLD, RTL, LAND, MISSION, GUIDED or TAKEOFF (mapped to the drone's autopilot), "
        "or one of its own modes",
        examples=["HOLD", "RTL", "LAND", "MISSION"],
        max_length=32,
        pattern=r"^[A-Za-z][A-Za-z0-9_.]*$",  # as given: no spaces around it, nothing to strip
    ),
]
MISSION_ITEMS = 200
"""The most mission items a tool call carries (the autopilot may hold more:
`gateway.fleet.missions.mission`)."""
ItemIndex = Annotated[int, Field(ge=1, le=MISSION_ITEMS, description="Item 1..N")]
