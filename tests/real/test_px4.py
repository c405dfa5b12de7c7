"""Real PX4 SIH (real time) through the gateway's vehicle layer and a real mavsdk_server."""

from __future__ import annotations

import pytest

from gateway.errors import CommandFailed, InvalidArgument
from gateway.fleet.fleet_ops import set_rtl_altitude_param
from gateway.fleet.mission import MissionItem
from gateway.fleet.vehicle import ConnectionState
from gateway.registry.spec import VehicleSpec
from tests.helpers.timing import scaled
from tests.real.flying import fly_mission, same_items, square, until

pytestmark = pytest.mark.real


async def test_px4_refuses_a_bad_mission_unarmed_and_flies_a_good_one_at_its_altitude(px4, registry):
    v = await registry.add(VehicleSpec(id="px1", url=px4.url))
    await v.wait_for_state(ConnectionState.READY, within_s=scaled(90))
    assert v.autopilot == "px4"
    items = square(v, 30.0, 15.0)

    # PX4 checks a mission after acknowledging it: its verdict comes back as the refusal, in its words
    bad = [items[0], MissionItem(kind="takeoff", lat=items[1].lat, lon=items[1].lon, alt_rel_m=10)]
    with pytest.raises(CommandFailed, match=r"rejected the mission \(2 items\): Mission rejected: takeoff"):
        await v.upload_mission(bad)
    with pytest.raises(CommandFailed, match="rejected its uploaded mission"):
        await v.start_mission()
    assert v.telemetry.fresh("armed") is False  # never armed for a rejected mission

    # no home slot: PX4 gets exactly the user's items, and gives them back
    assert await v.upload_mission(items) == 3
    back = await v.download_mission()
    assert same_items(back, items), back
    acceptance_m, _kind = await v.get_param("NAV_ACC_RAD")
    track = await fly_mission(v, 180)  # on the ground: PX4 takes off to the first item's altitude
    assert {k for k, *_ in track.samples} <= {0, 1, 2, 3}
    assert track.lowest_from(2) > 13.5, track.samples  # never back to home at ground level between items
    for item in items:  # the flown track passes each waypoint within PX4's acceptance radius
        assert track.closest_to(item.lat, item.lon) < acceptance_m + 1.0, item

    # flight modes: the common names map to PX4's; a mode PX4 lacks is refused with PX4's list
    await v.set_flight_mode("HOLD")
    await until("HOLD", lambda: v.telemetry.fresh("flight_mode") == "HOLD", 10, v)
    with pytest.raises(InvalidArgument, match=r"\(PX4\); its modes: HOLD, GUIDED, RTL, LAND, MISSION"):
        await v.set_flight_mode("SMART_RTL")
    value, _kind = await v.set_param("MPC_XY_VEL_MAX", 8.0)
    assert value == pytest.approx(8.0)

    # fleet_return_to_launch sets each drone's return altitude: PX4's RTL_RETURN_ALT, in metres
    await set_rtl_altitude_param(v, 20.0)
    assert (await v.get_param("RTL_RETURN_ALT"))[0] == pytest.approx(20.0)
    await v.set_flight_mode("RTL")
    await until("landed and disarmed", lambda: v.telemetry.fresh("armed") is False, 180, v)


async def test_px4_is_initialising_until_it_can_arm_and_a_refusal_says_why(px4, registry):
    v = await registry.add(VehicleSpec(id="px2", url=px4.url))
    waits: list[str] = []

    def ready() -> bool:
        waiting = v.status()["initialising"]  # what REST and list_drones show
        if waiting and waiting not in waits:
            waits.append(waiting)
        return v.state == ConnectionState.READY

    await until("ready", ready, 90, v)
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
