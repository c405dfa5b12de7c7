"""Navigation toolset: where the drone is, where it goes, and waiting for it to get there."""

from __future__ import annotations

import time
from typing import Annotated

from mcp.server.mcpserver import Context
from pydantic import Field

from gateway.errors import NotFound, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.operations import (
    GotoTracker,
    LandingTracker,
    OpStatus,
    YawTracker,
    age_s,
    check_positive_altitude,
    is_stale,
    position,
    value,
)
from gateway.mcp.access import FleetAccess
from gateway.mcp.results import ActionOut, ArrivalOut, OperationOut, PositionOut
from gateway.mcp.toolkit import AltFrame, DroneId, Lat, Lon, Metres, Toolset, Wait

toolset = Toolset("navigation")

NAV_KINDS = ("goto", "reposition", "move_to_relative")


def position_out(fa: FleetAccess, drone_id: str, which: str) -> PositionOut:
    v = fa.vehicle(drone_id)
    p = value(v, which)
    if p is None:
        raise VehicleNotReady(f"no {which} position received from {drone_id} yet (state: {v.state})")
    age = age_s(v, which) or 0.0
    stale = which == "position" and is_stale(v, age, fa.settings.link_lost_after_s)
    note = f" [STALE: {age:.0f} s old, link lost?]" if stale else ""
    return PositionOut(
        drone_id=drone_id,
        age_s=round(age, 2),
        stale=stale,
        lat_deg=p.lat_deg,
        lon_deg=p.lon_deg,
        alt_m=round(p.rel_alt_m, 2),
        alt_amsl_m=round(p.abs_alt_m, 2),
    ).say(f"{drone_id} {which}: {p.lat_deg:.7f}, {p.lon_deg:.7f}, {p.rel_alt_m:.1f} m above home{note}")


@toolset.tool(read_only=True)
async def get_position(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> PositionOut:
    """Current position: lat/lon deg, alt_m above home, alt_amsl_m."""
    return position_out(fa, drone_id, "position")


@toolset.tool(read_only=True)
async def get_home_position(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> PositionOut:
    """Home (launch) position: lat/lon deg, alt_amsl_m."""
    return position_out(fa, drone_id, "home")


async def _fly_to(
    fa: FleetAccess,
    ctx: Context,
    drone_id: str,
    lat: float,
    lon: float,
    alt_rel: float,
    wait: bool,
    kind: str,
    action: str,
    yaw_deg: float | None = None,
) -> OperationOut:
    geo.check_lat_lon(lat, lon)
    check_positive_altitude(alt_rel)
    v = fa.ready(drone_id)
    fa.guard_takeoff(v, action)
    fa.require_airborne(v, action)
    fa.check_motion(v, lat, lon, alt_rel)
    params = {"lat": lat, "lon": lon, "alt_m": round(alt_rel, 2)}
    tracker = GotoTracker(lat, lon, alt_rel, fa.settings.arrival_tolerance_m, kind=kind)
    return await fa.run(ctx, v, tracker, lambda: v.goto(lat, lon, alt_rel, yaw_deg), params, wait, action)


@toolset.tool(idempotent=True)
async def go_to_location(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    latitude_deg: Lat,
    longitude_deg: Lon,
    altitude_m: Annotated[
        float, Field(allow_inf_nan=False, description="m; above home unless alt_frame=amsl")
    ],
    alt_frame: AltFrame = "home",
    wait: Wait = True,
) -> OperationOut:
    """Fly to lat/lon (deg) at altitude_m (m above home, or AMSL); done on arrival."""
    v = fa.ready(drone_id)
    alt_rel = fa.relative_alt(v, altitude_m, alt_frame)
    return await _fly_to(
        fa, ctx, drone_id, latitude_deg, longitude_deg, alt_rel, wait, "goto", "go_to_location"
    )


@toolset.tool(idempotent=True)
async def reposition(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    latitude_deg: Lat,
    longitude_deg: Lon,
    altitude_m: Annotated[float | None, Field(allow_inf_nan=False, description="m; default: current")] = None,
    alt_frame: AltFrame = "home",
    wait: Wait = True,
) -> OperationOut:
    """Fly to lat/lon (deg) and hover; altitude_m above home, default: current."""
    v = fa.ready(drone_id)
    if altitude_m is None:
        pos = position(v)
        if pos is None:
            raise VehicleNotReady(f"no position received from {drone_id} yet")
        alt_rel = pos[2]
    else:
        alt_rel = fa.relative_alt(v, altitude_m, alt_frame)
    return await _fly_to(
        fa, ctx, drone_id, latitude_deg, longitude_deg, alt_rel, wait, "reposition", "reposition"
    )


@toolset.tool()
async def move_to_relative(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    north_m: Metres,
    east_m: Metres,
    down_m: Annotated[float, Field(allow_inf_nan=False, ge=-1000, le=1000, description="+ = descend")] = 0.0,
    wait: Wait = True,
) -> OperationOut:
    """Move north/east/down metres (NED, + down = descend) from here; done on arrival."""
    v = fa.ready(drone_id)
    fa.guard_takeoff(v, "move_to_relative")
    pos = position(v)
    if pos is None:
        raise VehicleNotReady(f"no position received from {drone_id} yet")
    lat, lon = geo.offset_position(pos[0], pos[1], north_m, east_m)
    return await _fly_to(
        fa, ctx, drone_id, lat, lon, pos[2] - down_m, wait, "move_to_relative", "move_to_relative"
    )


@toolset.tool(idempotent=True)
async def set_yaw(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    heading_deg: Annotated[float, Field(ge=0, lt=360, allow_inf_nan=False, description="deg from north, cw")],
    wait: Wait = True,
) -> OperationOut:
    """Turn in place to heading_deg (true north, clockwise); done when facing it."""
    v = fa.ready(drone_id)
    fa.guard_takeoff(v, "set_yaw")
    fa.require_airborne(v, "set_yaw")
    fa.safety.check_actuation(fa.context(v))
    return await fa.run(
        ctx,
        v,
        YawTracker(heading_deg),
        lambda: v.set_yaw(heading_deg),
        {"heading_deg": heading_deg},
        wait,
        "set_yaw",
    )


@toolset.tool(idempotent=True)
async def set_max_speed(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    speed_mps: Annotated[float, Field(gt=0, le=100, allow_inf_nan=False, description="m/s")],
) -> ActionOut:
    """Set the horizontal speed of gotos, m/s."""
    v = fa.ready(drone_id)
    vctx = fa.context(v)
    fa.safety.check_actuation(vctx)
    fa.safety.check_speed(vctx, speed_mps)
    await v.set_max_speed(speed_mps)
    return ActionOut(drone_id=drone_id, action="set_max_speed", message=f"max speed {speed_mps:g} m/s").say(
        f"{drone_id} max speed set to {speed_mps:g} m/s"
    )


@toolset.tool(read_only=True)
async def check_arrival(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ArrivalOut:
    """Has the last goto arrived? Answers at once with the distance left (m)."""
    v = fa.vehicle(drone_id)
    op = fa.operations.latest(drone_id)
    if op is None or op.kind not in NAV_KINDS:
        return ArrivalOut(
            drone_id=drone_id,
            arrived=False,
            operation_id=None,
            status=None,
            distance_m=None,
            vertical_m=None,
            message="no goto sent to this drone yet",
        ).say(f"{drone_id}: no goto sent yet")
    tracker = GotoTracker(
        op.params["lat"], op.params["lon"], op.params["alt_m"], fa.settings.arrival_tolerance_m
    )
    d = tracker.distance(v)
    horiz, dz = (None, None) if d is None else (round(d[0], 1), round(d[1], 1))
    arrived = op.status is OpStatus.succeeded
    text = f"{drone_id} {op.kind} {op.status.value}: {op.message}"
    return ArrivalOut(
        drone_id=drone_id,
        arrived=arrived,
        operation_id=op.id,
        status=op.status.value,
        distance_m=horiz,
        vertical_m=dz,
        message=op.message,
    ).say(text)


@toolset.tool()
async def monitor_flight(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    land_on_arrival: Annotated[bool, Field(description="Land once the goto arrives")] = False,
) -> OperationOut:
    """Wait (capped) for the drone's current action to finish and report it; call again if still running."""
    v = fa.vehicle(drone_id)
    op = fa.operations.latest(drone_id)
    if op is None:
        raise NotFound(f"{drone_id} has no action to monitor (state: {v.state}); nothing was started yet")
    start = time.monotonic()
    cap = fa.settings.mcp_wait_cap_s
    op = await fa.wait(ctx, op, cap)
    if land_on_arrival and op.kind in NAV_KINDS and op.status is OpStatus.succeeded and value(v, "in_air"):
        fa.safety.check_actuation(fa.context(v))
        op = await fa.operations.start(v, LandingTracker(kind="land"), v.land, {}, fa.session_key())
        op = await fa.wait(ctx, op, max(0.0, cap - (time.monotonic() - start)))
    return fa.out(op, v)
