"""AUTO mode: runs the stored mission item by item as ArduCopter's mode_auto / AP_Mission do."""

from __future__ import annotations

from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.mission import Item
from gateway.sim.modes import Mode

if TYPE_CHECKING:
    from gateway.sim.host import SimHost

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
    mav.MAV_CMD_DO_AUX_FUNCTION: "AuxFunction",
}
AUX_MOTOR_ESTOP = 31
"""RC auxiliary function 31, the motor emergency stop: switch position 2 (high) stops the motors while
the vehicle stays armed (it falls), 0 (low) releases it (ArduPilot's RC_Channel aux functions)."""


class AutoMixin:
    """Mission execution part of FlightController (shares its state and helpers)."""

    v: SimHost
    #: the motor emergency stop is on: the motors give no thrust, armed or not
    motors_stopped: bool = False

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
        elif item.command == mav.MAV_CMD_DO_AUX_FUNCTION and int(item.param1) == AUX_MOTOR_ESTOP:
            self.motors_stopped = int(item.param2) == 2

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

    def _run_goto(self, dt: float, item: Item) -> None:
        """Fly to the current item's target; on reaching it, hold there or go on to the next item."""
        v = self.v
        auto = v.auto
        if self.takeoff_alt is not None:
            if self._run_takeoff(dt):
                self._item_reached(announce=False)
            return
        remaining = self._fly_to_target(dt)
        radius = max(0.5, self._p("WPNAV_RADIUS") / 100.0)
        if remaining <= radius:
            hold = (
                item.param1 if item.command in (mav.MAV_CMD_NAV_WAYPOINT, mav.MAV_CMD_NAV_LOITER_TIME) else 0
            )
            if item.command == mav.MAV_CMD_NAV_TAKEOFF:
                self._item_reached(announce=False)
            elif hold > 0:
                auto.phase = "hold"
                auto.hold_until = v.t + hold
            else:
                self._item_reached(announce=True)

    def _run_auto(self, dt: float) -> None:
        v = self.v
        auto = v.auto
        if not auto.running:
            self._hold(dt)
            return
        item = v.mission.item(auto.current)
        if auto.phase == "goto":
            self._run_goto(dt, item)
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
