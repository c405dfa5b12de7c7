"""Kinematic multicopter model: position, velocity and yaw with speed and acceleration limits.

Not a dynamics model: the vehicle follows a position or velocity target the way ArduPilot's position
controller shapes it (square-root braking curve, acceleration limit), in a local NED frame around
the EKF origin. Callers integrate in small steps (see ``MAX_STEP_S``) whatever wall time elapsed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

MAX_STEP_S = 0.05
EARTH_RADIUS_M = 6378137.0


def wrap_360(deg: float) -> float:
    return deg % 360.0


def wrap_180(deg: float) -> float:
    return (deg + 180.0) % 360.0 - 180.0


@dataclass
class LocalFrame:
    """Flat-earth conversion around an origin; precise to centimetres over a few kilometres."""

    lat0: float
    lon0: float
    alt0: float  # AMSL of the origin (ground level), metres
    _m_per_deg_lat: float = field(init=False)
    _m_per_deg_lon: float = field(init=False)

    def __post_init__(self) -> None:
        self._m_per_deg_lat = math.pi / 180.0 * EARTH_RADIUS_M
        self._m_per_deg_lon = self._m_per_deg_lat * math.cos(math.radians(self.lat0))

    def to_ne(self, lat: float, lon: float) -> tuple[float, float]:
        return (lat - self.lat0) * self._m_per_deg_lat, (lon - self.lon0) * self._m_per_deg_lon

    def to_latlon(self, north: float, east: float) -> tuple[float, float]:
        return self.lat0 + north / self._m_per_deg_lat, self.lon0 + east / self._m_per_deg_lon


@dataclass
class Limits:
    """Speed (m/s) and acceleration (m/s^2) limits the position controller shapes its path with."""

    speed_h: float = 10.0
    speed_up: float = 2.5
    speed_dn: float = 1.5
    accel_h: float = 2.5
    accel_v: float = 1.0
    #: horizontal jerk limit (m/s^3) while speeding up, for legs ArduPilot plans as S-curves (WPNAV_JERK
    #: in RTL); None: the acceleration limit applies at once (GUIDED repositions)
    jerk_h: float | None = None


@dataclass
class Body:
    north: float = 0.0
    east: float = 0.0
    up: float = 0.0  # metres above the origin (ground)
    vn: float = 0.0
    ve: float = 0.0
    vu: float = 0.0
    yaw: float = 0.0  # degrees 0..360
    yaw_rate: float = 0.0  # deg/s
    accel_n: float = 0.0
    accel_e: float = 0.0

    @property
    def ground_speed(self) -> float:
        return math.hypot(self.vn, self.ve)

    def stop(self) -> None:
        self.vn = self.ve = self.vu = 0.0
        self.accel_n = self.accel_e = 0.0

    # -- horizontal -------------------------------------------------------------------------------
    def _apply_h(
        self, want_n: float, want_e: float, accel: float, dt: float, jerk: float | None = None
    ) -> None:
        dvn, dve = want_n - self.vn, want_e - self.ve
        dv = math.hypot(dvn, dve)
        if jerk is not None and math.hypot(want_n, want_e) > self.ground_speed:  # speeding up: S-curve
            accel = min(accel, math.hypot(self.accel_n, self.accel_e) + jerk * dt)
        max_dv = accel * dt
        if dv > max_dv > 0:
            dvn, dve = dvn * max_dv / dv, dve * max_dv / dv
        self.accel_n, self.accel_e = (dvn / dt, dve / dt) if dt > 0 else (0.0, 0.0)
        self.vn += dvn
        self.ve += dve
        self.north += self.vn * dt
        self.east += self.ve * dt

    def move_h_to(self, north: float, east: float, lim: Limits, dt: float) -> float:
        """One step towards a horizontal target; returns the remaining distance."""
        dn, de = north - self.north, east - self.east
        dist = math.hypot(dn, de)
        if dist < 0.02 and self.ground_speed < 0.3:
            self.north, self.east = north, east
            self.vn = self.ve = self.accel_n = self.accel_e = 0.0
            return 0.0
        speed = min(lim.speed_h, math.sqrt(2.0 * lim.accel_h * dist * 0.9))
        if speed * dt >= dist:
            speed = dist / dt
        want_n, want_e = (dn / dist * speed, de / dist * speed) if dist > 0 else (0.0, 0.0)
        self._apply_h(want_n, want_e, lim.accel_h, dt, lim.jerk_h)
        return math.hypot(north - self.north, east - self.east)

    def move_h_velocity(self, vn: float, ve: float, lim: Limits, dt: float) -> None:
        self._apply_h(vn, ve, lim.accel_h, dt)

    # -- vertical ---------------------------------------------------------------------------------
    def move_v_velocity_to_floor(
        self, floor_up: float, fast: float, slow: float, lim: Limits, dt: float, kp: float = 1.0
    ) -> None:
        """Descend at up to ``fast`` m/s, slowing with ArduPilot's square-root controller (gain ``kp``,
        acceleration ``lim.accel_v``) to reach ``floor_up`` at ``slow`` m/s, then go on at ``slow``."""
        err = self.up - floor_up
        linear = lim.accel_v / (kp * kp)
        if err > linear:
            rate = math.sqrt(2.0 * lim.accel_v * (err - linear / 2.0))
        else:
            rate = kp * max(0.0, err)
        self._apply_v(-min(fast, max(slow, rate)), lim.accel_v, dt)

    def _apply_v(self, want: float, accel: float, dt: float) -> None:
        dv = want - self.vu
        max_dv = accel * dt
        if abs(dv) > max_dv:
            dv = math.copysign(max_dv, dv)
        self.vu += dv
        self.up += self.vu * dt

    def move_v_to(self, up: float, lim: Limits, dt: float) -> float:
        """One step towards a target height; returns the remaining (signed) height error."""
        err = up - self.up
        if abs(err) < 0.02 and abs(self.vu) < 0.2:
            self.up, self.vu = up, 0.0
            return 0.0
        limit = lim.speed_up if err > 0 else lim.speed_dn
        speed = min(limit, math.sqrt(2.0 * lim.accel_v * abs(err) * 0.9))
        if speed * dt >= abs(err):
            speed = abs(err) / dt
        self._apply_v(math.copysign(speed, err), lim.accel_v, dt)
        return up - self.up

    def move_v_velocity(self, vu: float, lim: Limits, dt: float) -> None:
        self._apply_v(vu, lim.accel_v, dt)

    # -- yaw --------------------------------------------------------------------------------------
    def turn_to(self, yaw: float, rate_dps: float, dt: float) -> None:
        err = wrap_180(yaw - self.yaw)
        step = rate_dps * dt
        if abs(err) <= step:
            self.yaw_rate = err / dt if dt > 0 else 0.0
            self.yaw = wrap_360(yaw)
        else:
            self.yaw_rate = math.copysign(rate_dps, err)
            self.yaw = wrap_360(self.yaw + math.copysign(step, err))

    def attitude(self) -> tuple[float, float]:
        """Roll and pitch (radians) a multicopter needs for the current horizontal acceleration."""
        yaw = math.radians(self.yaw)
        fwd = self.accel_n * math.cos(yaw) + self.accel_e * math.sin(yaw)
        right = -self.accel_n * math.sin(yaw) + self.accel_e * math.cos(yaw)
        g = 9.80665
        return math.atan2(right, g), -math.atan2(fwd, g)
