"""Numeric limits: each rule refuses with its name and numbers, and allows just inside its limit."""

from __future__ import annotations

import math
from dataclasses import dataclass

import pytest
from hypothesis import given
from hypothesis import strategies as st

from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import RunningOperation, Target
from tests.fleet._util import at, ctx, ground, policy, settings


def target(north_m: float = 0.0, east_m: float = 0.0, alt: float = 20.0) -> Target:
    return Target(*at(north_m, east_m), alt)


def refusal(fn, *args, **kwargs) -> SafetyRefusal:
    with pytest.raises(SafetyRefusal) as info:
        fn(*args, **kwargs)
    return info.value


# --- altitude ---------------------------------------------------------------------------------------


def test_max_altitude_refuses_with_rule_and_numbers_and_allows_the_limit() -> None:
    p = policy()
    p.check_motion(ctx(), target(alt=120.0))
    err = refusal(p.check_motion, ctx(), target(alt=150.0))
    assert err.rule == "max_altitude"
    assert err.message == (
        "max_altitude: target altitude 150 m exceeds the limit of 120 m above home; "
        "nothing was sent: fly at most 120 m, or tell the user the limit"
    )
    assert err.details["alt_rel_m"] == 150.0 and err.details["limit_m"] == 120.0
    assert refusal(p.check_motion, ctx(), target(alt=120.01)).rule == "max_altitude"


def test_takeoff_altitude_band() -> None:
    p = policy()
    on_pad = ground()
    p.check_takeoff(on_pad, 120.0)
    p.check_takeoff(on_pad, 2.0)
    err = refusal(p.check_takeoff, on_pad, 121.0)
    assert err.rule == "max_altitude" and "takeoff altitude 121 m exceeds the limit of 120 m" in err.message
    err = refusal(p.check_takeoff, on_pad, 1.5)
    assert err.rule == "min_altitude" and "1.5 m is below the minimum of 2 m" in err.message


def test_negative_altitude_is_refused_as_below_home() -> None:
    err = refusal(policy().check_motion, ctx(), target(alt=-5.0))
    assert err.rule == "min_altitude"
    assert "target altitude -5 m is below home" in err.message
    assert err.details["alt_rel_m"] == -5.0


@given(alt=st.floats(min_value=2.0, max_value=120.0))
def test_any_altitude_inside_the_band_is_allowed(alt: float) -> None:
    policy().check_motion(ctx(), target(alt=alt))


@given(alt=st.floats(min_value=120.0, max_value=1e6, exclude_min=True))
def test_any_altitude_above_the_limit_is_refused(alt: float) -> None:
    assert refusal(policy().check_motion, ctx(), target(alt=alt)).rule == "max_altitude"


# --- distance and home --------------------------------------------------------------------------------


def test_max_distance_from_home() -> None:
    p = policy()
    p.check_motion(ctx(), target(north_m=999.0))
    err = refusal(p.check_motion, ctx(), target(north_m=1001.0))
    assert err.rule == "max_distance"
    assert "target is 1001 m from home, beyond the limit of 1000 m" in err.message
    assert err.details["distance_m"] == pytest.approx(1001.0, abs=0.01)
    assert err.details["limit_m"] == 1000.0


def test_missing_home_refuses_because_distance_cannot_be_checked() -> None:
    err = refusal(policy().check_motion, ctx(home=None), target(north_m=10.0))
    assert err.rule == "home_unknown"
    assert "no home position" in err.message and "1000 m" in err.message


# --- non-numbers ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "tgt",
    [
        Target(math.nan, 8.5, 20.0),
        Target(47.3, math.inf, 20.0),
        Target(47.3, 8.5, math.nan),
        Target(47.3, 8.5, -math.inf),
        Target(91.0, 8.5, 20.0),
        Target(47.3, 181.0, 20.0),
    ],
)
def test_non_finite_or_out_of_range_targets_are_refused(tgt: Target) -> None:
    err = refusal(policy().check_motion, ctx(), tgt)
    assert err.rule == "invalid_input"
    assert err.message.startswith("invalid_input: ")


def test_nan_takeoff_and_speed_are_refused() -> None:
    p = policy()
    assert refusal(p.check_takeoff, ground(), math.nan).rule == "invalid_input"
    assert refusal(p.check_speed, ctx(), math.inf).rule == "invalid_input"
    assert refusal(p.check_speed, ctx(), 0.0).rule == "invalid_input"
    assert refusal(p.check_speed, ctx(), -3.0).rule == "invalid_input"


# --- battery -----------------------------------------------------------------------------------------


def test_battery_minimum_for_takeoff() -> None:
    p = policy()
    p.check_takeoff(ground(battery_pct=30.0), 10.0)
    err = refusal(p.check_takeoff, ground(battery_pct=29.5), 10.0)
    assert err.rule == "min_battery_takeoff"
    assert "battery 29.5 % is below the 30 % needed to take off" in err.message
    assert err.details == {
        "rule": "min_battery_takeoff",
        "vehicle_id": "alpha",
        "battery_pct": 29.5,
        "minimum_pct": 30.0,
    }
    p.check_arm(ground(battery_pct=30.0))
    assert refusal(p.check_arm, ground(battery_pct=10.0)).rule == "min_battery_takeoff"


def test_battery_minimum_for_a_new_leg() -> None:
    p = policy()
    p.check_motion(ctx(battery_pct=25.0), target(north_m=50.0))
    err = refusal(p.check_motion, ctx(battery_pct=24.9), target(north_m=50.0))
    assert err.rule == "min_battery_leg"
    assert "battery 24.9 % is below the 25 % needed to start a new leg" in err.message


def test_unknown_battery_is_refused() -> None:
    err = refusal(policy().check_motion, ctx(battery_pct=None), target(north_m=5.0))
    assert err.rule == "battery_unknown" and "25 %" in err.message
    err = refusal(policy().check_takeoff, ground(battery_pct=None), 10.0)
    assert err.rule == "battery_unknown" and "30 %" in err.message


# --- speed ---------------------------------------------------------------------------------------------


def test_max_speed() -> None:
    p = policy()
    p.check_speed(ctx(), 15.0)
    err = refusal(p.check_speed, ctx(), 15.5)
    assert err.rule == "max_speed"
    assert err.message == "max_speed: speed 15.5 m/s exceeds the limit of 15 m/s"


# --- per-vehicle overrides -------------------------------------------------------------------------------


def test_vehicle_overrides_apply_to_that_vehicle_only() -> None:
    p = SafetyPolicy(settings(), vehicle_limits={"alpha": {"max_altitude_m": 50.0, "max_speed_mps": 5.0}})
    err = refusal(p.check_motion, ctx("alpha"), target(alt=60.0))
    assert err.rule == "max_altitude" and "limit of 50 m" in err.message
    p.check_motion(ctx("bravo"), target(alt=60.0))
    assert refusal(p.check_speed, ctx("alpha"), 6.0).rule == "max_speed"
    assert p.limits_for("bravo").max_altitude_m == 120.0


def test_vehicle_overrides_from_settings_and_runtime() -> None:
    p = SafetyPolicy(settings(vehicle_limits={"alpha": {"max_distance_m": 100.0}}))
    assert refusal(p.check_motion, ctx("alpha"), target(north_m=150.0)).rule == "max_distance"
    p.set_vehicle_limits("alpha", {})
    p.check_motion(ctx("alpha"), target(north_m=150.0))
    p.set_vehicle_limits("bravo", {"min_battery_leg_pct": 60})
    assert refusal(p.check_motion, ctx("bravo", battery_pct=59.0), target()).rule == "min_battery_leg"


@pytest.mark.parametrize(
    "bad",
    [
        {"max_altitude": 50.0},
        {"max_altitude_m": math.nan},
        {"max_altitude_m": -1.0},
        {"max_speed_mps": 0},
        {"min_battery_leg_pct": 150},
        {"min_altitude_m": 200.0},
        {"max_altitude_m": "high"},
    ],
)
def test_bad_vehicle_overrides_are_rejected_and_change_nothing(bad: dict) -> None:
    p = policy()
    with pytest.raises(InvalidArgument):
        p.set_vehicle_limits("alpha", bad)
    assert p.limits_for("alpha") == p.fleet_limits


# --- simulators only, modes -------------------------------------------------------------------------------


def test_simulators_only_refuses_real_vehicles_for_agents() -> None:
    p = policy(simulators_only=True)
    real = ctx(is_simulator=False)
    for check, args in [
        (p.check_motion, (target(),)),
        (p.check_takeoff, (10.0,)),
        (p.check_speed, (5.0,)),
        (p.check_mode, ("RTL",)),
        (p.check_actuation, ()),
        (p.check_kill, ()),
        (p.check_arm, ()),
    ]:
        err = refusal(check, real, *args)
        assert err.rule == "simulators_only" and "real vehicle" in err.message
    p.check_motion(ctx(is_simulator=True), target())
    p.check_motion(real, target(), via="rest")


def test_pilot_modes_are_refused_in_the_air_only() -> None:
    p = policy()
    err = refusal(p.check_mode, ctx(), "alt_hold")
    assert err.rule == "mode_deny_in_air" and "ALT_HOLD" in err.message
    p.check_mode(ctx(), "GUIDED")
    p.check_mode(ctx(), "RTL")
    p.check_mode(ground(), "STABILIZE")
    p.check_mode(ctx(), "STABILIZE", via="rest")
    assert refusal(p.check_mode, ctx(), "").rule == "invalid_input"


def test_armed_drone_above_one_metre_counts_as_airborne_even_if_landed_state_lags() -> None:
    p = policy()
    lagging = ctx(in_air=False, armed=True, alt_rel_m=8.0)
    assert refusal(p.check_mode, lagging, "LOITER").rule == "mode_deny_in_air"


# --- missions ----------------------------------------------------------------------------------------------


@dataclass
class Item:
    lat: float
    lon: float
    alt_rel_m: float
    kind: str = "waypoint"
    speed_mps: float | None = None


def item(north_m: float, east_m: float, alt: float = 20.0, **kw) -> Item:
    return Item(*at(north_m, east_m), alt, **kw)


def test_mission_items_are_checked_one_by_one_naming_the_item() -> None:
    p = policy()
    items = [Item(0.0, 0.0, 15.0, "takeoff"), item(100, 0), item(100, 100, alt=150.0), Item(0, 0, 0, "rtl")]
    err = refusal(p.check_mission, ground(), items)
    assert err.rule == "max_altitude"
    assert err.message == (
        "max_altitude: mission item 3: waypoint altitude 150 m exceeds the limit of 120 m above home; "
        "nothing was sent: fly at most 120 m, or tell the user the limit"
    )
    assert err.details["item"] == 3
    items[2] = item(100, 100, alt=120.0)
    p.check_mission(ground(), items)  # no refusal


def test_mission_item_speed_distance_and_empty() -> None:
    p = policy()
    err = refusal(p.check_mission, ctx(), [item(10, 0), item(20, 0, speed_mps=20.0)])
    assert err.rule == "max_speed" and "mission item 2: speed 20 m/s" in err.message
    err = refusal(p.check_mission, ctx(), [item(10, 0), item(2000, 0)])
    assert err.rule == "max_distance" and err.details["item"] == 2
    assert refusal(p.check_mission, ctx(), []).rule == "invalid_input"
    err = refusal(p.check_mission, ctx(), [item(10, 0), Item(math.nan, 8.5, 20.0)])
    assert err.rule == "invalid_input" and "mission item 2" in err.message


def test_mission_battery_uses_takeoff_minimum_on_the_ground() -> None:
    p = policy()
    err = refusal(p.check_mission, ground(battery_pct=28.0), [item(10, 0)])
    assert err.rule == "min_battery_takeoff"
    p.check_mission(ctx(battery_pct=28.0), [item(10, 0)])


def test_mission_land_item_checks_place_not_altitude() -> None:
    p = policy()
    p.check_mission(ctx(), [item(10, 0), item(20, 0, alt=0.0, kind="land")])
    err = refusal(p.check_mission, ctx(), [item(10, 0), item(1500, 0, alt=0.0, kind="land")])
    assert err.rule == "max_distance" and "mission item 2: landing point" in err.message


# --- refusals carry their numbers (the audit table stores them) ------------------------------------------


def test_a_refusal_names_its_rule_and_numbers() -> None:
    with pytest.raises(SafetyRefusal) as info:
        policy().check_motion(ctx("alpha"), target(alt=200.0))
    refused = info.value
    assert refused.rule == "max_altitude" and refused.message.startswith("max_altitude: ")
    assert {k: v for k, v in refused.details.items() if k != "rule"} == {
        "vehicle_id": "alpha",
        "alt_rel_m": 200.0,
        "limit_m": 120.0,
    }


# --- sequencing rules: what already runs on the drone -------------------------------------------------


def test_takeoff_in_progress_holds_agents_not_operators() -> None:
    p = policy()
    climbing = RunningOperation("op1", "takeoff", "climbing: 4.0 of 20.0 m", target_alt_m=20.0)
    err = refusal(p.check_takeoff_finished, ctx("alpha"), climbing, "go_to_location")
    assert err.rule == "takeoff_in_progress" and err.details["operation_id"] == "op1"
    assert "of 20 m above home); go_to_location was not sent" in err.message
    assert err.details["target_alt_m"] == 20.0
    p.check_takeoff_finished(ctx("alpha"), climbing, "go_to_location", via="rest")
    p.check_takeoff_finished(ctx("alpha"), None, "go_to_location")


def test_a_busy_drone_and_a_tight_stagger_are_refused_with_numbers() -> None:
    p = policy()
    busy = RunningOperation("op2", "goto", "40 m to go")
    err = refusal(p.check_not_busy, ctx("alpha"), busy, "formation_goto")
    assert err.rule == "drone_busy" and err.details["operation_id"] == "op2" and "fleet_hold" in err.message
    p.check_not_busy(ctx("alpha"), None, "formation_goto")
    err = refusal(p.check_stagger, 3.0)
    assert err.rule == "min_separation" and err.details == {"rule": "min_separation", "stagger_m": 3.0,
                                                             "limit_m": 5.0}  # fmt: skip
    p.check_stagger(5.0)


def test_altitude_band_and_summary() -> None:
    p = SafetyPolicy(settings(), vehicle_limits={"alpha": {"max_altitude_m": 60.0, "min_altitude_m": 4.0}})
    assert p.altitude_band(["alpha", "bravo"]) == (4.0, 60.0)
    assert p.altitude_band(["bravo"]) == (2.0, 120.0)
    assert p.altitude_band([]) == (2.0, 120.0)
    fleet = p.summary()
    assert fleet["limits"]["max_altitude_m"] == 120.0
    assert fleet["vehicle_overrides"]["alpha"]["max_altitude_m"] == 60.0
    assert "ARMING_*" in fleet["param_deny_patterns"] and fleet["locks"] == []
    one = p.summary("alpha")
    assert one["limits"]["max_altitude_m"] == 60.0 and one["locked"] is None
