"""Real ArduCopter SITL (speed-up 5) through the gateway's vehicle layer and a real mavsdk_server."""

from __future__ import annotations

import pytest

from gateway.errors import CommandFailed, InvalidArgument
from gateway.fleet import geo
from gateway.fleet.fleet_ops import set_rtl_altitude_param
from gateway.fleet.vehicle import ConnectionState
from gateway.registry.spec import VehicleSpec
from tests.helpers.timing import scaled
from tests.real.flying import fly_mission, rel_alt, same_items, square, until

pytestmark = pytest.mark.real


async def test_arducopter_arms_at_once_after_ready_and_flies_a_mission_at_its_altitude(arducopter, registry):
    v = await registry.add(VehicleSpec(id="ap1", url=arducopter.url))
    await v.wait_for_state(ConnectionState.READY, within_s=scaled(120))
    # right after "ready" the autopilot must accept arming in GUIDED (no "Need Position Estimate")
    await v.arm()
    await until("armed", lambda: v.telemetry.fresh("armed") is True, 20, v)
    assert v.telemetry.fresh("flight_mode") == "GUIDED"

    await v.takeoff(10)
    await until("10 m above home", lambda: (rel_alt(v) or 0) > 9.0, 60, v)

    items = square(v, 40.0, 15.0)
    assert await v.upload_mission(items) == 3
    back = await v.download_mission()
    assert same_items(back, items), back
    track = await fly_mission(v, 180)
    assert track.lowest_from(2) > 13.5, track.samples  # never below the mission's altitude between waypoints
    for item in items:  # the flown track passes each waypoint
        assert track.closest_to(item.lat, item.lon) < 5.0, item

    # flight modes: common names mapped to ArduCopter's, a mode it lacks refused with its list
    await v.set_flight_mode("BRAKE")
    assert v.telemetry.fresh("flight_mode") == "BRAKE"
    await v.set_flight_mode("GUIDED")
    with pytest.raises(InvalidArgument, match=r"mode 'TAKEOFF' is not a mode of drone 'ap1' \(ArduCopter\)"):
        await v.set_flight_mode("TAKEOFF")

    # parameters read and written with the vehicle's own type
    value, kind = await v.set_param("WPNAV_SPEED", 750)
    assert (value, kind) == (750.0, "float")
    assert (await v.get_param("WPNAV_SPEED"))[0] == 750.0

    await v.set_flight_mode("RTL")
    await until("landed and disarmed at home", lambda: v.telemetry.fresh("armed") is False, 180, v)
    home = v.telemetry.home
    pos = v.telemetry.fresh("position")
    assert home is not None and pos is not None
    assert geo.horizontal_distance_m(pos.lat_deg, pos.lon_deg, home.value.lat_deg, home.value.lon_deg) < 5.0


async def test_arducopter_is_initialising_until_it_can_arm_and_every_refusal_says_why(arducopter, registry):
    v = await registry.add(VehicleSpec(id="ap2", url=arducopter.url))
    waits: list[str] = []

    def ready() -> bool:
        waiting = v.status()["initialising"]  # what REST and list_drones show
        if waiting and waiting not in waits:
            waits.append(waiting)
        return v.state == ConnectionState.READY

    await until("ready", ready, 120, v)
    # GPS and home come ~20 s (simulated) before the EKF uses GPS: that span is "initialising"
    assert "waiting for the position estimate (the EKF is not using GPS yet)" in waits, waits
    await v.arm()  # at once after "ready"
    await until("armed", lambda: v.telemetry.fresh("armed") is True, 20, v)

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
    with pytest.raises(InvalidArgument, match=r"FENCE_ENABLE cannot hold 1000: drone 'ap2' stored -24"):
        await v.set_param("FENCE_ENABLE", 1000)  # ArduPilot clamps silently; the gateway refuses
    assert await v.get_param("FENCE_ENABLE") == (0, "int")

    await v.takeoff(5)
    await until("in the air", lambda: v.telemetry.fresh("in_air") is True, 30, v)
    with pytest.raises(CommandFailed) as silent:  # refused without a word: the drone's state says why
        await v.disarm()
    assert "(the autopilot gave no reason; it is mode GUIDED, armed, in the air)" in silent.value.message
    await v.land()
    await until("landed and disarmed", lambda: v.telemetry.fresh("armed") is False, 120, v)
