"""The Commander's seam: every verb by name with JSON arguments and a JSON result, waiting as a separate
step, and the door deciding the policy. The real Gateway (store, policy, operations) over fake drones."""

from __future__ import annotations

import asyncio
import json

import pytest

from gateway.errors import InvalidArgument, SafetyRefusal, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.commands.commander import VERBS, Commander
from gateway.fleet.operations.views import OperationView
from gateway.fleet.policy.caller import Caller
from gateway.runtime import Gateway
from tests.fakes import HOME, fake
from tests.fleet._util import AGENT, OPERATOR


async def test_a_verb_by_name_takes_and_gives_json_and_waiting_is_separate(gateway: Gateway) -> None:
    commander = gateway.commander
    started = await commander.call("takeoff", AGENT, drone_id="d1", alt_m=10)
    assert json.loads(json.dumps(started)) == started  # plain JSON, ready to cross a process boundary
    assert started["kind"] == "takeoff" and started["status"] == "running"
    progress: list[float] = []

    async def on_progress(view: OperationView) -> None:
        progress.append(view.progress)

    done = await commander.wait(started["operation_id"], 10.0, on_progress)
    assert done.status == "succeeded" and progress, done
    lat, lon = geo.offset_position(HOME[0], HOME[1], 30.0, 0.0)
    goto = await commander.call("goto", AGENT, drone_id="d1", lat_deg=lat, lon_deg=lon, alt_m=12)
    assert OperationView.model_validate(goto).kind == "goto"
    assert (await commander.wait(goto["operation_id"], 10.0)).status == "succeeded"
    page = await commander.call("list_params", AGENT, drone_id="d1", prefix="rtl")
    assert page["params"] == {"RTL_ALT": 1500.0} and page["next_offset"] is None
    assert fake(gateway, "d1").sent[:2] == [("takeoff", 10.0), ("goto", lat, lon, 12.0)]


async def test_unknown_verbs_and_bad_arguments_are_named_and_send_nothing(gateway: Gateway) -> None:
    commander = gateway.commander
    with pytest.raises(InvalidArgument, match=r"unknown verb 'fly'; verbs: .*takeoff"):
        await commander.call("fly", AGENT, drone_id="d1")
    with pytest.raises(InvalidArgument, match="invalid arguments for takeoff: alt_m: Field required"):
        await commander.call("takeoff", AGENT, drone_id="d1")
    with pytest.raises(InvalidArgument, match="speed: Extra inputs are not permitted"):
        await commander.call("set_speed", AGENT, drone_id="d1", speed_mps=5, speed=3)
    with pytest.raises(InvalidArgument, match="via must be one of mcp, rest, console, cluster"):
        Caller(via="radio", principal="x")  # type: ignore[arg-type]
    assert fake(gateway, "d1").sent == []


async def test_the_door_decides_locks_and_the_takeoff_guard(gateway: Gateway) -> None:
    commander: Commander = gateway.commander
    await commander.lock(OPERATOR, "d2", "battery swap")
    with pytest.raises(SafetyRefusal, match="operator_lock: drone d2 is locked by operator-1: battery swap"):
        await commander.call("takeoff", AGENT, drone_id="d2", alt_m=10)
    with pytest.raises(SafetyRefusal, match="only an operator may unlock"):
        await commander.call("unlock", AGENT, scope="d2")
    fake(gateway, "d2").speed = 2.0  # a slow climb: the calls below surely land inside it
    climbing = await commander.call("takeoff", OPERATOR, drone_id="d2", alt_m=60)  # locks bind agents
    await commander.unlock(OPERATOR, "d2")
    lat, lon = geo.offset_position(HOME[0], HOME[1], 30.0, 10.0)
    goto = {"drone_id": "d2", "lat_deg": lat, "lon_deg": lon, "alt_m": 60}
    with pytest.raises(SafetyRefusal, match="takeoff_in_progress: d2 is still taking off"):
        await commander.call("goto", AGENT, **goto)
    assert commander.operation(climbing["operation_id"]).status == "running"
    # an operator (here the console) may interrupt the climb: its goto supersedes the takeoff
    moved = await commander.call("goto", Caller("console", "bob"), **goto)
    assert moved["kind"] == "goto" and commander.operation(climbing["operation_id"]).status == "superseded"


def test_the_verb_table_names_every_verb_of_the_issue() -> None:
    wanted = {"takeoff", "goto", "move_relative", "reposition", "land", "return_to_launch", "hold", "set_yaw",
              "set_speed", "set_mode", "arm", "disarm", "kill", "upload_mission", "download_mission",
              "clear_mission", "start_mission", "pause_mission", "resume_mission", "set_current_item",
              "get_param", "set_param", "list_params", "formation_goto", "fleet_takeoff", "fleet_land",
              "fleet_return_to_launch", "fleet_hold", "stop_all"}  # fmt: skip
    assert wanted <= set(VERBS), wanted - set(VERBS)


async def test_a_verb_by_name_takes_a_drone_id_in_any_case(gateway: Gateway) -> None:
    """Operations and locks are keyed by the id string: 'D1' must reach them as d1."""
    commander = gateway.commander
    started = await commander.call("takeoff", AGENT, drone_id="D1", alt_m=10)
    assert started["drone_id"] == "d1"
    assert commander.operations.running("d1") is not None
    assert commander.canonical_id("ghost") == "ghost"  # the lookup then names the known ids


async def test_refusals_name_the_next_valid_call_with_numbers(gateway: Gateway) -> None:
    """Texts a small model misread (issue 12): each names the call that does what was meant."""
    commander = gateway.commander
    started = await commander.call("takeoff", AGENT, drone_id="d1", alt_m=10)
    assert (await commander.wait(started["operation_id"], 10.0)).status == "succeeded"
    with pytest.raises(InvalidArgument) as again:
        await commander.call("takeoff", AGENT, drone_id="d1", alt_m=15)
    assert str(again.value.message) == (
        "d1 already flies at 10 m; to climb to 15 m use "
        "move_to_relative(drone_id='d1', north_m=0, east_m=0, up_m=5)"
    )
    sent = list(fake(gateway, "d1").sent)
    with pytest.raises(InvalidArgument) as down:
        await commander.call("move_relative", AGENT, drone_id="d1", north_m=30, east_m=0, up_m=-10)
    assert "up_m=-10 would take d1 from 10.0 m to 0.0 m, below home" in down.value.message
    assert "to climb 10 m use up_m=10" in down.value.message
    with pytest.raises(InvalidArgument, match="latitude and longitude look swapped"):
        await commander.call("goto", AGENT, drone_id="d1", lat_deg=149.17, lon_deg=-35.36, alt_m=12)
    assert fake(gateway, "d1").sent == sent  # nothing was sent for any of them


async def test_a_goto_on_the_ground_to_a_refused_target_says_the_refusal_first(gateway: Gateway) -> None:
    """Taking off would not help: the small model took off as told, then gave up before hearing why."""
    lat, lon = geo.offset_position(HOME[0], HOME[1], 50_000.0, 0.0)
    with pytest.raises(SafetyRefusal, match="from home"):
        await gateway.commander.call("goto", AGENT, drone_id="d1", lat_deg=lat, lon_deg=lon, alt_m=30)
    near_lat, near_lon = geo.offset_position(HOME[0], HOME[1], 50.0, 0.0)
    with pytest.raises(VehicleNotReady, match="Call takeoff first"):
        await gateway.commander.call(
            "goto", AGENT, drone_id="d1", lat_deg=near_lat, lon_deg=near_lon, alt_m=30
        )
    assert fake(gateway, "d1").sent == []


async def test_a_relative_move_from_the_ground_takes_off_first_as_one_operation(gateway: Gateway) -> None:
    """One call: the climb, then the leg at the altitude asked, one operation; while it climbs, the
    takeoff guard holds other commands back, and the leg is not sent before the climb is done."""
    commander = gateway.commander
    d1 = fake(gateway, "d1")
    d1.speed = 2.0  # a slow climb: the refused call below surely lands inside it
    started = await commander.call("move_relative", AGENT, drone_id="d1", north_m=30, east_m=20, alt_m=12)
    assert started["kind"] == "move_to_relative" and started["status"] == "running"
    lat, lon = geo.offset_position(HOME[0], HOME[1], 30.0, 20.0)
    with pytest.raises(SafetyRefusal, match="takeoff_in_progress: d1 is still taking off"):
        await commander.call("goto", AGENT, drone_id="d1", lat_deg=lat, lon_deg=lon, alt_m=12)
    assert [c[0] for c in d1.sent] == ["takeoff"]  # the leg waits for the climb
    d1.speed = 150.0
    done = await commander.wait(started["operation_id"], 20.0)
    assert done.status == "succeeded" and done.kind == "move_to_relative", done
    assert d1.sent == [("takeoff", 12.0), ("goto", pytest.approx(lat), pytest.approx(lon), 12.0)]


async def test_a_climb_from_the_ground_is_up_m_and_a_landing_mid_climb_sends_no_leg(gateway: Gateway) -> None:
    commander = gateway.commander
    d1 = fake(gateway, "d1")
    d1.speed = 2.0
    started = await commander.call("move_relative", AGENT, drone_id="d1", north_m=40, up_m=15)
    landing = await commander.call("land", AGENT, drone_id="d1")  # a safety action: never held back
    assert (await commander.wait(landing["operation_id"], 20.0)).status == "succeeded"
    assert commander.operation(started["operation_id"]).status == "superseded"
    assert [c[0] for c in d1.sent] == ["takeoff", "land"] and d1.sent[0] == ("takeoff", 15.0)


async def test_a_leg_the_autopilot_refuses_after_the_climb_fails_the_operation_saying_so(
    gateway: Gateway,
) -> None:
    commander = gateway.commander
    fake(gateway, "d1").fail = {"goto": "not in GUIDED"}
    started = await commander.call("move_relative", AGENT, drone_id="d1", east_m=30, alt_m=10)
    done = await commander.wait(started["operation_id"], 20.0)
    assert done.status == "failed", done
    assert "the next leg was not accepted: goto on drone 'd1' failed: not in GUIDED" in done.message, done


async def test_a_relative_move_of_a_drone_on_the_ground_needs_an_altitude_and_a_leg_within_limits(
    gateway: Gateway,
) -> None:
    """Nothing flies: the leg beyond the distance limit is refused by that rule (naming the limit), and
    without an altitude the refusal names the call to make."""
    commander = gateway.commander
    with pytest.raises(InvalidArgument) as no_alt:
        await commander.call("move_relative", AGENT, drone_id="d1", north_m=100, east_m=0)
    assert "move_to_relative(drone_id='d1', north_m=100, east_m=0, alt_m=<metres above home>)" in (
        no_alt.value.message
    )
    with pytest.raises(SafetyRefusal) as far:
        await commander.call("move_relative", AGENT, drone_id="d1", north_m=0, east_m=5000, alt_m=30)
    assert far.value.rule == "max_distance" and "beyond the limit of 1000 m" in far.value.message
    with pytest.raises(InvalidArgument, match=r"give either up_m .* that is 5 m above home\) or alt_m"):
        await commander.call("move_relative", AGENT, drone_id="d1", north_m=10, up_m=5, alt_m=30)
    assert fake(gateway, "d1").sent == []


async def test_a_climb_and_an_altitude_that_name_the_same_height_are_one_height(gateway: Gateway) -> None:
    """ "12 m up" of a drone on the ground is 12 m above home: up_m=12 with alt_m=12 flies, once."""
    commander = gateway.commander
    started = await commander.call("move_relative", AGENT, drone_id="d1", north_m=10, up_m=12, alt_m=12)
    assert (await commander.wait(started["operation_id"], 10.0)).status == "succeeded"
    assert fake(gateway, "d1").sent[0] == ("takeoff", 12.0)


async def test_an_altitude_of_zero_beside_a_climb_is_the_altitude_not_given(gateway: Gateway) -> None:
    """Both filled in, as a small model does ("hop charlie up to 6 m": up_m=6, alt_m=0): from the ground the
    climb is the takeoff's altitude, as up_m=0 beside alt_m is the climb not given."""
    commander = gateway.commander
    started = await commander.call("move_relative", AGENT, drone_id="d1", north_m=0, up_m=6, alt_m=0)
    assert (await commander.wait(started["operation_id"], 10.0)).status == "succeeded"
    assert fake(gateway, "d1").sent[0] == ("takeoff", 6.0)


async def test_an_altitude_of_zero_beside_a_leg_keeps_the_altitude(gateway: Gateway) -> None:
    """ "40 m west" of a flying drone as west_m=40, alt_m=0: the leg at the altitude it flies; alt_m=0 alone
    is still refused, saying to land instead."""
    commander = gateway.commander
    started = await commander.call("takeoff", AGENT, drone_id="d1", alt_m=10)
    assert (await commander.wait(started["operation_id"], 10.0)).status == "succeeded"
    moved = await commander.call("move_relative", AGENT, drone_id="d1", west_m=40, alt_m=0)
    assert (await commander.wait(moved["operation_id"], 20.0)).status == "succeeded"
    lat, lon = geo.offset_position(HOME[0], HOME[1], 0.0, -40.0)
    assert fake(gateway, "d1").sent[-1] == (
        "goto",
        pytest.approx(lat),
        pytest.approx(lon),
        pytest.approx(10.0),
    )
    with pytest.raises(InvalidArgument, match=r"alt_m 0 is not above home.*use land to come down"):
        await commander.call("move_relative", AGENT, drone_id="d1", alt_m=0)


async def test_a_relative_move_that_goes_nowhere_is_said_not_flown(gateway: Gateway) -> None:
    """ "Another 10 m higher" sent as alt_m=10 by a drone at 10 m: nothing to do, said with the argument
    that climbs (it was reported as arrived, and the climb never flew)."""
    commander = gateway.commander
    started = await commander.call("takeoff", AGENT, drone_id="d1", alt_m=10)
    assert (await commander.wait(started["operation_id"], 10.0)).status == "succeeded"
    sent = list(fake(gateway, "d1").sent)
    with pytest.raises(InvalidArgument, match=r"already flies at 10 m, the altitude asked for.*up_m is the"):
        await commander.call("move_relative", AGENT, drone_id="d1", north_m=0, east_m=0, alt_m=10)
    assert fake(gateway, "d1").sent == sent  # nothing was sent


async def test_a_flying_drone_moves_to_an_altitude_above_home(gateway: Gateway) -> None:
    commander = gateway.commander
    started = await commander.call("takeoff", AGENT, drone_id="d1", alt_m=10)
    assert (await commander.wait(started["operation_id"], 10.0)).status == "succeeded"
    moved = await commander.call("move_relative", AGENT, drone_id="d1", east_m=20, alt_m=25)
    assert (await commander.wait(moved["operation_id"], 10.0)).status == "succeeded"
    lat, lon = geo.offset_position(HOME[0], HOME[1], 0.0, 20.0)
    assert fake(gateway, "d1").sent[-1] == ("goto", pytest.approx(lat), pytest.approx(lon), 25.0)


async def test_west_m_and_south_m_fly_the_way_a_request_says_them(gateway: Gateway) -> None:
    """ "40 m west and 25 m south at 12 m" as west_m=40, south_m=25 (a 1.5B model wrote west_m three
    times after being refused for it); north_m beside south_m cannot be read and changes nothing."""
    commander = gateway.commander
    with pytest.raises(InvalidArgument) as both:
        await commander.call("move_relative", AGENT, drone_id="d1", north_m=10, south_m=5, alt_m=12)
    assert both.value.message == (
        "give north_m or south_m, not both (here north_m=10, south_m=5): south_m=N is north_m=-N; "
        "nothing was sent"
    )
    assert fake(gateway, "d1").sent == []
    started = await commander.call("move_relative", AGENT, drone_id="d1", west_m=40, south_m=25, alt_m=12)
    assert (await commander.wait(started["operation_id"], 20.0)).status == "succeeded"
    lat, lon = geo.offset_position(HOME[0], HOME[1], -25.0, -40.0)
    assert fake(gateway, "d1").sent[-1] == ("goto", pytest.approx(lat), pytest.approx(lon), 12.0)


async def test_a_drone_whose_stop_ends_cancelled_under_it_fails_alone_the_fleet_stop_answers(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Something one drone's stop awaits ending cancelled (a connection lost under a library) is that
    drone's failure: the other drones are stopped and the operator gets the fleet stop's answer."""
    commander = gateway.commander
    for drone_id in ("d1", "d2"):
        took = await commander.call("takeoff", AGENT, drone_id=drone_id, alt_m=10)
        assert (await commander.wait(took["operation_id"], 10.0)).status == "succeeded"
    operator = commander.parts["OperatorVerbs"]
    flight = operator.flight  # type: ignore[attr-defined]
    land = flight.land

    async def land_cancelled_for_d1(caller: Caller, drone_id: str, *args: object, **kw: object) -> object:
        if drone_id == "d1":
            raise asyncio.CancelledError
        return await land(caller, drone_id, *args, **kw)

    monkeypatch.setattr(flight, "land", land_cancelled_for_d1)
    result = await commander.stop_all(OPERATOR, "land")
    outcomes = {r.drone_id: r.outcome for r in result.results}
    assert outcomes["d1"] == "failed" and outcomes["d2"] == "sent", result.results
    assert ("land",) in [tuple(s[:1]) for s in fake(gateway, "d2").sent]
