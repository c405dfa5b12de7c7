"""Flight logic of the simulated copter: modes, takeoff, guided targets, AUTO missions, RTL, landing,
auto-disarm and failsafe actions, following ArduCopter 4.x behaviour."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.mission import FRAME_ABS, Item
from gateway.sim.modes import PILOT_THROTTLE, REQUIRES_POSITION, SUPPORTED, Mode
from gateway.sim.physics import Limits

if TYPE_CHECKING:
    from gateway.sim.vehicle import SimVehicle

SPOOL_UP_S = 3.5  # motors spool up before lift-off (measured: 0.2 m reached 4.1 s after NAV_TAKEOFF)
LAND_DETECT_S = 2.0  # touchdown -> "Disarming motors" in LAND / RTL / AUTO land (measured 2.1 s)
YAW_RATE_DPS = 60.0  # ATC_SLEW_YAW default 6000 cdeg/s
PILOT_DESCENT_FALLBACK = 2.5
GUIDED_VEL_TIMEOUT_S = 3.0

NAV_CMDS = {
    mav.MAV_CMD_NAV_WAYPOINT: "WP",
    mav.MAV_CMD_NAV_TAKEOFF: "Takeoff",
    mav.MAV_CMD_NAV_LAND: "Land",
    mav.MAV_CMD_NAV_RETURN_TO_LAUNCH: "RTL",
    mav.MAV_CMD_NAV_LOITER_TIME: "LoitTime",
    mav.MAV_CMD_NAV_LOITER_UNLIM: "LoitUnlim",
}
DO_CMDS = {
    mav.MAV_CMD_DO_CHANGE_SPEED: "ChangeSpeed",
    mav.MAV_CMD_CONDITION_YAW: "CondYaw",
    mav.MAV_CMD_DO_SET_HOME: "SetHome",
}

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


@dataclass
class AutoState:
    """Mission execution state (the part MISSION_CURRENT reports)."""

    current: int = 0
    running: bool = False
    started: bool = False
    complete: bool = False
    phase: str = "idle"  # idle | goto | hold | land | rtl | loiter_unlim
    hold_until: float = 0.0


class FlightController:
    def __init__(self, v: SimVehicle) -> None:
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
        self.rtl_alt = 0.0
        self.rtl_loiter_until = 0.0
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
    def arm(self, force: bool) -> tuple[bool, str | None]:
        v = self.v
        if v.armed:
            return True, None
        if not force:
            if v.mode not in _armable_modes(v):
                return False, "Mode not armable"
            failure = v.prearm_failure()
            if failure:
                return False, failure
        v.armed = True
        v.landed = True
        self.landed_since = v.t
        self.touchdown_t = None
        v.auto_armed = False
        v.set_home_here()
        v.text(mav.MAV_SEVERITY_INFO, "Arming motors")
        return True, None

    def disarm(self, reason: str | None = None) -> None:
        v = self.v
        if not v.armed:
            return
        v.armed = False
        v.auto_armed = False
        self.takeoff_alt = None
        self.spool_until = None
        self.descending = False
        self.touchdown_t = None
        if v.landed:
            v.body.stop()
        v.text(mav.MAV_SEVERITY_INFO, "Disarming motors")
        if v.flight_time_s > 0:
            v._stat_params()
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
            rtl_alt = self._p("RTL_ALT") / 100.0
            self.rtl_alt = max(b.up, self._home_up() + rtl_alt) if rtl_alt > 0 else b.up
        elif mode == Mode.SMART_RTL:
            self.rtl_phase = "return"
            self.rtl_alt = b.up
        elif mode == Mode.AUTO and (v.flying or v.auto_armed):
            self.start_mission()

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
    # guided
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

    # ------------------------------------------------------------------------------------------------
    # missions
    def mission_changed(self) -> None:
        auto = self.v.auto
        if auto.current >= self.v.mission.count():
            auto.current = 0
        auto.complete = False

    def set_mission_current(self, seq: int) -> bool:
        v = self.v
        if not 0 <= seq < v.mission.count():
            return False
        v.auto.current = seq
        v.auto.complete = False
        if v.mode == Mode.AUTO and v.auto.running:
            self._begin_item(max(1, seq))
        return True

    def start_mission(self) -> None:
        v = self.v
        auto = v.auto
        if v.mission.count() <= 1:
            return
        if auto.complete or auto.current < 1:
            auto.current = 1
        auto.running = True
        auto.started = True
        auto.complete = False
        self._begin_item(auto.current)

    def _item_target(self, item: Item) -> tuple[float, float, float]:
        b = self.v.body
        if item.x == 0 and item.y == 0:
            north, east = b.north, b.east
        else:
            north, east = self.v.frame.to_ne(item.lat, item.lon)
        up = (
            b.up
            if item.z == 0 and item.command != mav.MAV_CMD_NAV_WAYPOINT
            else self._alt_to_up(item.z, item.frame)
        )
        return north, east, up

    def _begin_item(self, seq: int) -> None:
        v = self.v
        auto = v.auto
        while seq < v.mission.count():
            item = v.mission.item(seq)
            auto.current = seq
            name = NAV_CMDS.get(item.command) or DO_CMDS.get(item.command)
            if name:
                v.text(mav.MAV_SEVERITY_INFO, f"Mission: {seq} {name}")
            if item.command in NAV_CMDS:
                self._start_nav(item)
                return
            self._do_command(item)
            seq += 1
        self._mission_complete()

    def _do_command(self, item: Item) -> None:
        if item.command == mav.MAV_CMD_DO_CHANGE_SPEED:
            self.change_speed(int(item.param1), item.param2)
        elif item.command == mav.MAV_CMD_CONDITION_YAW:
            self.condition_yaw(item.param1, item.param2, item.param3, bool(item.param4))
        elif item.command == mav.MAV_CMD_DO_SET_HOME and item.param1 == 1:
            self.v.set_home_here()

    def _start_nav(self, item: Item) -> None:
        v = self.v
        auto = v.auto
        b = v.body
        self.descending = False
        self.rtl_phase = None
        self.yaw_target = None
        cmd = item.command
        if cmd == mav.MAV_CMD_NAV_TAKEOFF:
            up = self._home_up() + item.z
            if v.landed:
                self._begin_takeoff(up)
            else:
                self.target = (b.north, b.east, max(up, b.up))
            auto.phase = "goto"
        elif cmd in (mav.MAV_CMD_NAV_WAYPOINT, mav.MAV_CMD_NAV_LOITER_TIME):
            self.target = self._item_target(item)
            auto.phase = "goto"
        elif cmd == mav.MAV_CMD_NAV_LOITER_UNLIM:
            self.target = self._item_target(item)
            auto.phase = "loiter_unlim"
        elif cmd == mav.MAV_CMD_NAV_LAND:
            if item.x or item.y:
                north, east = v.frame.to_ne(item.lat, item.lon)
                self.target = (north, east, b.up)
                auto.phase = "goto_land"
            else:
                self.target = self.stopping_point()
                self.descending = True
                auto.phase = "land"
        elif cmd == mav.MAV_CMD_NAV_RETURN_TO_LAUNCH:
            self.rtl_phase = "climb"
            rtl_alt = self._p("RTL_ALT") / 100.0
            self.rtl_alt = max(b.up, self._home_up() + rtl_alt) if rtl_alt > 0 else b.up
            auto.phase = "rtl"

    def _item_reached(self, announce: bool) -> None:
        v = self.v
        seq = v.auto.current
        if announce:
            v.text(mav.MAV_SEVERITY_INFO, f"Reached command #{seq}")
        v.broadcast(mav.MAVLink_mission_item_reached_message(seq))
        self._begin_item(seq + 1)

    def _mission_complete(self) -> None:
        v = self.v
        auto = v.auto
        auto.running = False
        auto.complete = True
        auto.phase = "idle"
        if v.flying:
            self.target = self.stopping_point()  # hover at the last waypoint, still in AUTO

    def _run_auto(self, dt: float) -> None:
        v = self.v
        auto = v.auto
        if not auto.running:
            self._hold(dt)
            return
        item = v.mission.item(auto.current)
        if auto.phase == "goto":
            if self.takeoff_alt is not None:
                if self._run_takeoff(dt):
                    self._item_reached(announce=False)
                return
            remaining = self._fly_to_target(dt)
            radius = max(0.5, self._p("WPNAV_RADIUS") / 100.0)
            if remaining <= radius:
                hold = (
                    item.param1
                    if item.command in (mav.MAV_CMD_NAV_WAYPOINT, mav.MAV_CMD_NAV_LOITER_TIME)
                    else 0
                )
                if item.command == mav.MAV_CMD_NAV_TAKEOFF:
                    self._item_reached(announce=False)
                elif hold > 0:
                    auto.phase = "hold"
                    auto.hold_until = v.t + hold
                else:
                    self._item_reached(announce=True)
        elif auto.phase == "hold":
            self._fly_to_target(dt)
            if v.t >= auto.hold_until:
                self._item_reached(announce=True)
        elif auto.phase == "loiter_unlim":
            self._fly_to_target(dt)
        elif auto.phase == "goto_land":
            if self._fly_to_target(dt) <= 0.5:
                self.descending = True
                auto.phase = "land"
        elif auto.phase == "land":
            self._descend(dt)
        elif auto.phase == "rtl":
            self._run_rtl(dt)

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

    # ------------------------------------------------------------------------------------------------
    # simulation step
    def step(self, dt: float) -> None:
        v = self.v
        b = v.body
        if not v.armed:
            if not v.landed:  # disarmed in the air: motors stopped, it falls
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
        rel = v.rel_alt()
        land_alt_low = self._p("LAND_ALT_LOW") / 100.0
        high = self._p("LAND_SPEED_HIGH") / 100.0 or lim.speed_dn
        speed = high if rel > land_alt_low else self._p("LAND_SPEED") / 100.0
        # slow down smoothly to the final descent rate over the last metres above LAND_ALT_LOW
        b.move_v_velocity(-max(0.1, speed), lim, dt)

    def _pilot_throttle_low(self, dt: float) -> None:
        """Pilot-throttle modes with the SITL RC throttle at minimum: hold position (LOITER/POSHOLD) and
        descend at the pilot's maximum descent rate (MAVSDK hold on ArduPilot descends, MAVSDK#2039)."""
        v = self.v
        b = v.body
        lim = self.limits()
        rate = (
            self._p("PILOT_SPEED_DN") / 100.0 or self._p("PILOT_SPEED_UP") / 100.0 or PILOT_DESCENT_FALLBACK
        )
        if v.mode in (Mode.LOITER, Mode.POSHOLD) and v.position_ok:
            if self.target is None:
                self.target = (b.north, b.east, b.up)
            b.move_h_to(self.target[0], self.target[1], lim, dt)
        else:
            b.move_h_velocity(0.0, 0.0, Limits(accel_h=1.0), dt)
        b.move_v_velocity(-rate, lim, dt)

    def _run_rtl(self, dt: float) -> None:
        v = self.v
        b = v.body
        lim = self.limits()
        hn, he = self._home_ne()
        phase = self.rtl_phase
        if phase == "climb":
            b.move_h_velocity(0.0, 0.0, lim, dt)
            if abs(b.move_v_to(self.rtl_alt, lim, dt)) < 0.1 and b.ground_speed < 0.2:
                self.rtl_phase = "return"
        elif phase == "return":
            self.target = (hn, he, self.rtl_alt)
            if math.hypot(hn - b.north, he - b.east) > 2.0:
                self._face(hn, he, dt)
            if self._fly_to_target(dt) < 0.3:
                self.rtl_phase = "loiter"
                self.rtl_loiter_until = v.t + self._p("RTL_LOIT_TIME") / 1000.0
        elif phase == "loiter":
            self._hold(dt)
            if v.t >= self.rtl_loiter_until:
                self.rtl_phase = "final"
                self.descending = True
                self.target = (hn, he, b.up)
        else:
            self._descend(dt)


def _armable_modes(v: SimVehicle) -> frozenset[Mode]:
    from gateway.sim.modes import ARMABLE_FROM_GCS

    if int(v.params.get("AUTO_OPTIONS")) & 1:
        return ARMABLE_FROM_GCS | {Mode.AUTO}
    return ARMABLE_FROM_GCS
