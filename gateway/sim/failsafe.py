"""Failsafes: what triggers them at each step (GCS heartbeat loss, GPS loss, battery) and the reactions
(GCS loss, battery, EKF) and the geofence, with ArduCopter's actions and texts."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.modes import REQUIRES_POSITION, Mode

if TYPE_CHECKING:
    from gateway.sim.host import SimHost


# Failsafe action numbers (FailsafeAction in ArduCopter / BATT_FS_*_ACT values).
FS_NONE, FS_LAND, FS_RTL, FS_SMARTRTL, FS_SMARTRTL_LAND, FS_TERMINATE, FS_AUTO_LAND_START, FS_BRAKE_LAND = (
    range(8)
)


# FS_GCS_ENABLE value -> failsafe action (ArduCopter failsafe_gcs_on_event).
_GCS_ACTIONS = {
    1: FS_RTL,
    2: FS_RTL,
    3: FS_SMARTRTL,
    4: FS_SMARTRTL_LAND,
    5: FS_LAND,
    6: FS_AUTO_LAND_START,
    7: FS_BRAKE_LAND,
}


class FailsafeMixin:
    """Failsafe and fence part of FlightController (shares its state and helpers)."""

    v: SimHost

    # ------------------------------------------------------------------------------------------------
    # failsafes
    def do_failsafe_action(self, action: int) -> None:
        v = self.v
        if action == FS_NONE:
            return
        if action == FS_TERMINATE:
            self.disarm()
            return
        if action in (FS_SMARTRTL, FS_SMARTRTL_LAND):
            if self.set_mode(Mode.SMART_RTL)[0]:
                return
            if action == FS_SMARTRTL_LAND:
                v.text(mav.MAV_SEVERITY_WARNING, "SmartRTL Unavailable, Using Land Mode")
                self.set_mode(Mode.LAND)
                return
            v.text(mav.MAV_SEVERITY_WARNING, "SmartRTL Unavailable, Trying RTL Mode")
        if action == FS_BRAKE_LAND:
            if self.set_mode(Mode.BRAKE)[0]:
                return
            v.text(mav.MAV_SEVERITY_WARNING, "Trying Land Mode")
            self.set_mode(Mode.LAND)
            return
        if action == FS_LAND:
            self._land_with_pause()
            return
        # RTL (and AUTO DO_LAND_START, which the simulator answers with RTL)
        if not self.set_mode(Mode.RTL)[0]:
            self._land_with_pause()

    def _land_with_pause(self) -> None:
        self.set_mode(Mode.LAND)
        self.land_pause_until = self.v.t + 4.0

    def _should_disarm_on_failsafe(self) -> bool:
        v = self.v
        if v.mode in (Mode.STABILIZE, Mode.ACRO):
            return v.landed
        if v.mode == Mode.AUTO:
            return not v.auto_armed and v.landed
        return v.landed

    def gcs_failsafe(self, fs_gcs: int) -> None:
        v = self.v
        action = _GCS_ACTIONS.get(fs_gcs, FS_RTL)
        if not v.armed:
            v.text(mav.MAV_SEVERITY_WARNING, "GCS Failsafe")
            return
        if self._should_disarm_on_failsafe():
            self.disarm()
            v.text(mav.MAV_SEVERITY_WARNING, "GCS Failsafe - Disarming")
            return
        v.text(mav.MAV_SEVERITY_WARNING, "GCS Failsafe")
        self.do_failsafe_action(action)

    def battery_failsafe(self, action: int) -> None:
        v = self.v
        if v.armed and self._should_disarm_on_failsafe():
            self.disarm()
            v.text(mav.MAV_SEVERITY_WARNING, "Battery Failsafe - Disarming")
            return
        v.text(mav.MAV_SEVERITY_WARNING, "Battery Failsafe")
        if v.armed:
            self.do_failsafe_action(action)

    def ekf_check(self) -> None:
        """Position lost while flying a mode that needs it: EKF failsafe -> LAND (FS_EKF_ACTION)."""
        v = self.v
        bad = not v.position_ok and v.t >= v.timeline.ekf_gps
        if not bad:
            if self.ekf_failsafe:
                self.ekf_failsafe = False
                v.text(mav.MAV_SEVERITY_CRITICAL, "EKF Failsafe Cleared")
            return
        if self.ekf_failsafe or not v.flying:
            return
        self.ekf_failsafe = True
        v.text(mav.MAV_SEVERITY_CRITICAL, "EKF Failsafe")
        if v.mode not in REQUIRES_POSITION:
            return
        if int(self._p("FS_EKF_ACTION")) == 2:
            self._enter(Mode.ALT_HOLD)
        else:
            self._enter(Mode.LAND)
            self.land_pause_until = v.t + 4.0

    # ------------------------------------------------------------------------------------------------
    # geofence (FENCE_ENABLE, FENCE_TYPE bits 1 = max altitude, 2 = circle around home)
    def _fence_types(self) -> int:
        if self._p("FENCE_ENABLE") <= 0:
            return 0
        return int(self._p("FENCE_TYPE")) & 0b11

    def _breaches_at(self, north: float, east: float, up: float, margin: float = 0.0) -> int:
        types = self._fence_types()
        breaches = 0
        if types & 1 and up - self._home_up() > self._p("FENCE_ALT_MAX") - margin:
            breaches |= 1
        hn, he = self._home_ne()
        if types & 2 and math.hypot(north - hn, east - he) > self._p("FENCE_RADIUS") - margin:
            breaches |= 2
        return breaches

    def destination_allowed(self, north: float, east: float, up: float) -> bool:
        """GUIDED refuses destinations outside the fence (ModeGuided::set_destination)."""
        return not self._breaches_at(north, east, up)

    def fence_check(self) -> None:
        v = self.v
        b = v.body
        breaches = self._breaches_at(b.north, b.east, b.up) if v.armed else 0
        new = breaches & ~self.fence_breaches
        self.fence_breaches = breaches
        if not new:
            return
        if not v.landed:
            names = [name for bit, name in ((1, "Max Alt"), (2, "Circle")) if new & bit]
            plural = "s" if len(names) > 1 else ""
            v.text(mav.MAV_SEVERITY_NOTICE, f"{' and '.join(names)} fence{plural} breached")
        action = int(self._p("FENCE_ACTION"))
        if action == 0 or v.landed:
            return
        if v.mode in (Mode.LAND, Mode.RTL) or (v.mode == Mode.AUTO and self.descending):
            return
        if action == 2:
            self.set_mode(Mode.LAND)
        elif action == 4:
            if not self.set_mode(Mode.BRAKE)[0]:
                self.set_mode(Mode.LAND)
        elif action in (3, 5) and self.set_mode(Mode.SMART_RTL)[0]:
            return
        elif not self.set_mode(Mode.RTL)[0]:
            self.set_mode(Mode.LAND)


def check_failsafes(v: SimHost) -> None:
    """What triggers the failsafes, judged at each step: GCS heartbeat loss, GPS loss, battery."""
    # GCS heartbeat loss: only heartbeats from MAV_GCS_SYSID count (ArduPilot's sysid_mygcs_seen).
    fs_gcs = int(v.params.get("FS_GCS_ENABLE"))
    if fs_gcs and v._gcs_last_seen is not None:
        timeout = v.params.get("FS_GCS_TIMEOUT")
        lost = v.t - v._gcs_last_seen > timeout
        if lost and not v.failsafe_gcs:
            v.failsafe_gcs = True
            v.flight.gcs_failsafe(fs_gcs)
        elif not lost and v.failsafe_gcs:
            v.failsafe_gcs = False
            v.text(mav.MAV_SEVERITY_WARNING, "GCS Failsafe Cleared")
    elif v.failsafe_gcs and not fs_gcs:
        v.failsafe_gcs = False
    # GPS loss -> the EKF loses its position a moment later.
    if v.gps_lost and v._gps_lost_at is None:
        v._gps_lost_at = v.t
    elif not v.gps_lost:
        v._gps_lost_at = None
    v.flight.ekf_check()
    # Battery: AP_BattMonitor only checks its failsafes while armed
    p = v.params.get
    if not v.armed:
        v.battery.check(v.t, 0, 0, 0, 0, 0)  # resets the low-voltage timer
        return
    level = v.battery.check(
        v.t,
        p("BATT_LOW_VOLT"),
        p("BATT_LOW_MAH"),
        p("BATT_CRT_VOLT"),
        p("BATT_CRT_MAH"),
        p("BATT_LOW_TIMER"),
    )
    if level:
        b = v.battery
        v.text(
            mav.MAV_SEVERITY_WARNING,
            f"Battery 1 is {level} {b.voltage:.2f}V used {b.consumed_mah:.0f} mAh",
        )
        action = int(p("BATT_FS_CRT_ACT") if level == "critical" else p("BATT_FS_LOW_ACT"))
        v.flight.battery_failsafe(action)
