"""Formation planning: slot geometry, travel-minimising slot assignment, and separation by altitude layers.

Geometry: slots are laid out in a body frame (forward along ``heading_deg``, right-hand side), centred so
their centroid is the requested centre, rotated to north/east and converted to lat/lon with
`gateway.fleet.geo` around the centre. All drones' relative altitudes are taken as one frame: the homes
of a fleet flown in formation are assumed to be at the same elevation (within a metre or so).

Execution model (what the executor must do): a plan has three **phases** and every drone finishes phase
k before any drone starts phase k+1:
  1. climb/descend vertically to the drone's transit altitude (layered drones only),
  2. fly straight to the slot: horizontally at the transit altitude (layered drones), or directly in 3D
     from the start to the slot (drones without conflicts),
  3. descend/climb vertically to the formation altitude (layered drones only).
Within each phase, each pair of drones' segments is checked by *geometric* segment-to-segment minimum
distance, which ignores timing. This is deliberate: it is conservative and holds whatever the drones'
speeds, accelerations and command latencies (each drone has its own link and autopilot, so
"simultaneous constant-speed flight" would be an assumption the real fleet does not keep). The
barrier between phases is what lets the three checks stand for the whole manoeuvre.

A pair is required to stay at least ``min_separation_m`` apart, or, when it already starts closer than
that, never to get closer than it starts.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING

from gateway.errors import InvalidArgument
from gateway.fleet import geo
from gateway.fleet.formation.assignment import min_cost_assignment
from gateway.fleet.formation.shapes import TOL_M
from gateway.fleet.policy.safety_inputs import Target
from gateway.fleet.policy.safety_rules import Rule, fmt, refuse
from gateway.util.json_types import JsonObject

if TYPE_CHECKING:
    import numpy as np


@dataclass(frozen=True)
class DroneStart:
    """Where a drone is now: id, latitude, longitude, altitude above home (m)."""

    id: str
    lat: float
    lon: float
    alt_rel_m: float


@dataclass(frozen=True)
class Conflict:
    """Two drones whose direct paths would have come within the minimum separation, and the fix."""

    a: str
    b: str
    closest_m: float
    resolution: str


@dataclass
class SlotAssignment:
    drone_id: str
    slot_index: int
    lat: float
    lon: float
    alt_rel_m: float
    north_m: float  # slot offset from the centre
    east_m: float
    transit_alt_m: float | None  # None: flies directly (no conflict needed resolving)
    distance_m: float  # length of the drone's path, all legs
    legs: list[Target]
    conflicts_resolved: list[str] = field(default_factory=list)


@dataclass
class FormationPlan:
    formation: str
    center_lat: float
    center_lon: float
    alt_m: float
    spacing_m: float
    heading_deg: float
    min_separation_m: float
    slots: list[SlotAssignment]
    conflicts: list[Conflict]
    phases: list[dict[str, Target]]  # per phase: drone id -> waypoint; absent = stays put
    total_distance_m: float
    min_clearance_m: float | None  # smallest distance between two drones' segments in a phase; None: 1 drone
    notes: list[str] = field(default_factory=list)

    def slot_for(self, drone_id: str) -> SlotAssignment:
        for slot in self.slots:
            if slot.drone_id == drone_id:
                return slot
        raise KeyError(drone_id)

    def to_dict(self) -> JsonObject:
        return asdict(self)


# ------------------------------------------------------------------------------------------------
# planning


def _check_numbers(
    *,
    alt_m: float,
    spacing_m: float,
    heading_deg: float,
    min_separation_m: float,
    max_altitude_m: float,
    min_transit_alt_m: float,
) -> None:
    """Every number finite, spacing and separation positive, the altitude within the ceiling."""
    for name, value in (
        ("alt_m", alt_m),
        ("spacing_m", spacing_m),
        ("heading_deg", heading_deg),
        ("min_separation_m", min_separation_m),
        ("max_altitude_m", max_altitude_m),
        ("min_transit_alt_m", min_transit_alt_m),
    ):
        geo.check_finite(name, value)
    if spacing_m <= 0 or min_separation_m <= 0:
        raise InvalidArgument("spacing_m and min_separation_m must be above 0 m")
    if not 0 < alt_m <= max_altitude_m:
        raise InvalidArgument(
            f"formation altitude {fmt(alt_m)} m must be above 0 and at most "
            f"{fmt(max_altitude_m)} m above home"
        )


def plan_formation(
    drones: Sequence[DroneStart | tuple[str, float, float, float]],
    formation: str,
    center_lat: float,
    center_lon: float,
    alt_m: float,
    spacing_m: float,
    heading_deg: float,
    min_separation_m: float,
    *,
    max_altitude_m: float = 120.0,
    min_transit_alt_m: float = 5.0,
    wedge_half_angle_deg: float = 45.0,
) -> FormationPlan:
    """Plan a formation move; raises InvalidArgument for malformed input and SafetyRefusal
    (rule ``min_separation``) when the formation or the paths to it cannot keep the separation."""
    starts = _normalise_drones(drones)
    geo.check_lat_lon(center_lat, center_lon)
    _check_numbers(
        alt_m=alt_m,
        spacing_m=spacing_m,
        heading_deg=heading_deg,
        min_separation_m=min_separation_m,
        max_altitude_m=max_altitude_m,
        min_transit_alt_m=min_transit_alt_m,
    )
    if spacing_m < min_separation_m:
        raise refuse(
            Rule.MIN_SEPARATION,
            f"formation spacing {fmt(spacing_m)} m is below the minimum separation of "
            f"{fmt(min_separation_m)} m",
            spacing_m=spacing_m,
            limit_m=min_separation_m,
        )
    heading = heading_deg % 360.0
    n = len(starts)

    # numpy (about 17 MiB) is loaded when a formation is first planned, not when the gateway starts
    import numpy as np

    from gateway.fleet.formation import formation_geometry as geom

    offsets = geom.formation_offsets(formation, n, spacing_m, wedge_half_angle_deg)
    slots_ne = geom.rotate_to_ned(offsets, heading)
    slot_min = geom.min_pairwise(slots_ne)
    if slot_min < min_separation_m - TOL_M:
        raise refuse(
            Rule.MIN_SEPARATION,
            f"two {formation} slots would be {fmt(slot_min, 2)} m apart, below the minimum separation of "
            f"{fmt(min_separation_m)} m",
            closest_m=slot_min,
            limit_m=min_separation_m,
        )

    # Local frame around the centre: x = north, y = east, z = up (metres above home).
    start_xyz = np.array(
        [[*geo.ned_offset(center_lat, center_lon, d.lat, d.lon), d.alt_rel_m] for d in starts]
    )
    slot_xyz = np.column_stack([slots_ne, np.full(n, float(alt_m))])

    cost = np.linalg.norm(start_xyz[:, None, :] - slot_xyz[None, :, :], axis=2)
    slot_of = min_cost_assignment(cost.tolist())
    target_xyz = np.array([slot_xyz[slot_of[i]] for i in range(n)])

    required = np.full((n, n), float(min_separation_m))
    for i in range(n):
        for j in range(i + 1, n):
            d0 = float(np.linalg.norm(start_xyz[i] - start_xyz[j]))
            required[i, j] = required[j, i] = min(min_separation_m, d0)

    layering = geom.Layering(
        start_xyz,
        target_xyz,
        required,
        alt_m,
        min_separation_m,
        max_altitude_m,
        min_transit_alt_m,
        [d.id for d in starts],
    )
    transit, direct_conflicts = layering.solve()

    phases_xyz = layering.phase_segments(transit)
    clearance = layering.min_clearance(transit)
    notes = []
    close_pairs = [
        (starts[i].id, starts[j].id, required[i, j])
        for i in range(n)
        for j in range(i + 1, n)
        if required[i, j] < min_separation_m
    ]
    for first, second, d0 in close_pairs:
        notes.append(
            f"drones {first} and {second} start {fmt(d0, 2)} m apart, below the minimum separation; "
            "their paths never bring them closer than that"
        )

    conflicts: list[Conflict] = []
    per_drone: dict[int, list[str]] = {i: [] for i in range(n)}
    for i, j, closest in direct_conflicts:
        resolution = f"{_describe(starts[i].id, transit[i])}, {_describe(starts[j].id, transit[j])}"
        conflicts.append(Conflict(starts[i].id, starts[j].id, round(closest, 2), resolution))
        per_drone[i].append(f"with {starts[j].id}: direct paths {fmt(closest, 2)} m apart; {resolution}")
        per_drone[j].append(f"with {starts[i].id}: direct paths {fmt(closest, 2)} m apart; {resolution}")

    def to_wp(p: np.ndarray) -> Target:
        lat, lon = geo.offset_position(center_lat, center_lon, float(p[0]), float(p[1]))
        return Target(lat, lon, round(float(p[2]), 3))

    phases: list[dict[str, Target]] = [{}, {}, {}]
    slots: list[SlotAssignment] = []
    for i, d in enumerate(starts):
        legs: list[Target] = []
        length = 0.0
        for k in range(3):
            a, b = phases_xyz[k][i]
            if np.linalg.norm(b - a) > TOL_M:
                wp = to_wp(b)
                phases[k][d.id] = wp
                legs.append(wp)
                length += float(np.linalg.norm(b - a))
        t = target_xyz[i]
        lat, lon = geo.offset_position(center_lat, center_lon, float(t[0]), float(t[1]))
        slots.append(
            SlotAssignment(
                drone_id=d.id,
                slot_index=slot_of[i],
                lat=lat,
                lon=lon,
                alt_rel_m=float(alt_m),
                north_m=round(float(t[0]), 3),
                east_m=round(float(t[1]), 3),
                transit_alt_m=transit[i],
                distance_m=round(length, 2),
                legs=legs,
                conflicts_resolved=per_drone[i],
            )
        )

    return FormationPlan(
        formation=formation,
        center_lat=center_lat,
        center_lon=center_lon,
        alt_m=float(alt_m),
        spacing_m=float(spacing_m),
        heading_deg=heading,
        min_separation_m=float(min_separation_m),
        slots=slots,
        conflicts=conflicts,
        phases=phases,
        total_distance_m=round(sum(s.distance_m for s in slots), 2),
        min_clearance_m=round(clearance, 3) if math.isfinite(clearance) else None,
        notes=notes,
    )


def _describe(drone_id: str, transit: float | None) -> str:
    return f"{drone_id} direct" if transit is None else f"{drone_id} transits at {fmt(transit)} m"


def _normalise_drones(drones: Iterable[DroneStart | tuple[str, float, float, float]]) -> list[DroneStart]:
    out: list[DroneStart] = []
    for item in drones:
        if isinstance(item, DroneStart):
            d = item
        else:
            try:
                drone_id, lat, lon, alt = item
            except (TypeError, ValueError):
                raise InvalidArgument(f"each drone must be (id, lat, lon, alt_rel_m); got {item!r}") from None
            d = DroneStart(drone_id, lat, lon, alt)
        if not isinstance(d.id, str) or not d.id:
            raise InvalidArgument(f"drone id must be a non-empty string; got {d.id!r}")
        geo.check_lat_lon(d.lat, d.lon)
        geo.check_finite(f"altitude of drone {d.id}", d.alt_rel_m)
        out.append(d)
    if not out:
        raise InvalidArgument("a formation needs at least one drone")
    ids = [d.id for d in out]
    dupes = sorted({i for i in ids if ids.count(i) > 1})
    if dupes:
        raise InvalidArgument(f"drone ids appear more than once: {dupes}")
    return out


# ------------------------------------------------------------------------------------------------
# fleet takeoff / RTL staggering


def staggered_altitudes(
    drone_ids: Sequence[str], base_alt_m: float, stagger_m: float, max_altitude_m: float = 120.0
) -> dict[str, float]:
    """base, base + stagger, base + 2*stagger ... in the order given; refuses when the top one exceeds
    ``max_altitude_m``."""
    geo.check_finite("base_alt_m", base_alt_m)
    geo.check_finite("stagger_m", stagger_m)
    if stagger_m < 0:
        raise InvalidArgument(f"stagger_m must be 0 or more; got {stagger_m}")
    if base_alt_m <= 0:
        raise InvalidArgument(f"base altitude must be above 0 m; got {base_alt_m}")
    ids = list(drone_ids)
    if len(set(ids)) != len(ids):
        raise InvalidArgument(
            f"drone ids appear more than once: {sorted({i for i in ids if ids.count(i) > 1})}"
        )
    out = {drone_id: base_alt_m + k * stagger_m for k, drone_id in enumerate(ids)}
    top = max(out.values(), default=base_alt_m)
    if top > max_altitude_m + TOL_M:
        raise refuse(
            Rule.MAX_ALTITUDE,
            f"staggering {len(ids)} drones {fmt(stagger_m)} m apart from {fmt(base_alt_m)} m reaches "
            f"{fmt(top)} m, above the limit of {fmt(max_altitude_m)} m above home",
            top_m=top,
            limit_m=max_altitude_m,
        )
    return out


def takeoff_altitudes(
    drone_ids: Sequence[str], alt_m: float, stagger_m: float, max_altitude_m: float = 120.0
) -> dict[str, float]:
    """Fleet takeoff: each drone climbs to its own altitude so neighbours on the pad never share one."""
    return staggered_altitudes(drone_ids, alt_m, stagger_m, max_altitude_m)


def rtl_altitudes(
    drone_ids: Sequence[str], rtl_alt_m: float, stagger_m: float, max_altitude_m: float = 120.0
) -> dict[str, float]:
    """Fleet return-to-launch: a distinct return altitude per drone (set each drone's RTL altitude, e.g.
    MAVSDK ``action.set_return_to_launch_altitude``, before commanding RTL). The autopilot returns at
    its current altitude when that is higher, so layers hold only for drones below their RTL altitude."""
    return staggered_altitudes(drone_ids, rtl_alt_m, stagger_m, max_altitude_m)
