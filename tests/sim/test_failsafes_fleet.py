"""Failsafes (GCS heartbeat loss, low battery) and several vehicles flown at once."""

from __future__ import annotations

import asyncio

from mavsdk_grpc.telemetry import FlightMode

from tests.helpers import mavsdk_system, sim_process
from tests.helpers.timing import eventually
from tests.sim.flying import SPEEDUP, distance_m, offset, ready_to_fly, take_off, wait_for


async def _texts(sim, index: int = 0) -> list[str]:
    return [text for _t, _s, text in await sim.control.status_texts(index)]


async def test_gcs_heartbeat_loss_triggers_rtl_only_for_the_configured_gcs() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await ready_to_fly(drone)
        # mavsdk_server heartbeats come once per wall second = SPEEDUP simulated seconds
        await drone.param.set_param_float("FS_GCS_TIMEOUT", 90.0)
        await drone.param.set_param_int("FS_GCS_ENABLE", 1)
        await take_off(drone, 10.0)

        # MAV_GCS_SYSID is still 255: heartbeats of mavsdk_server (245) do not count, so the vehicle has
        # "never seen its GCS" and the failsafe cannot trigger (ArduCopter's failsafe_gcs_check)
        await wait_for(drone.telemetry.in_air(), lambda a: a)
        for _ in range(3):
            await asyncio.sleep(1.1)  # several heartbeats of mavsdk_server
            truth = await sim.control.state(0)
            assert truth["gcs_heartbeat_age_s"] is None and not truth["failsafe_gcs"]

        await drone.param.set_param_int("MAV_GCS_SYSID", 245)

        async def gcs_seen() -> bool:  # a heartbeat from system 245 (ArduPilot: never seen, no failsafe)
            return (await sim.control.state(0))["gcs_heartbeat_age_s"] is not None

        await eventually(gcs_seen, "a heartbeat of the configured GCS seen", within_s=10)
        await sim.control.link_down(0)

        async def failsafe() -> dict | None:  # FS_GCS_TIMEOUT: 3 s wall at speed-up 30
            truth = await sim.control.state(0)
            return truth if truth["failsafe_gcs"] else None

        truth = await eventually(failsafe, "the GCS failsafe", within_s=30)
        assert truth["mode"] == "RTL"
        await sim.control.link_up(0)
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.RETURN_TO_LAUNCH)
        assert "GCS Failsafe" in await _texts(sim)

        async def cleared() -> bool:  # heartbeats from 245 again: the failsafe clears (it stays in RTL)
            return "GCS Failsafe Cleared" in await _texts(sim)

        await eventually(cleared, "the GCS failsafe cleared", within_s=30)
        truth = await sim.control.state(0)
        assert not truth["failsafe_gcs"] and truth["mode"] == "RTL"


async def test_low_battery_failsafe_returns_home() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await ready_to_fly(drone)
        await drone.param.set_param_int("BATT_FS_LOW_ACT", 2)  # RTL
        await take_off(drone, 10.0)
        battery = await wait_for(drone.telemetry.battery(), lambda _b: True)
        assert battery.remaining_percent <= 100.0 and battery.voltage_v > 12.0

        await sim.control.set_battery(0, 15.0)  # 10.3 V < BATT_LOW_VOLT 10.5 V
        battery = await wait_for(drone.telemetry.battery(), lambda b: b.remaining_percent < 20.0)
        assert battery.voltage_v < 10.5
        # BATT_LOW_TIMER (10 simulated seconds) later: failsafe, RTL
        await wait_for(
            drone.telemetry.flight_mode(), lambda m: m == FlightMode.RETURN_TO_LAUNCH, timeout_s=60
        )
        texts = await _texts(sim)
        assert "Battery Failsafe" in texts
        assert any(t.startswith("Battery 1 is low") for t in texts)
        truth = await sim.control.state(0)
        assert truth["failsafe_battery"] == "low" and truth["armed"]


async def _fly(sim, index: int, url: str) -> None:
    async with mavsdk_system(url) as drone:
        await ready_to_fly(drone)
        await take_off(drone, 10.0 + 5 * index)
        home = await wait_for(drone.telemetry.home(), lambda _h: True)
        here = await wait_for(drone.telemetry.position(), lambda _p: True)
        lat, lon = offset(here.latitude_deg, here.longitude_deg, 60.0, 10.0 * index)
        await drone.action.goto_location(lat, lon, home.absolute_altitude_m + 10.0 + 5 * index, 0.0)
        await wait_for(
            drone.telemetry.position(),
            lambda p: distance_m(p.latitude_deg, p.longitude_deg, lat, lon) < 2.0,
            timeout_s=90,
        )
        await drone.action.land()
        await wait_for(drone.telemetry.armed(), lambda armed: not armed, timeout_s=120)
        truth = await sim.control.state(index)
        assert distance_m(truth["lat"], truth["lon"], lat, lon) < 2.0 and truth["landed"]


async def test_three_vehicles_through_three_mavsdk_servers() -> None:
    async with sim_process(3, speedup=SPEEDUP) as sim:
        assert sim.sysids == [1, 2, 3]
        assert len(set(sim.urls)) == 3
        await asyncio.gather(*(_fly(sim, i, url) for i, url in enumerate(sim.urls)))
        homes = [(await sim.control.state(i))["home"] for i in range(3)]
        assert distance_m(homes[0]["lat"], homes[0]["lon"], homes[1]["lat"], homes[1]["lon"]) > 3.0
