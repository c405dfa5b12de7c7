"""Plan steps to gateway tool calls, deterministically (units, geometry, order), the fleet read through
``Sensors``; nothing the plan lacks is guessed but a grounded drone's takeoff height, DEFAULT_TAKEOFF_M."""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Coroutine, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

from fleet_agent import geometry
from fleet_agent.plan import (
    POLYGON_SIDES,
    Altitude,
    Ask,
    Choose,
    Condition,
    Formation,
    Hold,
    Land,
    Leg,
    Move,
    Pattern,
    Reference,
    Report,
    ReturnHome,
    Takeoff,
)

#: the height (m above home) a drone on the ground takes off to before a move that names none
DEFAULT_TAKEOFF_M = 10.0

#: a return home that starts this close to home (m, horizontally) is flown as a landing: the autopilot's
#: return first climbs to its own return altitude, a climb nobody asked for when the drone is there
AT_HOME_M = 3.0

#: a drone flying this close to a height (m) is at it: the gateway refuses a move there that goes nowhere
AT_HEIGHT_M = 1.0


@dataclass(frozen=True)
class Call:
    tool: str
    args: dict[str, Any]
    drone: str | None = None

    @property
    def drones(self) -> list[str]:
        return [self.drone] if self.drone else [str(d) for d in self.args.get("drone_ids") or []]


@dataclass(frozen=True)
class Said:
    """A line of the answer: a reading, a decision, a question back."""

    text: str


Compiled = list[Call | Said]


@dataclass(frozen=True)
class DroneState:
    lat: float | None
    lon: float | None
    alt_m: float | None
    flying: bool
    battery_pct: float | None
    mode: str | None = None


class Sensors(Protocol):
    async def state(self, drone: str) -> DroneState: ...
    async def home(self, drone: str) -> tuple[float, float]: ...
    async def place(self, name: str) -> tuple[float, float]: ...


class CompileError(ValueError):
    """A step the host cannot turn into calls (e.g. a reference without its drone); told in the answer."""


@dataclass
class Compiler:
    sensors: Sensors
    _handlers: dict[type, Callable[[Any], Coroutine[Any, Any, Compiled]]] = field(init=False)

    def __post_init__(self) -> None:
        self._handlers = {
            Takeoff: self._height, Altitude: self._height, Land: self._simple, ReturnHome: self._simple,
            Hold: self._simple, Move: self._move, Pattern: self._pattern, Formation: self._formation,
            Report: self._report, Condition: self._selected, Choose: self._selected, Ask: self._ask,
        }  # fmt: skip

    async def compile(self, step: Any) -> Compiled:
        return await self._handlers[type(step)](step)

    async def _simple(self, step: Land | ReturnHome | Hold) -> Compiled:
        """A hold of a drone on the ground keeps it there: the request names a drone it leaves alone."""
        if isinstance(step, Hold) and not (await self.sensors.state(step.drone)).flying:
            return [Said(f"{step.drone} stays on the ground.")]
        if isinstance(step, ReturnHome) and await self._at_home(step.drone):
            return [Call("land", {"drone_id": step.drone}, step.drone)]
        tool = {"land": "land", "return_home": "return_to_launch", "hold": "hold_position"}[step.action]
        return [Call(tool, {"drone_id": step.drone}, step.drone)]

    async def _ending(self, step: Takeoff | Altitude | Move | Pattern, north: float = 0.0,
                      east: float = 0.0) -> Compiled:  # fmt: skip
        """The step's ``after``; a return home of a drone the step leaves over its home is a landing.
        ``north``, ``east``: where the step takes the drone from where it is now (m)."""
        if step.after == "return_home" and await self._at_home(step.drone, north, east):
            return [Call("land", {"drone_id": step.drone}, step.drone)]
        return ends_with(step.after, step.drone)

    async def _at_home(self, drone: str, north: float = 0.0, east: float = 0.0) -> bool:
        """Whether ``drone``, moved ``north`` and ``east`` from where it is, is over its home."""
        state = await self.sensors.state(drone)
        if not state.flying:  # the autopilot sets its home where it arms (the home read now may be older)
            return math.hypot(north, east) <= AT_HOME_M
        if state.lat is None or state.lon is None:
            return False
        try:
            home = await self.sensors.home(drone)
        except CompileError:
            return False
        n, e = geometry.offset_between(home[0], home[1], state.lat, state.lon)
        return math.hypot(n + north, e + east) <= AT_HOME_M

    async def _height(self, step: Takeoff | Altitude) -> Compiled:
        """A climb or descent to the step's height; to 0 m, a landing (nothing for a drone on the ground).
        None for a drone flying at it: the gateway refuses that move, and then no later move is sent."""
        state = await self.sensors.state(step.drone)
        if step.altitude.metres <= 0:
            if state.flying:
                return [Call("land", {"drone_id": step.drone}, step.drone)]
            return [Said(f"{step.drone} stays on the ground (a height of 0 m).")]
        if state.flying and abs((state.alt_m or 0.0) - step.altitude.metres) < AT_HEIGHT_M:
            return [Said(f"{step.drone} flies at {state.alt_m:.1f} m already."), *await self._ending(step)]
        tool = "move_to_relative" if state.flying else "takeoff"
        args = {"drone_id": step.drone, "alt_m": step.altitude.metres}
        return [Call(tool, args, step.drone), *await self._ending(step)]

    async def _lift(self, drone: str, alt: float | None, up: float) -> tuple[Compiled, bool]:
        """A takeoff first when the drone is on the ground; whether it took off to the climb ``up`` (from
        the ground, "10 m up" and "at 10 m" are one climb)."""
        state = await self.sensors.state(drone)
        if state.flying:
            return [], False
        height = alt if alt is not None else (up if up > 0 else DEFAULT_TAKEOFF_M)
        return [Call("takeoff", {"drone_id": drone, "alt_m": height}, drone)], up > 0 and height == up

    async def _move(self, step: Move) -> Compiled:
        calls = await self._move_only(step)
        if step.origin.kind != "here":
            return [*calls, *ends_with(step.after, step.drone)]
        north, east, _ = sum_legs(step.legs)
        return [*calls, *await self._ending(step, north, east)]

    async def _move_only(self, step: Move) -> Compiled:
        """The move's calls. A move that goes nowhere sideways and gives its height flies to that height:
        its up/down legs are the climb to it, not a climb added on top."""
        north, east, up = sum_legs(step.legs)
        alt = step.altitude.metres if step.altitude is not None else None
        if step.origin.kind != "here":
            return await self._move_from(step, north, east, up, alt)
        if step.altitude is not None and all(leg.direction in ("up", "down") for leg in step.legs):
            return await self._height(Altitude(action="altitude", drone=step.drone, altitude=step.altitude))
        first = step.legs[0]  # a drone on the ground takes off to its first climb; the rest is flown after it
        lead = first.distance.metres if first.direction == "up" and len(step.legs) > 1 else up
        calls, climbed = await self._lift(step.drone, alt, lead)
        partial = climbed and lead != up
        for i, (n, e, u) in enumerate(flown_segments(step.legs[1:] if partial else step.legs)):
            args: dict[str, Any] = {"drone_id": step.drone, "north_m": n, "east_m": e}
            if i == 0 and alt is not None and not calls:
                args["alt_m"] = alt
            elif u and (partial or not climbed):
                args["up_m"] = u
            calls.append(Call("move_to_relative", args, step.drone))
        return calls

    async def _move_from(self, step: Move, north: float, east: float, up: float,
                         alt: float | None) -> Compiled:  # fmt: skip
        lat, lon = await self.origin(step.origin, step.drone)
        target = geometry.offset_position(lat, lon, north, east)
        if alt is None:
            alt = await self._height_from(step, up)
        calls, _ = await self._lift(step.drone, alt, 0.0)
        args = {"drone_id": step.drone, "lat_deg": round(target[0], 7), "lon_deg": round(target[1], 7),
                "alt_m": alt}  # fmt: skip
        return [*calls, Call("go_to_location", args, step.drone)]

    async def _height_from(self, step: Move, up: float) -> float:
        """The height of a move from an origin that gives none: a flying origin drone's, else the mover's,
        plus the up/down legs; with neither flying, the climb, or the default height."""
        other = step.origin.drone if step.origin.kind == "drone" else None
        for drone in (other, step.drone):
            state = await self.sensors.state(drone) if drone else None
            if state is not None and state.flying:
                return (state.alt_m or 0.0) + up
        return up or DEFAULT_TAKEOFF_M

    async def origin(self, ref: Reference, drone: str) -> tuple[float, float]:
        """Where a reference is: a drone's position (now), a home (its drone's, else the mover's), a place."""
        if ref.kind == "home":
            return await self.sensors.home(ref.drone or drone)
        if ref.kind == "point":
            if ref.lat_deg is None or ref.lon_deg is None:
                raise CompileError("a point needs lat_deg and lon_deg")
            return ref.lat_deg, ref.lon_deg
        if ref.kind == "place":
            if not ref.place:
                raise CompileError("a move from a place names no place")
            return await self.sensors.place(ref.place)
        other = ref.drone if ref.kind == "drone" else drone
        if not other:
            raise CompileError("a move from another drone names no drone")
        state = await self.sensors.state(other)
        if state.lat is None or state.lon is None:
            raise CompileError(f"{other} reports no position")
        return state.lat, state.lon

    async def _pattern(self, step: Pattern) -> Compiled:
        legs = pattern_legs(step)
        alt = step.altitude.metres if step.altitude is not None else None
        calls, _ = await self._lift(step.drone, alt, 0.0)
        if step.altitude is not None and not calls:
            calls = await self._height(Altitude(action="altitude", drone=step.drone, altitude=step.altitude))
        moves = [
            Call("move_to_relative", {"drone_id": step.drone, "north_m": n, "east_m": e}, step.drone)
            for n, e in legs
        ]
        return [*calls, *moves, *ends_with(step.after, step.drone)]

    async def _formation(self, step: Formation) -> Compiled:
        north, east, _ = sum_legs(step.legs)
        args: dict[str, Any] = {
            "drone_ids": list(step.drones), "formation": gateway_formation(step.shape, len(step.drones)),
            "alt_m": step.altitude.metres, "spacing_m": step.spacing.metres,
        }  # fmt: skip
        if step.origin is not None and step.origin.kind != "here":
            lat, lon = await self.origin(step.origin, step.drones[0])
            centre = geometry.offset_position(lat, lon, north, east)
            args["center_lat_deg"], args["center_lon_deg"] = round(centre[0], 7), round(centre[1], 7)
        else:
            args.update({k: v for k, v in (("north_m", north), ("east_m", east)) if v})
        return [Call("formation_goto", args), *(c for d in step.drones for c in ends_with(step.after, d))]

    async def _report(self, step: Report) -> Compiled:
        states = {d: await self.sensors.state(d) for d in step.drones}
        lines: Compiled = [Said(describe_state(d, s, step.readings)) for d, s in states.items()]
        if step.pick != "none":
            chosen, value = pick(states, step.readings[0], step.pick)
            if chosen is not None:
                lines.append(Said(f"{chosen} has the {step.pick} {step.readings[0]} ({value:g})."))
        return lines

    async def branch(self, step: Any) -> tuple[list[Said], list[Any]] | None:
        """For an ``if`` or a ``choose``: what it says and the steps it selects, each compiled when its turn
        comes (after the calls before it have flown); None for any other step."""
        if isinstance(step, Condition):
            return await self._condition_branch(step)
        if isinstance(step, Choose):
            return await self._choose_branch(step)
        return None

    async def _condition_branch(self, step: Condition) -> tuple[list[Said], list[Any]]:
        drones = [step.drone, *([step.than] if step.than else [])]
        read = [reading_value(await self.sensors.state(d), step.reading) for d in drones]
        values = [v for v in read if v is not None]
        if len(values) < len(drones):
            return [Said(f"{' or '.join(drones)} reports no {step.reading}: nothing was done.")], []
        value = values[0] - (values[1] if step.than else 0.0)
        holds = _COMPARISONS[step.compare](value, step.value)
        how = f"{step.compare.replace('_', ' ')} {step.value:g}: {'so' if holds else 'not'}"
        unit = _UNITS[step.reading]
        lead = f", {step.than} {values[1]:g} {unit}, a lead of {value:g}" if step.than else ""
        said = Said(f"{step.drone}: {step.reading} {values[0]:g} {unit}{lead}, {how}.")
        return [said], list(step.then if holds else step.otherwise)

    async def _selected(self, step: Condition | Choose) -> Compiled:
        said, steps = await self.branch(step) or ([], [])
        return [*said, *[item for s in steps for item in await self.compile(s)]]

    async def _choose_branch(self, step: Choose) -> tuple[list[Said], list[Any]]:
        states = {d: await self.sensors.state(d) for d in step.among}
        chosen, value = pick(states, step.reading, step.pick)
        if chosen is None:
            nobody = f"none of {', '.join(step.among)} reports its {step.reading}: nothing was done."
            return [Said(nobody)], []
        said = Said(f"{chosen} has the {step.pick} {step.reading} ({value:g} {_UNITS[step.reading]}).")
        return [said], chosen_steps(step, chosen)

    async def _ask(self, step: Ask) -> Compiled:
        return [Said(step.text)]


_UNITS = {"battery": "%", "altitude": "m"}
_COMPARISONS = {"above": operator.gt, "below": operator.lt, "at_least": operator.ge, "at_most": operator.le}


#: a polygon of drones: the gateway's circle when the polygon has as many corners as there are drones
#: (neighbours ``spacing`` apart on a circle are its sides), else the nearest of its shapes
_POLYGON_FORMATIONS = {"triangle": (3, "wedge"), "square": (4, "grid")}


def gateway_formation(shape: str, count: int) -> str:
    if shape not in _POLYGON_FORMATIONS:
        return shape
    corners, otherwise = _POLYGON_FORMATIONS[shape]
    return "circle" if count == corners else otherwise


def ends_with(after: str, drone: str) -> Compiled:
    """The landing or return a step's ``after`` asks of ``drone`` (none when the drone stays)."""
    tool = {"land": "land", "return_home": "return_to_launch"}.get(after)
    return [] if tool is None else [Call(tool, {"drone_id": drone}, drone)]


def flown_segments(legs: list[Leg]) -> list[tuple[float, float, float]]:
    """(north_m, east_m, up_m) of each move, in the legs' order: each horizontal leg is one move (a dogleg
    passes its corner); a climb or descent goes with the leg before it (the first, when it comes first)."""
    segments: list[tuple[float, float, float]] = []
    climb_first = 0.0
    for leg in legs:
        north, east, up = sum_legs([leg])
        if north or east:
            segments.append((north, east, climb_first))
            climb_first = 0.0
        elif segments:
            n, e, u = segments[-1]
            segments[-1] = (n, e, round(u + up, 2) + 0.0)
        else:
            climb_first = round(climb_first + up, 2) + 0.0
    return segments or [(0.0, 0.0, climb_first)]


def sum_legs(legs: list[Leg]) -> tuple[float, float, float]:
    """(north_m, east_m, up_m) of legs flown one after the other."""
    north = east = up = 0.0
    for leg in legs:
        metres = leg.distance.metres
        if leg.direction in ("up", "down"):
            up += metres if leg.direction == "up" else -metres
            continue
        n, e = geometry.COMPASS[leg.direction]
        north, east = north + n * metres, east + e * metres
    return round(north, 2) + 0.0, round(east, 2) + 0.0, round(up, 2) + 0.0


def pattern_legs(step: Pattern) -> list[geometry.Offset]:
    heading = 0.0 if step.heading in (None, "up", "down") else geometry.compass_heading(step.heading)
    clockwise = step.turn != "left"
    if step.shape in POLYGON_SIDES or step.shape == "polygon":
        sides = POLYGON_SIDES.get(step.shape) or step.sides or 4
        return geometry.polygon_legs(sides, step.size.metres, heading, clockwise)
    if step.shape == "rectangle":
        width = step.spacing.metres if step.spacing is not None else step.size.metres
        return geometry.rectangle_legs(step.size.metres, width, heading, clockwise)
    if step.shape == "orbit":
        return geometry.orbit_legs(step.size.metres, clockwise=clockwise, start_deg=heading)
    spacing = step.spacing.metres if step.spacing is not None else step.size.metres / 4
    return geometry.survey_legs(step.lines or 2, step.size.metres, spacing, heading, clockwise)


def reading_value(state: DroneState, reading: str) -> float | None:
    return {"battery": state.battery_pct, "altitude": state.alt_m}.get(reading)


def pick(states: dict[str, DroneState], reading: str, how: str) -> tuple[str | None, float]:
    """The drone with the highest or lowest reading (None when none reports it)."""
    known = {d: v for d, s in states.items() if (v := reading_value(s, reading)) is not None}
    if not known:
        return None, 0.0
    chosen = max(known, key=known.__getitem__) if how == "highest" else min(known, key=known.__getitem__)
    return chosen, known[chosen]


def chosen_steps(step: Choose, chosen: str) -> list[Any]:
    """The steps of a choice flown by the drone chosen. Steps written once for each drone of ``among``
    (the same climb for every candidate) are one set of steps: those of the first candidate named."""
    drones = [getattr(s, "drone", None) for s in step.then]
    first = next((d for d in drones if d in step.among), None)
    kept = [s for s, d in zip(step.then, drones, strict=True) if d == first or d not in step.among]
    return [with_drone(s, chosen) for s in kept]


def with_drone(step: Any, drone: str) -> Any:
    """The step flown by ``drone`` (a formation's or a report's drones are left as written)."""
    return step.model_copy(update={"drone": drone}) if hasattr(step, "drone") else step


def describe_state(drone: str, state: DroneState, readings: Sequence[str]) -> str:
    parts = []
    for reading in readings:
        if reading == "battery":
            battery = "unknown" if state.battery_pct is None else f"{state.battery_pct:g} %"
            parts.append(f"battery {battery}")
        elif reading == "altitude" or (reading == "flying" and state.alt_m is not None):
            parts.append(f"altitude {state.alt_m or 0.0:.1f} m")
        elif reading == "position" and state.lat is not None and state.lon is not None:
            parts.append(f"at {state.lat:.6f}, {state.lon:.6f}")
        elif reading == "mode":
            parts.append(f"mode {state.mode or 'unknown'}")
    parts.append("flying" if state.flying else "on the ground")
    return f"{drone}: {', '.join(dict.fromkeys(parts))}."
