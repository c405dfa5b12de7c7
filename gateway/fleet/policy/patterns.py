"""Flight modes by what they need and what they fly.

Each autopilot dialect lists the modes an agent may select in the air, and why (``AIR_MODES`` in
`gateway.fleet.dialects.ardupilot` and `px4`): a mode that reads the pilot's throttle or sticks sinks or
drifts without RC input, so an agent may not select it in the air; a mode the dialect does not list is
refused too (the gateway does not know what it flies). A mode that flies a pattern (ArduCopter's CIRCLE)
is judged, for anyone who selects it in the air, by the pattern's real extent: its far side lies
``pattern_reach`` radii from where it starts (CIRCLE: the centre is one radius ahead, so two radii), in
any direction the vehicle may be heading; that disc must keep within the distance limit from the
vehicle's origin and clear of the geofence zones.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from gateway.fleet import geo
from gateway.fleet.policy.geofence import GeofenceSet
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.policy.safety_rules import Rule, Via, fmt
from gateway.fleet.policy.vehicle_limits import Limits

if TYPE_CHECKING:
    from gateway.fleet.dialects.modes import ModeChoice


def check_air_mode(ctx: VehicleContext, choice: ModeChoice, via: Via) -> None:
    """An agent may select in the air only the modes its dialect lists as flyable without a pilot."""
    if via != "mcp" or not ctx.airborne or choice.in_air.allowed:
        return
    raise ctx.refuse(
        Rule.MODE_IN_AIR,
        f"mode {choice.native} {choice.in_air.why}, so agents may not select it in the air; nothing was "
        "sent. Use hold (GUIDED), LAND or RTL instead",
        mode=choice.native,
    )


def check_pattern(
    fences: GeofenceSet, ctx: VehicleContext, limits: Limits, choice: ModeChoice, radius_m: float | None
) -> None:
    """A pattern mode entered in the air: its extent (``pattern_reach`` radii around where the vehicle is)
    against the distance limit from the origin and the geofence zones."""
    if not choice.pattern_radius or not ctx.airborne:
        return
    names = "/".join(name for name, _ in choice.pattern_radius)
    if radius_m is None:
        raise ctx.refuse(
            Rule.PATTERN_EXTENT,
            f"mode {choice.native} flies a circle whose radius ({names}) could not be read, so its extent "
            "cannot be checked; nothing was sent",
            mode=choice.native,
        )
    reach = max(0.0, radius_m) * choice.pattern_reach
    reference = ctx.distance_origin
    if ctx.position is None or reference is None:
        raise ctx.refuse(
            Rule.POSITION_UNKNOWN,
            f"the position or origin of drone {ctx.vehicle_id} is unknown, so the extent of mode "
            f"{choice.native} cannot be checked; nothing was sent",
        )
    lat, lon = ctx.position[0], ctx.position[1]
    from_origin = geo.horizontal_distance_m(reference[0], reference[1], lat, lon)
    what = (
        f"mode {choice.native} with a radius of {fmt(radius_m)} m flies up to {fmt(reach)} m from where it "
        "starts (its centre lies one radius ahead)"
    )
    if from_origin + reach > limits.max_distance_m:
        raise ctx.refuse(
            Rule.PATTERN_EXTENT,
            f"{what}: up to {fmt(from_origin + reach)} m from the origin, beyond the distance limit of "
            f"{fmt(limits.max_distance_m)} m; nothing was sent",
            mode=choice.native,
            reach_m=round(reach, 2),
            distance_m=round(from_origin + reach, 2),
            limit_m=limits.max_distance_m,
        )
    for zone in fences.for_vehicle(ctx.vehicle_id):
        if zone.kind == "keep_out" and zone.distance_m(lat, lon) <= reach:
            raise ctx.refuse(
                Rule.PATTERN_EXTENT,
                f"{what}: within {fmt(reach)} m lies keep-out zone '{zone.name}' "
                f"({fmt(zone.distance_m(lat, lon))} m away); nothing was sent",
                mode=choice.native,
                zone=zone.name,
            )
        if zone.kind == "keep_in" and zone.depth_m(lat, lon) < reach:
            raise ctx.refuse(
                Rule.PATTERN_EXTENT,
                f"{what}: keep-in zone '{zone.name}' ends {fmt(zone.depth_m(lat, lon))} m away; nothing "
                "was sent",
                mode=choice.native,
                zone=zone.name,
            )
