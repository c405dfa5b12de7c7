"""Missions under the policy when they start and item by item: the mission the drone holds is read back
and checked at every start (initiate, resume, a mode change into the mission mode, a jump to an item)
from where the drone is now, against the zones in force now; items whose effect the gateway does not
model are refused for agents by name, and marked unchecked for operators."""

from __future__ import annotations

import pytest

from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet.dialects.mission_semantics import arducopter_mission, px4_mission
from gateway.fleet.missions import mission_files
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.mission_check import MissionSemantics
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.runtime import Gateway
from tests.fakes import HOME, fake
from tests.fleet._util import AGENT, OPERATOR, at, ctx, settings

FROM_HERE = r"^geofence_keep_out: mission item 2: from where the drone is now: the straight path"
WPL_HOME = f"QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t{HOME[0]}\t{HOME[1]}\t{HOME[2]}\t1\n"


def wpl(*rows: tuple[int, int, float, float, float, float, float, float, float]) -> str:
    """A WPL file: home, a takeoff to 20 m, then (frame, command, p1..p4, north m, east m, alt) rows."""
    lines = [WPL_HOME, "1\t0\t3\t22\t0\t0\t0\t0\t0\t0\t20\t1\n"]
    for seq, (frame, command, p1, p2, p3, p4, north, east, alt) in enumerate(rows, start=2):
        lat, lon = at(north, east) if (north, east) != (0, 0) else (0.0, 0.0)
        lines.append(f"{seq}\t0\t{frame}\t{command}\t{p1}\t{p2}\t{p3}\t{p4}\t{lat}\t{lon}\t{alt}\t1\n")
    return "".join(lines)


def items_of(text: str, semantics: MissionSemantics | None = None) -> list[MissionItem]:
    zero = (semantics or arducopter_mission()).zero_position_is_here
    parsed = mission_files.parse(text)
    return mission_files.mission_items(parsed, HOME, (HOME[0], HOME[1], 0.0), zero_is_here=zero)


def refused(text: str, semantics: MissionSemantics | None = None, **limits: float) -> SafetyRefusal:
    semantics = semantics or arducopter_mission()
    with pytest.raises(SafetyRefusal) as err:
        SafetyPolicy(settings(**limits)).check_mission(ctx(), items_of(text, semantics), "mcp", semantics)
    return err.value


# --- item by item: what the gateway cannot check is refused by name ------------------------------------


@pytest.mark.parametrize(
    ("row", "name"),
    [
        ((3, 218, 31, 2, 0, 0, 0, 0, 0), "DO_AUX_FUNCTION (218)"),  # motor emergency stop
        ((3, 218, 11, 0, 0, 0, 0, 0, 0), "DO_AUX_FUNCTION (218)"),  # the fence off
        ((3, 42703, 0, 0, 0, 0, 0, 0, 0), "NAV_ATTITUDE_TIME (42703)"),
        ((3, 176, 1, 4, 0, 0, 0, 0, 0), "DO_SET_MODE (176)"),
        ((3, 208, 2, 0, 0, 0, 0, 0, 0), "DO_PARACHUTE (208)"),
        ((3, 92, 1, 0, 0, 0, 0, 0, 0), "NAV_GUIDED_ENABLE (92)"),
        ((3, 30, 1, 0, 0, 0, 0, 0, 500), "NAV_CONTINUE_AND_CHANGE_ALT (30)"),
        ((3, 82, 0, 0, 0, 0, 50, 0, 20), "NAV_SPLINE_WAYPOINT (82)"),
        ((3, 4242, 0, 0, 0, 0, 0, 0, 0), "command 4242 (4242)"),
    ],
)
def test_items_the_gateway_does_not_model_are_refused_for_agents_by_name(row: tuple, name: str) -> None:
    err = refused(wpl(row))
    assert err.rule == "mission_unchecked" and err.details["item"] == 2
    assert err.message.startswith(f"mission_unchecked: mission item 2: {name} is a command whose effect")
    assert "cannot check on ArduCopter" in err.message and "altitude" not in err.message


def test_an_operator_may_store_an_unchecked_item_and_learns_which() -> None:
    items = items_of(wpl((3, 218, 31, 2, 0, 0, 0, 0, 0), (3, 16, 0, 0, 0, 0, 50, 0, 20)))
    unchecked = SafetyPolicy(settings()).check_mission(ctx(), items, "rest", arducopter_mission())
    assert [u.text() for u in unchecked] == [
        "mission item 2: DO_AUX_FUNCTION (218) is a command whose effect the gateway cannot check on "
        "ArduCopter"
    ]
    # the limits still hold for operators on every item the gateway reads
    high = items_of(wpl((3, 218, 31, 2, 0, 0, 0, 0, 0), (3, 16, 0, 0, 0, 0, 50, 0, 200)))
    with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 3: "):
        SafetyPolicy(settings()).check_mission(ctx(), high, "rest", arducopter_mission())


def test_a_frame_the_gateway_does_not_model_is_named() -> None:
    err = refused(wpl((10, 16, 0, 0, 0, 0, 50, 0, 20)))  # above terrain: the gateway knows no terrain
    assert err.rule == "mission_unchecked"
    assert "mission item 2: NAV_WAYPOINT (16) in frame GLOBAL_TERRAIN_ALT (10)" in err.message


def test_loiter_radii_count_in_the_distance_limit_and_the_zones() -> None:
    err = refused(wpl((3, 18, 3, 0, 2000, 0, 100, 0, 30)))  # LOITER_TURNS radius 2000 m, 100 m out
    assert err.rule == "max_distance" and "loiter circle of radius 2000 m reaches 2100 m" in err.message
    err = refused(wpl((3, 17, 0, 0, -2000, 0, 100, 0, 30)))  # LOITER_UNLIM, counter-clockwise
    assert err.rule == "max_distance" and err.details["item"] == 2
    err = refused(wpl((3, 19, 10, 0, 950, 0, 100, 0, 30)))  # LOITER_TIME
    assert err.rule == "max_distance"
    ok = items_of(wpl((3, 18, 3, 0, 50, 0, 100, 0, 30)))
    SafetyPolicy(settings()).check_mission(ctx(), ok, "mcp", arducopter_mission())


def test_a_loiter_circle_counts_from_the_origin_when_the_autopilot_moved_its_home() -> None:
    import dataclasses

    from gateway.fleet import geo

    # the autopilot re-armed 400 m north: its home walked, the vehicle's origin stayed where it was
    walked = (*geo.offset_position(HOME[0], HOME[1], 400, 0), HOME[2])
    moved = dataclasses.replace(ctx(), home=walked, origin=HOME)
    circle = items_of(wpl((3, 18, 3, 0, 300, 0, 750, 0, 30)))  # 750 m north of the origin, radius 300 m
    with pytest.raises(SafetyRefusal) as err:  # 1,050 m from the origin; 650 m from the walked home
        SafetyPolicy(settings()).check_mission(moved, circle, "mcp", arducopter_mission())
    assert err.value.rule == "max_distance" and "reaches 1050 m from its origin" in err.value.message


def test_a_loiter_circle_may_not_reach_a_keep_out_zone() -> None:
    from tests.fleet._util import square
    from tests.fleet.test_geofence import fenced

    p = fenced(("school", "keep_out", square(300, 0, 50), "*"))
    near = items_of(wpl((3, 18, 3, 0, 200, 0, 100, 0, 30)))  # centre 200 m from the zone: radius 200
    with pytest.raises(SafetyRefusal, match=r"^geofence_keep_out: mission item 2: the loiter circle"):
        p.check_mission(ctx(), near, "mcp", arducopter_mission())
    p.check_mission(ctx(), items_of(wpl((3, 18, 3, 0, 20, 0, 100, 0, 30))), "mcp", arducopter_mission())


def test_change_speed_is_judged_by_its_speed_type() -> None:
    err = refused(wpl((2, 178, 2, 14, -1, 0, 0, 0, 0)))  # climb at 14 m/s
    assert err.rule == "max_speed" and "climb rate 14 m/s exceeds the vertical limit of" in err.message
    err = refused(wpl((2, 178, 3, 9, -1, 0, 0, 0, 0)))  # descent
    assert err.rule == "max_speed" and "descent rate 9 m/s" in err.message
    err = refused(wpl((2, 178, 1, 20, -1, 0, 0, 0, 0)))  # ground speed above 15
    assert err.rule == "max_speed" and "speed 20 m/s exceeds the limit of 15 m/s" in err.message
    assert refused(wpl((2, 178, 7, 3, -1, 0, 0, 0, 0))).rule == "mission_unchecked"  # no such type
    ok = items_of(wpl((2, 178, 1, 12, -1, 0, 0, 0, 0), (2, 178, 2, 2, -1, 0, 0, 0, 0)))
    SafetyPolicy(settings()).check_mission(ctx(), ok, "mcp", arducopter_mission())
    # PX4 flies any speed type as its cruise (horizontal) speed
    px4 = items_of(wpl((2, 178, 2, 14, -1, 0, 0, 0, 0)), px4_mission())
    SafetyPolicy(settings()).check_mission(ctx(), px4, "mcp", px4_mission())
    assert refused(wpl((2, 178, 2, 16, -1, 0, 0, 0, 0)), px4_mission()).rule == "max_speed"


def test_jumps_are_bounded_and_the_leg_back_is_checked() -> None:
    from tests.fleet._util import square
    from tests.fleet.test_geofence import fenced

    base = ((3, 16, 0, 0, 0, 0, 100, 0, 20), (3, 16, 0, 0, 0, 0, 100, 200, 20))
    assert "repeats -1 times" in refused(wpl(*base, (2, 177, 2, -1, 0, 0, 0, 0, 0))).message
    assert "DO_JUMP to item 9" in refused(wpl(*base, (2, 177, 9, 1, 0, 0, 0, 0, 0))).message
    text = wpl(*base, (3, 16, 0, 0, 0, 0, 300, 100, 20), (2, 177, 2, 3, 0, 0, 0, 0, 0))
    SafetyPolicy(settings()).check_mission(ctx(), items_of(text), "mcp", arducopter_mission())
    # a zone between item 4 and item 2: only the jump flies that leg
    p = fenced(("school", "keep_out", square(200, 50, 20), "*"))
    with pytest.raises(SafetyRefusal, match=r"mission item 5: the jump back to item 2: the straight path"):
        p.check_mission(ctx(), items_of(text), "mcp", arducopter_mission())


def test_px4_has_its_own_commands_and_reads_zero_as_written() -> None:
    err = refused(wpl((3, 18, 3, 0, 10, 0, 100, 0, 30)), px4_mission())  # no LOITER_TURNS on a PX4 copter
    assert err.rule == "mission_unchecked" and "cannot check on PX4" in err.message
    err = refused(wpl((3, 16, 0, 0, 0, 0, 0, 0, 20)), px4_mission())  # 0, 0 is 0, 0 on PX4
    assert err.rule == "max_distance" and err.details["item"] == 2


# --- at the start: the held mission, now, from here ----------------------------------------------------


def stored(drone: str, gateway: Gateway, *waypoints: tuple[float, float, float]) -> None:
    """A mission put on the drone by another ground station: a takeoff, then these waypoints."""
    items = [MissionItem(kind="takeoff", alt_rel_m=10.0)]
    items += [MissionItem(lat=at(n, e)[0], lon=at(n, e)[1], alt_rel_m=alt) for n, e, alt in waypoints]
    fake(gateway, drone).mission = items


async def test_a_mission_stored_by_another_ground_station_is_checked_at_every_start(
    gateway: Gateway,
) -> None:
    commander = gateway.commander
    stored("d1", gateway, (50, 0, 20), (100, 0, 200))  # a waypoint 200 m up (limit 120)
    for verb, args in (("start_mission", {}), ("resume_mission", {})):
        with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 3: waypoint altitude 200 m"):
            await commander.call(verb, AGENT, drone_id="d1", **args)
    with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 3:"):
        await commander.call("set_mode", AGENT, drone_id="d1", mode="MISSION")
    with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 3:"):
        await commander.call("set_mode", AGENT, drone_id="d1", mode="AUTO")
    with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 3:"):
        await commander.call("set_current_item", AGENT, drone_id="d1", index=2)
    with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 3:"):
        await commander.call("start_mission", OPERATOR, drone_id="d1")  # the limits hold operators too
    assert fake(gateway, "d1").sent == []
    stored("d1", gateway, (50, 0, 20), (100, 0, 30))
    started = await commander.call("start_mission", AGENT, drone_id="d1")
    assert started["status"] == "running" and fake(gateway, "d1").sent == [("start_mission",)]


async def test_an_empty_waypoint_list_is_refused_not_the_stored_mission_started(gateway: Gateway) -> None:
    stored("d1", gateway, (50, 0, 20))
    with pytest.raises(InvalidArgument, match="waypoints is an empty list"):
        await gateway.commander.start_mission(AGENT, "d1", [])
    assert fake(gateway, "d1").sent == []


async def test_a_zone_added_after_the_upload_and_the_drone_moved_are_seen_at_the_start(
    gateway: Gateway,
) -> None:
    commander = gateway.commander
    north = at(200, 0)
    await commander.call(
        "upload_mission", AGENT, drone_id="d1",
        items=[{"kind": "takeoff", "alt_rel_m": 10}, {"lat": north[0], "lon": north[1], "alt_rel_m": 20}],
    )  # fmt: skip
    gateway.require_safety().geofences.add(
        "late", "keep_out", {"type": "Polygon", "coordinates": [_square(100, 0, 20)]}
    )
    with pytest.raises(SafetyRefusal, match=FROM_HERE):
        await commander.call("start_mission", AGENT, drone_id="d1")
    gateway.require_safety().geofences.remove("late")
    # the drone is elsewhere now: the leg from where it is to the item it resumes at is checked
    took = await commander.call("takeoff", AGENT, drone_id="d1", alt_m=10)
    await commander.wait(took["operation_id"], 10.0)
    east = at(200, 300)
    await commander.wait(
        (await commander.call("goto", AGENT, drone_id="d1", lat_deg=east[0], lon_deg=east[1], alt_m=10))[
            "operation_id"
        ],
        10.0,
    )
    gateway.require_safety().geofences.add(
        "between", "keep_out", {"type": "Polygon", "coordinates": [_square(200, 150, 20)]}
    )
    sent = len(fake(gateway, "d1").sent)
    with pytest.raises(SafetyRefusal, match=FROM_HERE):
        await commander.call("resume_mission", AGENT, drone_id="d1")
    assert len(fake(gateway, "d1").sent) == sent


def _square(north: float, east: float, half: float) -> list[list[float]]:
    corners = [(north - half, east - half), (north - half, east + half), (north + half, east + half),
               (north + half, east - half), (north - half, east - half)]  # fmt: skip
    return [[at(n, e)[1], at(n, e)[0]] for n, e in corners]
