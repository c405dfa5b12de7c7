"""ArduCopter's boot as the simulator plays it: the timeline of its milestones (simulated seconds since
boot), the texts it sends on the way, its pre-arm checks (failing until the milestones they wait for)
and its periodic STAT_* parameters."""

from __future__ import annotations

from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.modes import REQUIRES_POSITION, Mode

if TYPE_CHECKING:
    from gateway.sim.host import SimHost


BOOT_TEXTS = [
    ("baro", "Barometer 1 calibration complete"),
    ("baro", "Barometer 2 calibration complete"),
    ("ready", "ArduPilot Ready"),
    ("ready", "AHRS: DCM active"),
    ("rc7", "RC7: SaveWaypoint LOW"),
    ("ekf_init", "EKF3 IMU0 initialised"),
    ("ekf_init", "EKF3 IMU1 initialised"),
    ("ekf_init", "AHRS: EKF3 active"),
    ("tilt", "EKF3 IMU0 tilt alignment complete"),
    ("tilt", "EKF3 IMU1 tilt alignment complete"),
    ("yaw_align", "EKF3 IMU0 MAG0 initial yaw alignment complete"),
    ("yaw_align", "EKF3 IMU1 MAG0 initial yaw alignment complete"),
    ("gps_detect", "GPS 1: probing for u-blox at 230400 baud"),
    ("gps_detect", "GPS 1: detected u-blox"),
    ("origin", "EKF3 IMU0 origin set"),
    ("origin", "Field Elevation Set: {field_elev}m"),
    ("origin2", "EKF3 IMU1 origin set"),
    ("ekf_gps", "EKF3 IMU0 is using GPS"),
    ("ekf_gps", "EKF3 IMU1 is using GPS"),
]

PREARM_DISPLAY_PERIOD_S = 30.0
PREARM_CHECK_PERIOD_S = 1.0


class BootSequence:
    """One boot of a `SimVehicle` (made again at each reboot): how far its timeline has got, and its
    pre-arm checks."""

    def __init__(self, v: SimHost) -> None:
        self.v = v
        self._text_i = 0
        self._prearm_next_display = 15.0 + 13.0
        self._prearm_checked_at: float | None = None
        self._prearm_bit = False
        self._next_stat = 30.0

    def step(self) -> None:
        v = self.v
        tl = v.timeline
        while self._text_i < len(BOOT_TEXTS):
            attr, text = BOOT_TEXTS[self._text_i]
            if v.t < getattr(tl, attr):
                break
            self._text_i += 1
            v.text(mav.MAV_SEVERITY_INFO, text.format(field_elev=round(v.frame.alt0)))
            if attr == "origin" and "origin set" in text:
                v.set_origin()
            if attr == "baro" and text.startswith("Barometer 2"):
                for name in ("BARO1_GND_PRESS", "BARO2_GND_PRESS", "INS_GYR_ID", "INS_ACC_ID"):
                    v.notify_param(name, v.params.get(name))
            if attr == "rc7":
                v.notify_param("EK3_SRC1_POSXY", 3)
        if v.t >= self._next_stat:
            self._next_stat += 30.0
            self.stat_params()
        if v.t >= self._prearm_next_display:
            self._prearm_next_display = v.t + PREARM_DISPLAY_PERIOD_S
            if not v.armed:
                failure = self.prearm_failure()
                if failure:
                    v.text(mav.MAV_SEVERITY_CRITICAL, f"PreArm: {failure}")

    def stat_params(self) -> None:
        v = self.v
        if v.flight_time_s > 0:
            v.notify_param("STAT_FLTTIME", round(v.flight_time_s))
        v.notify_param("STAT_RUNTIME", round(v.t))

    def prearm_bit(self) -> bool:
        """SYS_STATUS's pre-arm bit. ArduCopter re-runs its pre-arm checks about once a second, so the bit
        lags a mode change: right after GUIDED is selected it can still say "armable" while arming in
        GUIDED is refused with "Need Position Estimate" (seen on real ArduCopter SITL)."""
        v = self.v
        if self._prearm_checked_at is None or v.t - self._prearm_checked_at >= PREARM_CHECK_PERIOD_S:
            self._prearm_checked_at = v.t
            self._prearm_bit = self.prearm_failure() is None
        return self._prearm_bit

    def prearm_failure(self, mode: Mode | None = None) -> str | None:
        """First failing pre-arm check for ``mode`` (default: current), as ArduPilot words it."""
        failures = self.prearm_failures(mode)
        return failures[0] if failures else None

    def prearm_failures(self, mode: Mode | None = None) -> list[str]:
        """Every failing pre-arm check for ``mode`` (default: current), in the order ArduCopter 4.7
        reports them on an arming attempt (one "Arm: ..." text each; measured on SITL, see Timeline)."""
        v = self.v
        mode = v.mode if mode is None else mode
        checks = v.params.get("ARMING_CHECK") != 0
        failures = self._sensor_failures(checks)
        position = self._position_failure(checks, mode)
        if position:
            failures.append(position)
        if checks and v.t < v.timeline.mag_ok:
            failures.append("Battery 1 unhealthy")
        if checks:
            battery = self._battery_arming_failure()
            if battery:
                failures.append(f"Battery 1 {battery}")
            if v.failsafe_gcs:
                failures.append("GCS failsafe on")
        return failures

    def _sensor_failures(self, checks: bool) -> list[str]:
        """The inertial, attitude and compass checks, in ArduCopter's order."""
        tl = self.v.timeline
        t = self.v.t
        failures: list[str] = []
        if t < tl.tilt:
            failures.append("Need Alt Estimate")
        if checks and t < tl.accels_ok:
            failures.append("Accels inconsistent")
        elif checks and t < tl.prearm_ok:
            failures.append("Gyros inconsistent")
        if t < tl.tilt:
            failures.append("EKF attitude is bad")
        if checks and t < tl.mag_ok:
            failures.append("Compass 1 not healthy")
        return failures

    def _position_failure(self, checks: bool, mode: Mode) -> str | None:
        """The first of the GPS fix, home and position-estimate checks that fails."""
        v = self.v
        tl = v.timeline
        if checks and tl.gps_detect <= v.t < tl.gps_fix:
            return "GPS 1: Bad fix"
        if not v.origin_set:
            return "AHRS: waiting for home"
        if mode in REQUIRES_POSITION and not v.position_ok:
            return "Need Position Estimate"
        return None

    def _battery_arming_failure(self) -> str | None:
        """AP_BattMonitor_Backend::arming_checks: thresholds compared with the present state, no timer."""
        v = self.v
        p = v.params.get
        b = v.battery
        remaining = b.capacity_mah - b.consumed_mah
        checks = [
            (p("BATT_LOW_VOLT") > 0 and b.voltage < p("BATT_LOW_VOLT"), "low voltage failsafe"),
            (p("BATT_LOW_MAH") > 0 and remaining < p("BATT_LOW_MAH"), "low capacity failsafe"),
            (p("BATT_CRT_VOLT") > 0 and b.voltage < p("BATT_CRT_VOLT"), "critical voltage failsafe"),
            (p("BATT_CRT_MAH") > 0 and remaining < p("BATT_CRT_MAH"), "critical capacity failsafe"),
            (p("BATT_ARM_VOLT") > 0 and b.voltage < p("BATT_ARM_VOLT"), "below minimum arming voltage"),
            (p("BATT_ARM_MAH") > 0 and remaining < p("BATT_ARM_MAH"), "below minimum arming capacity"),
        ]
        return next((text for failed, text in checks if failed), None)
