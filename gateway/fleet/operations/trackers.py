"""Trackers: what "done" means for each kind of operation.

A tracker judges one operation from the vehicle's telemetry each time the operation's monitor polls it
(every POLL_S seconds): progress, a message, an estimate of the time left, done or failed, and the
operation's next command when it has one (`ClimbThenGoTracker`'s leg)."""

from __future__ import annotations

import math
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Protocol

from gateway.fleet import geo
from gateway.fleet.vehicles.protocols import FlyingVehicle, VehicleView
from gateway.fleet.vehicles.readings import (
    climb_rate,
    ground_speed,
    home,
    is_landed,
    is_landed_and_disarmed,
    position,
    value,
)

POLL_S = 0.2
"""How often a monitor looks at the telemetry cache (the cache itself is updated by streams)."""
LEFT_AUTO_GRACE_S = 2.0
"""How long a mission may be out of AUTO before the operation fails (the gateway's own pause supersedes
the operation right after switching mode)."""


@dataclass
class Poll:
    """One look at the vehicle by a tracker."""

    progress: float
    message: str
    done: bool = False
    failed: str | None = None
    eta_s: float | None = None
    then: Callable[[], Awaitable[object]] | None = None
    """The operation's next command, for the manager to send (under the drone's command lock, only while
    the operation still runs): the leg of a `ClimbThenGoTracker` once its climb is done."""


class Tracker(Protocol):
    """Judges an operation from the vehicle's telemetry. ``poll`` is called every POLL_S seconds."""

    kind: str

    async def poll(self, vehicle: FlyingVehicle) -> Poll: ...


FINISH_SETTLE_S = 2.0
"""How long a finished mission's drone is watched before the mission counts as done: a motor stop or
a disarm in its last item shows as a fall within this time (free fall passes FALLING_MPS in 1 s)."""
FALLING_MPS = 10.0
"""A descent faster than this is a fall: no autopilot descends this fast on its own (ArduCopter's
LAND_SPEED_HIGH and WPNAV_SPEED_DN stop at 5 m/s, PX4's MPC_Z_VEL_MAX_DN at 4 m/s)."""
CRASH_WORDS = ("crash", "thrust loss", "emergency stop", "estop", "parachute", "terminat")
"""Words of the autopilot's texts (notice or worse) that say a flight ended badly."""
DISARMED_IN_AIR_ABOVE_M = 2.5
"""A disarm this far above home is one in the air. Lower, it is a landing's own disarm whose landed
state has not arrived yet (the armed flag and the landed state come in different messages, and a loaded
link delivers the disarm first)."""
FAILSAFE_WORDS = ("failsafe",)
"""... and that a failsafe took over (a failure for a mission; what a landing already does)."""


@dataclass
class FlightEnd:
    """What ends a flying operation as failed, whatever else the autopilot reports (a mission's
    "finished" included): a crash or failsafe in the autopilot's own words, a disarm or motor stop in
    the air, a fall, or a landing the operation did not plan (``lands``: it ends on the ground). The
    failure carries what the autopilot said (STATUSTEXT) since the operation began."""

    lands: bool = False
    #: a failsafe's words end it too (not for a landing: landing is what a failsafe does)
    failsafe_ends: bool = True
    _started: float = field(default_factory=time.time)
    _airborne: bool = False
    _alt: float | None = None

    def failure(self, vehicle: VehicleView) -> str | None:
        armed = value(vehicle.telemetry.armed)
        pos = position(vehicle)
        landed = is_landed(vehicle)
        if not landed and armed and pos is not None and pos[2] > 1.0:
            self._airborne, self._alt = True, pos[2]
        said = vehicle.recent_texts(max(0.0, time.time() - self._started))
        words = CRASH_WORDS + (FAILSAFE_WORDS if self.failsafe_ends else ())
        crash = [t for t in said if any(w in t.lower() for w in words) and "clear" not in t.lower()]
        rate = climb_rate(vehicle)
        at = "" if self._alt is None else f" (last seen {self._alt:.1f} m above home)"
        if crash:
            why = "the autopilot reported a crash or failsafe"
        elif not self._airborne:
            return None
        elif armed is False and not landed and pos is not None and pos[2] > DISARMED_IN_AIR_ABOVE_M:
            why = f"the motors were disarmed in the air{at}"
        elif rate is not None and rate < -FALLING_MPS:
            why = f"the drone is falling at {-rate:.1f} m/s{at}"
        elif landed and not self.lands:
            why = f"the drone came down, which the operation did not plan{at}"
        else:
            return None
        return why + (f"; the autopilot said: {' | '.join(said)}" if said else "")


def takeoff_tolerance_m(target_alt_m: float) -> float:
    """How close to the takeoff altitude counts as reached (ArduPilot stops a little short)."""
    return min(1.0, max(0.3, 0.05 * target_alt_m))


# ------------------------------------------------------------------------------------------------
# Trackers: what "done" means for each kind of operation
# ------------------------------------------------------------------------------------------------


@dataclass
class TakeoffTracker:
    target_alt_m: float
    kind: str = "takeoff"
    _seen_armed: bool = False

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        pos = position(vehicle)
        armed = value(vehicle.telemetry.armed)
        if armed:
            self._seen_armed = True
        elif self._seen_armed and armed is False:
            return Poll(0.0, "vehicle disarmed during takeoff", failed="vehicle disarmed during takeoff")
        if pos is None:
            return Poll(0.0, "waiting for position telemetry")
        alt = pos[2]
        remaining = self.target_alt_m - alt
        progress = max(0.0, min(1.0, alt / self.target_alt_m))
        if remaining <= takeoff_tolerance_m(self.target_alt_m):
            return Poll(1.0, f"reached {alt:.1f} m above home", done=True, eta_s=0.0)
        rate = climb_rate(vehicle)
        eta = remaining / max(rate or 0.0, 0.5) if rate and rate > 0.2 else remaining / 1.0
        return Poll(progress, f"climbing: {alt:.1f} of {self.target_alt_m:.1f} m", eta_s=eta)


@dataclass
class GotoTracker:
    """Arrived = within the horizontal tolerance and about at the target altitude."""

    lat: float
    lon: float
    alt_rel_m: float
    tolerance_m: float
    kind: str = "goto"
    _start_dist: float | None = None

    def distance(self, vehicle: VehicleView) -> tuple[float, float] | None:
        pos = position(vehicle)
        if pos is None:
            return None
        return geo.horizontal_distance_m(pos[0], pos[1], self.lat, self.lon), self.alt_rel_m - pos[2]

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        if value(vehicle.telemetry.armed) is False or is_landed(vehicle):
            return Poll(0.0, "vehicle is not flying", failed="vehicle landed or disarmed before arriving")
        d = self.distance(vehicle)
        if d is None:
            return Poll(0.0, "waiting for position telemetry")
        horiz, dz = d
        dist3 = math.hypot(horiz, dz)
        if self._start_dist is None:
            self._start_dist = max(dist3, 0.01)
        progress = max(0.0, min(1.0, 1.0 - dist3 / self._start_dist))
        if horiz <= self.tolerance_m and abs(dz) <= max(self.tolerance_m, 1.0):
            return Poll(1.0, f"arrived ({horiz:.1f} m from target)", done=True, eta_s=0.0)
        speed = ground_speed(vehicle)
        eta = dist3 / max(speed or 0.0, 1.0)
        return Poll(progress, f"{horiz:.0f} m to go, {dz:+.1f} m vertical", eta_s=eta)


@dataclass
class ClimbThenGoTracker:
    """One operation from the ground: take off to the leg's altitude, then fly the leg there. The leg's
    command (``send_leg``) is sent by the manager only once the climb is reached, so the takeoff guard's
    rule (nothing but the climb until it is done: the source paper's crash was a goto sent mid-climb)
    holds inside the operation too, and the guard refuses other commands while ``climbing``."""

    takeoff: TakeoffTracker
    leg: GotoTracker
    send_leg: Callable[[], Awaitable[object]]
    kind: str = "move_to_relative"
    climbing: bool = True

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        if not self.climbing:
            return await self.leg.poll(vehicle)
        climb = await self.takeoff.poll(vehicle)
        if climb.failed is not None:
            return climb
        target = self.takeoff.target_alt_m
        if not climb.done:
            return Poll(0.3 * climb.progress, f"taking off first: {climb.message}", eta_s=climb.eta_s)
        self.climbing = False
        return Poll(0.3, f"took off to {target:g} m; flying the leg", then=self.send_leg)


@dataclass
class YawTracker:
    heading_deg: float
    kind: str = "set_yaw"
    tolerance_deg: float = 5.0

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        heading = value(vehicle.telemetry.heading_deg)
        if heading is None:
            return Poll(0.0, "waiting for heading telemetry")
        err = abs((float(heading) - self.heading_deg + 180.0) % 360.0 - 180.0)
        if err <= self.tolerance_deg:
            return Poll(1.0, f"heading {float(heading):.0f} deg", done=True, eta_s=0.0)
        return Poll(max(0.0, 1.0 - err / 180.0), f"turning: {err:.0f} deg to go", eta_s=err / 30.0)


@dataclass
class LandingTracker:
    """Land and RTL: done once landed and disarmed (ArduPilot disarms itself after touchdown); failed
    on a crash, a failsafe or a disarm in the air (`FlightEnd`)."""

    kind: str = "land"
    _start: tuple[float, float] | None = None  # (altitude, horizontal distance to home) at start
    _end: FlightEnd = field(default_factory=lambda: FlightEnd(lands=True, failsafe_ends=False))

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        failed = self._end.failure(vehicle)
        if failed is not None:
            return Poll(0.0, failed, failed=failed)
        if is_landed_and_disarmed(vehicle):
            return Poll(1.0, "landed and disarmed", done=True, eta_s=0.0)
        pos = position(vehicle)
        if pos is None:
            return Poll(0.0, "waiting for position telemetry")
        alt = max(pos[2], 0.0)
        horiz = 0.0
        h = home(vehicle)
        if self.kind == "return_to_launch" and h is not None:
            horiz = geo.horizontal_distance_m(pos[0], pos[1], h[0], h[1])
        if self._start is None:
            self._start = (max(alt, 0.1), horiz)
        total = self._start[0] + self._start[1]
        progress = max(0.0, min(0.99, 1.0 - (alt + horiz) / max(total, 0.1)))
        speed = ground_speed(vehicle) or 0.0
        eta = horiz / max(speed, 1.0) + alt / 1.0
        if is_landed(vehicle):
            return Poll(0.99, "on the ground, waiting for disarm", eta_s=3.0)
        where = f"{horiz:.0f} m from home, " if self.kind == "return_to_launch" else ""
        return Poll(progress, f"{where}{alt:.1f} m above home", eta_s=eta)


@dataclass
class MissionTracker:
    """Done when the autopilot says the mission is finished (asked at most once a second) and the drone
    flies on or landed as the mission planned; failed when the flight ended otherwise (`FlightEnd`: a
    crash, a failsafe, a disarm or motor stop in the air, a landing the mission has no item for) or the
    autopilot left AUTO. ``lands``: the mission has a land or return item."""

    kind: str = "mission"
    lands: bool = False
    _asked_at: float = 0.0
    _seen_auto: bool = False
    _left_auto_at: float | None = None
    _end: FlightEnd = field(default_factory=FlightEnd)
    _finished_at: float | None = None

    def __post_init__(self) -> None:
        self._end.lands = self.lands

    async def poll(self, vehicle: FlyingVehicle) -> Poll:
        prog = value(vehicle.telemetry.mission_progress)
        current, total = (int(prog.current), int(prog.total)) if prog is not None else (0, 0)
        ended = self._end.failure(vehicle)
        if ended is not None:
            return Poll(0.0, ended, failed=f"{ended} (at item {current} of {total})")
        left = self._left_auto(vehicle) if self._finished_at is None else None
        if left is not None and await vehicle.is_mission_finished():
            left, self._finished_at = None, time.monotonic()  # PX4 holds once its mission is done
        if left is not None:
            said = vehicle.recent_texts(LEFT_AUTO_GRACE_S + 5.0)
            words = f"; the autopilot said: {' | '.join(said)}" if said else ""
            return Poll(
                0.0,
                left,
                failed=f"{left} at item {current} of {total}; the mission is no longer being flown{words}",
            )
        now = time.monotonic()
        if self._finished_at is not None:
            if now - self._finished_at >= FINISH_SETTLE_S:
                return Poll(1.0, f"mission finished ({total} items)", done=True, eta_s=0.0)
            return Poll(0.99, f"mission finished ({total} items); checking the drone flies on", eta_s=1.0)
        if now - self._asked_at >= 1.0:
            self._asked_at = now
            if await vehicle.is_mission_finished():
                self._finished_at = now
                return Poll(0.99, f"mission finished ({total} items); checking the drone flies on", eta_s=1.0)
        progress = max(0.0, min(0.99, (current - 1) / total)) if total else 0.0
        return Poll(progress, f"item {current} of {total}")

    def _left_auto(self, vehicle: FlyingVehicle) -> str | None:
        """The autopilot itself left AUTO (a failsafe, a pilot, another ground station) for longer than
        LEFT_AUTO_GRACE_S. The gateway's own pause/hold supersedes the operation before that."""
        mode = value(vehicle.telemetry.flight_mode)
        if mode is None:
            return None
        if str(mode).upper() in ("AUTO", "MISSION", "AUTO.MISSION"):
            self._seen_auto, self._left_auto_at = True, None
            return None
        if not self._seen_auto:
            return None
        now = time.monotonic()
        if self._left_auto_at is None:
            self._left_auto_at = now
        if now - self._left_auto_at < LEFT_AUTO_GRACE_S:
            return None
        return f"the autopilot switched from AUTO to {mode} (failsafe, pilot or another ground station)"
