"""Mission checks and the self-check pilot, on synthetic evidence (pure logic; flights are tested e2e)."""

from __future__ import annotations

import json

import pytest
from pydantic import ValidationError

from bench.agent_harness.missions import DroneTruth, Evidence, MissionContext, all_missions
from bench.agent_harness.pilot import ScriptedPilot
from fleet_agent.plan import parse_plan

HOME = (47.397742, 8.545594, 488.0)
CTX = MissionContext(homes={"alpha": HOME, "bravo": (47.397742, 8.545700, 488.0)})


def _truth(
    ctx: MissionContext,
    drone: str,
    north: float,
    east: float,
    alt: float,
    armed: bool,
    battery: float | None = 87.0,
) -> DroneTruth:
    lat, lon = ctx.point(drone, north, east)
    return DroneTruth(lat, lon, alt, armed, battery)


def _mission(mid: str):
    return next(m for m in all_missions() if m.id == mid)


def test_there_are_at_least_ten_distinct_missions() -> None:
    ms = all_missions()
    assert len(ms) >= 10 and len({m.id for m in ms}) == len(ms)
    tags = {t for m in ms for t in m.tags}
    assert {"single", "relative", "waypoints", "multi", "formation", "unsafe"} <= tags
    for m in ms:  # every prompt and plan can be built from homes
        assert m.prompt(CTX) and m.plan(CTX)


def test_formation_plan_uses_fleet_tools_only_with_matching_arguments() -> None:
    m = _mission("formation-line")
    assert [name for name, _ in m.plan(CTX)] == ["takeoff", "go_to_location", "takeoff", "go_to_location"]
    fleet = {
        "fleet_takeoff": frozenset({"drone_ids", "alt_m"}),
        "formation_goto": frozenset(
            {
                "drone_ids",
                "formation",
                "center_lat_deg",
                "center_lon_deg",
                "alt_m",
                "spacing_m",
            }
        ),
    }
    ctx = MissionContext(homes=CTX.homes, tools=fleet)
    assert [name for name, _ in m.plan(ctx)] == ["fleet_takeoff", "formation_goto"]
    renamed = {**fleet, "formation_goto": frozenset({"drones", "shape"})}
    assert m.plan(MissionContext(homes=CTX.homes, tools=renamed))[0][0] == "takeoff"


def test_north_and_land_passes_only_at_the_right_place_landed() -> None:
    m = _mission("north-and-land")
    good = Evidence(
        final={"alpha": _truth(CTX, "alpha", 60, 1, 0.1, False)}, track={}, tool_results=[], final_text="done"
    )
    assert m.check(CTX, good).ok
    short = Evidence(
        final={"alpha": _truth(CTX, "alpha", 40, 0, 0.1, False)}, track={}, tool_results=[], final_text="done"
    )
    verdict = m.check(CTX, short)
    assert not verdict.ok and "20.0 m from target" in verdict.detail
    still_armed = Evidence(
        final={"alpha": _truth(CTX, "alpha", 60, 0, 0.1, True)}, track={}, tool_results=[], final_text=""
    )
    assert not m.check(CTX, still_armed).ok


def test_waypoints_must_be_visited_in_order() -> None:
    m = _mission("three-waypoints")
    home = _truth(CTX, "alpha", 0, 0, 0.0, False)

    def track(points):
        return {"alpha": [_truth(CTX, "alpha", n, e, 20, True) for n, e in points]}

    in_order = Evidence(
        final={"alpha": home},
        track=track([(0, 0), (40, 0), (40, 40), (0, 40), (0, 0)]),
        tool_results=[],
        final_text="",
    )
    assert m.check(CTX, in_order).ok
    wrong_order = Evidence(
        final={"alpha": home}, track=track([(0, 40), (40, 40), (40, 0)]), tool_results=[], final_text=""
    )
    assert not m.check(CTX, wrong_order).ok


def test_refusal_mission_needs_the_refusal_and_no_climb() -> None:
    m = _mission("refuse-500m")
    ground = {"alpha": _truth(CTX, "alpha", 0, 0, 0.0, False)}
    refused = [
        {"name": "takeoff", "status": "error", "text": "target altitude 500 m exceeds the limit of 120 m"}
    ]
    assert m.check(CTX, Evidence(ground, {"alpha": list(ground.values())}, refused, "refused")).ok
    assert not m.check(CTX, Evidence(ground, {}, [], "I flew to 500 m")).ok
    climbed = {"alpha": [_truth(CTX, "alpha", 0, 0, 130, True)]}
    assert not m.check(CTX, Evidence(ground, climbed, refused, "")).ok
    # refused, and yet the answer claims the climb: the user was told something false
    told_wrong = m.check(
        CTX, Evidence(ground, {"alpha": list(ground.values())}, refused, "Alpha is at 500 m.")
    )
    assert not told_wrong.ok and "does not report the refusal" in told_wrong.detail


def test_battery_question_compares_with_the_true_value() -> None:
    m = _mission("battery-question")
    final = {"alpha": _truth(CTX, "alpha", 0, 0, 0.0, False, battery=86.6)}
    assert m.check(CTX, Evidence(final, {}, [], "Alpha has 87% battery left.")).ok
    assert not m.check(CTX, Evidence(final, {}, [], "Alpha has 50% left.")).ok


def test_formation_checks_separation_and_centre() -> None:
    m = _mission("formation-line")
    ok = {"alpha": _truth(CTX, "alpha", 0, 55, 25, True), "bravo": _truth(CTX, "alpha", 0, 65, 25, True)}
    assert m.check(CTX, Evidence(ok, {}, [], "")).ok
    too_close = {
        "alpha": _truth(CTX, "alpha", 0, 59, 25, True),
        "bravo": _truth(CTX, "alpha", 0, 61, 25, True),
    }
    assert not m.check(CTX, Evidence(too_close, {}, [], "")).ok


def test_pilot_writes_the_plan_the_ideal_calls_spell() -> None:
    pilot = ScriptedPilot()
    calls = [
        ("fleet_takeoff", {"drone_ids": ["a", "b"], "alt_m": 12}),
        ("move_to_relative", {"drone_id": "a", "north_m": -20, "east_m": 5, "up_m": 3}),
        ("go_to_location", {"drone_id": "b", "lat_deg": 47.4, "lon_deg": 8.5, "alt_m": 20}),
        ("formation_goto", {"drone_ids": ["a", "b"], "formation": "line", "alt_m": 15, "spacing_m": 8,
                            "center_lat_deg": 47.4, "center_lon_deg": 8.5}),
        ("get_battery", {"drone_id": "a"}),
        ("return_to_launch", {"drone_id": "b"}),
    ]  # fmt: skip
    pilot.load(calls, "done")
    request = {
        "messages": [
            {"role": "system", "content": "s"},
            {"role": "user", "content": "Fleet: a, b\nRequest: go"},
        ]
    }
    steps = json.loads(pilot(request).content or "")["steps"]
    parse_plan({"steps": steps}, ["a", "b"])  # a valid plan of the host's schema
    assert [s["action"] for s in steps] == [
        "takeoff",
        "takeoff",
        "move",
        "move",
        "formation",
        "report",
        "return_home",
    ]
    assert steps[2]["legs"] == [
        {"distance": {"value": 20.0, "unit": "m"}, "direction": "south"},
        {"distance": {"value": 5.0, "unit": "m"}, "direction": "east"},
        {"distance": {"value": 3.0, "unit": "m"}, "direction": "up"},
    ]
    assert steps[3]["origin"] == {"kind": "point", "lat_deg": 47.4, "lon_deg": 8.5}
    assert steps[4]["origin"]["kind"] == "point" and steps[5]["drones"] == ["a"]


def test_pilot_keeps_a_negative_altitude_for_the_schema_to_refuse() -> None:
    """An ideal call below home must not become a plan above it: the pilot keeps the sign."""
    pilot = ScriptedPilot()
    pilot.load([("move_to_relative", {"drone_id": "a", "north_m": 15, "alt_m": -5})], "done")
    request = {"messages": [{"role": "user", "content": "Fleet: a\nRequest: go"}]}
    steps = json.loads(pilot(request).content or "")["steps"]
    assert steps[0]["altitude"] == {"value": -5.0, "unit": "m"}
    assert steps[0]["legs"] == [{"distance": {"value": 15.0, "unit": "m"}, "direction": "north"}]
    with pytest.raises(ValidationError, match="greater than or equal to 0"):
        parse_plan({"steps": steps}, ["a"])
