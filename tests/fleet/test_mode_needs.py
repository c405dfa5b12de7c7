"""Flight modes by what they need (the dialect's list of modes an agent may select in the air) and by
what they fly (a pattern's extent against the distance limit from the origin and the zones)."""

from __future__ import annotations

import pytest

from gateway.errors import SafetyRefusal
from gateway.fleet.dialects import ARDUPILOT, PX4_DIALECT
from gateway.fleet.policy.geofence import GeofenceSet
from gateway.fleet.policy.safety import SafetyPolicy
from tests.fleet._util import ctx, ground, policy, settings, square


def refusal(fn, *args, **kwargs) -> SafetyRefusal:
    with pytest.raises(SafetyRefusal) as info:
        fn(*args, **kwargs)
    return info.value


@pytest.mark.parametrize("mode", ["CIRCLE", "STABILIZE", "ALT_HOLD", "POSHOLD"])
def test_modes_that_read_the_pilots_throttle_are_refused_for_agents_in_the_air(mode: str) -> None:
    choice = ARDUPILOT.resolve_mode(mode)
    assert choice is not None and not choice.in_air.allowed
    # with no name on GATEWAY_MODE_DENY_IN_AIR, the dialect's own list still refuses it
    p = policy(mode_deny_in_air="")
    err = refusal(p.check_mode_choice, ctx(), choice, "mcp", 10.0)
    assert err.rule == "mode_deny_in_air", err.message
    assert f"mode {mode} reads the pilot's throttle and sticks" in err.message
    assert "sinks to the ground" in err.message and "nothing was sent" in err.message
    p.check_mode_choice(ground(), choice, "mcp", 10.0)  # on the ground: any offered mode


@pytest.mark.parametrize(
    ("dialect", "mode"),
    [(ARDUPILOT, "GUIDED"), (ARDUPILOT, "RTL"), (ARDUPILOT, "LAND"), (ARDUPILOT, "MISSION"),
     (ARDUPILOT, "BRAKE"), (ARDUPILOT, "SMART_RTL"), (PX4_DIALECT, "AUTO.LOITER"), (PX4_DIALECT, "RTL"),
     (PX4_DIALECT, "LAND"), (PX4_DIALECT, "MISSION"), (PX4_DIALECT, "TAKEOFF")],
)  # fmt: skip
def test_modes_that_fly_without_a_pilot_are_listed_with_their_reason(dialect, mode: str) -> None:
    choice = dialect.resolve_mode(mode)
    assert choice is not None and choice.in_air.allowed and choice.in_air.why
    policy().check_mode_choice(ctx(), choice, "mcp", None)


def test_every_offered_mode_says_why_it_may_or_may_not_be_selected_in_the_air() -> None:
    for dialect in (ARDUPILOT, PX4_DIALECT):
        for name in dialect.mode_names():
            choice = dialect.resolve_mode(name)
            assert choice is not None
            assert choice.in_air.why and "does not model" not in choice.in_air.why, name


def test_operators_may_select_a_pilot_mode_in_the_air_but_a_pattern_is_judged_by_its_extent() -> None:
    circle = ARDUPILOT.resolve_mode("CIRCLE")
    assert circle is not None and circle.pattern_reach == 2.0
    p = policy(vehicle_limits={"alpha": {"max_distance_m": 1000}})
    p.check_mode_choice(ctx(north_m=500), circle, "rest", 200.0)  # 500 + 2 x 200 = 900 m
    err = refusal(p.check_mode_choice, ctx(north_m=515), circle, "rest", 300.0)
    assert err.rule == "pattern_extent", err.message
    assert "mode CIRCLE with a radius of 300 m flies up to 600 m from where it starts" in err.message
    assert "up to 1115 m from the origin, beyond the distance limit of 1000 m" in err.message
    assert err.details["reach_m"] == 600.0
    unread = refusal(p.check_mode_choice, ctx(), circle, "rest", None)
    assert unread.rule == "pattern_extent" and "could not be read" in unread.message
    p.check_mode_choice(ground(), circle, "rest", None)  # not in the air: nothing flies a circle yet


def test_a_pattern_counts_its_extent_against_the_zones() -> None:
    circle = ARDUPILOT.resolve_mode("CIRCLE")
    assert circle is not None
    fences = GeofenceSet()
    fences.add("tower", "keep_out", square(0, 150, 20))
    p = SafetyPolicy(settings(), geofences=fences)
    p.check_mode_choice(ctx(), circle, "rest", 60.0)  # 120 m reach, the zone's edge is 130 m away
    err = refusal(p.check_mode_choice, ctx(), circle, "rest", 70.0)
    assert err.rule == "pattern_extent" and "keep-out zone 'tower' (130 m away)" in err.message
    inside = GeofenceSet()
    inside.add("field", "keep_in", square(0, 0, 100))
    p = SafetyPolicy(settings(), geofences=inside)
    assert (
        "keep-in zone 'field' ends 100 m away"
        in refusal(p.check_mode_choice, ctx(), circle, "rest", 60.0).message
    )


def test_the_pattern_counts_from_the_origin_not_from_a_moved_home() -> None:
    circle = ARDUPILOT.resolve_mode("CIRCLE")
    assert circle is not None
    here = ctx(north_m=900)
    moved_home = (here.position[0], here.position[1], 488.0)  # type: ignore[index]
    from dataclasses import replace

    flown = replace(here, home=moved_home, origin=ctx().home)
    err = refusal(policy().check_mode_choice, flown, circle, "rest", 100.0)
    assert "up to 1100 m from the origin" in err.message
