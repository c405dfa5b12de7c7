"""Mission toolset: waypoint missions (user waypoint 1 is the first item; the home slot is hidden)."""

from __future__ import annotations

from typing import Annotated, Literal

from mcp.server.mcpserver import Context
from pydantic import BaseModel, Field

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.fleet.operations import MissionTracker, value
from gateway.mcp.access import FleetAccess
from gateway.mcp.results import (
    ActionOut,
    MissionItemOut,
    MissionOut,
    MissionProgressOut,
    OperationOut,
    ValueOut,
)
from gateway.mcp.toolkit import DroneId, Lat, Lon, Toolset, Wait
from gateway.mcp.tools.flight import hold

toolset = Toolset("mission")

MAX_ITEMS = 200


class Waypoint(BaseModel):
    lat: Lat
    lon: Lon
    alt_m: Annotated[float, Field(ge=0, le=10_000, allow_inf_nan=False, description="m above home")]
    kind: Literal["waypoint", "takeoff", "land", "rtl", "loiter_time"] = "waypoint"
    hold_s: Annotated[float, Field(ge=0, le=3600, allow_inf_nan=False)] = 0.0
    speed_mps: Annotated[float | None, Field(gt=0, le=50, allow_inf_nan=False)] = None


Waypoints = Annotated[list[Waypoint], Field(min_length=1, max_length=MAX_ITEMS, description="Items 1..N")]


def _items(waypoints: list[Waypoint]) -> list:
    from gateway.fleet.vehicle import MissionItem

    for n, w in enumerate(waypoints, 1):
        geo.check_lat_lon(w.lat, w.lon)
        if w.kind in ("waypoint", "loiter_time") and w.alt_m <= 0:
            raise InvalidArgument(f"waypoint {n}: alt_m must be above 0 m above home")
    return [
        MissionItem(
            lat=w.lat, lon=w.lon, alt_rel_m=w.alt_m, kind=w.kind, hold_s=w.hold_s, speed_mps=w.speed_mps
        )
        for w in waypoints
    ]


async def _upload(fa: FleetAccess, v, waypoints: list[Waypoint]) -> int:
    items = _items(waypoints)
    vctx = fa.context(v)
    fa.safety.check_actuation(vctx)
    fa.safety.check_mission(vctx, items)
    if fa.operations.running(v.id) is not None and fa.operations.running(v.id).kind == "mission":
        raise InvalidArgument(f"{v.id} is flying a mission; call pause_mission before uploading another")
    await v.upload_mission(items)
    return len(items)


@toolset.tool(idempotent=True)
async def upload_mission(fa: FleetAccess, ctx: Context, drone_id: DroneId, waypoints: Waypoints) -> ActionOut:
    """Upload waypoints (alt_m above home) without starting them."""
    v = fa.ready(drone_id)
    n = await _upload(fa, v, waypoints)
    return ActionOut(drone_id=drone_id, action="upload_mission", message=f"{n} items uploaded").say(
        f"{drone_id}: mission of {n} items uploaded; start it with initiate_mission or resume_mission"
    )


async def _start(fa: FleetAccess, ctx: Context, v, wait: bool, action: str) -> OperationOut:
    fa.guard_takeoff(v, action)
    vctx = fa.context(v)
    fa.safety.check_actuation(vctx)
    if not value(v, "in_air"):
        items = await v.download_mission()
        if not items:
            raise InvalidArgument(f"{v.id} has no mission; give waypoints to initiate_mission")
        if items[0].kind != "takeoff":
            raise InvalidArgument(
                f"{v.id} is on the ground and the mission does not start with a takeoff item; "
                "call takeoff first or make item 1 kind='takeoff'"
            )
        fa.safety.check_takeoff(vctx, items[0].alt_rel_m)

    return await fa.run(ctx, v, MissionTracker(), v.start_mission, {}, wait, action)


@toolset.tool()
async def initiate_mission(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    waypoints: Annotated[
        list[Waypoint] | None, Field(max_length=MAX_ITEMS, description="Upload first")
    ] = None,
    wait: Wait = True,
) -> OperationOut:
    """Upload (if waypoints given) and start the mission; done when finished."""
    v = fa.ready(drone_id)
    fa.guard_takeoff(v, "initiate_mission")
    if waypoints:
        await _upload(fa, v, waypoints)
    return await _start(fa, ctx, v, wait, "initiate_mission")


@toolset.tool(read_only=True)
async def download_mission(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> MissionOut:
    """The mission stored on the drone (alt_m above home)."""
    v = fa.ready(drone_id)
    items = await v.download_mission()
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
        for n, i in enumerate(items, 1)
    ]
    return MissionOut(drone_id=drone_id, count=len(out), items=out).say(
        f"{drone_id}: mission of {len(out)} items"
    )


async def _progress(fa: FleetAccess, drone_id: str) -> MissionProgressOut:
    v = fa.vehicle(drone_id)
    prog = value(v, "mission_progress")
    current, total = (int(prog.current), int(prog.total)) if prog is not None else (0, 0)
    finished = await v.is_mission_finished()
    op = fa.operations.latest(drone_id)
    status = op.status.value if op is not None and op.kind == "mission" else None
    return MissionProgressOut(
        drone_id=drone_id, current=current, total=total, finished=finished, operation_status=status
    ).say(f"{drone_id}: item {current} of {total}" + (", finished" if finished else ""))


@toolset.tool(read_only=True)
async def print_mission_progress(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> MissionProgressOut:
    """Current item (1..N) of the mission and whether it finished."""
    return await _progress(fa, drone_id)


@toolset.tool(read_only=True)
async def is_mission_finished(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ValueOut:
    """true when the mission has run to its end."""
    v = fa.ready(drone_id)
    finished = bool(await v.is_mission_finished())
    return ValueOut(drone_id=drone_id, age_s=0.0, stale=False, value=finished).say(
        f"{drone_id}: mission {'finished' if finished else 'not finished'}"
    )


@toolset.tool(idempotent=True)
async def pause_mission(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ActionOut:
    """Pause = safe hold: hover in GUIDED (not LOITER). resume_mission continues."""
    out = await hold(fa, drone_id, "pause_mission")
    out.message += " (paused as a GUIDED hold)"
    return out.say(f"{drone_id} mission paused: holding position in GUIDED; resume_mission continues")


@toolset.tool(idempotent=True)
async def hold_mission_position(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ActionOut:
    """Hover in place (GUIDED) during a mission; resume_mission continues."""
    return await hold(fa, drone_id, "hold_mission_position")


@toolset.tool()
async def resume_mission(fa: FleetAccess, ctx: Context, drone_id: DroneId, wait: Wait = True) -> OperationOut:
    """Continue the mission from its current item; done when finished."""
    v = fa.ready(drone_id)
    return await _start(fa, ctx, v, wait, "resume_mission")


@toolset.tool(destructive=True, idempotent=True)
async def clear_mission(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ActionOut:
    """Delete the mission stored on the drone."""
    v = fa.ready(drone_id)
    running = fa.operations.running(drone_id)
    if running is not None and running.kind == "mission":
        raise InvalidArgument(f"{drone_id} is flying its mission; call pause_mission first")
    fa.safety.check_actuation(fa.context(v))
    await v.clear_mission()
    return ActionOut(drone_id=drone_id, action="clear_mission", message="mission cleared").say(
        f"{drone_id}: mission cleared"
    )


@toolset.tool(idempotent=True)
async def set_current_waypoint(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    index: Annotated[int, Field(ge=1, le=MAX_ITEMS, description="Item 1..N")],
) -> ActionOut:
    """Make mission item `index` the next target."""
    v = fa.ready(drone_id)
    prog = value(v, "mission_progress")
    total = int(prog.total) if prog is not None else None
    if total is not None and total > 0 and index > total:
        raise InvalidArgument(f"index {index} is beyond the mission's {total} items (valid: 1..{total})")
    fa.guard_takeoff(v, "set_current_waypoint")
    fa.safety.check_actuation(fa.context(v))
    await v.set_current_mission_item(index)
    return ActionOut(drone_id=drone_id, action="set_current_waypoint", message=f"next item {index}").say(
        f"{drone_id}: next mission item is {index}"
    )
