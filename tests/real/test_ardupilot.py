"""Real ArduCopter SITL (speed-up 5) through the gateway's vehicle layer and a real mavsdk_server."""

from __future__ import annotations

import pytest

from gateway.errors import InvalidArgument
from gateway.fleet import geo
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
