"""What a mission item does at the autopilot, as the policy checks it: fail closed.

Each dialect lists the mission commands and frames whose effect the gateway models (`MissionSemantics`,
built in `gateway.fleet.dialects.mission_semantics`): a position item (its point, the leg to it and, for
the loiters, the circle of its radius, counted in the distance limit and against the zones), a return,
a speed change (by its speed type, against the horizontal or the vertical limit), a jump (its repeats
bounded, the leg back checked) and harmless items (yaw, region of interest, camera, gimbal, waits). Every
other command, or a position item in a frame the gateway does not model, is *unchecked*: refused for
agents, naming the item and the command, and allowed for operators (REST) only as an unchecked mission.

`judge` tells one MAVLink item's `Effect` (or why it is unchecked); `SafetyPolicy.check_mission`
(`gateway.fleet.policy.safety`) composes the checks with the limits and zones in force.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Literal, Protocol

#: the most times a DO_JUMP may repeat (-1, "for ever" on ArduPilot, is refused as well)
MAX_JUMP_REPEATS = 100

EffectKind = Literal["position", "rtl", "speed", "jump", "harmless"]
SpeedAxis = Literal["horizontal", "climb", "descent"]


class RawLike(Protocol):
    """The fields of a MAVLink mission item the checks read (`gateway.fleet.missions.mission.RawItem`)."""

    @property
    def frame(self) -> int: ...
    @property
    def command(self) -> int: ...
    @property
    def param1(self) -> float: ...
    @property
    def param2(self) -> float: ...
    @property
    def param3(self) -> float: ...


@dataclass(frozen=True)
class Position:
    """A NAV command that flies to a point: its kind for the policy, and which parameter (1..4) holds the
    radius of the circle the autopilot may fly around it (None: it stops at the point)."""

    kind: Literal["waypoint", "loiter_time", "land", "takeoff"]
    radius_param: int | None = None


@dataclass(frozen=True)
class Effect:
    """What one item does, as the policy checks it. ``radius_m``: the circle around a position item;
    ``speed_mps``/``axis``: a speed change; ``target``/``repeats``: a jump (target as a user number)."""

    kind: EffectKind
    radius_m: float = 0.0
    speed_mps: float | None = None
    axis: SpeedAxis = "horizontal"
    target: int | None = None
    repeats: int = 0


@dataclass(frozen=True)
class Unchecked:
    """An item whose effect the gateway cannot check: what it is and why."""

    number: int
    command: int
    why: str

    @property
    def name(self) -> str:
        return command_name(self.command)

    def text(self) -> str:
        return f"mission item {self.number}: {self.name} ({self.command}) {self.why}"


@dataclass(frozen=True)
class MissionSemantics:
    """The mission commands and frames an autopilot's dialect models, with that autopilot's meaning."""

    autopilot: str
    positions: Mapping[int, Position]
    harmless: frozenset[int]
    position_frames: frozenset[int]
    #: DO_CHANGE_SPEED's speed type (param1) -> the axis it sets; an absent type is unchecked
    speed_types: Mapping[int, SpeedAxis] = field(default_factory=dict)
    #: every speed type sets this axis (PX4 reads no speed type on a multicopter)
    speed_any_type: SpeedAxis | None = None
    #: DO_JUMP's param1 is the wire sequence number: user number = param1 + jump_offset
    jump_offset: int = 0
    #: latitude and longitude 0 of a position item mean "where the vehicle is" (ArduPilot), not 0, 0
    zero_position_is_here: bool = True

    def judge(self, raw: RawLike) -> Effect | str:
        """The item's effect, or why the gateway cannot check it (a phrase after the command's name)."""
        from pymavlink.dialects.v20 import ardupilotmega as mav  # loaded with the first mission judged

        cmd = raw.command
        if cmd in self.harmless:
            return Effect("harmless")
        if cmd == mav.MAV_CMD_NAV_RETURN_TO_LAUNCH:
            return Effect("rtl")
        position = self.positions.get(cmd)
        if position is not None:
            if raw.frame not in self.position_frames:
                return (
                    f"in frame {frame_name(raw.frame)} ({raw.frame}), whose altitude or position the gateway "
                    "cannot check"
                )
            radius = 0.0
            if position.radius_param is not None:
                value = (raw.param1, raw.param2, raw.param3)[position.radius_param - 1]
                radius = abs(value) if value == value else 0.0  # NaN: the autopilot's default (0 here)
            return Effect("position", radius_m=radius)
        if cmd == mav.MAV_CMD_DO_CHANGE_SPEED:
            speed = raw.param2
            if not speed == speed or speed <= 0:  # NaN, 0 or -1: no change
                return Effect("harmless")
            axis = self.speed_any_type or self.speed_types.get(int(raw.param1))
            if axis is None:
                return f"with speed type {raw.param1:g}, which the gateway cannot check"
            return Effect("speed", speed_mps=speed, axis=axis)
        if cmd == mav.MAV_CMD_DO_JUMP:
            return Effect("jump", target=int(raw.param1) + self.jump_offset, repeats=int(raw.param2))
        return f"is a command whose effect the gateway cannot check on {self.autopilot}"


def command_name(command: int) -> str:
    from pymavlink.dialects.v20 import ardupilotmega as mav

    entry = mav.enums["MAV_CMD"].get(command)
    return entry.name.removeprefix("MAV_CMD_") if entry is not None else f"command {command}"


def frame_name(frame: int) -> str:
    from pymavlink.dialects.v20 import ardupilotmega as mav

    entry = mav.enums["MAV_FRAME"].get(frame)
    return entry.name.removeprefix("MAV_FRAME_") if entry is not None else "unknown"
