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


async def test_set_flight_mode_reads_the_circle_radius_and_refuses_a_circle_past_the_limit(tmp_path) -> None:
    from tests.fakes import fake, fake_gateway, spread, unit_settings
    from tests.fleet._util import AGENT, OPERATOR

    async with fake_gateway(unit_settings(tmp_path, max_distance_m=300), spread(1)) as gateway:
        d1 = fake(gateway, "d1")
        c = gateway.commander
        took = await c.takeoff(AGENT, "d1", 10.0)
        assert (await c.wait(took.operation_id, 10)).status == "succeeded"
        agent = await _refused(c.set_mode(AGENT, "d1", "CIRCLE"))
        assert agent.rule == "mode_deny_in_air"
        d1.params["CIRCLE_RADIUS"] = 20000.0  # 200 m: its far side lies 400 m away
        operator = await _refused(c.set_mode(OPERATOR, "d1", "CIRCLE"))
        assert operator.rule == "pattern_extent" and "flies up to 400 m" in operator.message
        assert not [e for e in d1.log if e[1] == "mode"], d1.log  # nothing was sent
        d1.params["CIRCLE_RADIUS"] = 5000.0  # 50 m: 100 m from where it starts, within 300 m
        assert (await c.set_mode(OPERATOR, "d1", "CIRCLE")).facts["mode"] == "CIRCLE"
        d1.params.pop("CIRCLE_RADIUS")
        d1.params["CIRCLE_RADIUS_M"] = 200.0  # the 4.7 name, in metres
        assert "flies up to 400 m" in (await _refused(c.set_mode(OPERATOR, "d1", "CIRCLE"))).message


async def _refused(call) -> SafetyRefusal:
    with pytest.raises(SafetyRefusal) as info:
        await call
    return info.value
