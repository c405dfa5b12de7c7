"""Mission protocol and AUTO execution through MAVSDK's mission_raw (the ArduPilot way: seq 0 = home)."""

from __future__ import annotations

import asyncio

from mavsdk_grpc.mission_raw import MissionItem
from mavsdk_grpc.telemetry import FlightMode

from tests.helpers import mavsdk_system, sim_process
from tests.sim.flying import SPEEDUP, arm, distance_m, offset, ready_to_fly, take_off, wait_for

NAV_WAYPOINT, NAV_RTL, NAV_TAKEOFF, DO_CHANGE_SPEED = 16, 20, 22, 178
FRAME_REL_INT = 6


def _item(seq: int, command: int, lat: float = 0.0, lon: float = 0.0, alt: float = 0.0, p1=0.0, p2=0.0):
    return MissionItem(
        seq, FRAME_REL_INT if seq else 0, command, 1 if seq == 0 else 0, 1,
        p1, p2, 0.0, 0.0, round(lat * 1e7), round(lon * 1e7), alt, 0,
    )  # fmt: skip


def _plan(lat0: float, lon0: float) -> list[MissionItem]:
    a = offset(lat0, lon0, 40.0, 0.0)
    b = offset(lat0, lon0, 40.0, 40.0)
    return [
        _item(0, NAV_WAYPOINT),  # placeholder: ArduPilot keeps home at seq 0
        _item(1, NAV_TAKEOFF, alt=12.0),
        _item(2, DO_CHANGE_SPEED, p1=1.0, p2=8.0),
        _item(3, NAV_WAYPOINT, *a, 12.0),
        _item(4, NAV_WAYPOINT, *b, 15.0),
    ]


async def test_mission_upload_download_run_and_rtl() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await ready_to_fly(drone)
        home = await wait_for(drone.telemetry.home(), lambda _h: True)
        plan = _plan(home.latitude_deg, home.longitude_deg)
        await drone.mission_raw.upload_mission(plan)

        downloaded = await drone.mission_raw.download_mission()
        assert len(downloaded) == len(plan)
        assert downloaded[0].frame == 0 and downloaded[0].command == NAV_WAYPOINT
        assert abs(downloaded[0].x / 1e7 - home.latitude_deg) < 1e-6
        assert abs(downloaded[0].z - home.absolute_altitude_m) < 0.1  # home, absolute altitude
        for sent, got in zip(plan[1:], downloaded[1:], strict=True):
            assert (got.seq, got.frame, got.command, got.x, got.y) == (
                sent.seq, sent.frame, sent.command, sent.x, sent.y,
            )  # fmt: skip
            assert abs(got.z - sent.z) < 1e-3 and abs(got.param2 - sent.param2) < 1e-6

        await take_off(drone, 5.0)  # airborne in GUIDED, then AUTO runs the mission from item 1
        await drone.mission_raw.start_mission()
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.MISSION)
        progress = await wait_for(
            drone.mission_raw.mission_progress(), lambda p: p.current == p.total - 1, timeout_s=120
        )
        assert progress.total == len(plan)
        await wait_for(drone.mission_raw.mission_progress(), lambda p: p.current == p.total, timeout_s=120)
        truth = await sim.control.state(0)
        wp = plan[4]
        assert distance_m(truth["lat"], truth["lon"], wp.x / 1e7, wp.y / 1e7) < 3.0
        assert truth["mode"] == "AUTO" and truth["armed"]  # a mission ending with a waypoint hovers
        texts = [text for _t, _s, text in await sim.control.status_texts(0)]
        assert "Flight plan received" in texts and "Reached command #4" in texts

        await drone.action.return_to_launch()
        await wait_for(drone.telemetry.armed(), lambda armed: not armed, timeout_s=120)
        truth = await sim.control.state(0)
        assert distance_m(truth["lat"], truth["lon"], home.latitude_deg, home.longitude_deg) < 2.0
        assert truth["mode"] == "RTL" and truth["landed"]


async def test_auto_armed_on_the_ground_waits_and_clear_leaves_only_home() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await ready_to_fly(drone)
        home = await wait_for(drone.telemetry.home(), lambda _h: True)
        await drone.mission_raw.upload_mission(_plan(home.latitude_deg, home.longitude_deg))
        await sim.control.set_param(0, "DISARM_DELAY", 0)  # no auto-disarm while we watch it wait
        await arm(drone)
        # mission_raw.start_mission() is DO_SET_MODE AUTO only: armed on the ground the mission does not
        # start (not "auto-armed"); MAV_CMD_MISSION_START would take off (test_guided_raw)
        await drone.mission_raw.start_mission()
        await asyncio.sleep(1.0)  # 30 simulated seconds
        truth = await sim.control.state(0)
        assert truth["mode"] == "AUTO" and truth["armed"] and truth["landed"] and truth["rel_alt_m"] == 0
        await drone.action.disarm()

        await drone.mission_raw.clear_mission()
        assert len(await drone.mission_raw.download_mission()) == 1  # only home remains
