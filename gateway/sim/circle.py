"""ArduCopter's CIRCLE mode (AC_Circle, mode_circle.cpp), as far as what it flies matters to the gateway.

* The centre lies one CIRCLE_RADIUS ahead of the stopping point along the vehicle's heading, and the
  vehicle starts on the perimeter at the angle pointing back at where it was: the far side of the circle
  is two radii from where CIRCLE was entered.
* It turns at CIRCLE_RATE (degrees per second, positive clockwise), no faster than the horizontal speed
  limit allows on that radius, ramping up at the acceleration limit.
* The altitude follows the pilot's throttle, as in LOITER: with the throttle at its minimum (no RC) it
  descends at the pilot's maximum descent rate, down to the ground.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gateway.sim.physics import Limits


@dataclass
class Circle:
    centre_n: float
    centre_e: float
    radius_m: float
    angle_rad: float  # where on the perimeter the target is, from the centre (0 = north)
    rate_dps: float
    angular_vel: float = 0.0

    @classmethod
    def ahead_of(cls, north: float, east: float, yaw_deg: float, radius_m: float, rate_dps: float) -> Circle:
        yaw = math.radians(yaw_deg)
        centre_n = north + radius_m * math.cos(yaw)
        centre_e = east + radius_m * math.sin(yaw)
        return cls(centre_n, centre_e, radius_m, yaw - math.pi, rate_dps)

    def target(self, lim: Limits, dt: float) -> tuple[float, float]:
        """The perimeter point to fly to after ``dt`` more seconds."""
        if self.radius_m <= 0:
            return self.centre_n, self.centre_e
        wanted = math.radians(self.rate_dps)
        ceiling = lim.speed_h / self.radius_m
        wanted = math.copysign(min(abs(wanted), ceiling), wanted)
        step = lim.accel_h / self.radius_m * dt
        self.angular_vel += max(-step, min(step, wanted - self.angular_vel))
        self.angle_rad += self.angular_vel * dt
        return (
            self.centre_n + self.radius_m * math.cos(self.angle_rad),
            self.centre_e + self.radius_m * math.sin(self.angle_rad),
        )

    def farthest_from(self, north: float, east: float) -> float:
        """How far the circle's far side lies from (north, east)."""
        return math.hypot(self.centre_n - north, self.centre_e - east) + self.radius_m
