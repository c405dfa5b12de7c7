"""Flying the simulator through real mavsdk_server processes, the way the gateway will."""

from __future__ import annotations

import asyncio

import pytest
from mavsdk_grpc.telemetry import LandedState

from tests.helpers import mavsdk_system, sim_process
from tests.helpers.timing import eventually
from tests.sim.flying import SPEEDUP, arm, distance_m, offset, ready_to_fly, set_rates, take_off, wait_for


async def test_health_becomes_ok_only_when_rates_are_requested() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await set_rates(drone)
        health = await wait_for(
            drone.telemetry.health(), lambda h: h.is_global_position_ok and h.is_home_position_ok
        )
        assert health.is_accelerometer_calibration_ok and health.is_gyrometer_calibration_ok
        home = await wait_for(drone.telemetry.home(), lambda _h: True)
        truth = await sim.control.state(0)
        assert distance_m(home.latitude_deg, home.longitude_deg, truth["lat"], truth["lon"]) < 1.0
        info = await drone.info.get_version()
        assert (info.flight_sw_major, info.flight_sw_minor) == (4, 7)


async def test_arm_takeoff_goto_land_autodisarm() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await ready_to_fly(drone)
        await take_off(drone, 10.0)
        position = await wait_for(drone.telemetry.position(), lambda _p: True)
        assert abs(position.relative_altitude_m - 10.0) < 1.0
        assert await wait_for(drone.telemetry.in_air(), lambda _a: True)

        home = await wait_for(drone.telemetry.home(), lambda _h: True)
        lat, lon = offset(position.latitude_deg, position.longitude_deg, 80.0, 60.0)  # 100 m away
        await drone.action.goto_location(lat, lon, home.absolute_altitude_m + 10.0, 0.0)
        arrived = await wait_for(
            drone.telemetry.position(),
            lambda p: distance_m(p.latitude_deg, p.longitude_deg, lat, lon) < 2.0,
            timeout_s=90,
        )
        assert abs(arrived.relative_altitude_m - 10.0) < 1.0
        truth = await sim.control.state(0)
        assert truth["mode"] == "GUIDED"
        assert distance_m(truth["lat"], truth["lon"], lat, lon) < 2.0

        await drone.action.land()
        await wait_for(drone.telemetry.landed_state(), lambda s: s == LandedState.LANDING)
        await wait_for(drone.telemetry.armed(), lambda armed: not armed, timeout_s=90)
        truth = await sim.control.state(0)
        assert truth["landed"] and truth["rel_alt_m"] < 0.2 and truth["mode"] == "LAND"
        texts = [text for _t, _sev, text in await sim.control.status_texts(0)]
        assert "Arming motors" in texts and "Disarming motors" in texts


async def test_armed_on_ground_without_takeoff_auto_disarms() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await ready_to_fly(drone)
        await arm(drone)
        assert await wait_for(drone.telemetry.armed(), lambda armed: armed)
        # DISARM_DELAY (10 s simulated) later the vehicle disarms by itself
        await wait_for(drone.telemetry.armed(), lambda armed: not armed, timeout_s=60)
        truth = await sim.control.state(0)
        assert not truth["armed"] and truth["landed"]


async def test_tcp_port_accepts_a_new_client_after_the_previous_one_left() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim:
        for _ in range(2):
            async with mavsdk_system(sim.urls[0]) as drone:
                await set_rates(drone)
                await wait_for(drone.telemetry.position(), lambda _p: True)
            await asyncio.sleep(0.2)


async def test_reboot_loses_stream_rates_until_requested_again() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await set_rates(drone)
        await wait_for(drone.telemetry.position(), lambda _p: True)
        await (
            drone.action.reboot()
        )  # MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN: TCP dropped, mavsdk_server reconnects

        async def rebooted() -> dict | None:
            truth = await sim.control.state(0)
            return truth if truth["client_connected"] and truth["boots"] == 2 else None

        truth = await eventually(rebooted, "reboot and reconnection", within_s=10)
        assert truth["mode"] == "STABILIZE"
        with pytest.raises(TimeoutError):  # rates are gone and mavsdk_server does not re-request them
            await wait_for(drone.telemetry.position(), lambda _p: True, timeout_s=1.5)
        await set_rates(drone)
        await wait_for(drone.telemetry.position(), lambda _p: True)
