"""Parameters by their effect: a value the autopilot adds to where the vehicle is (RTL_CLIMB_MIN), a
radius whose pattern reaches two radii away (CIRCLE_RADIUS), and allowlisted parameters held to the
autopilot's documented range."""

from __future__ import annotations

import pytest

from gateway.errors import SafetyRefusal
from gateway.fleet.dialects import ARDUPILOT, PX4_DIALECT
from tests.fleet._util import policy

AP = ARDUPILOT.limit_params
PX = PX4_DIALECT.limit_params


def refusal(fn, *args, **kwargs) -> SafetyRefusal:
    with pytest.raises(SafetyRefusal) as info:
        fn(*args, **kwargs)
    return info.value


@pytest.mark.parametrize(("name", "value"), [("RTL_CLIMB_MIN_M", 30), ("RTL_CLIMB_MIN_M", 0.5),
                                             ("RTL_CLIMB_MIN", 3000), ("RTL_CLIMB_MIN", 1)])  # fmt: skip
def test_a_climb_added_to_the_current_altitude_is_judged_from_the_altitude_limit(name: str, value) -> None:
    err = refusal(policy().check_param_write, name, value, vehicle_id="alpha", governed=AP)
    assert err.rule == "param_limit", err.message
    assert "is added by the autopilot to where the vehicle is" in err.message
    assert "from 120 m, as far as an agent may fly" in err.message
    assert err.message.endswith(f"accepted: 0 {AP[name].unit}; nothing was written")
    policy().check_param_write(name, 0, vehicle_id="alpha", governed=AP)
    policy().check_param_write(name, value, via="rest", governed=AP)  # operators: any value


def test_rtl_climb_min_30_m_names_the_altitude_it_would_reach() -> None:
    err = refusal(policy().check_param_write, "RTL_CLIMB_MIN_M", 30, vehicle_id="alpha", governed=AP)
    assert "it would go to 150 m, beyond the max_altitude_m limit of 120 m" in err.message


def test_a_circle_radius_counts_twice_against_the_distance_limit() -> None:
    p = policy(vehicle_limits={"alpha": {"max_distance_m": 1000}})
    err = refusal(p.check_param_write, "CIRCLE_RADIUS_M", 1000, vehicle_id="alpha", governed=AP)
    assert err.rule == "param_limit"
    assert "reaches two radii (2000 m) from where it starts" in err.message
    assert "accepted: 0 to 500 m" in err.message
    p.check_param_write("CIRCLE_RADIUS_M", 500, vehicle_id="alpha", governed=AP)
    assert (
        "accepted: 0 to 50000 cm"
        in refusal(p.check_param_write, "CIRCLE_RADIUS", 60000, vehicle_id="alpha", governed=AP).message
    )


@pytest.mark.parametrize(
    ("name", "value", "accepted", "governed"),
    [("WPNAV_RADIUS", 1e9, "5 to 1000 cm", AP), ("WPNAV_ACCEL", 1e7, "50 to 500 cm/s/s", AP),
     ("LOIT_BRK_DELAY", 1e6, "0 to 2 s", AP), ("LOIT_BRK_DELAY", -1, "0 to 2 s", AP),
     ("CIRCLE_RATE", 720, "-90 to 90 deg/s", AP), ("LOIT_BRK_JRK_M", 0, "5 to 50 m/s/s/s", AP),
     ("NAV_ACC_RAD", 5000, "0.05 to 200 m", PX), ("MPC_ACC_HOR", 100, "2 to 15 m/s^2", PX)],
)  # fmt: skip
def test_allowlisted_parameters_are_written_only_within_the_autopilots_range(
    name: str, value: float, accepted: str, governed
) -> None:
    err = refusal(policy().check_param_write, name, value, vehicle_id="alpha", governed=governed)
    assert err.rule == "param_range", err.message
    assert f"{name} " in err.message and "outside the autopilot's documented range" in err.message
    assert f"accepted: {accepted}; nothing was written" in err.message
    assert err.details["param"] == name and err.details["value"] == value
    policy().check_param_write(name, value, via="rest", governed=governed)  # operators: any value


def test_allowlisted_parameters_within_range_are_written_and_ranges_do_not_open_the_allowlist() -> None:
    policy().check_param_write("WPNAV_RADIUS", 300, vehicle_id="alpha", governed=AP)
    policy().check_param_write("LOIT_BRK_DELAY", 1.5, vehicle_id="alpha", governed=AP)
    closed = policy(agent_param_allow="")
    assert refusal(closed.check_param_write, "WPNAV_RADIUS", 300, governed=AP).rule == "param_not_allowed"
