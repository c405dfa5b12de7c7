"""Formation planner: geometry, optimal assignment, separation by layering, refusals, staggering."""

from __future__ import annotations

import itertools
import json
import math
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize

from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet import geo
from gateway.fleet.formation.formation import (
    DroneStart,
    FormationPlan,
    plan_formation,
    rtl_altitudes,
    takeoff_altitudes,
)
from gateway.fleet.formation.formation_geometry import segment_distance
from gateway.fleet.formation.shapes import FORMATIONS
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import VehicleContext
from tests.fleet._util import HOME
from tests.fleet._util import settings as make_settings

CENTER = (47.3980, 8.5460)


def start_at(drone_id: str, north: float, east: float, alt: float = 20.0) -> DroneStart:
    lat, lon = geo.offset_position(CENTER[0], CENTER[1], north, east)
    return DroneStart(drone_id, lat, lon, alt)


def local(lat: float, lon: float) -> np.ndarray:
    return np.array(geo.ned_offset(CENTER[0], CENTER[1], lat, lon))


def slots_ne(plan: FormationPlan) -> np.ndarray:
    """Slot positions (north, east) relative to the centre, by slot index."""
    ordered = sorted(plan.slots, key=lambda s: s.slot_index)
    return np.array([local(s.lat, s.lon) for s in ordered])


def body(ne: np.ndarray, heading_deg: float) -> np.ndarray:
    """(north, east) -> (forward, right) for a formation facing heading_deg."""
    h = math.radians(heading_deg)
    fwd = ne[:, 0] * math.cos(h) + ne[:, 1] * math.sin(h)
    right = -ne[:, 0] * math.sin(h) + ne[:, 1] * math.cos(h)
    return np.column_stack([fwd, right])


def pair_distances(points: np.ndarray) -> list[float]:
    return [float(np.linalg.norm(a - b)) for a, b in itertools.combinations(points, 2)]


def plan_for(formation: str, n: int, spacing: float = 10.0, heading: float = 30.0, **kw) -> FormationPlan:
    drones = [start_at(f"d{i}", -60.0 + 9.0 * i, -40.0, 15.0 + 6.0 * i) for i in range(n)]
    return plan_formation(drones, formation, *CENTER, 30.0, spacing, heading, 5.0, **kw)


# --- geometry ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("formation", FORMATIONS)
@pytest.mark.parametrize("n", [1, 2, 3, 4, 5, 7, 9])
@pytest.mark.parametrize("heading", [0.0, 30.0, 135.0, 270.0])
def test_slots_are_centred_and_at_least_spacing_apart(formation: str, n: int, heading: float) -> None:
    plan = plan_for(formation, n, spacing=10.0, heading=heading)
    ne = slots_ne(plan)
    assert np.allclose(ne.mean(axis=0), 0.0, atol=1e-3), "centroid must be the requested centre"
    if n > 1:
        assert min(pair_distances(ne)) == pytest.approx(10.0, abs=1e-3)
    assert all(s.alt_rel_m == 30.0 for s in plan.slots)
    assert sorted(s.slot_index for s in plan.slots) == list(range(n))


@pytest.mark.parametrize("heading", [0.0, 45.0, 200.0])
def test_line_is_abreast_perpendicular_to_heading(heading: float) -> None:
    b = body(slots_ne(plan_for("line", 5, heading=heading)), heading)
    assert np.allclose(b[:, 0], 0.0, atol=1e-3)
    assert np.allclose(np.diff(b[:, 1]), 10.0, atol=1e-3)


@pytest.mark.parametrize("heading", [0.0, 45.0, 200.0])
def test_column_runs_along_heading_leader_ahead(heading: float) -> None:
    b = body(slots_ne(plan_for("column", 4, heading=heading)), heading)
    assert np.allclose(b[:, 1], 0.0, atol=1e-3)
    assert np.allclose(np.diff(b[:, 0]), -10.0, atol=1e-3)
    assert b[0, 0] > 0


@pytest.mark.parametrize("heading", [0.0, 90.0, 315.0])
def test_wedge_points_along_heading(heading: float) -> None:
    b = body(slots_ne(plan_for("wedge", 5, heading=heading)), heading)
    apex = b[0]
    assert apex[1] == pytest.approx(0.0, abs=1e-3)
    assert all(apex[0] > other[0] for other in b[1:]), "apex leads"
    # Two arms, symmetric, neighbours on an arm spacing apart.
    left = [b[0], b[1], b[3]]
    right = [b[0], b[2], b[4]]
    for arm in (left, right):
        assert [float(np.linalg.norm(arm[k + 1] - arm[k])) for k in range(2)] == pytest.approx([10.0, 10.0])
    assert b[1][1] == pytest.approx(-b[2][1], abs=1e-3) and b[1][0] == pytest.approx(b[2][0], abs=1e-3)


def test_grid_is_near_square() -> None:
    b = body(slots_ne(plan_for("grid", 7, heading=0.0)), 0.0)
    rows = sorted({round(x, 3) for x in b[:, 0]}, reverse=True)
    cols = sorted({round(x, 3) for x in b[:, 1]})
    assert len(rows) == 3 and len(cols) == 3
    assert np.allclose(np.diff(rows), -10.0) and np.allclose(np.diff(cols), 10.0)


@pytest.mark.parametrize("n", [2, 3, 6, 10])
def test_circle_neighbours_are_spacing_apart_and_slot0_ahead(n: int) -> None:
    heading = 60.0
    ne = slots_ne(plan_for("circle", n, heading=heading))
    radii = np.linalg.norm(ne, axis=1)
    assert np.allclose(radii, radii[0], atol=1e-3)
    neighbours = [float(np.linalg.norm(ne[k] - ne[(k + 1) % n])) for k in range(n)]
    assert neighbours == pytest.approx([10.0] * n, abs=1e-3)
    bearing = math.degrees(math.atan2(ne[0][1], ne[0][0])) % 360
    assert bearing == pytest.approx(heading, abs=1e-3)


# --- assignment -------------------------------------------------------------------------------------------


def assignment_cost(plan: FormationPlan, starts: list[DroneStart]) -> float:
    by_id = {d.id: d for d in starts}
    total = 0.0
    for s in plan.slots:
        d = by_id[s.drone_id]
        a = np.array([*local(d.lat, d.lon), d.alt_rel_m])
        b = np.array([*local(s.lat, s.lon), s.alt_rel_m])
        total += float(np.linalg.norm(a - b))
    return total


coords = st.tuples(
    st.floats(min_value=-80, max_value=80), st.floats(min_value=-80, max_value=80), st.floats(10, 40)
)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    positions=st.lists(coords, min_size=2, max_size=5),
    formation=st.sampled_from(FORMATIONS),
    heading=st.floats(min_value=0, max_value=359),
)
def test_assignment_is_optimal_against_brute_force(positions, formation: str, heading: float) -> None:
    starts = [start_at(f"d{i}", n, e, a) for i, (n, e, a) in enumerate(positions)]
    try:
        plan = plan_formation(starts, formation, *CENTER, 30.0, 8.0, heading, 5.0, max_altitude_m=400.0)
    except SafetyRefusal as exc:
        assert exc.rule == "min_separation"
        return
    slot_pts = [
        np.array([*local(s.lat, s.lon), s.alt_rel_m]) for s in sorted(plan.slots, key=lambda s: s.slot_index)
    ]
    start_pts = [np.array([*local(d.lat, d.lon), d.alt_rel_m]) for d in starts]
    best = min(
        sum(float(np.linalg.norm(start_pts[i] - slot_pts[p[i]])) for i in range(len(starts)))
        for p in itertools.permutations(range(len(starts)))
    )
    assert assignment_cost(plan, starts) == pytest.approx(best, abs=1e-3)


# --- separation and layering ------------------------------------------------------------------------------


def numerical_segment_distance(p1, q1, p2, q2) -> float:
    """Minimum of |P(s) - Q(t)| over the unit square by numerical optimisation (convex problem)."""

    def f(x):
        d = (p1 + (q1 - p1) * x[0]) - (p2 + (q2 - p2) * x[1])
        return float(d @ d)

    best = math.inf
    for x0 in ([0.5, 0.5], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]):
        res = minimize(
            f, x0, bounds=[(0, 1), (0, 1)], method="L-BFGS-B", options={"ftol": 1e-14, "gtol": 1e-10}
        )
        best = min(best, res.fun)
    return math.sqrt(max(best, 0.0))


def independent_segment_distance(p1, q1, p2, q2) -> float:
    """Exact minimum by enumerating the candidates of a convex quadratic on the unit square: the
    interior stationary point (when inside) and the minimum along each of the four edges."""
    d1, d2 = q1 - p1, q2 - p2

    def dist(s: float, t: float) -> float:
        return float(np.linalg.norm((p1 + d1 * s) - (p2 + d2 * t)))

    def closest_param(origin, direction, point) -> float:
        length2 = float(direction @ direction)
        return 0.0 if length2 == 0 else min(1.0, max(0.0, float((point - origin) @ direction) / length2))

    candidates = []
    for s in (0.0, 1.0):  # edges s fixed: best t for the point P(s)
        candidates.append(dist(s, closest_param(p2, d2, p1 + d1 * s)))
    for t in (0.0, 1.0):
        candidates.append(dist(closest_param(p1, d1, p2 + d2 * t), t))
    matrix = np.array([[d1 @ d1, -(d1 @ d2)], [-(d1 @ d2), d2 @ d2]])
    rhs = np.array([-(d1 @ (p1 - p2)), d2 @ (p1 - p2)])
    if abs(np.linalg.det(matrix)) > 1e-9:
        s, t = np.linalg.solve(matrix, rhs)
        if 0 <= s <= 1 and 0 <= t <= 1:
            candidates.append(dist(float(s), float(t)))
    return min(candidates)


def flown_segments(
    plan: FormationPlan, starts: list[DroneStart]
) -> list[dict[str, tuple[np.ndarray, np.ndarray]]]:
    """Each drone's segment per phase, rebuilt from the plan's phases only (stays put when absent)."""
    pos = {d.id: np.array([*local(d.lat, d.lon), d.alt_rel_m]) for d in starts}
    phases = []
    for phase in plan.phases:
        segs = {}
        for d in starts:
            wp = phase.get(d.id)
            end = pos[d.id] if wp is None else np.array([*local(wp.lat, wp.lon), wp.alt_rel_m])
            segs[d.id] = (pos[d.id], end)
            pos[d.id] = end
        phases.append(segs)
    return phases


def assert_separated(plan: FormationPlan, starts: list[DroneStart], sep: float) -> float:
    """Check every phase pairwise, independently of the planner; returns the closest approach."""
    segments = flown_segments(plan, starts)
    start_pts = {d.id: np.array([*local(d.lat, d.lon), d.alt_rel_m]) for d in starts}
    closest = math.inf
    for a, b in itertools.combinations([d.id for d in starts], 2):
        required = min(sep, float(np.linalg.norm(start_pts[a] - start_pts[b])))
        for k, segs in enumerate(segments):
            d = independent_segment_distance(*segs[a], *segs[b])
            assert d >= required - 1e-3, f"phase {k + 1}: {a} and {b} come {d:.3f} m close (need {required})"
            closest = min(closest, d)
    # Everyone ends in its slot.
    for s in plan.slots:
        end = segments[-1][s.drone_id][1]
        assert np.allclose(end, [*local(s.lat, s.lon), s.alt_rel_m], atol=1e-3)
    return closest


def test_in_trail_drones_are_layered_apart() -> None:
    # a and b sit 15 m apart on the north axis; the column's two slots are on the same axis ahead, so
    # whichever way they are assigned, their direct paths overlap: one of them must take another layer.
    starts = [start_at("a", -30, 0, 30.0), start_at("b", -15, 0, 30.0)]
    plan = plan_formation(starts, "column", *CENTER, 30.0, 10.0, 0.0, 5.0)
    assert len(plan.conflicts) == 1
    conflict = plan.conflicts[0]
    assert {conflict.a, conflict.b} == {"a", "b"} and conflict.closest_m == 0.0
    transits = sorted((s.transit_alt_m is None, s.transit_alt_m) for s in plan.slots)
    assert transits == [(False, 35.0), (True, None)]
    layered = next(s for s in plan.slots if s.transit_alt_m is not None)
    assert [wp.alt_rel_m for wp in layered.legs] == [35.0, 35.0, 30.0]
    assert layered.conflicts_resolved and "transits at 35 m" in layered.conflicts_resolved[0]
    assert set(plan.phases[0]) == {layered.drone_id} and set(plan.phases[2]) == {layered.drone_id}
    assert len(plan.phases[1]) == 2
    assert assert_separated(plan, starts, 5.0) == pytest.approx(5.0, abs=1e-3)
    assert plan.min_clearance_m == pytest.approx(5.0, abs=1e-3)
    body_json = json.loads(json.dumps(plan.to_dict(), allow_nan=False))
    assert body_json["conflicts"][0]["resolution"] and len(body_json["phases"]) == 3


def test_stacked_and_scattered_fleets_are_separated() -> None:
    # Three drones stacked 6 m apart vertically over one point (a staggered takeoff) spreading to a line.
    stacked = [start_at("a", 0, 0, 10.0), start_at("b", 0, 0, 16.0), start_at("c", 0, 0, 22.0)]
    assert_separated(plan_formation(stacked, "line", *CENTER, 30.0, 10.0, 0.0, 5.0), stacked, 5.0)
    scattered = [start_at("a", 0, -50, 30.0), start_at("b", 0, 50, 30.0), start_at("c", 0, -60, 30.0)]
    assert_separated(plan_formation(scattered, "circle", *CENTER, 30.0, 10.0, 0.0, 5.0), scattered, 5.0)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    positions=st.lists(coords, min_size=2, max_size=7),
    formation=st.sampled_from(FORMATIONS),
    heading=st.floats(min_value=0, max_value=359),
    spacing=st.floats(min_value=5.0, max_value=15.0),
)
def test_random_starts_never_bring_two_paths_within_min_separation(
    positions, formation, heading, spacing
) -> None:
    starts = [start_at(f"d{i}", n, e, a) for i, (n, e, a) in enumerate(positions)]
    try:
        plan = plan_formation(starts, formation, *CENTER, 30.0, spacing, heading, 5.0)
    except SafetyRefusal as exc:
        assert exc.rule == "min_separation" and "transit altitude" in exc.message
        return
    assert_separated(plan, starts, 5.0)
    for s in plan.slots:
        if s.transit_alt_m is not None:
            assert 5.0 <= s.transit_alt_m <= 120.0


def test_layering_succeeds_on_typical_fleets() -> None:
    """Seeded fleets of up to 8 drones scattered in 100 m, at 10-40 m: every one gets a separated plan."""
    rng = random.Random(7)
    layered_plans = 0
    for trial in range(40):
        n = rng.randint(2, 8)
        starts = []
        while len(starts) < n:  # starts at least the minimum separation apart, as a flying fleet would be
            cand = start_at(
                f"d{len(starts)}", rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(10, 40)
            )
            pts = [np.array([*local(d.lat, d.lon), d.alt_rel_m]) for d in starts]
            here = np.array([*local(cand.lat, cand.lon), cand.alt_rel_m])
            if all(np.linalg.norm(here - p) >= 5.0 for p in pts):
                starts.append(cand)
        formation = FORMATIONS[trial % len(FORMATIONS)]
        plan = plan_formation(starts, formation, *CENTER, 30.0, 8.0, rng.uniform(0, 360), 5.0)
        assert_separated(plan, starts, 5.0)
        layered_plans += bool(plan.conflicts)
    assert layered_plans > 0, "the sample should include conflicts that needed layering"


def test_drones_starting_too_close_never_get_closer() -> None:
    starts = [start_at("a", 0, 0, 20.0), start_at("b", 0, 3, 20.0), start_at("c", 40, 0, 20.0)]
    plan = plan_formation(starts, "line", *CENTER, 30.0, 10.0, 0.0, 5.0)
    assert_separated(plan, starts, 5.0)
    assert any("start 3 m apart" in note for note in plan.notes)


@settings(max_examples=100, deadline=None)
@given(st.lists(st.floats(min_value=-50, max_value=50), min_size=12, max_size=12))
def test_segment_distance_matches_numerical_minimum(values) -> None:
    p1, q1, p2, q2 = (np.array(values[i : i + 3]) for i in range(0, 12, 3))
    assert segment_distance(p1, q1, p2, q2) == pytest.approx(
        independent_segment_distance(p1, q1, p2, q2), abs=1e-3
    )
    # Degenerate segments (points).
    assert segment_distance(p1, p1, p2, p2) == pytest.approx(float(np.linalg.norm(p1 - p2)))


# --- refusals and bad input -------------------------------------------------------------------------------


def test_spacing_below_minimum_separation_is_refused_with_numbers() -> None:
    starts = [start_at("a", 0, 0), start_at("b", 20, 0)]
    with pytest.raises(SafetyRefusal) as info:
        plan_formation(starts, "line", *CENTER, 30.0, 3.0, 0.0, 5.0)
    err = info.value
    assert err.rule == "min_separation"
    assert err.message == "min_separation: formation spacing 3 m is below the minimum separation of 5 m"
    assert err.details["spacing_m"] == 3.0 and err.details["limit_m"] == 5.0
    assert plan_formation(starts, "line", *CENTER, 30.0, 5.0, 0.0, 5.0).spacing_m == 5.0


def test_no_room_for_layers_is_refused() -> None:
    # In-trail drones need a second layer; a ceiling at the formation altitude and a floor just below
    # leave none.
    starts = [start_at("a", -30, 0, 30.0), start_at("b", -15, 0, 30.0)]
    with pytest.raises(SafetyRefusal) as info:
        plan_formation(
            starts, "column", *CENTER, 30.0, 10.0, 0.0, 5.0, max_altitude_m=30.0, min_transit_alt_m=29.0
        )
    assert info.value.rule == "min_separation" and "no transit altitude" in info.value.message


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"formation": "diamond"}, "unknown formation"),
        ({"alt_m": 0.0}, "must be above 0"),
        ({"alt_m": 150.0}, "at most 120 m"),
        ({"alt_m": math.nan}, "alt_m must be a finite number"),
        ({"spacing_m": -1.0}, "above 0 m"),
        ({"heading_deg": math.inf}, "heading_deg"),
        ({"center_lat": 95.0}, "latitude"),
    ],
)
def test_bad_plan_arguments(kwargs, fragment) -> None:
    args = {
        "formation": "line", "center_lat": CENTER[0], "center_lon": CENTER[1], "alt_m": 30.0,
        "spacing_m": 10.0, "heading_deg": 0.0, "min_separation_m": 5.0,
    }  # fmt: skip
    args.update(kwargs)
    with pytest.raises(InvalidArgument) as info:
        plan_formation([start_at("a", 0, 0)], **args)
    assert fragment in info.value.message


@pytest.mark.parametrize(
    ("drones", "fragment"),
    [
        ([], "at least one drone"),
        ([("a", 47.39, 8.54, 10.0), ("a", 47.391, 8.54, 10.0)], "more than once"),
        ([("a", 47.39, 8.54)], "(id, lat, lon, alt_rel_m)"),
        ([("a", math.nan, 8.54, 10.0)], "latitude"),
        ([("a", 47.39, 8.54, math.inf)], "altitude of drone a"),
    ],
)
def test_bad_drone_lists(drones, fragment) -> None:
    with pytest.raises(InvalidArgument) as info:
        plan_formation(drones, "line", *CENTER, 30.0, 10.0, 0.0, 5.0)
    assert fragment in info.value.message


def test_plan_accepts_tuples_and_reports_per_drone_details() -> None:
    lat, lon = geo.offset_position(CENTER[0], CENTER[1], -30, 0)
    plan = plan_formation([("a", lat, lon, 20.0)], "circle", *CENTER, 30.0, 10.0, 0.0, 5.0)
    slot = plan.slot_for("a")
    assert slot.distance_m == pytest.approx(math.hypot(30.0, 10.0), abs=0.05)
    assert slot.transit_alt_m is None and len(slot.legs) == 1
    assert plan.to_dict()["slots"][0]["drone_id"] == "a"
    assert plan.min_clearance_m is None  # one drone: nothing to keep apart
    json.dumps(plan.to_dict(), allow_nan=False)
    with pytest.raises(KeyError):
        plan.slot_for("zz")


# --- the policy over a plan -------------------------------------------------------------------------------


def contexts_for(starts: list[DroneStart]) -> dict[str, VehicleContext]:
    return {
        d.id: VehicleContext(
            d.id, True, True, True, 80.0, (HOME[0], HOME[1], HOME[2]), (d.lat, d.lon, d.alt_rel_m)
        )
        for d in starts
    }


def test_policy_checks_every_leg_of_a_plan() -> None:
    starts = [start_at("a", 0, -30, 30.0), start_at("b", 0, 30, 30.0), start_at("c", 10, 0, 30.0)]
    plan = plan_formation(starts, "line", *CENTER, 30.0, 10.0, 180.0, 5.0)
    policy = SafetyPolicy(make_settings())
    policy.check_formation(contexts_for(starts), plan)
    tight = SafetyPolicy(make_settings(vehicle_limits={"b": {"max_altitude_m": 25.0}}))
    with pytest.raises(SafetyRefusal) as info:
        tight.check_formation(contexts_for(starts), plan)
    assert info.value.rule == "max_altitude" and "formation, drone b, leg 1" in info.value.message
    stricter = SafetyPolicy(make_settings(min_separation_m=8.0))
    with pytest.raises(SafetyRefusal) as info:
        stricter.check_formation(contexts_for(starts), plan)
    assert info.value.rule == "min_separation" and "below the minimum separation of 8 m" in info.value.message
    with pytest.raises(SafetyRefusal) as info:
        policy.check_formation(contexts_for(starts[:2]), plan)
    assert info.value.rule == "invalid_input" and "drone c" in info.value.message


# --- staggering -------------------------------------------------------------------------------------------


def test_takeoff_and_rtl_staggering() -> None:
    assert takeoff_altitudes(["a", "b", "c"], 10.0, 5.0) == {"a": 10.0, "b": 15.0, "c": 20.0}
    assert rtl_altitudes(["a", "b"], 30.0, 6.0) == {"a": 30.0, "b": 36.0}
    assert takeoff_altitudes(["a"], 10.0, 0.0) == {"a": 10.0}
    with pytest.raises(SafetyRefusal) as info:
        rtl_altitudes([f"d{i}" for i in range(10)], 80.0, 5.0)
    assert (
        info.value.rule == "max_altitude" and "reaches 125 m, above the limit of 120 m" in info.value.message
    )
    with pytest.raises(InvalidArgument):
        takeoff_altitudes(["a", "a"], 10.0, 5.0)
    with pytest.raises(InvalidArgument):
        takeoff_altitudes(["a"], 10.0, -1.0)
