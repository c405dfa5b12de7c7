"""The safety policy's checks of one number, point or leg: a finite input, a latitude and longitude, an
altitude against the band, a target's distance from home and its geofences, the straight leg to it, and
a battery minimum. `SafetyPolicy` composes them for each command."""

from __future__ import annotations

import math

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.fleet.policy.geofence import GeofenceSet
from gateway.fleet.policy.safety_inputs import (
    Target,
    VehicleContext,
)
from gateway.fleet.policy.safety_rules import (
    Rule,
    fmt,
    geofence_refusal,
)
from gateway.fleet.policy.vehicle_limits import Limits


def require_finite(ctx: VehicleContext, name: str, value: object) -> None:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ctx.refuse(Rule.INVALID_INPUT, f"{name} must be a finite number; got {value!r}")


def require_lat_lon(ctx: VehicleContext, lat: float, lon: float) -> None:
    try:
        geo.check_lat_lon(lat, lon)
    except InvalidArgument as exc:
        raise ctx.refuse(Rule.INVALID_INPUT, exc.message) from None


def start_of(ctx: VehicleContext) -> tuple[float, float] | None:
    if ctx.position is not None:
        return (ctx.position[0], ctx.position[1])
    return None


def check_point(fences: GeofenceSet, ctx: VehicleContext, limits: Limits, target: Target, what: str) -> None:
    for name, value in (("latitude", target.lat), ("longitude", target.lon)):
        require_finite(ctx, f"{what} {name}", value)
    require_finite(ctx, f"{what} altitude", target.alt_rel_m)
    require_lat_lon(ctx, target.lat, target.lon)
    check_altitude(ctx, limits, f"{what} altitude", target.alt_rel_m)
    check_horizontal(fences, ctx, limits, target, what)


def check_horizontal(
    fences: GeofenceSet, ctx: VehicleContext, limits: Limits, target: Target, what: str
) -> None:
    require_finite(ctx, f"{what} latitude", target.lat)
    require_finite(ctx, f"{what} longitude", target.lon)
    require_lat_lon(ctx, target.lat, target.lon)
    origin = ctx.distance_origin
    if origin is None:
        raise ctx.refuse(
            Rule.HOME_UNKNOWN,
            f"drone {ctx.vehicle_id} has no home position yet, so the distance limit of "
            f"{fmt(limits.max_distance_m)} m from home cannot be checked; wait for a GPS fix and home",
            limit_m=limits.max_distance_m,
        )
    distance = geo.horizontal_distance_m(origin[0], origin[1], target.lat, target.lon)
    if distance > limits.max_distance_m:
        where = origin_words(ctx)
        raise ctx.refuse(
            Rule.MAX_DISTANCE,
            f"{what} is {fmt(distance)} m from {where}, beyond the limit of {fmt(limits.max_distance_m)} m; "
            f"nothing was sent: tell the user it cannot be flown, or choose a point within "
            f"{fmt(limits.max_distance_m)} m of {where.split(' (')[0]}",
            distance_m=round(distance, 2),
            limit_m=limits.max_distance_m,
        )
    for v in fences.check_target(ctx.vehicle_id, target.lat, target.lon):
        raise geofence_refusal(ctx, v, what)


def origin_words(ctx: VehicleContext) -> str:
    """How a refusal names the point the distance limit counts from: "home" while the vehicle's origin
    is its home, else the origin, with how far the autopilot's home has moved from it."""
    if ctx.origin is None or ctx.home is None:
        return "home"
    moved = geo.horizontal_distance_m(ctx.origin[0], ctx.origin[1], ctx.home[0], ctx.home[1])
    if moved < 1.0:
        return "home"
    return (
        f"its origin (the first home it reported; the distance limit counts from there, not from the "
        f"home the autopilot set {fmt(moved)} m away when it last armed)"
    )


def check_leg(
    fences: GeofenceSet,
    ctx: VehicleContext,
    start: tuple[float, float] | None,
    end: tuple[float, float],
    what: str = "target",
    width_m: float = 0.0,
) -> None:
    """The straight leg start -> end (lat, lon) against the drone's zones (``width_m``: a loiter circle
    at either end); with zones in force, an unknown start is refused (``what``: the end, in words)."""
    zones = fences.for_vehicle(ctx.vehicle_id)
    if not zones:
        return
    if start is None:
        raise ctx.refuse(
            Rule.POSITION_UNKNOWN,
            f"the position of drone {ctx.vehicle_id} is unknown, so the path to the {what} cannot be "
            f"checked against {len(zones)} geofence zone(s)",
        )
    for v in fences.check_leg(ctx.vehicle_id, start, end, width_m):
        raise geofence_refusal(ctx, v, "path")


def check_altitude(ctx: VehicleContext, limits: Limits, what: str, alt: float) -> None:
    if alt < 0:
        raise ctx.refuse(
            Rule.MIN_ALTITUDE,
            f"{what} {fmt(alt)} m is below home; altitudes are metres above home and must be at least "
            f"{fmt(limits.min_altitude_m)} m (use land to descend)",
            alt_rel_m=alt,
            limit_m=limits.min_altitude_m,
        )
    if alt < limits.min_altitude_m:
        raise ctx.refuse(
            Rule.MIN_ALTITUDE,
            f"{what} {fmt(alt)} m is below the minimum of {fmt(limits.min_altitude_m)} m above home "
            "(use land to descend)",
            alt_rel_m=alt,
            limit_m=limits.min_altitude_m,
        )
    if alt > limits.max_altitude_m:
        raise ctx.refuse(
            Rule.MAX_ALTITUDE,
            f"{what} {fmt(alt)} m exceeds the limit of {fmt(limits.max_altitude_m)} m above home; "
            f"nothing was sent: fly at most {fmt(limits.max_altitude_m)} m, or tell the user the limit",
            alt_rel_m=alt,
            limit_m=limits.max_altitude_m,
        )


def check_battery(ctx: VehicleContext, minimum: float, rule: Rule) -> None:
    purpose = "take off" if rule is Rule.BATTERY_TAKEOFF else "start a new leg"
    if minimum <= 0:
        return
    pct = ctx.battery_pct
    if pct is None or not math.isfinite(pct):
        raise ctx.refuse(
            Rule.BATTERY_UNKNOWN,
            f"battery level of drone {ctx.vehicle_id} is unknown; {fmt(minimum)} % is needed to {purpose}",
            minimum_pct=minimum,
        )
    if pct < minimum:
        raise ctx.refuse(
            rule,
            f"battery {fmt(pct)} % is below the {fmt(minimum)} % needed to {purpose}; nothing was "
            + ("sent: tell the user" if not ctx.airborne else "sent: bring it home (return_to_launch)"),
            battery_pct=pct,
            minimum_pct=minimum,
        )
