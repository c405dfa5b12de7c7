"""A mission, item by item, against the limits and zones in force: what `SafetyPolicy.check_mission`
runs after its locks and battery checks, on an upload and again on every start (`check_items`).

Items built by the gateway (kind waypoint, takeoff, land, rtl, loiter_time) are checked by their kind;
items a file or the autopilot holds are judged by their MAVLink command with the autopilot's semantics
(`gateway.fleet.policy.mission_check`): positions with their circle (a loiter's radius counted in the
distance limit and the zones), each leg (widened by the circles at its ends), speed changes by axis,
jumps (repeats bounded, the leg back checked), harmless items passed. An item the gateway cannot check
is refused for agents (rule mission_unchecked) and returned to operators, whose mission is then marked
unchecked. ``starts``: the item numbers the autopilot may begin from (1 on the ground; in the air also
the item it resumes at), each reached by a leg from where the drone is now.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from gateway.fleet import geo
from gateway.fleet.policy.geofence import GeofenceSet
from gateway.fleet.policy.mission_check import (
    MAX_JUMP_REPEATS,
    Effect,
    MissionSemantics,
    Unchecked,
    command_name,
)
from gateway.fleet.policy.safety_checks import (
    check_altitude,
    check_horizontal,
    check_leg,
    check_point,
    origin_words,
    require_finite,
    start_of,
)
from gateway.fleet.policy.safety_inputs import MissionItemLike, Target, VehicleContext
from gateway.fleet.policy.safety_rules import (
    DENIED_MISSION_COMMANDS,
    Rule,
    Via,
    fmt,
    geofence_refusal,
    prefixed,
)
from gateway.fleet.policy.vehicle_limits import Limits

_BUILT_KINDS = {"waypoint": "waypoint", "takeoff": "takeoff", "land": "land", "loiter_time": "loiter_time"}


@dataclass(frozen=True)
class _Point:
    lat: float
    lon: float
    radius_m: float = 0.0


def check_items(
    fences: GeofenceSet,
    ctx: VehicleContext,
    limits: Limits,
    items: Sequence[MissionItemLike],
    via: Via,
    semantics: MissionSemantics | None,
    starts: Iterable[int] = (1,),
) -> list[Unchecked]:
    """Check every item and leg; return the items the gateway cannot check (operators only)."""
    unchecked: list[Unchecked] = []
    points: dict[int, _Point] = {}
    jumps: list[tuple[int, _Point | None, int]] = []
    here = start_of(ctx)
    drone = _Point(*here) if here is not None else None
    previous: _Point | None = None  # the legs from the drone: below, for each item it may start from
    for number, item in enumerate(items, start=1):
        prefix = f"mission item {number}: "
        effect = _effect(ctx, item, number, via, semantics, unchecked)
        if effect is None or effect.kind == "harmless":
            continue
        with prefixed(prefix, item=number):
            if effect.kind == "speed":
                _check_speed(ctx, limits, effect)
            elif effect.kind == "jump":
                _check_jump(ctx, effect, len(items))
                assert effect.target is not None
                jumps.append((number, previous or drone, effect.target))
            elif effect.kind == "rtl":
                previous = _Point(ctx.home[0], ctx.home[1]) if ctx.home else None
            else:
                point = _check_position(fences, ctx, limits, item, effect, previous, not points)
                if point is not None:
                    points[number] = previous = point
    for number, origin, target in jumps:
        with prefixed(f"mission item {number}: the jump back to item {target}: ", item=number):
            _check_leg(fences, ctx, origin, _first_point(points, target, len(items))[1])
    for first in sorted(set(starts)):
        reached, point = _first_point(points, first, len(items))
        with prefixed(f"mission item {reached}: from where the drone is now: ", item=reached):
            _check_leg(fences, ctx, drone, point)
    return unchecked


def _effect(
    ctx: VehicleContext,
    item: MissionItemLike,
    number: int,
    via: Via,
    semantics: MissionSemantics | None,
    unchecked: list[Unchecked],
) -> Effect | None:
    """The item's effect; None when it is unchecked (an operator's: recorded; an agent's: refused)."""
    raw = getattr(item, "raw", None)
    if raw is None:  # built by the gateway from its own kinds
        if item.kind == "rtl":
            return Effect("rtl")
        if item.kind in _BUILT_KINDS:
            return Effect("position")
        command = item.command or 0
        judged: Effect | str = f"has no MAVLink item the gateway can read ({item.kind})"
    else:
        command = raw.command
        denied = DENIED_MISSION_COMMANDS.get(command)
        if denied is not None:
            raise ctx.refuse(
                Rule.MISSION_COMMAND,
                f"mission item {number}: {denied} ({command}) is not accepted in a mission: it would "
                "change what the safety layer relies on",
                item=number,
                command=command,
            )
        if semantics is None:
            judged = "cannot be checked: the drone's autopilot is not known yet"
        else:
            judged = semantics.judge(raw)
    if isinstance(judged, Effect):
        return judged
    found = Unchecked(number, command, judged)
    if via == "mcp":
        raise ctx.refuse(
            Rule.MISSION_UNCHECKED,
            f"{found.text()}, so nothing was sent: agents may store and start only missions whose every "
            "item the gateway checks. Remove the item, or ask an operator (who may store and start it "
            "over REST, marked unchecked)",
            item=number,
            command=command,
            command_name=command_name(command),
        )
    unchecked.append(found)
    return None


def _check_speed(ctx: VehicleContext, limits: Limits, effect: Effect) -> None:
    speed = effect.speed_mps
    require_finite(ctx, "speed", speed)
    assert speed is not None
    if effect.axis == "horizontal":
        limit, what = limits.max_speed_mps, "speed"
    else:
        limit, what = limits.max_vertical_speed_mps, f"{effect.axis} rate"
    if speed > limit:
        kind = "" if effect.axis == "horizontal" else "vertical "
        raise ctx.refuse(
            Rule.MAX_SPEED,
            f"{what} {fmt(speed)} m/s exceeds the {kind}limit of {fmt(limit)} m/s",
            speed_mps=speed,
            limit_mps=limit,
            axis=effect.axis,
        )


def _check_jump(ctx: VehicleContext, effect: Effect, count: int) -> None:
    if not 0 <= effect.repeats <= MAX_JUMP_REPEATS:
        raise ctx.refuse(
            Rule.MISSION_UNCHECKED,
            f"DO_JUMP repeats {effect.repeats} times; the gateway accepts 0..{MAX_JUMP_REPEATS} repeats "
            "(-1, for ever, is refused)",
            repeats=effect.repeats,
        )
    if effect.target is None or not 1 <= effect.target <= count:
        raise ctx.refuse(
            Rule.MISSION_UNCHECKED,
            f"DO_JUMP to item {effect.target}, which the mission does not have (items 1..{count})",
            target=effect.target,
        )


def _check_position(
    fences: GeofenceSet,
    ctx: VehicleContext,
    limits: Limits,
    item: MissionItemLike,
    effect: Effect,
    previous: _Point | None,
    first: bool,
) -> _Point | None:
    """Check a position item and the leg to it; the point it leaves the drone at (None: a takeoff,
    which climbs where the drone is)."""
    kind = item.kind
    if kind == "takeoff":
        require_finite(ctx, "takeoff altitude", item.alt_rel_m)
        check_altitude(ctx, limits, "takeoff altitude", item.alt_rel_m)
        return None
    target = Target(item.lat, item.lon, item.alt_rel_m)
    if kind == "land":  # the altitude of a land item is not flown; only the place matters
        check_horizontal(fences, ctx, limits, target, "landing point")
    else:
        check_point(fences, ctx, limits, target, "waypoint")
    point = _Point(item.lat, item.lon, effect.radius_m)
    if point.radius_m > 0:
        _check_circle(fences, ctx, limits, point)
    _check_leg(fences, ctx, previous, point, first and previous is None)
    return point


def _check_circle(fences: GeofenceSet, ctx: VehicleContext, limits: Limits, point: _Point) -> None:
    """A loiter's circle: its far edge within the distance limit (counted from the vehicle's origin, as
    every other point is, not from a home the autopilot may have moved), all of it clear of the zones."""
    origin = ctx.distance_origin
    assert origin is not None  # check_point refused an unknown home
    reach = geo.horizontal_distance_m(origin[0], origin[1], point.lat, point.lon) + point.radius_m
    if reach > limits.max_distance_m:
        raise ctx.refuse(
            Rule.MAX_DISTANCE,
            f"the loiter circle of radius {fmt(point.radius_m)} m reaches {fmt(reach)} m from "
            f"{origin_words(ctx)}, beyond the limit of {fmt(limits.max_distance_m)} m; nothing was sent",
            distance_m=round(reach, 2),
            limit_m=limits.max_distance_m,
            radius_m=point.radius_m,
        )
    for v in fences.check_target(ctx.vehicle_id, point.lat, point.lon, point.radius_m):
        raise geofence_refusal(ctx, v, f"the loiter circle of radius {fmt(point.radius_m)} m")


def _check_leg(
    fences: GeofenceSet, ctx: VehicleContext, start: _Point | None, end: _Point | None, first: bool = False
) -> None:
    """The leg start -> end against the zones; ``first``: a leg from the mission's start (no item
    before it), checked from the drone's position once per possible start instead."""
    if end is None or first:
        return
    width = end.radius_m if start is None else max(start.radius_m, end.radius_m)
    begin = None if start is None else (start.lat, start.lon)
    check_leg(fences, ctx, begin, (end.lat, end.lon), "item", width)


def _first_point(points: dict[int, _Point], first: int, count: int) -> tuple[int, _Point | None]:
    """The first position the mission flies to from item ``first`` on, and its number."""
    return next(((k, points[k]) for k in range(first, count + 1) if k in points), (first, None))
