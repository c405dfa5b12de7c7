"""Flight logic of the simulated copter, following ArduCopter 4.x: arming, modes, RTL, landing, auto-disarm
(takeoff and GUIDED targets in guided.py, AUTO missions in auto.py, failsafes and fence in failsafe.py)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.auto import DO_CMDS, AutoMixin
from gateway.sim.circle import Circle
from gateway.sim.failsafe import FailsafeMixin
from gateway.sim.guided import YAW_RATE_DPS, GuidedMixin
from gateway.sim.modes import PILOT_THROTTLE, REQUIRES_POSITION, SUPPORTED, Mode
from gateway.sim.physics import Limits

if TYPE_CHECKING:
    from gateway.sim.host import SimHost

#: ArduCopter's RTL climb leg ends this long after RTL starts even when already at RTL_ALT (an S-curve
#: leg of no length; measured on SITL: the return starts 1.0-1.1 s after the mode change)
RTL_CLIMB_MIN_S = 1.0
RTL_ALT_MIN_M = 0.3  # ArduCopter's RTL_ALT_MIN (config.h, 30 cm)
#: ArduCopter's S-curve return leg ends (and RTL_LOIT_TIME starts) this long after the vehicle is within
#: 0.3 m of home: its jerk-limited stop settles slowly (measured on SITL: descent starts 8.7 s after
#: coming within 1 m of home with RTL_LOIT_TIME 5 s)
RTL_ARRIVAL_SETTLE_S = 2.4
LAND_DETECT_S = 2.0  # touchdown -> "Disarming motors" in LAND / RTL / AUTO land (measured 2.1 s)
PILOT_DESCENT_FALLBACK = 2.5


class FlightController(GuidedMixin, AutoMixin, FailsafeMixin):
    """Modes, navigation and the per-step flight logic of one simulated copter."""

    def __init__(self, v: SimHost) -> None:
        self.v = v
        self.target: tuple[float, float, float] | None = None  # north, east, up (m)
        self.vel_target: tuple[float, float, float, float] | None = None  # vn, ve, vu, expiry t
        self.yaw_target: float | None = None
        self.yaw_rate = YAW_RATE_DPS
        self.speed_override: dict[str, float] = {}
        self.takeoff_alt: float | None = None  # up (m) the current takeoff climbs to
        self.spool_until: float | None = None
        self.descending = False  # LAND-like descent active (LAND, RTL final, AUTO land)
        self.rtl_phase: str | None = None
        self.circle: Circle | None = None
        self.rtl_alt = 0.0
        self.rtl_loiter_until = 0.0
        self.rtl_started = 0.0
        self.touchdown_t: float | None = None
        self.landed_since = 0.0
        self.land_pause_until = 0.0
        self.ekf_failsafe = False
        self.fence_breaches = 0  # bitmask: 1 max altitude, 2 circle

    # ------------------------------------------------------------------------------------------------
    # parameters
    def _p(self, name: str) -> float:
        return self.v.params.get(name)

    def limits(self) -> Limits:
        speed_h = self.speed_override.get("h", self._p("WPNAV_SPEED") / 100.0)
        if self.v.mode == Mode.RTL and self._p("RTL_SPEED") > 0 and "h" not in self.speed_override:
            speed_h = self._p("RTL_SPEED") / 100.0
        return Limits(
            jerk_h=self._p("WPNAV_JERK") if self.v.mode == Mode.RTL and self.rtl_phase == "return" else None,
            speed_h=max(0.2, speed_h),
            speed_up=max(0.1, self.speed_override.get("up", self._p("WPNAV_SPEED_UP") / 100.0)),
            speed_dn=max(0.1, self.speed_override.get("dn", self._p("WPNAV_SPEED_DN") / 100.0)),
            accel_h=max(0.5, self._p("WPNAV_ACCEL") / 100.0),
            accel_v=max(0.5, self._p("WPNAV_ACCEL_Z") / 100.0),
        )

    def _home_up(self) -> float:
        v = self.v
        return (v.home[2] - v.frame.alt0) if v.home else 0.0

    def _home_ne(self) -> tuple[float, float]:
        v = self.v
        return v.frame.to_ne(v.home[0], v.home[1]) if v.home else (0.0, 0.0)

    # ------------------------------------------------------------------------------------------------
    # status queries
    def takeoff_pending(self) -> bool:
        return self.spool_until is not None

    def is_taking_off(self) -> bool:
        return self.takeoff_alt is not None and self.spool_until is None

    def is_landing(self) -> bool:
        return self.descending

    def on_ground(self) -> bool:
        return self.v.landed

    def nav_output(self) -> tuple[float, float, float]:
        b = self.v.body
        if self.target is None:
            return b.yaw, 0.0, 0.0
        n, e, up = self.target
        bearing = math.degrees(math.atan2(e - b.east, n - b.north)) % 360
        return bearing, math.hypot(n - b.north, e - b.east), up - b.up

    # ------------------------------------------------------------------------------------------------
    # arming
    def arm(self, force: bool) -> tuple[bool, list[str]]:
        """Arm (``force``: without checks); a refusal returns every failing check, in ArduPilot's words."""
        v = self.v
        if v.armed:
            return True, []
        if not force:
            if v.mode not in _armable_modes(v):
                return False, ["Mode not armable"]
            failures = v.boot_state.prearm_failures()
            if failures:
                return False, failures
        v.armed = True
        v.landed = True
        self.landed_since = v.t
        self.touchdown_t = None
        v.auto_armed = False
        v.set_home_here()
        v.text(mav.MAV_SEVERITY_INFO, "Arming motors")
        return True, []

    def _no_takeoff_or_landing(self) -> None:
        """Disarmed: no takeoff spools up or climbs, no descent or touchdown is under way."""
        self.takeoff_alt = self.spool_until = self.touchdown_t = None
        self.descending = False

    def disarm(self, reason: str | None = None) -> None:
        v = self.v
        if not v.armed:
            return
        v.armed = False
        v.auto_armed = False
        self._no_takeoff_or_landing()
        if v.landed:
            v.body.stop()
        v.text(mav.MAV_SEVERITY_INFO, "Disarming motors")
        if v.flight_time_s > 0:
            v.boot_state.stat_params()
            v.notify_param("MOT_THST_HOVER", v.params.get("MOT_THST_HOVER"))
        if v.auto.running and v.landed:
            v.auto.running = False

    # ------------------------------------------------------------------------------------------------
    # modes
    def set_mode(self, number: int, announce_failure: bool = True) -> tuple[bool, str | None]:
        v = self.v
        try:
            mode = Mode(number)
        except ValueError:
            mode = None
        if mode is None or mode not in SUPPORTED:
            v.text(mav.MAV_SEVERITY_WARNING, f"No such mode {number}")
            return False, "no such mode"
        if mode == v.mode:
            return True, None
        if v.armed:
            if mode in REQUIRES_POSITION and not v.position_ok:
                return self._mode_failed(mode, "requires position", announce_failure)
            if mode == Mode.AUTO:
                if v.mission.count() <= 1:
                    return self._mode_failed(mode, "init failed", announce_failure)
                if v.landed and not self._mission_starts_with_takeoff():
                    v.text(mav.MAV_SEVERITY_CRITICAL, "Auto: Missing Takeoff Cmd")
                    return self._mode_failed(mode, "init failed", announce_failure)
        self._enter(mode)
        v.broadcast(v.heartbeat())  # ArduPilot announces a new mode at once (set_mode sends a HEARTBEAT)
        return True, None

    def _mode_failed(self, mode: Mode, why: str, announce: bool) -> tuple[bool, str]:
        if announce:
            self.v.text(mav.MAV_SEVERITY_WARNING, f"Mode change to {mode.name} failed: {why}")
        return False, why

    def _enter(self, mode: Mode) -> None:
        v = self.v
        previous = v.mode
        v.mode = mode
        self.speed_override.clear()
        self.vel_target = None
        self.yaw_target = None
        self.descending = False
        self.rtl_phase = None
        if previous == Mode.AUTO:
            v.auto.running = False
            v.auto.phase = "idle"
        if mode != Mode.GUIDED:
            self.takeoff_alt = None
            if mode != Mode.AUTO:
                self.spool_until = None
        b = v.body
        self.target = self.stopping_point() if v.flying else None
        if mode == Mode.LAND:
            self.land_pause_until = v.t
            self.descending = True
        elif mode == Mode.RTL:
            self.rtl_phase = "climb"
            self.rtl_started = v.t
            self.rtl_alt = self._home_up() + self._return_alt_rel()
        elif mode == Mode.SMART_RTL:
            self.rtl_phase = "return"
            self.rtl_alt = b.up
        elif mode == Mode.CIRCLE:
            n, e, _up = self.stopping_point() if v.flying else (b.north, b.east, b.up)
            radius = max(0.0, self._p("CIRCLE_RADIUS") / 100.0)
            self.circle = Circle.ahead_of(n, e, b.yaw, radius, self._p("CIRCLE_RATE"))
        elif mode == Mode.AUTO and (v.flying or v.auto_armed):
            self.start_mission()

    def _return_alt_rel(self) -> float:
        """The return altitude above home as ModeRTL::compute_return_target sets it: the higher of RTL_ALT
        and the current altitude plus RTL_CLIMB_MIN (at least RTL_ALT_MIN); it never descends. (The
        cone that lowers the target close to home, RTL_CONE_SLOPE, is not modelled.)"""
        current = self.v.rel_alt()
        climb_min = max(0.0, self._p("RTL_CLIMB_MIN") / 100.0)
        target = max(self._p("RTL_ALT") / 100.0, RTL_ALT_MIN_M, current + climb_min)
        return max(target, current)

    def stopping_point(self) -> tuple[float, float, float]:
        """Where the vehicle comes to rest braking at the acceleration limits (ArduPilot's stopping point):
        mode changes in flight hold there instead of turning back to where the switch happened."""
        b = self.v.body
        lim = self.limits()
        speed = b.ground_speed
        ahead = speed / (2.0 * lim.accel_h) if speed > 0 else 0.0
        up = b.up + b.vu * abs(b.vu) / (2.0 * lim.accel_v)
        return b.north + b.vn * ahead, b.east + b.ve * ahead, up

    def _mission_starts_with_takeoff(self) -> bool:
        items = self.v.mission.items
        for item in items[1:]:
            if item.command in DO_CMDS:
                continue
            return item.command == mav.MAV_CMD_NAV_TAKEOFF
        return False

    # ------------------------------------------------------------------------------------------------
    # simulation step
    def step(self, dt: float) -> None:
        v = self.v
        b = v.body
        if not v.armed or self.motors_stopped:
            if not v.landed:  # disarmed (or motors emergency-stopped) in the air: it falls
                b.vn *= 0.99
                b.ve *= 0.99
                b.vu = max(-30.0, b.vu - 9.80665 * dt)
                b.north += b.vn * dt
                b.east += b.ve * dt
                b.up += b.vu * dt
                self._ground_contact()
            return
        if v.landed:
            self._step_on_ground(dt)
            return
        mode = v.mode
        if mode == Mode.GUIDED:
            self._run_guided(dt)
        elif mode == Mode.AUTO:
            self._run_auto(dt)
        elif mode in (Mode.RTL, Mode.SMART_RTL):
            self._run_rtl(dt)
        elif mode == Mode.LAND:
            self._descend(dt)
        elif mode == Mode.BRAKE:
            self._hold(dt)
        elif mode == Mode.CIRCLE:
            self._run_circle(dt)
        elif mode in PILOT_THROTTLE:
            self._pilot_throttle_low(dt)
        else:
            self._hold(dt)
        self._yaw(dt)
        self._ground_contact()
        self.fence_check()

    def _step_on_ground(self, dt: float) -> None:
        v = self.v
        if self.spool_until is not None:
            if v.t >= self.spool_until:
                self.spool_until = None
                v.landed = False
                self.touchdown_t = None
            return
        if self.touchdown_t is not None and (self.descending or v.mode == Mode.LAND):
            if v.t - self.touchdown_t >= LAND_DETECT_S:
                self.disarm()
                if v.mode == Mode.AUTO:
                    v.auto.running = False
                    v.auto.complete = True
            return
        delay = self._p("DISARM_DELAY")
        if delay > 0 and v.t - self.landed_since >= delay:
            self.disarm()

    def _ground_contact(self) -> None:
        v = self.v
        b = v.body
        ground = 0.0
        if b.up <= ground and b.vu <= 0 and not v.landed:
            speed = -b.vu
            b.up = ground
            b.stop()
            v.landed = True
            self.touchdown_t = v.t
            self.landed_since = v.t
            self.target = None
            self.vel_target = None
            v.text(mav.MAV_SEVERITY_INFO, f"SIM Hit ground at {speed:.6f} m/s")

    def _fly_to_target(self, dt: float) -> float:
        if self.target is None:
            self._hold(dt)
            return 0.0
        lim = self.limits()
        b = self.v.body
        n, e, up = self.target
        remaining_h = b.move_h_to(n, e, lim, dt)
        remaining_v = b.move_v_to(up, lim, dt)
        if self.yaw_target is None and remaining_h > 2.0 and self.v.mode != Mode.RTL:
            self._face(n, e, dt)
        return math.hypot(remaining_h, remaining_v)

    def _face(self, n: float, e: float, dt: float) -> None:
        b = self.v.body
        b.turn_to(math.degrees(math.atan2(e - b.east, n - b.north)), YAW_RATE_DPS, dt)

    def _yaw(self, dt: float) -> None:
        b = self.v.body
        if self.yaw_target is not None:
            b.turn_to(self.yaw_target, self.yaw_rate, dt)
        elif b.yaw_rate and self.target is None:
            b.yaw_rate = 0.0

    def _hold(self, dt: float) -> None:
        b = self.v.body
        if self.target is None:
            self.target = (b.north, b.east, b.up)
        lim = self.limits()
        b.move_h_to(self.target[0], self.target[1], lim, dt)
        b.move_v_to(self.target[2], lim, dt)

    def _run_takeoff(self, dt: float) -> bool:
        """Climb to the takeoff altitude; True once reached."""
        b = self.v.body
        lim = self.limits()
        assert self.takeoff_alt is not None
        b.move_h_to(b.north, b.east, lim, dt)
        remaining = b.move_v_to(self.takeoff_alt, lim, dt)
        if abs(remaining) < 0.05:
            self.target = (b.north, b.east, self.takeoff_alt)
            self.takeoff_alt = None
            return True
        return False

    def _run_guided(self, dt: float) -> None:
        v = self.v
        b = v.body
        if self.takeoff_alt is not None:
            self._run_takeoff(dt)
            return
        if self.vel_target is not None:
            vn, ve, vu, expiry = self.vel_target
            if v.t > expiry:
                vn = ve = vu = 0.0
            lim = self.limits()
            b.move_h_velocity(vn, ve, lim, dt)
            b.move_v_velocity(vu, lim, dt)
            return
        self._fly_to_target(dt)

    def _descend(self, dt: float) -> None:
        v = self.v
        b = v.body
        lim = self.limits()
        if self.target is None:
            self.target = (b.north, b.east, b.up)
        if v.position_ok:
            b.move_h_to(self.target[0], self.target[1], lim, dt)
        else:
            b.move_h_velocity(0.0, 0.0, lim, dt)
        if v.t < self.land_pause_until:
            b.move_v_velocity(0.0, lim, dt)
            return
        # ArduCopter's land_run_vertical_control: fast (LAND_SPEED_HIGH or WPNAV_SPEED_DN) high up, slowing
        # with its square-root controller to reach LAND_ALT_LOW at LAND_SPEED, then LAND_SPEED
        land_alt_low = max(1.0, self._p("LAND_ALT_LOW") / 100.0)
        high = self._p("LAND_SPEED_HIGH") / 100.0 or lim.speed_dn
        slow = max(0.1, self._p("LAND_SPEED") / 100.0)
        floor = b.up - v.rel_alt() + land_alt_low
        b.move_v_velocity_to_floor(floor, max(slow, high), slow, lim, dt)

    def _pilot_throttle_low(self, dt: float) -> None:
        """Pilot-throttle modes with the SITL RC throttle at minimum: hold position (LOITER/POSHOLD) and
        descend at the pilot's maximum descent rate (MAVSDK hold on ArduPilot descends, MAVSDK#2039)."""
        v = self.v
        b = v.body
        lim = self.limits()
        rate = self._pilot_descent_rate()
        if v.mode in (Mode.LOITER, Mode.POSHOLD) and v.position_ok:
            if self.target is None:
                self.target = (b.north, b.east, b.up)
            b.move_h_to(self.target[0], self.target[1], lim, dt)
        else:
            b.move_h_velocity(0.0, 0.0, Limits(accel_h=1.0), dt)
        b.move_v_velocity(-rate, lim, dt)

    def _run_circle(self, dt: float) -> None:
        """CIRCLE (gateway.sim.circle): round the centre one radius ahead, the altitude on the pilot's
        throttle (at its minimum without RC: it descends)."""
        b = self.v.body
        lim = self.limits()
        if self.circle is None:
            self.circle = Circle.ahead_of(b.north, b.east, b.yaw, self._p("CIRCLE_RADIUS") / 100.0, 0.0)
        n, e = self.circle.target(lim, dt)
        b.move_h_to(n, e, lim, dt)
        b.move_v_velocity(-self._pilot_descent_rate(), lim, dt)

    def _pilot_descent_rate(self) -> float:
        return (
            self._p("PILOT_SPEED_DN") / 100.0 or self._p("PILOT_SPEED_UP") / 100.0 or PILOT_DESCENT_FALLBACK
        )

    def _run_rtl(self, dt: float) -> None:
        v = self.v
        b = v.body
        lim = self.limits()
        hn, he = self._home_ne()
        phase = self.rtl_phase
        if phase == "climb":
            b.move_h_velocity(0.0, 0.0, lim, dt)
            climbed = abs(b.move_v_to(self.rtl_alt, lim, dt)) < 0.1 and b.ground_speed < 0.2
            if climbed and v.t - self.rtl_started >= RTL_CLIMB_MIN_S:
                self.rtl_phase = "return"
        elif phase == "return":
            self.target = (hn, he, self.rtl_alt)
            if math.hypot(hn - b.north, he - b.east) > 2.0:
                self._face(hn, he, dt)
            if self._fly_to_target(dt) < 0.3:
                self.rtl_phase = "loiter"
                self.rtl_loiter_until = v.t + RTL_ARRIVAL_SETTLE_S + self._p("RTL_LOIT_TIME") / 1000.0
        elif phase == "loiter":
            self._hold(dt)
            if v.t >= self.rtl_loiter_until:
                self.rtl_phase = "final"
                self.descending = True
                self.target = (hn, he, b.up)
        else:
            self._descend(dt)


def _armable_modes(v: SimHost) -> frozenset[Mode]:
    from gateway.sim.modes import ARMABLE_FROM_GCS

    if int(v.params.get("AUTO_OPTIONS")) & 1:
        return ARMABLE_FROM_GCS | {Mode.AUTO}
    return ARMABLE_FROM_GCS
