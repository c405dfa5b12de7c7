"""Readiness and refusals on real autopilots, at the vehicle layer (a real mavsdk_server each): a drone
is "initialising" until it can arm, arms at once once "ready", and every refusal says why in the
autopilot's words, or by the drone's state when the autopilot gives none. The tours (tour.py) fly the
tools through MCP; these check the words exactly where the autopilot chooses them."""

from __future__ import annotations

import pytest

from gateway.errors import CommandFailed, InvalidArgument
from gateway.fleet.operations.fleet_steps import set_rtl_altitude_param
from gateway.fleet.vehicles.vehicle import ConnectionState, Vehicle
from gateway.registry.spec import VehicleSpec
from tests.real.waits import until

pytestmark = pytest.mark.real


async def ready_noting_waits(v: Vehicle, within_s: float) -> list[str]:
    """Wait for "ready"; returns every "initialising" reason seen on the way (what REST and list_drones
    show)."""
    waits: list[str] = []

    def ready() -> bool:
        waiting = v.status()["initialising"]
        if waiting and waiting not in waits:
            waits.append(waiting)
        return v.state == ConnectionState.READY

    await until("ready", ready, within_s, v)
    return waits


async def test_arducopter_is_initialising_until_it_can_arm_and_every_refusal_says_why(arducopter, registry):
    v = await registry.add(VehicleSpec(id="ap2", url=arducopter.url))
    waits = await ready_noting_waits(v, 120)
    # GPS and home come ~20 s (simulated) before the EKF uses GPS: that span is "initialising"
    assert "waiting for the position estimate (the EKF is not using GPS yet)" in waits, waits
    await v.arm()  # at once after "ready"
    await until("armed", lambda: v.telemetry.fresh("armed") is True, 20, v)
    assert v.telemetry.fresh("flight_mode") == "GUIDED"  # the dialect's arming mode

    with pytest.raises(CommandFailed, match=r"(?i)autopilot says: 'Mode change to AUTO failed: init failed'"):
        await v.set_flight_mode("MISSION")  # AUTO, armed on the ground, no mission
    await v.disarm()
    await until("disarmed", lambda: v.telemetry.fresh("armed") is False, 20, v)

    await v.set_param("BATT_LOW_VOLT", 30.0)  # above the battery's voltage: the arming checks refuse
    with pytest.raises(CommandFailed, match=r"'ap2' refused to arm: autopilot says 'Arm: Battery 1 low"):
        await v.arm()
    await v.set_param("BATT_LOW_VOLT", 0.0)
    # fleet_return_to_launch's return altitude: this ArduPilot has RTL_ALT_M (metres) instead of RTL_ALT (cm)
    await set_rtl_altitude_param(v, 20.0)
    assert (await v.get_param("RTL_ALT_M"))[0] == pytest.approx(20.0)
    assert v.return_altitude_param() == ("RTL_ALT_M", 1.0)
    with pytest.raises(InvalidArgument, match=r"FENCE_ENABLE cannot hold 1000: drone 'ap2' stored -24"):
        await v.set_param("FENCE_ENABLE", 1000)  # ArduPilot clamps silently; the gateway refuses
    assert await v.get_param("FENCE_ENABLE") == (0, "int")

    await v.takeoff(5)
    await until("in the air", lambda: v.on_ground() is False, 30, v)
    with pytest.raises(CommandFailed) as silent:  # refused without a word: the drone's state says why
        await v.disarm()
    assert "(the autopilot gave no reason; it is mode GUIDED, armed, in the air)" in silent.value.message
    await v.land()
    await until("landed and disarmed", lambda: v.telemetry.fresh("armed") is False, 120, v)


async def test_px4_is_initialising_until_it_can_arm_and_a_refusal_says_why(px4, registry):
    v = await registry.add(VehicleSpec(id="px2", url=px4.url))
    waits = await ready_noting_waits(v, 90)
    # PX4 SIH has its GPS position within seconds: how many steps are seen depends on the machine's load
    assert waits and all(w.startswith("waiting for ") for w in waits), waits
    assert v.status()["initialising"] is None
    await v.arm()  # at once after "ready"
    await until("armed", lambda: v.telemetry.fresh("armed") is True, 20, v)
    await v.disarm()
    await until("disarmed", lambda: v.telemetry.fresh("armed") is False, 20, v)

    await v.set_flight_mode("LAND")
    with pytest.raises(CommandFailed, match=r"'px2' refused to arm: autopilot says '(Arming|Preflight)"):
        await v.arm()  # PX4 does not arm in LAND
    assert v.telemetry.fresh("armed") is False
