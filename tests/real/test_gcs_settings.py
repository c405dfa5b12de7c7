"""The ground-station settings the README gives for ArduPilot, flown on ArduCopter SITL:

- ``MAV_GCS_SYSID 245`` (the gateway, ``GATEWAY_GCS_SYSID``) with ``MAV_GCS_SYSID_HI 255``: ArduPilot
  takes RC_CHANNELS_OVERRIDE only from a system id it counts as a ground station (GCS_Common.cpp,
  handle_rc_channels_override -> GCS::sysid_is_gcs: MAV_GCS_SYSID alone, or the range up to
  MAV_GCS_SYSID_HI). A pilot's ground station at 255 (MAVProxy, QGroundControl) that takes a copter over
  in LOITER flies it with its sticks: the copter keeps its altitude. With 245 alone its overrides are
  dropped and LOITER sinks without throttle.
- ``FS_GCS_ENABLE 1``: when the gateway (and every other ground station in that range) goes silent for
  FS_GCS_TIMEOUT, the copter flying in GUIDED returns to launch.

A pilot's link (pymavlink, system id 255, on SITL's SERIAL1) sends the override and switches the mode as
MAVProxy does. Figures are printed, never asserted as times."""

from __future__ import annotations

import asyncio
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from pymavlink import mavutil

from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.test_tour_ardupilot import ARDUCOPTER
from tests.real.tour import gateway_over

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]

#: the settings the README gives (section "On the autopilot"), written as a pilot's ground station would
DOCUMENTED = {"MAV_GCS_SYSID": 245, "MAV_GCS_SYSID_HI": 255, "FS_GCS_ENABLE": 1}
#: SITL runs at speed-up 5: its 5 s FS_GCS_TIMEOUT is 1 s of wall time, the period of mavsdk_server's
#: HEARTBEAT, so the failsafe would come and go between two of them; 10 s of SITL time is 2 s of wall time
#: (5 s of real time at speed-up 1 holds five HEARTBEATs)
SITL_TIMEOUT = {"FS_GCS_TIMEOUT": 10}
COPTER = mavutil.mavlink.enums["COPTER_MODE"]
LOITER = next(k for k, v in COPTER.items() if v.name == "COPTER_MODE_LOITER")
GUIDED = next(k for k, v in COPTER.items() if v.name == "COPTER_MODE_GUIDED")
RTL = next(k for k, v in COPTER.items() if v.name == "COPTER_MODE_RTL")
CENTRE = 1500  # every stick centred, throttle included: LOITER holds its altitude


def pilot_link(address: str) -> tuple[Any, int]:
    """A pilot's ground station (system id 255, as MAVProxy) on the autopilot's second port."""
    conn = mavutil.mavlink_connection(
        address, source_system=255, source_component=mavutil.mavlink.MAV_COMP_ID_MISSIONPLANNER
    )
    hb = conn.recv_match(type="HEARTBEAT", blocking=True, timeout=scaled(30))
    assert hb is not None, f"no HEARTBEAT from the autopilot on {address}"
    return conn, hb.get_srcSystem()


def set_params(conn: Any, target: int, values: dict[str, int]) -> None:
    for name, value in values.items():
        deadline = time.monotonic() + scaled(20)
        while True:
            conn.mav.param_set_send(
                target, 1, name.encode(), float(value), mavutil.mavlink.MAV_PARAM_TYPE_INT32
            )
            echo = conn.recv_match(type="PARAM_VALUE", blocking=True, timeout=1.0)
            if echo is not None and echo.param_id == name and round(echo.param_value) == value:
                break
            assert time.monotonic() < deadline, f"{name} was not set to {value} (last: {echo})"


class Sticks(threading.Thread):
    """The pilot's ground station while it holds the sticks: HEARTBEAT at 1 Hz, RC_CHANNELS_OVERRIDE with
    every stick centred at 10 Hz, and the mode switches asked of it (the only writer of the link)."""

    def __init__(self, conn: Any, target: int) -> None:
        super().__init__(name="pilot-sticks", daemon=True)
        self.conn, self.target = conn, target
        self.stop = threading.Event()
        self.modes: list[int] = []

    def run(self) -> None:
        last_heartbeat = 0.0
        while not self.stop.is_set():
            now = time.monotonic()
            if now - last_heartbeat >= 1.0:
                self.conn.mav.heartbeat_send(
                    mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0
                )
                last_heartbeat = now
            while self.modes:
                self.conn.mav.set_mode_send(
                    self.target, mavutil.mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, self.modes.pop(0)
                )
            self.conn.mav.rc_channels_override_send(self.target, 1, *([CENTRE] * 4), *([65535] * 4))
            self.stop.wait(0.1)


async def test_a_pilot_takes_over_in_loiter_and_the_gcs_failsafe_acts_when_the_gateway_is_silent(
    arducopter: Autopilot, tmp_path: Path
) -> None:
    assert arducopter.gcs is not None
    conn: Any = None
    sticks: Sticks | None = None
    try:
        async with gateway_over(tmp_path, ARDUCOPTER, [arducopter]) as (tour, _settings):
            # SITL opens its second port once the first (the gateway's) is connected
            conn, target = pilot_link(arducopter.gcs)
            set_params(conn, target, {**SITL_TIMEOUT, **DOCUMENTED})
            sticks = Sticks(conn, target)
            d = tour.ids[0]
            took_off = await tour.finish(await tour.ok("takeoff", drone_id=d, alt_m=15), 90)
            assert took_off["status"] == "succeeded", took_off

            # The pilot takes over: sticks centred, LOITER. The copter keeps its altitude.
            sticks.start()
            sticks.modes.append(LOITER)
            await tour.until("get_flight_mode", lambda r: r["value"] == "LOITER", 20, "LOITER", drone_id=d)
            heights: list[float] = []
            loop = asyncio.get_running_loop()
            watch_until = loop.time() + scaled(8.0)  # 40 s of flight at SITL's speed-up 5
            while loop.time() < watch_until:
                heights.append((await tour.position(d))["alt_m"])
                await asyncio.sleep(0.3)
            low, high = min(heights), max(heights)
            print(f"\nLOITER under the pilot's sticks: {low:.1f}..{high:.1f} m, {len(heights)} readings")
            assert len(heights) >= 10 and min(heights) > 13.0 and max(heights) < 17.0, heights
            assert (await tour.ok("get_flight_mode", drone_id=d))["value"] == "LOITER"

            # The pilot hands back in GUIDED (the gateway's mode) and lets go of the link.
            sticks.modes.append(GUIDED)
            await tour.until("get_flight_mode", lambda r: r["value"] == "GUIDED", 20, "GUIDED", drone_id=d)
            sticks.stop.set()
            sticks.join(timeout=scaled(5))
            # The pilot is silent, the gateway is not: its HEARTBEAT (245) alone holds the failsafe off
            # for three FS_GCS_TIMEOUTs (2 s of wall time each)
            held_until = loop.time() + 6.0
            while loop.time() < held_until:
                assert (await tour.ok("get_flight_mode", drone_id=d))["value"] == "GUIDED"
                await asyncio.sleep(0.3)
        # The gateway has stopped: nothing in 245..255 speaks. FS_GCS_ENABLE 1: the copter returns.
        silent_at = time.monotonic()
        deadline = silent_at + scaled(60)
        mode = None
        while mode != RTL:
            hb = conn.recv_match(type="HEARTBEAT", blocking=True, timeout=1.0)
            if hb is not None and hb.get_srcSystem() == target:
                mode = hb.custom_mode
            assert time.monotonic() < deadline, f"no GCS failsafe: still in mode {mode}"
        print(f"GCS failsafe (RTL) {time.monotonic() - silent_at:.1f} s after the gateway went silent")
    finally:
        if sticks is not None:
            sticks.stop.set()
        if conn is not None:
            conn.close()
