"""Mission files in and out (QGC WPL 110, QGC .plan): parsing, the policy's reading of each item with
ArduPilot's semantics, items sent as written, and files written back from a downloaded mission."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import pytest

from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet.dialects.mission_semantics import arducopter_mission, px4_mission
from gateway.fleet.missions import mission, mission_files
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import VehicleContext
from tests.fleet._util import settings

DATA = Path(__file__).resolve().parents[1] / "data" / "missions"
CANGPS = (DATA / "CANGPSCopterMission.txt").read_text()
PX4_PLAN = (DATA / "px4_survey.plan").read_text()
CMAC = (-35.362881, 149.165222, 582.0)


def cmac_ctx(**kw: object) -> VehicleContext:
    base = {"vehicle_id": "alpha", "is_simulator": True, "armed": False, "in_air": False, "battery_pct": 90.0,
            "home": CMAC, "position": (CMAC[0], CMAC[1], 0.0)}  # fmt: skip
    base.update(kw)
    return VehicleContext(**base)  # type: ignore[arg-type]


def test_the_ardupilot_autotest_mission_is_read_as_ardupilot_reads_it() -> None:
    parsed = mission_files.parse(CANGPS)
    assert parsed.home == CMAC and len(parsed.items) == 12
    items = mission_files.mission_items(parsed, CMAC, (CMAC[0], CMAC[1], 0.0))
    kinds = [i.kind for i in items]
    assert kinds == ["takeoff", "waypoint", "other", "loiter_time", "waypoint", "waypoint", "waypoint",
                     "waypoint", "waypoint", "other", "waypoint", "rtl"]  # fmt: skip
    assert items[1].alt_rel_m == 20.0  # altitude 0: the previous item's altitude
    assert (items[3].lat, items[3].lon, items[3].alt_rel_m) == (-35.364652, 149.163501, 20.0)  # 0, 0: here
    assert (items[10].lat, items[10].lon, items[10].alt_rel_m) == (-35.364652, 149.163995, 20.0)
    assert items[2].command == 115 and items[9].command == 177  # CONDITION_YAW, DO_JUMP pass through
    SafetyPolicy(settings()).check_mission(cmac_ctx(), items, "rest", arducopter_mission())


def test_file_items_go_to_the_autopilot_as_written() -> None:
    parsed = mission_files.parse(CANGPS)
    items = mission_files.mission_items(parsed, CMAC, None)
    plan = mission.encode(items, CMAC, home_slot=True)
    assert [w.seq for w in plan.items] == list(range(13)) and plan.user_to_wire == list(range(1, 13))
    yaw = plan.items[3]
    assert (yaw.frame, yaw.command, yaw.param1, yaw.param2, yaw.param3, yaw.param4) == (3, 115, 640, 20, 1, 1)
    wp = plan.items[2]
    assert (wp.x, wp.y, wp.z) == (-353646520, 1491635010, 0.0)  # altitude 0 kept: the autopilot reads it
    assert (plan.items[11].x, plan.items[11].y) == (0, 0)
    jump = plan.items[10]
    assert (jump.command, jump.param1, jump.param2) == (177, 8.0, 1.0)
    px4 = mission.encode(items, None, home_slot=False)
    assert px4.items[0].command == 22 and len(px4.items) == 12


def _downloaded(plan: mission.WirePlan) -> list[SimpleNamespace]:
    """The items as a download returns them (MAVSDK's MissionItem: the same fields, autocontinue too)."""
    return [SimpleNamespace(**vars(w)) for w in plan.items]


@pytest.mark.parametrize("fmt", ["waypoints", "plan"])
def test_a_downloaded_mission_writes_back_to_the_same_items(fmt: str) -> None:
    for text, home_slot in ((CANGPS, True), (PX4_PLAN, False)):
        parsed = mission_files.parse(text)
        items = mission_files.mission_items(parsed, parsed.home, None)
        wire = mission.encode(items, parsed.home, home_slot=home_slot)
        decoded, _plan = mission.decode(_downloaded(wire), home_slot=home_slot)
        raws = mission_files.raw_items(decoded)
        written = mission_files.write(fmt, raws, parsed.home, "ardupilot")  # type: ignore[arg-type]
        again = mission_files.parse(written)
        assert len(again.items) == len(parsed.items)
        for a, b in zip(again.items, parsed.items, strict=True):
            assert (a.frame, a.command, a.autocontinue) == (b.frame, b.command, b.autocontinue)
            for x, y in zip(vars(a).values(), vars(b).values(), strict=True):
                assert x == pytest.approx(y, abs=1e-6, nan_ok=True)
        assert again.home == pytest.approx(parsed.home)
    plan = json.loads(mission_files.write("plan", raws, parsed.home, "px4"))
    assert plan["fileType"] == "Plan" and plan["mission"]["firmwareType"] == 12 and plan["version"] == 1


def test_px4_plan_speed_and_roi_are_checked_and_passed() -> None:
    parsed = mission_files.parse(PX4_PLAN)
    home = (47.397742, 8.545594, 488.0)
    items = mission_files.mission_items(parsed, home, (home[0], home[1], 0.0))
    assert [i.kind for i in items] == ["takeoff", "other", "waypoint", "other", "waypoint", "waypoint", "rtl"]
    assert items[1].speed_mps == 4.0 and items[3].command == 195
    ctx = cmac_ctx(home=home, position=(home[0], home[1], 0.0))
    SafetyPolicy(settings()).check_mission(ctx, items, "rest", px4_mission())
    with pytest.raises(SafetyRefusal, match=r"max_speed: mission item 2:") as refused:
        SafetyPolicy(settings(max_speed_mps=3.0)).check_mission(ctx, items, "rest", px4_mission())
    assert refused.value.details.get("item") == 2


def test_a_refused_item_is_named_with_its_sequence_number_and_rule() -> None:
    far = CANGPS.replace("-35.365361\t149.164563", "-35.465361\t149.164563")  # item 7, 11 km south
    items = mission_files.mission_items(mission_files.parse(far), CMAC, None)
    with pytest.raises(SafetyRefusal, match=r"^max_distance: mission item 7: ") as refused:
        SafetyPolicy(settings()).check_mission(cmac_ctx(), items, "rest", arducopter_mission())
    assert refused.value.details["item"] == 7
    row6 = "\t16\t1.000000\t0.000000\t0.000000\t0.000000\t-35.365361\t149.163995\t"
    global_alt = CANGPS.replace(f"6\t0\t3{row6}40.0", f"6\t0\t0{row6}800.0")  # frame 0: AMSL
    items = mission_files.mission_items(mission_files.parse(global_alt), CMAC, None)
    assert items[5].alt_rel_m == pytest.approx(218.0)  # 800 m AMSL above a home at 582 m
    with pytest.raises(SafetyRefusal, match=r"^max_altitude: mission item 6: "):
        SafetyPolicy(settings()).check_mission(cmac_ctx(), items, "rest", arducopter_mission())
    set_param = CANGPS.replace("3\t0\t3\t115\t640.000000", "3\t0\t3\t180\t640.000000")
    items = mission_files.mission_items(mission_files.parse(set_param), CMAC, None)
    with pytest.raises(SafetyRefusal, match=r"^mission_command_deny: mission item 3: DO_SET_PARAMETER"):
        SafetyPolicy(settings()).check_mission(cmac_ctx(), items, "rest", arducopter_mission())


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("QGC WPL 120\n", "version '120' is not supported"),
        ("hello", "begins with 'QGC WPL 110'"),
        ("QGC WPL 110\n0\t1\t0\t16\t0\t0\n", "line 2: expected 12 columns, got 6"),
        ("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t1\t2\t3\t1\n2\t0\t3\t16\t0\t0\t0\t0\t1\t2\t3\t1\n",
         "line 3: sequence number 2, expected 1"),
        ("QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t1\t2\t3\t1\n", "no items"),
        ("QGC WPL 110\n1\t0\t3\t16\t0\t0\t0\t0\t95\t2\t3\t1\n", "latitude/longitude 95.0, 2.0 out of range"),
        ('{"fileType": "Plan", "mission": {"items": [{"type": "ComplexItem", "complexItemType": "survey"}]}}',
         "mission item 1 is a survey item"),
        ('{"fileType": "Plan", "mission": {"items": [{"type": "SimpleItem", "command": 16, "frame": 3, '
         '"params": [0, 0]}]}}', "mission item 1: params must be a list of 7"),
        ("{not json", "not valid JSON"),
    ],
)  # fmt: skip
def test_bad_files_are_refused_in_one_line_naming_the_place(text: str, says: str) -> None:
    with pytest.raises(InvalidArgument, match=says.replace("(", r"\(").replace(")", r"\)")):
        mission_files.parse(text)


def test_items_at_here_need_a_known_position() -> None:
    text = (
        "QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t-35.36\t149.16\t582\t1\n"
        "1\t0\t3\t22\t0\t0\t0\t0\t0\t0\t20\t1\n"  # takeoff where the vehicle is
        "2\t0\t3\t16\t0\t0\t0\t0\t0\t0\t0\t1\n"  # a waypoint there, at the same altitude
    )
    with pytest.raises(InvalidArgument, match=r"mission item 2: .* not known yet"):
        mission_files.mission_items(mission_files.parse(text), CMAC, None)
    items = mission_files.mission_items(mission_files.parse(text), CMAC, (-35.36, 149.16, 0.0))
    assert (items[1].lat, items[1].lon, items[1].alt_rel_m) == (-35.36, 149.16, 20.0)


def test_json_input_cannot_carry_a_raw_item() -> None:
    """Only a parsed file attaches MAVLink items; an agent's JSON mission item never does."""
    with pytest.raises(ValueError, match="Extra inputs"):
        mission.MissionItem.model_validate({"lat": 1, "lon": 1, "alt_rel_m": 5, "_raw": {"frame": 3}})
    item = mission.MissionItem.model_validate({"lat": 1, "lon": 1, "alt_rel_m": 5})
    assert item.raw is None and "raw" not in mission.MissionItem.model_json_schema()["properties"]


@pytest.mark.parametrize(
    ("part", "value", "words"),
    [
        (
            "geoFence",
            {
                "circles": [],
                "polygons": [{"inclusion": True, "polygon": [[47, 8], [47, 8.1], [47.1, 8]]}],
                "version": 2,
            },
            "has a geofence (1 polygons, 0 circles)",
        ),
        (
            "geoFence",
            {
                "circles": [{"circle": {"center": [47, 8], "radius": 50}, "inclusion": False}],
                "polygons": [],
                "version": 2,
            },
            "has a geofence (0 polygons, 1 circles)",
        ),
        ("rallyPoints", {"points": [[47, 8, 30]], "version": 2}, "has 1 rally points"),
    ],
)
def test_a_plans_geofence_or_rally_points_are_refused_never_dropped(
    part: str, value: object, words: str
) -> None:
    doc = json.loads(PX4_PLAN)
    doc[part] = value
    with pytest.raises(InvalidArgument, match=r"nothing was sent") as refused:
        mission_files.parse(json.dumps(doc))
    assert words in str(refused.value)
    assert mission_files.parse(PX4_PLAN).items  # empty ones (as QGroundControl writes them) pass
