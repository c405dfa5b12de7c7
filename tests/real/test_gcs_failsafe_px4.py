"""PX4's data-link-loss failsafe as the README gives it, flown on PX4 SIH: the gateway flies the drone
(takeoff, then PX4's own Hold), then goes silent (the gateway stops: its mavsdk_server sidecar, the one
ground station PX4 hears, stops with it), and PX4 returns to launch within COM_DL_LOSS_T plus its
failsafe hold COM_FAIL_ACT_T.

Read from PX4's source (commander/Commander.cpp, dataLinkCheck: the link is lost after COM_DL_LOSS_T
seconds without a HEARTBEAT of type GCS on any MAVLink instance, telemetry_status.heartbeat_type_gcs;
commander/failsafe/failsafe.cpp: gcs_connection_lost -> NAV_DLL_ACT, after COM_FAIL_ACT_T seconds of
Hold; COM_DLL_EXCEPT exempts mission or offboard). A watcher on PX4's ground-station port (UDP 18570 +
instance) reads the HEARTBEATs and writes the parameters as a pilot's ground station would; it sends no
HEARTBEAT of its own (one of type GCS would keep the link "alive"). Figures are printed, never asserted
as times beyond PX4's own deadline."""

from __future__ import annotations

import asyncio
import struct
import threading
import time
from pathlib import Path
from typing import Any

import pytest
from pymavlink import mavutil

from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.test_tour_px4 import PX4
from tests.real.tour import gateway_over

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]

#: Real time (the fixtures' ``px4`` reads this): the checks time PX4's own timeouts (COM_DL_LOSS_T,
#: COM_FAIL_ACT_T, which PX4 counts on its simulated clock) with the wall clock, and the README's
#: values are written over the ones rcS stretches by the speed factor; at factor F the failsafe would
#: come F times sooner in wall time and "never before COM_DL_LOSS_T" could not hold.
PX4_SPEED_FACTOR = 1.0

#: the settings the README gives (section "On the autopilot", PX4), each with its type on PX4
DOCUMENTED: dict[str, tuple[float, int]] = {
    "NAV_DLL_ACT": (2, mavutil.mavlink.MAV_PARAM_TYPE_INT32),  # 2: Return mode
    "COM_DL_LOSS_T": (10, mavutil.mavlink.MAV_PARAM_TYPE_INT32),  # seconds without a GCS HEARTBEAT
    "COM_FAIL_ACT_T": (5.0, mavutil.mavlink.MAV_PARAM_TYPE_REAL32),  # Hold before the action
    "COM_DLL_EXCEPT": (0, mavutil.mavlink.MAV_PARAM_TYPE_INT32),  # no mode exempt
}


def watcher(address: str) -> tuple[Any, int]:
    """A link on PX4's ground-station port that says nothing PX4 counts as a ground station: a
    PARAM_REQUEST_READ makes PX4 answer to its address, and then stream to it."""
    conn = mavutil.mavlink_connection(address, source_system=254, source_component=191)
    deadline = time.monotonic() + scaled(30)
    while True:
        conn.mav.param_request_read_send(0, 0, b"NAV_DLL_ACT", -1)
        hb = conn.recv_match(type="HEARTBEAT", blocking=True, timeout=1.0)
        if hb is not None and hb.autopilot == mavutil.mavlink.MAV_AUTOPILOT_PX4:
            return conn, hb.get_srcSystem()
        assert time.monotonic() < deadline, f"no HEARTBEAT from PX4 on {address}"


def set_params(conn: Any, target: int, values: dict[str, tuple[float, int]]) -> None:
    """PARAM_SET as QGroundControl sends it to PX4: an int32's bytes in the float field (PX4 encodes
    parameters bytewise, MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE), read back the same way."""
    for name, (value, kind) in values.items():
        integer = kind == mavutil.mavlink.MAV_PARAM_TYPE_INT32
        wire = struct.unpack("<f", struct.pack("<i", int(value)))[0] if integer else float(value)
        deadline = time.monotonic() + scaled(20)
        while True:
            conn.mav.param_set_send(target, 1, name.encode(), wire, kind)
            # PX4 echoes a change only: read the value back either way
            conn.mav.param_request_read_send(target, 1, name.encode(), -1)
            echo = conn.recv_match(type="PARAM_VALUE", blocking=True, timeout=1.0)
            if echo is not None and echo.param_id == name:
                got = echo.param_value
                if integer:
                    got = struct.unpack("<i", struct.pack("<f", got))[0]
                if abs(got - value) < 1e-3:
                    break
            assert time.monotonic() < deadline, f"{name} was not set to {value} (last: {echo})"


class Heard(threading.Thread):
    """Reads the watcher's link as fast as PX4 streams to it (its ground-station port carries several
    messages at 50 Hz): the autopilot's latest mode and armed state, and its STATUSTEXTs."""

    def __init__(self, conn: Any, target: int) -> None:
        super().__init__(name="px4-watcher", daemon=True)
        self.conn, self.target = conn, target
        self.stop = threading.Event()
        self.mode: str | None = None
        self.armed: bool | None = None
        self.modes: list[str] = []
        self.said: list[str] = []

    def run(self) -> None:
        while not self.stop.is_set():
            msg = self.conn.recv_match(type=["HEARTBEAT", "STATUSTEXT"], blocking=True, timeout=0.5)
            if msg is None or msg.get_srcSystem() != self.target:
                continue
            if msg.get_type() == "STATUSTEXT":
                self.said.append(msg.text)
                continue
            self.mode = mode_of(msg)
            self.armed = bool(msg.base_mode & mavutil.mavlink.MAV_MODE_FLAG_SAFETY_ARMED)
            if not self.modes or self.modes[-1] != self.mode:
                self.modes.append(self.mode)


def mode_of(hb: Any) -> str:
    return str(mavutil.mode_string_v10(hb))


async def test_px4_returns_when_the_gateway_goes_silent(px4: Autopilot, tmp_path: Path) -> None:
    assert px4.gcs is not None
    conn: Any = None
    heard: Heard | None = None
    try:
        async with gateway_over(tmp_path, PX4, [px4]) as (tour, _settings):
            conn, target = watcher(px4.gcs)
            set_params(conn, target, DOCUMENTED)
            heard = Heard(conn, target)
            heard.start()
            d = tour.ids[0]
            took_off = await tour.finish(await tour.ok("takeoff", drone_id=d, alt_m=10), 120)
            assert took_off["status"] == "succeeded", took_off
            # the gateway's HEARTBEAT keeps the link: PX4 holds, longer than COM_DL_LOSS_T + COM_FAIL_ACT_T
            await asyncio.sleep(20.0)
            assert heard.modes[-1] == "LOITER" and "RTL" not in heard.modes, heard.modes  # PX4's Hold
        # The gateway has stopped, its sidecar with it: no ground station speaks to PX4 any more.
        silent_at = time.monotonic()
        loss_s = DOCUMENTED["COM_DL_LOSS_T"][0] + DOCUMENTED["COM_FAIL_ACT_T"][0]
        deadline = silent_at + loss_s + scaled(15)
        while heard.mode != "RTL":
            assert heard.armed, f"disarmed before the failsafe: {heard.modes}"
            assert time.monotonic() < deadline, (
                f"no data-link-loss failsafe within {loss_s:g} s: {heard.modes}; "
                f"PX4 said {heard.said[-10:]}; {px4.log_tail(20)}"
            )
            await asyncio.sleep(0.2)
        after = time.monotonic() - silent_at
        print(f"\nPX4 data-link-loss failsafe (RTL) {after:.1f} s after the gateway stopped")
        # never before PX4's own timeout: the return is the data-link loss, not another failsafe
        assert after >= DOCUMENTED["COM_DL_LOSS_T"][0], (after, heard.modes, heard.said)
        assert heard.modes[-2:] == ["LOITER", "RTL"], heard.modes
    finally:
        if heard is not None:
            heard.stop.set()
            heard.join(timeout=5)
        if conn is not None:
            conn.close()
