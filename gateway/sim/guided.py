"""GUIDED flight of the simulated copter, following ArduCopter 4.x: takeoff, position and velocity
targets, yaw and speed changes (part of `gateway.sim.flight.FlightController`)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.mission import FRAME_ABS
from gateway.sim.modes import Mode

if TYPE_CHECKING:
    from gateway.sim.host import SimHost

SPOOL_UP_S = 3.5  # motors spool up before lift-off (measured: 0.2 m reached 4.1 s after NAV_TAKEOFF)
YAW_RATE_DPS = 60.0  # ATC_SLEW_YAW default 6000 cdeg/s
GUIDED_VEL_TIMEOUT_S = 3.0


class GuidedMixin:
    """GUIDED part of FlightController (shares its state and helpers)."""

    v: SimHost

    def takeoff(self, alt_rel: float) -> bool:
        v = self.v
        if not v.armed or not v.landed or v.mode != Mode.GUIDED or not alt_rel > 0:
            return False
        self._begin_takeoff(self._home_up() + alt_rel)
        return True

    def _begin_takeoff(self, up: float) -> None:
        v = self.v
        v.auto_armed = True
        self.takeoff_alt = max(up, v.body.up + 0.5)
        self.spool_until = v.t + SPOOL_UP_S
        self.target = (v.body.north, v.body.east, self.takeoff_alt)

    def guided_goto(self, north: float, east: float, up: float, yaw: float | None = None) -> bool:
        if not self.destination_allowed(north, east, up):
            return False
        self.target = (north, east, up)
        self.vel_target = None
        self.takeoff_alt = None
        self.yaw_target = yaw
        return True

    def position_target(self, msg) -> None:
        """SET_POSITION_TARGET_GLOBAL_INT / _LOCAL_NED in GUIDED (ignored in other modes, like ArduPilot)."""
        v = self.v
        if v.mode != Mode.GUIDED or not v.flying:
            return
        mask = msg.type_mask
        use_pos = not mask & 0x7
        use_vel = not mask & 0x38
        b = v.body
        yaw = None if mask & 0x400 else math.degrees(msg.yaw) % 360
        if msg.get_type() == "SET_POSITION_TARGET_GLOBAL_INT":
            if use_pos:
                north, east = v.frame.to_ne(msg.lat_int / 1e7, msg.lon_int / 1e7)
                up = self._alt_to_up(msg.alt, msg.coordinate_frame)
                self.guided_goto(north, east, up, yaw)
            elif use_vel:
                self._velocity(msg.vx, msg.vy, msg.vz, yaw)
            return
        frame = msg.coordinate_frame
        x, y, z = msg.x, msg.y, msg.z
        vx, vy = msg.vx, msg.vy
        if frame in (mav.MAV_FRAME_BODY_NED, mav.MAV_FRAME_BODY_OFFSET_NED, mav.MAV_FRAME_BODY_FRD):
            c, s = math.cos(math.radians(b.yaw)), math.sin(math.radians(b.yaw))
            x, y = x * c - y * s, x * s + y * c
            vx, vy = vx * c - vy * s, vx * s + vy * c
        if use_pos:
            if frame == mav.MAV_FRAME_LOCAL_NED:
                self.guided_goto(x, y, -z, yaw)
            else:  # offsets from the vehicle
                self.guided_goto(b.north + x, b.east + y, b.up - z, yaw)
        elif use_vel:
            self._velocity(vx, vy, msg.vz, yaw)

    def _velocity(self, vn: float, ve: float, vd: float, yaw: float | None) -> None:
        self.vel_target = (vn, ve, -vd, self.v.t + GUIDED_VEL_TIMEOUT_S)
        self.target = None
        self.takeoff_alt = None
        self.yaw_target = yaw

    def _alt_to_up(self, alt: float, frame: int) -> float:
        if frame in FRAME_ABS:
            return alt - self.v.frame.alt0
        return self._home_up() + alt

    def condition_yaw(self, angle: float, rate: float, direction: float, relative: bool) -> bool:
        if not 0 <= angle <= 360 or not self.v.flying:
            return False
        yaw = self.v.body.yaw + (angle if direction >= 0 else -angle) if relative else angle
        self.yaw_target = yaw % 360
        self.yaw_rate = rate if rate > 0 else YAW_RATE_DPS
        return True

    def change_speed(self, kind: int, speed: float) -> bool:
        if not speed > 0:
            return False
        key = {0: "h", 1: "h", 2: "up", 3: "dn"}.get(kind)
        if key is None:
            return False
        self.speed_override[key] = speed
        return True
