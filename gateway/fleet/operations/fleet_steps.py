"""The steps and phases a fleet operation is made of, built from plans (formation, fleet takeoff,
landing, staggered return): what each drone is sent, as JSON the drone's owner can rebuild
(`build_step`), and the return order and altitudes. `gateway.fleet.operations.fleet_ops.FleetOperations` runs
them; each drone's step is one run of the Commander's pass.
"""

from __future__ import annotations

import math
from collections.abc import Awaitable, Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Required

from typing_extensions import TypedDict

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.fleet.operations.fleet_operation import SlotSummary
from gateway.fleet.operations.trackers import GotoTracker, LandingTracker, TakeoffTracker, Tracker
from gateway.fleet.vehicles.protocols import VehicleView, flying
from gateway.util.json_types import JsonObject

if TYPE_CHECKING:
    from gateway.fleet.formation.formation import FormationPlan

Send = Callable[[], Awaitable[None]]
"""Sends one command to a drone (returns once the drone accepted it)."""


class StepSpec(TypedDict, total=False):
    """One drone's step as JSON (see `build_step`): what the node owning the drone rebuilds it from.
    ``typing_extensions``' TypedDict: pydantic validates it (as a routed verb's argument) on Python 3.11."""

    send: Required[str]  # goto, takeoff, land or rtl
    lat: float
    lon: float
    alt_m: float
    tolerance_m: float
    kind: str
    phase: int | None
    timeout_s: float | None
    guard: str | None
    arm_within_s: float | None


@dataclass
class Step:
    """One drone's part of a phase: send a command, then track it as the drone's current operation.
    ``spec`` describes it as JSON (see `build_step`), so the node owning the drone can run it there."""

    vehicle: VehicleView
    tracker: Tracker
    send: Send
    params: JsonObject
    timeout_s: float | None  # the step fails if not finished by then (the vehicle keeps going)
    spec: StepSpec


@dataclass
class Phase:
    name: str
    steps: dict[str, Step]
    abort_on_failure: bool = False  # a failed step ends the fleet operation and holds the others


# ------------------------------------------------------------------------------------------------
# staggered return altitudes
# ------------------------------------------------------------------------------------------------


def rtl_order(
    positions: Mapping[str, tuple[float, float, float]],
    homes: Mapping[str, tuple[float, float]],
    separation_m: float,
) -> tuple[list[str], list[str]]:
    """Order drones from lowest to highest return altitude so that a drone whose straight way home
    passes within ``separation_m`` of another drone's home flies above that drone (which may already be
    descending there). Returns (order, notes); a cycle (two drones passing over each other's homes)
    cannot be ordered and is named in the notes. Ids without a known position or home go first (lowest)
    in the order given."""
    ids = list(positions)
    above: dict[str, set[str]] = {i: set() for i in ids}  # i must be above each of above[i]
    for i in ids:
        if i not in homes:
            continue
        lat, lon, _alt = positions[i]
        for j in ids:
            if j == i or j not in homes:
                continue
            if _passes_near(lat, lon, homes[i], homes[j], separation_m):
                above[i].add(j)
    order: list[str] = []
    notes: list[str] = []
    remaining = list(ids)
    while remaining:
        ready = [i for i in remaining if not (above[i] & set(remaining) - {i})]
        if not ready:  # a cycle: take the first, say so
            i = remaining[0]
            clash = sorted(above[i] & set(remaining))
            notes.append(
                f"the ways home of {i} and {', '.join(clash)} pass over each other's homes: their descents "
                "cannot both be kept below the other's return altitude"
            )
            ready = [i]
        for i in ready:
            order.append(i)
            remaining.remove(i)
    return order, notes


def _passes_near(
    lat: float, lon: float, home: tuple[float, float], other_home: tuple[float, float], sep: float
) -> bool:
    """Does the straight path (lat, lon) -> home pass within ``sep`` m of ``other_home`` (local plane)?"""
    hn, he = geo.ned_offset(lat, lon, home[0], home[1])
    on, oe = geo.ned_offset(lat, lon, other_home[0], other_home[1])
    length2 = hn * hn + he * he
    t = 0.0 if length2 < 1e-9 else max(0.0, min(1.0, (on * hn + oe * he) / length2))
    return math.hypot(on - t * hn, oe - t * he) < sep


# ------------------------------------------------------------------------------------------------
# building fleet operations (the MCP tools and REST call these; no MCP in here)
# ------------------------------------------------------------------------------------------------

FORMATION_PHASES = (
    "climb or descend in place to transit altitudes",
    "fly to the slots",
    "climb or descend in place to the formation altitude",
)
FORMATION_TOLERANCE_M = 1.0
"""A formation leg counts as done within this distance of its waypoint: the next phase's separation
check starts from the planned point, so the barrier keeps arrivals tight."""


def step_timeout_s(distance_m: float, slowest_mps: float = 1.0, margin_s: float = 120.0) -> float:
    """Time after which a step that has not finished is given up: generous, meant to catch a stuck
    drone, never to hurry one."""
    return margin_s + max(0.0, distance_m) / slowest_mps


def build_step(vehicle: VehicleView, spec: StepSpec) -> Step:
    """One drone's step from its JSON description (the node owning the drone rebuilds it from the same):

    - ``{"send": "goto", "lat", "lon", "alt_m", "tolerance_m", "kind", "phase"?}``: a tracked goto;
    - ``{"send": "takeoff", "alt_m", "arm_within_s"?}`` (how long arming may wait), ``{"send": "land"}``,
      ``{"send": "rtl", "alt_m"}`` (return at that altitude above home);

    each with an optional ``timeout_s`` and ``guard`` (the action the takeoff guard names: the
    Commander's pass runs the guard, inside the drone's command lock too; no guard: a recovery step)."""
    send = spec.get("send")
    timeout = spec.get("timeout_s")
    timeout_s = None if timeout is None else float(timeout)
    if send == "goto":
        lat, lon, alt = float(spec["lat"]), float(spec["lon"]), float(spec["alt_m"])
        params: JsonObject = {"lat_deg": lat, "lon_deg": lon, "alt_m": alt}
        phase = spec.get("phase")
        if phase is not None:
            params["phase"] = int(phase)
        tolerance = float(spec.get("tolerance_m", FORMATION_TOLERANCE_M))
        tracker: Tracker = GotoTracker(lat, lon, alt, tolerance, kind=str(spec.get("kind", "formation")))
        return Step(vehicle, tracker, _goto(vehicle, lat, lon, alt), params, timeout_s, spec.copy())
    if send == "takeoff":
        alt = float(spec["alt_m"])
        arm_within = spec.get("arm_within_s")
        return Step(
            vehicle,
            TakeoffTracker(alt),
            _takeoff(vehicle, alt, None if arm_within is None else float(arm_within)),
            {"alt_m": alt},
            timeout_s,
            spec.copy(),
        )
    if send == "land":
        land = lambda: flying(vehicle).land()  # noqa: E731
        return Step(vehicle, LandingTracker(kind="land"), land, {}, timeout_s, spec.copy())
    if send == "rtl":
        alt = float(spec["alt_m"])
        return Step(
            vehicle,
            LandingTracker(kind="return_to_launch"),
            _rtl(vehicle, alt, set_rtl_altitude_param),
            {"rtl_alt_m": alt},
            timeout_s,
            spec.copy(),
        )
    raise InvalidArgument(f"unknown fleet step {send!r}; steps: goto, takeoff, land, rtl")


def formation_phases(
    plan: FormationPlan, vehicles: Mapping[str, VehicleView], guard: str | None = None
) -> list[Phase]:
    """The three phases of a `FormationPlan` as fleet-operation phases (each leg a tracked goto);
    ``guard``: the action the takeoff guard names (None: no guard)."""
    phases: list[Phase] = []
    for index, name in enumerate(FORMATION_PHASES):
        steps: dict[str, Step] = {}
        for drone_id, wp in plan.phases[index].items():
            slot = plan.slot_for(drone_id)
            spec: StepSpec = {
                "send": "goto",
                "lat": wp.lat,
                "lon": wp.lon,
                "alt_m": wp.alt_rel_m,
                "tolerance_m": FORMATION_TOLERANCE_M,
                "kind": "formation",
                "phase": index + 1,
                "timeout_s": step_timeout_s(slot.distance_m),
                "guard": guard,
            }
            steps[drone_id] = build_step(vehicles[drone_id], spec)
        phases.append(Phase(name, steps, abort_on_failure=True))
    return phases


def slot_summaries(plan: FormationPlan) -> dict[str, SlotSummary]:
    """Per drone: its slot's target, transit altitude and distance to fly (for results)."""
    return {
        s.drone_id: {
            "target_lat_deg": round(s.lat, 7),
            "target_lon_deg": round(s.lon, 7),
            "target_alt_m": round(s.alt_rel_m, 2),
            "transit_alt_m": None if s.transit_alt_m is None else round(s.transit_alt_m, 2),
            "distance_m": round(s.distance_m, 1),
        }
        for s in plan.slots
    }


def takeoff_phase(
    vehicles: Mapping[str, VehicleView],
    altitudes: Mapping[str, float],
    guard: str | None = None,
    arm_within_s: float | None = None,
) -> Phase:
    """Every drone takes off to its altitude; ``arm_within_s`` bounds each drone's wait to arm; ``guard``
    names the action in the takeoff guard's refusals (None: no guard)."""
    steps = {
        d: build_step(
            v,
            {
                "send": "takeoff",
                "alt_m": altitudes[d],
                "arm_within_s": arm_within_s,
                "timeout_s": step_timeout_s(altitudes[d], slowest_mps=0.5),
                "guard": guard,
            },
        )
        for d, v in vehicles.items()
    }
    return Phase("take off to staggered altitudes", steps)


def land_phase(vehicles: Mapping[str, VehicleView]) -> Phase:
    return Phase("land in place", {d: build_step(v, {"send": "land"}) for d, v in vehicles.items()})


def rtl_phases(
    vehicles: Mapping[str, VehicleView],
    altitudes: Mapping[str, float],
    positions: Mapping[str, tuple[float, float, float]],
) -> list[Phase]:
    """Return to launch in two phases: (1) every drone climbs or descends in place to its return altitude,
    (2) each drone's RTL altitude is set, then RTL (the autopilot flies home at that altitude and lands;
    it would return at its current altitude if that were higher, which is why phase 1 also descends).
    The barrier keeps a drone from heading home while a neighbour is still moving through its layer."""
    climbs: dict[str, Step] = {}
    for d, v in vehicles.items():
        pos = positions.get(d)
        if pos is None or abs(pos[2] - altitudes[d]) <= FORMATION_TOLERANCE_M:
            continue
        lat, lon, alt = pos
        climbs[d] = build_step(
            v,
            {
                "send": "goto",
                "lat": lat,
                "lon": lon,
                "alt_m": altitudes[d],
                "tolerance_m": FORMATION_TOLERANCE_M,
                "kind": "fleet_climb",
                "timeout_s": step_timeout_s(abs(altitudes[d] - alt), slowest_mps=0.5),
            },
        )
    returns = {d: build_step(v, {"send": "rtl", "alt_m": altitudes[d]}) for d, v in vehicles.items()}
    return [
        Phase("climb or descend in place to return altitudes", climbs),
        Phase("return home and land", returns),
    ]


def _goto(vehicle: VehicleView, lat: float, lon: float, alt: float) -> Send:
    return lambda: flying(vehicle).goto(lat, lon, alt)


def _takeoff(vehicle: VehicleView, alt: float, arm_within_s: float | None) -> Send:
    if arm_within_s is None:
        return lambda: flying(vehicle).takeoff(alt)
    return lambda: flying(vehicle).takeoff(alt, arm_within_s)


def _rtl(
    vehicle: VehicleView, alt: float, set_rtl_altitude: Callable[[VehicleView, float], Awaitable[None]]
) -> Send:
    async def send() -> None:
        await set_rtl_altitude(vehicle, alt)
        await flying(vehicle).return_to_launch()

    return send


async def set_rtl_altitude_param(vehicle: VehicleView, alt_m: float) -> None:
    """The vehicle's return altitude above home, in its autopilot's parameter and units
    (``Vehicle.set_return_altitude``); the autopilot returns higher if it is already higher."""
    await flying(vehicle).set_return_altitude(alt_m)


def default_rtl_base_m(positions: Iterable[tuple[float, float, float]], floor_m: float = 15.0) -> float:
    """Lowest return altitude: above every drone's current altitude (an autopilot already higher than
    its RTL altitude returns at its current one, which would undo the layers), and at least ``floor_m``."""
    highest = max((p[2] for p in positions), default=0.0)
    return float(max(floor_m, math.ceil(highest + FORMATION_TOLERANCE_M)))
