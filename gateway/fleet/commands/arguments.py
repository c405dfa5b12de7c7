"""The argument types the verbs declare and every door shares (an MCP tool's inputSchema is built from
them, `gateway.mcp.declared`): pydantic ``Annotated`` bounds, with short descriptions (the tool list's
size is paid on every turn of a model). fleet/ never imports the MCP layer; the MCP layer reuses these."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field

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
ParamName = Annotated[str, Field(pattern=r"^[A-Za-z0-9_]{1,16}$", description="e.g. WPNAV_SPEED")]
DroneIds = Annotated[list[str], Field(min_length=1, max_length=64, description="Drone ids")]
SomeDrones = Annotated[list[str] | None, Field(description="Drone ids; default: all")]
FleetAlt = Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False, description="m above home")]


class Waypoint(BaseModel):
    """One mission item as a caller writes it (``alt_m`` above home); the verb makes it a `MissionItem`.
    (The name is the schema's ``$defs`` key clients see.) A field it does not have is refused."""

    model_config = ConfigDict(extra="forbid")

    lat_deg: Lat
    lon_deg: Lon
    alt_m: Annotated[float, Field(ge=0, le=10_000, allow_inf_nan=False, description="m above home")]
    kind: Literal["waypoint", "takeoff", "land", "rtl", "loiter_time"] = "waypoint"
    hold_s: Annotated[float, Field(ge=0, le=3600, allow_inf_nan=False)] = 0.0
    speed_mps: Annotated[float | None, Field(gt=0, le=50, allow_inf_nan=False)] = None


#: each field of a `Waypoint` (a mission item in a caller's words, the units in the names) and the
#: `MissionItem` field it is; the mission tools present a drone's items in the same words
ITEM_FIELDS = {
    "lat_deg": "lat",
    "lon_deg": "lon",
    "alt_m": "alt_rel_m",
    "kind": "kind",
    "hold_s": "hold_s",
    "speed_mps": "speed_mps",
}


def in_caller_words(item: object) -> dict[str, object]:
    """A `MissionItem`'s fields under a caller's names (those of `Waypoint`)."""
    return {name: getattr(item, field) for name, field in ITEM_FIELDS.items()}


Waypoints = Annotated[list[Waypoint], Field(min_length=1, max_length=MISSION_ITEMS, description="Items 1..N")]
OptionalWaypoints = Annotated[
    list[Waypoint] | None, Field(max_length=MISSION_ITEMS, description="Upload first")
]
