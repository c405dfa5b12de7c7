"""Mission toolset: waypoint missions (user waypoint 1 is the first item; the home slot is hidden). The
tools here build or present missions; the thin ones (pause, resume, clear, next item) are declared with
their verbs."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.fleet.commands.arguments import MISSION_ITEMS
from gateway.fleet.missions.mission import MissionItem
from gateway.mcp.access import ToolCall
from gateway.mcp.results import (
    ActionOut,
    MissionItemOut,
    MissionOut,
    MissionProgressOut,
    OperationOut,
    ValueOut,
    action_out,
)
from gateway.mcp.toolkit import DroneId, Lat, Lon, Toolset, Wait

toolset = Toolset("mission")

MAX_ITEMS = MISSION_ITEMS


class Waypoint(BaseModel):
    """One mission item as a model writes it (``alt_m`` above home); becomes a fleet `MissionItem`.
    (The name is the schema's ``$defs`` key clients see.) A field it does not have is refused."""

    model_config = ConfigDict(extra="forbid")

    lat_deg: Lat
    lon_deg: Lon
    alt_m: Annotated[float, Field(ge=0, le=10_000, allow_inf_nan=False, description="m above home")]
    kind: Literal["waypoint", "takeoff", "land", "rtl", "loiter_time"] = "waypoint"
    hold_s: Annotated[float, Field(ge=0, le=3600, allow_inf_nan=False)] = 0.0
    speed_mps: Annotated[float | None, Field(gt=0, le=50, allow_inf_nan=False)] = None


Waypoints = Annotated[list[Waypoint], Field(min_length=1, max_length=MAX_ITEMS, description="Items 1..N")]


def mission_items(waypoints: list[Waypoint]) -> list[MissionItem]:
    for n, w in enumerate(waypoints, 1):
        geo.check_lat_lon(w.lat_deg, w.lon_deg)
        if w.kind in ("waypoint", "loiter_time") and w.alt_m <= 0:
            raise InvalidArgument(f"waypoint {n}: alt_m must be above 0 m above home")
    return [
        MissionItem(
            lat=w.lat_deg,
            lon=w.lon_deg,
            alt_rel_m=w.alt_m,
            kind=w.kind,
            hold_s=w.hold_s,
            speed_mps=w.speed_mps,
        )
        for w in waypoints
    ]


@toolset.tool(idempotent=True)
async def upload_mission(call: ToolCall, drone_id: DroneId, waypoints: Waypoints) -> ActionOut:
    """Upload waypoints (alt_m above home) without starting them."""
    result = await call.commander.upload_mission(call.caller, drone_id, mission_items(waypoints))
    return action_out(
        result,
        f"{drone_id}: mission of {result.facts['items']} items uploaded; start it with initiate_mission "
        "or resume_mission",
    )


@toolset.tool(
    advertise={
        "waypoints": {
            "type": "array",
            "items": {"type": "object"},
            "description": "Items as upload_mission's; omit to start the drone's mission (checked first)",
        }
    }
)
async def initiate_mission(
    call: ToolCall,
    drone_id: DroneId,
    waypoints: Annotated[
        list[Waypoint] | None, Field(max_length=MAX_ITEMS, description="Upload first")
    ] = None,
    wait: Wait = True,
) -> OperationOut:
    """Upload (if waypoints given) and start the mission; done when finished."""
    items = None if waypoints is None else mission_items(waypoints)  # [] is refused, never "what is stored"
    op = await call.commander.start_mission(call.caller, drone_id, items, "initiate_mission")
    return await call.finish(op, wait, "initiate_mission")


@toolset.tool(read_only=True)
async def download_mission(call: ToolCall, drone_id: DroneId) -> MissionOut:
    """The mission stored on the drone (alt_m above home)."""
    mission = await call.commander.download_mission(call.caller, drone_id)
    out = [
        MissionItemOut(
            index=n,
            kind=i.kind,
            lat_deg=i.lat,
            lon_deg=i.lon,
            alt_m=i.alt_rel_m,
            hold_s=i.hold_s,
            speed_mps=i.speed_mps,
        )
        for n, i in enumerate(mission.items, 1)
    ]
    return MissionOut(drone_id=drone_id, count=len(out), items=out).say(
        f"{drone_id}: mission of {len(out)} items"
    )


@toolset.tool(read_only=True)
async def print_mission_progress(call: ToolCall, drone_id: DroneId) -> MissionProgressOut:
    """Current item (1..N) of the mission and whether it finished."""
    p = await call.commander.mission_progress(call.caller, drone_id)
    return MissionProgressOut(
        drone_id=drone_id,
        current=p.current,
        total=p.total,
        finished=p.finished,
        operation_status=p.operation_status,
    ).say(f"{drone_id}: item {p.current} of {p.total}" + (", finished" if p.finished else ""))


@toolset.tool(read_only=True)
async def is_mission_finished(call: ToolCall, drone_id: DroneId) -> ValueOut:
    """true when the mission has run to its end."""
    finished = (await call.commander.mission_progress(call.caller, drone_id)).finished
    return ValueOut(drone_id=drone_id, age_s=0.0, stale=False, value=finished).say(
        f"{drone_id}: mission {'finished' if finished else 'not finished'}"
    )


# here: the tools the verbs declare for this toolset (@command(tool=Tool(..., "mission")), mostly in
# gateway/fleet/commands/mission_verbs.py), built by gateway/mcp/declared.py (the hand-written: this module)
toolset.declared_here()
