"""Navigation toolset: where the drone is and whether it got there (reads); where it goes and waiting
for it (monitor_flight) are commands, declared with their verbs."""

from __future__ import annotations

from typing import Literal

from gateway.errors import VehicleNotReady
from gateway.fleet.vehicles.readings import age_s, is_stale, value
from gateway.mcp.access import ToolCall
from gateway.mcp.results import ArrivalOut, PositionOut
from gateway.mcp.toolkit import DroneId, Toolset

toolset = Toolset("navigation")


def position_out(call: ToolCall, drone_id: str, which: Literal["position", "home"]) -> PositionOut:
    v = call.commander.vehicle(drone_id)
    p = value(v.telemetry.position if which == "position" else v.telemetry.home)
    if p is None:
        gps = value(v.telemetry.gps_info)
        fix = "" if gps is None else f"; GPS fix {gps.fix_type}, {gps.num_satellites} satellites"
        what = "position" if which == "position" else f"{which} position"
        raise VehicleNotReady(
            f"no {what} from {drone_id} yet: the autopilot has no global position fix "
            f"(state: {v.state}{fix}); try again once its GPS has a fix"
        )
    age = age_s(v, which) or 0.0
    stale = which == "position" and is_stale(v, age, call.settings.link_lost_after_s)
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
async def get_position(call: ToolCall, drone_id: DroneId) -> PositionOut:
    """Current position: lat_deg, lon_deg, alt_m above home, alt_amsl_m."""
    return position_out(call, drone_id, "position")


@toolset.tool(read_only=True)
async def get_home_position(call: ToolCall, drone_id: DroneId) -> PositionOut:
    """Home (launch) position: lat_deg, lon_deg, alt_amsl_m."""
    return position_out(call, drone_id, "home")


# here: the tools the verbs declare for this toolset (@command(tool=Tool(..., "navigation")), mostly in
# gateway/fleet/commands/navigation_verbs.py), built by gateway/mcp/declared.py (the hand-written: this
# module)
toolset.declared_here()


@toolset.tool(read_only=True)
async def check_arrival(call: ToolCall, drone_id: DroneId) -> ArrivalOut:
    """Has the last goto arrived? Answers at once with the distance left (m)."""
    a = await call.commander.arrival(call.caller, drone_id)
    text = (
        f"{drone_id}: no goto sent yet" if a.kind is None else f"{drone_id} {a.kind} {a.status}: {a.message}"
    )
    return ArrivalOut.model_validate(a, from_attributes=True).say(text)
