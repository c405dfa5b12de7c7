"""A mission is verified when it starts, on real PX4 SIH: another ground station (pymavlink on PX4's GCS
MAVLink instance) stores a mission with a waypoint 200 m up (limit 120); initiate_mission without
waypoints, resume_mission, set_flight_mode MISSION and set_current_waypoint are all refused naming item
3 (PX4's sequence number 2, plus one) and the rule, on the ground and in the air, and the autopilot (its
own telemetry) stays where it was. A DO_GRIPPER item, which PX4 stores but the gateway does not model,
is refused by name as unchecked (PX4 itself refuses to store a NAV_LOITER_TURNS: MAV_MISSION_UNSUPPORTED)."""

from __future__ import annotations

import asyncio
import time
from pathlib import Path

import pytest
from pymavlink import mavutil

from gateway.fleet import geo
from tests.helpers.gcs_mission import GcsItem, upload
from tests.helpers.timing import scaled
from tests.real.test_tour_px4 import PX4
from tests.real.tour import Tour, boot, gateway_over

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]

#: Real time (the fixtures' ``px4`` reads this): at speed factor 3 the takeoff after the second ground
#: station's mission upload got no answer from mavsdk_server to its MIS_TAKEOFF_ALT write within 10 s,
#: every run but the first of six; at 1 it passes. Not yet explained.
PX4_SPEED_FACTOR = 1.0

mav = mavutil.mavlink
ALTITUDE = "max_altitude: mission item 3: waypoint altitude 200 m exceeds the limit of 120 m"


async def where(t: Tour, d: str) -> tuple[str, bool, float, tuple[float, float]]:
    """The autopilot's own mode, armed state, altitude above home and position."""
    mode = (await t.ok("get_flight_mode", drone_id=d))["value"]
    armed = (await t.ok("get_armed", drone_id=d))["value"]
    pos = await t.ok("get_position", drone_id=d)
    return str(mode), bool(armed), float(pos["alt_m"]), (pos["lat_deg"], pos["lon_deg"])


async def test_a_stored_mission_is_checked_at_every_start_on_px4(launch, tmp_path: Path) -> None:
    autopilots = launch("px4", 1)
    gcs = autopilots[0].gcs
    assert gcs is not None
    async with gateway_over(tmp_path, PX4, autopilots) as (t, _settings):
        d = t.ids[0]
        mode, armed, _alt, here = await where(t, d)
        near = geo.offset_position(*here, 50.0, 0.0)
        far = geo.offset_position(*here, 100.0, 0.0)
        items = [
            GcsItem(mav.MAV_CMD_NAV_TAKEOFF, alt=10),
            GcsItem(mav.MAV_CMD_NAV_WAYPOINT, *near, 30),
            GcsItem(mav.MAV_CMD_NAV_WAYPOINT, *far, 200),
        ]
        await asyncio.to_thread(upload, gcs, items, home_slot=False)
        # on a loaded machine PX4's home position can go stale for a moment ("not ready: waiting for the
        # home position", a refusal of its own): the refusals below are the mission's, so ready first
        await boot(t)

        began = time.monotonic()
        await t.refused("initiate_mission", ALTITUDE, drone_id=d, wait=False)
        # printed, never asserted: the refusal includes reading the mission back from the autopilot
        print(
            f"\nFIGURE initiate_mission refused after reading back 3 items: {time.monotonic() - began:.2f} s"
        )
        await t.refused("initiate_mission", "waypoints is an empty list", drone_id=d, waypoints=[])
        await t.refused("resume_mission", ALTITUDE, drone_id=d)
        await t.refused("set_flight_mode", ALTITUDE, drone_id=d, mode="MISSION")
        assert (await where(t, d))[:2] == (mode, armed) == (mode, False)

        took = await t.ok("takeoff", drone_id=d, alt_m=10)
        took = await t.finish(took, 120)
        assert took["status"] == "succeeded", took
        # PX4 ends its TAKEOFF mode in HOLD once at its own acceptance radius, which can come a few seconds
        # after the gateway's takeoff has succeeded: the mode the refusals must leave is that HOLD
        held = await t.until(
            "get_flight_mode", lambda a: a["value"] == "HOLD", 30, "PX4's HOLD after its takeoff", drone_id=d
        )
        flying = str(held["value"])
        await t.refused("resume_mission", ALTITUDE, drone_id=d)
        await t.refused("set_flight_mode", ALTITUDE, drone_id=d, mode="MISSION")
        await t.refused("set_current_waypoint", ALTITUDE, drone_id=d, index=2)
        mode, armed, alt, _ = await where(t, d)
        assert mode == flying and armed and alt < 15.0, (mode, armed, alt)

        # an item PX4 stores and the gateway does not model
        grip = [
            GcsItem(mav.MAV_CMD_NAV_WAYPOINT, *near, 20),
            GcsItem(mav.MAV_CMD_DO_GRIPPER, frame=mav.MAV_FRAME_MISSION, params=(1, 0, 0, 0)),
        ]
        await asyncio.to_thread(upload, gcs, grip, home_slot=False)
        text = await t.refused(
            "resume_mission", "mission_unchecked: mission item 2: DO_GRIPPER (211) is a", drone_id=d
        )
        assert "cannot check on PX4" in text
        mode, armed, alt, _ = await where(t, d)
        assert mode == flying and armed and alt > 5.0, (mode, armed, alt)
        landed = await t.finish(await t.ok("land", drone_id=d), 120)
        assert landed["status"] == "succeeded", landed
