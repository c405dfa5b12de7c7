"""Operator locks, the parameter deny list and the kill decision table."""

from __future__ import annotations

from datetime import UTC, datetime

import pytest

from gateway.config import DEFAULT_PARAM_DENY_PATTERNS
from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet.dialects import ARDUPILOT, PX4_DIALECT
from gateway.fleet.policy.operator_locks import LockBook, LockView, ReadOnlyLocks
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import Target
from tests.fleet._util import at, ctx, ground, policy, settings


def refusal(fn, *args, **kwargs) -> SafetyRefusal:
    with pytest.raises(SafetyRefusal) as info:
        fn(*args, **kwargs)
    return info.value


def locked_policy(book: LockBook, **overrides) -> SafetyPolicy:
    return SafetyPolicy(settings(**overrides), locks=book.view())


TARGET = Target(*at(50, 0), 20.0)


def actuating_checks(p: SafetyPolicy):
    return [
        ("motion", p.check_motion, (TARGET,)),
        ("takeoff", p.check_takeoff, (10.0,)),
        ("speed", p.check_speed, (5.0,)),
        ("mode", p.check_mode, ("RTL",)),
        ("actuation", p.check_actuation, ()),
        ("arm", p.check_arm, ()),
        ("kill", p.check_kill, ()),
        ("mission", p.check_mission, ([],)),
    ]


# --- locks ---------------------------------------------------------------------------------------------


def test_vehicle_lock_refuses_every_actuating_check_with_the_operators_reason() -> None:
    book = LockBook()
    book.lock("alpha", "battery swap in progress", "alice")
    p = locked_policy(book)
    for name, check, args in actuating_checks(p):
        err = refusal(check, ctx("alpha"), *args)
        assert err.rule == "operator_lock", name
        assert "drone alpha is locked by alice: battery swap in progress" in err.message
        assert "Only an operator can unlock it" in err.message
    p.check_motion(ctx("bravo"), TARGET)


def test_fleet_lock_refuses_all_vehicles_and_both_reasons_show() -> None:
    book = LockBook()
    book.lock("*", "airspace closed", "tower")
    p = locked_policy(book)
    for vid in ("alpha", "bravo"):
        err = refusal(p.check_motion, ctx(vid), TARGET)
        assert err.rule == "operator_lock" and "the fleet is locked by tower: airspace closed" in err.message
    book.lock("alpha", "maintenance", "bob")
    err = refusal(p.check_takeoff, ground("alpha"), 10.0)
    assert (
        "the fleet is locked by tower: airspace closed; drone alpha is locked by bob: maintenance"
        in err.message
    )
    assert err.details["reason"] == book.reason_for("alpha")


def test_unlock_restores_and_operators_are_not_held() -> None:
    book = LockBook()
    book.lock("alpha", "inspection", "alice")
    p = locked_policy(book)
    p.check_motion(ctx("alpha"), TARGET, via="rest")
    p.check_kill(ctx("alpha"), via="rest")
    assert book.unlock("alpha").reason == "inspection"
    assert book.unlock("alpha") is None
    assert book.reason_for("alpha") is None
    p.check_motion(ctx("alpha"), TARGET)


def test_a_fleet_lock_refusal_names_the_rule_and_the_drone() -> None:
    book = LockBook()
    book.lock("*", "stop", "ops")
    err = refusal(locked_policy(book).check_motion, ctx("alpha"), TARGET)
    assert err.rule == "operator_lock" and err.details["vehicle_id"] == "alpha" and "stop" in err.message


def test_the_mcp_view_cannot_unlock_or_lock() -> None:
    book = LockBook()
    book.lock("alpha", "hands off", "alice")
    view = book.view()
    assert isinstance(view, ReadOnlyLocks)
    assert not hasattr(view, "unlock") and not hasattr(view, "lock")
    assert not hasattr(view, "_locks") and not hasattr(view, "__dict__")
    with pytest.raises(AttributeError):
        view.extra = 1  # type: ignore[attr-defined]
    assert view.reason_for("alpha") == "drone alpha is locked by alice: hands off"
    assert [lk.scope for lk in view.all()] == ["alpha"]
    assert view.locks_for("bravo") == []
    p = locked_policy(book)
    assert not hasattr(p.locks, "unlock")
    # The view follows the book live.
    book.unlock("alpha")
    assert view.reason_for("alpha") is None


def test_lockview_protocol_is_satisfied_by_both() -> None:
    book = LockBook()
    views: list[LockView] = [book, book.view()]
    for v in views:
        assert v.reason_for("x") is None and v.all() == []


def test_lock_records_round_trip_and_relocking_replaces() -> None:
    book = LockBook()
    when = datetime(2026, 11, 21, 7, 0, tzinfo=UTC)
    book.lock("*", "storm", "ops", at=when)
    book.lock("bravo", "first", "alice")
    book.lock("bravo", "second", "bob")
    records = book.to_records()
    assert [r["scope"] for r in records] == ["*", "bravo"]
    assert records[0]["locked_at"] == "2026-11-21T07:00:00+00:00"
    again = LockBook.from_records(records)
    assert again.to_records() == records
    assert again.get("bravo").reason == "second" and again.get("bravo").by == "bob"


@pytest.mark.parametrize(
    ("scope", "reason", "by", "fragment"),
    [
        ("Alpha", "r", "op", "scope"),
        ("a" * 33, "r", "op", "scope"),
        ("", "r", "op", "scope"),
        ("alpha", "  ", "op", "reason"),
        ("alpha", "x" * 501, "op", "limit is 500"),
        ("alpha", "r", "", "who set it"),
    ],
)
def test_bad_locks_are_rejected_and_change_nothing(scope, reason, by, fragment) -> None:
    book = LockBook()
    with pytest.raises(InvalidArgument) as info:
        book.lock(scope, reason, by)
    assert fragment in info.value.message
    assert book.all() == []


def test_bad_lock_records() -> None:
    with pytest.raises(InvalidArgument, match="lacks 'by'"):
        LockBook.from_records([{"scope": "*", "reason": "r", "locked_at": "2026-11-21T07:00:00+00:00"}])
    with pytest.raises(InvalidArgument, match="locked_at"):
        LockBook.from_records([{"scope": "*", "reason": "r", "by": "x", "locked_at": "yesterday"}])


# --- parameter deny list -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "name",
    [
        "ARMING_CHECK",
        "arming_check",
        "FENCE_ENABLE",
        "FENCE_ALT_MAX",
        "FS_GCS_ENABLE",
        "FS_THR_ENABLE",
        "FS_EKF_ACTION",
        "BATT_FS_LOW_ACT",
        "BATT2_FS_CRT_ACT",
        "BATT_LOW_VOLT",
        "BATT_CRT_MAH",
        "SYSID_THISMAV",
        "SYSID_MYGCS",
        "MAV_SYSID",
        "MAV_GCS_SYSID",
        "BRD_SAFETY_DEFLT",
        "COM_ARM_WO_GPS",
        "COM_DL_LOSS_T",
        "GF_ACTION",
        "GF_MAX_HOR_DIST",
        "NAV_DLL_ACT",
        "NAV_RCL_ACT",
        "CBRK_SUPPLY_CHK",
        "CBRK_IO_SAFETY",
        "MAV_SYS_ID",
        "BAT_CRIT_THR",
        "BAT1_EMERGEN_THR",
        "FD_FAIL_P",
    ],
)
def test_protected_parameters_are_refused_for_agents(name: str) -> None:
    err = refusal(policy().check_param_write, name, vehicle_id="alpha")
    assert err.rule == "param_deny"
    assert f"parameter {name.upper()} matches the protected pattern" in err.message
    assert err.details["param"] == name.upper() and err.details["pattern"] in DEFAULT_PARAM_DENY_PATTERNS


AP = ARDUPILOT.limit_params
PX = PX4_DIALECT.limit_params


@pytest.mark.parametrize(
    ("name", "value", "governed", "words"),
    [
        (
            "WPNAV_SPEED",
            4000,
            AP,
            "WPNAV_SPEED 4000 cm/s (40 m/s) would let the autopilot exceed the max_speed_mps",
        ),
        ("RTL_ALT", 30000, AP, "RTL_ALT 30000 cm (300 m) would let the autopilot exceed the max_altitude_m"),
        (
            "RTL_ALT_M",
            300,
            AP,
            "RTL_ALT_M 300 m would let the autopilot exceed the max_altitude_m limit of 120",
        ),
        (
            "LAND_SPEED",
            500,
            AP,
            "LAND_SPEED 500 cm/s is above the autopilot's range for it; accepted: 30 to 200",
        ),
        (
            "RTL_SPEED_MS",
            16,
            AP,
            "exceed the max_speed_mps limit of 15 m/s (horizontal speed); accepted: 0 to 15",
        ),
        ("WPNAV_SPEED_UP", 600, AP, "exceed the max_vertical_speed_mps limit of 5 m/s"),
        ("WPNAV_SPEED", 10, AP, "WPNAV_SPEED 10 cm/s is below its range; accepted: 20 to 1500 cm/s"),
        ("MPC_XY_VEL_MAX", 20, PX, "MPC_XY_VEL_MAX 20 m/s would let the autopilot exceed the max_speed_mps"),
        ("MPC_XY_CRUISE", 16, PX, "limit of 15 m/s"),
        ("RTL_RETURN_ALT", 300, PX, "RTL_RETURN_ALT 300 m would let the autopilot exceed the max_altitude_m"),
        ("RTL_RETURN_ALT", 130, PX, "exceed the max_altitude_m limit of 120 m"),
        ("MPC_Z_VEL_MAX_UP", 6, PX, "exceed the max_vertical_speed_mps limit of 5 m/s"),
        ("MPC_LAND_SPEED", 4.5, PX, "above the autopilot's range"),
    ],
)
def test_parameters_that_set_what_the_autopilot_flies_at_are_held_to_the_limits(
    name: str, value: float, governed, words: str
) -> None:
    err = refusal(policy().check_param_write, name, value, vehicle_id="alpha", governed=governed)
    assert err.rule == "param_limit" and words in err.message, err.message
    assert err.message.endswith("nothing was written")
    policy().check_param_write(name, value, via="rest", governed=governed)  # operators: any value


def test_a_vehicles_own_limits_bound_its_parameters() -> None:
    p = policy(vehicle_limits={"alpha": {"max_speed_mps": 5}})
    assert (
        "limit of 5 m/s"
        in refusal(p.check_param_write, "WPNAV_SPEED", 600, vehicle_id="alpha", governed=AP).message
    )
    p.check_param_write("WPNAV_SPEED", 600, vehicle_id="bravo", governed=AP)


@pytest.mark.parametrize(
    ("name", "value", "governed"),
    [("WPNAV_SPEED", 1500, AP), ("RTL_ALT", 3000, AP), ("LAND_SPEED", 150, AP), ("WPNAV_ACCEL", 250, AP),
     ("MPC_XY_VEL_MAX", 12, PX), ("RTL_RETURN_ALT", 60, PX), ("MPC_ACC_HOR", 3, PX), ("NAV_ACC_RAD", 2, PX)],
)  # fmt: skip
def test_parameters_within_the_limits_or_allowlisted_are_written(name: str, value: float, governed) -> None:
    policy().check_param_write(name, value, vehicle_id="alpha", governed=governed)  # no refusal


@pytest.mark.parametrize(
    "name", ["GPS1_TYPE", "EK3_SRC1_POSXY", "SERIAL0_PROTOCOL", "BATT_CAPACITY", "MAV1_POSITION",
             "MOT_SPIN_MIN", "INS_ACCOFFS_X", "SIM_SPEEDUP", "EKF2_GPS_CTRL", "SYS_AUTOSTART",
             "DISARM_DELAY"],
)  # fmt: skip
def test_parameters_neither_governed_nor_allowlisted_are_refused_for_agents(name: str) -> None:
    err = refusal(policy().check_param_write, name, 0, vehicle_id="alpha", governed={**AP, **PX})
    assert err.rule == "param_not_allowed", err.message
    assert f"{name} is neither, so nothing was written" in err.message
    assert "GATEWAY_AGENT_PARAM_ALLOW" in err.message and "REST" in err.message
    policy(agent_param_allow=f"{name[:3]}*").check_param_write(
        name, 0, governed=AP
    )  # the operator allowed it
    policy().check_param_write(name, 0, via="rest")


@pytest.mark.parametrize("name", ["", "WAY_TOO_LONG_PARAMETER_NAME", "ARMING CHECK", "FENCE-ENABLE", 5])
def test_malformed_parameter_names_are_refused(name) -> None:
    assert refusal(policy().check_param_write, name).rule == "invalid_input"


# --- kill ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("via", "airborne", "agents_may_kill", "allowed", "needs_confirmation"),
    [
        ("rest", True, False, True, False),
        ("rest", False, False, True, False),
        ("rest", True, True, True, False),
        ("mcp", False, False, True, False),  # on the ground kill = disarm
        ("mcp", False, True, True, False),
        ("mcp", True, False, False, None),  # refused: operator decision
        ("mcp", True, True, True, True),  # allowed only with a human's confirmation
    ],
)
def test_kill_decision_table(via, airborne, agents_may_kill, allowed, needs_confirmation) -> None:
    p = policy(agents_may_kill=agents_may_kill)
    drone = ctx() if airborne else ground()
    if allowed:
        assert p.check_kill(drone, via=via) is needs_confirmation
    else:
        err = refusal(p.check_kill, drone, via=via)
        assert err.rule == "kill_in_air"
        assert "Only an operator may do this" in err.message


@pytest.mark.parametrize(("via", "confirmed", "refused"), [("mcp", False, True), ("mcp", True, False),
                                                          ("rest", False, False)])  # fmt: skip
def test_an_agents_kill_needs_its_confirmation(via, confirmed, refused) -> None:
    p = policy(agents_may_kill=True)
    if refused:
        err = refusal(p.check_kill_confirmed, ctx("alpha"), confirmed, via)
        assert err.rule == "kill_not_confirmed" and "nothing sent" in err.message
    else:
        p.check_kill_confirmed(ctx("alpha"), confirmed, via)


def test_kill_has_no_confirm_flag_to_widen_it() -> None:
    p = policy(agents_may_kill=False)
    with pytest.raises(TypeError):
        p.check_kill(ctx(), confirm=True)  # type: ignore[call-arg]
    with pytest.raises(InvalidArgument):
        p.check_kill(ctx(), via="operator")  # type: ignore[arg-type]


def test_kill_on_the_ground_still_respects_locks() -> None:
    book = LockBook()
    book.lock("alpha", "leave it", "alice")
    assert refusal(locked_policy(book).check_kill, ground("alpha")).rule == "operator_lock"
