"""Parameters and flight modes through MAVSDK, plus arming refused under GPS loss."""

from __future__ import annotations

import asyncio

import pytest
from mavsdk_grpc.action import ActionError
from mavsdk_grpc.param import ParamError
from mavsdk_grpc.telemetry import FlightMode

from tests.helpers import mavsdk_system, sim_process
from tests.helpers.timing import eventually, scaled
from tests.sim.flying import SPEEDUP, arm, ready_to_fly, set_rates, take_off, wait_for


async def test_parameter_get_set_readback_list_and_unknown() -> None:
    async with sim_process(1, speedup=SPEEDUP, sysid_base=7) as sim, mavsdk_system(sim.urls[0]) as drone:
        assert await drone.param.get_param_int("MAV_SYSID") == 7
        assert await drone.param.get_param_float("WPNAV_SPEED") == pytest.approx(1000.0)
        await drone.param.set_param_float("WPNAV_SPEED", 800.0)
        assert await drone.param.get_param_float("WPNAV_SPEED") == pytest.approx(800.0)
        await drone.param.set_param_int("RTL_ALT", 2000)
        assert await drone.param.get_param_int("RTL_ALT") == 2000
        truth = await sim.control.state(0)
        assert truth["sysid"] == 7

        everything = await drone.param.get_all_params()
        assert len(everything.int_params) + len(everything.float_params) == 1354
        assert "WPNAV_SPEED" in {p.name for p in everything.float_params}
        assert "MAV_SYSID" in {p.name for p in everything.int_params}

        with pytest.raises(ParamError):  # 4.6 name on a 4.7 vehicle: no reply at all -> MAVSDK times out
            await drone.param.get_param_int("SYSID_THISMAV")


async def test_mode_changes_show_in_telemetry() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        await set_rates(drone)
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.STABILIZED)
        await drone.action.hold()  # LOITER
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.HOLD)
        await drone.action.return_to_launch()  # RTL while disarmed: accepted, nothing happens
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.RETURN_TO_LAUNCH)
        assert (await sim.control.state(0))["mode"] == "RTL"
        await drone.mission_raw.start_mission()  # AUTO (allowed while disarmed, even without a mission)
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.MISSION)
        await drone.action.hold()
        await wait_for(drone.telemetry.health(), lambda h: h.is_armable)
        await take_off(drone, 8.0)  # switches to GUIDED (MAVSDK: OFFBOARD)
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.OFFBOARD)
        # MAVSDK's hold() is LOITER on ArduPilot: with the RC throttle at minimum the copter sinks
        await drone.action.hold()
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.HOLD)
        await wait_for(drone.telemetry.position(), lambda p: p.relative_altitude_m < 5.0)
        await drone.action.land()
        await wait_for(drone.telemetry.flight_mode(), lambda m: m == FlightMode.LAND)
        assert (await sim.control.state(0))["mode"] == "LAND"


async def test_arming_refused_under_gps_loss() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, mavsdk_system(sim.urls[0]) as drone:
        texts: list[str] = []

        async def collect() -> None:
            async for status in drone.telemetry.status_text():
                texts.append(status.text)

        collector = asyncio.create_task(collect())  # subscribed long before the refusal
        try:
            await ready_to_fly(drone)
            await sim.control.gps_loss(0)
            await wait_for(
                drone.telemetry.health(), lambda h: not h.is_armable and not h.is_global_position_ok
            )
            gps = await wait_for(drone.telemetry.gps_info(), lambda g: True)
            assert gps.num_satellites == 0
            with pytest.raises(ActionError) as refused:
                await drone.action.arm()
            assert "FAILED" in str(refused.value) or "DENIED" in str(refused.value)
            await asyncio.wait_for(_until(lambda: "Arm: Need Position Estimate" in texts), scaled(10))
        finally:
            collector.cancel()
        assert not (await sim.control.state(0))["armed"]

        await sim.control.gps_loss(0, lost=False)
        await wait_for(drone.telemetry.health(), lambda h: h.is_armable)
        await arm(drone)
        assert (await sim.control.state(0))["armed"]


async def _until(condition) -> None:
    async def check() -> bool:
        return bool(condition())

    await eventually(check, "condition", within_s=50)
