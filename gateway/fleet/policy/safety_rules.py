"""The safety policy's rules table and refusal wording.

`Rule` names every rule (they appear in refusals, audit rows and docs/safety.md); `refuse` builds a
`SafetyRefusal` whose message starts with the rule's name and `fmt` writes the numbers in it; the
mission command tables; the geofence refusal's wording; `prefixed` re-words a refusal for a mission item
or a formation leg."""

from __future__ import annotations

from enum import StrEnum
from types import TracebackType
from typing import Literal

from gateway.errors import SafetyRefusal
from gateway.fleet.policy.geofence import Violation
from gateway.fleet.policy.safety_inputs import VehicleContext

Via = Literal["mcp", "rest"]


class Rule(StrEnum):
    """Names of the rules; they appear in refusals, audit rows and docs/safety.md."""

    OPERATOR_LOCK = "operator_lock"
    TAKEN_OVER = "taken_over"
    SIMULATORS_ONLY = "simulators_only"
    INVALID_INPUT = "invalid_input"
    MIN_ALTITUDE = "min_altitude"
    MAX_ALTITUDE = "max_altitude"
    HOME_UNKNOWN = "home_unknown"
    MAX_DISTANCE = "max_distance"
    KEEP_IN = "geofence_keep_in"
    KEEP_OUT = "geofence_keep_out"
    POSITION_UNKNOWN = "position_unknown"
    BATTERY_UNKNOWN = "battery_unknown"
    BATTERY_TAKEOFF = "min_battery_takeoff"
    BATTERY_LEG = "min_battery_leg"
    MAX_SPEED = "max_speed"
    PARAM_DENY = "param_deny"
    PARAM_LIMIT = "param_limit"
    PARAM_NOT_ALLOWED = "param_not_allowed"
    PARAM_RANGE = "param_range"
    MODE_IN_AIR = "mode_deny_in_air"
    PATTERN_EXTENT = "pattern_extent"
    KILL_IN_AIR = "kill_in_air"
    MIN_SEPARATION = "min_separation"
    TAKEOFF_IN_PROGRESS = "takeoff_in_progress"
    DRONE_BUSY = "drone_busy"
    KILL_NOT_CONFIRMED = "kill_not_confirmed"
    MISSION_COMMAND = "mission_command_deny"
    MISSION_UNCHECKED = "mission_unchecked"


#: mission commands that would undo the safety layer from inside a mission: DO_SET_HOME (179),
#: DO_SET_PARAMETER (180), DO_FLIGHTTERMINATION (185), DO_FENCE_ENABLE (207), DO_MOTOR_TEST (209)
DENIED_MISSION_COMMANDS = {179: "DO_SET_HOME", 180: "DO_SET_PARAMETER", 185: "DO_FLIGHTTERMINATION",
                           207: "DO_FENCE_ENABLE", 209: "DO_MOTOR_TEST"}  # fmt: skip


def refuse(rule: Rule | str, text: str, **numbers: object) -> SafetyRefusal:
    """A refusal whose message starts with the rule name (of a drone's command: `VehicleContext.refuse`,
    which names the drone)."""
    return SafetyRefusal(str(rule), f"{rule}: {text}", **numbers)


def fmt(value: float, digits: int = 1) -> str:
    """A number for messages: at most `digits` decimals, no trailing zeros."""
    text = f"{value:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def geofence_refusal(ctx: VehicleContext, v: Violation, what: str) -> SafetyRefusal:
    if v.kind == "keep_in" and v.breach == "target":
        text = f"{what} is {fmt(v.metres)} m outside keep-in zone '{v.zone}'"
        rule = Rule.KEEP_IN
    elif v.kind == "keep_in":
        text = f"the straight path to the target leaves keep-in zone '{v.zone}' for {fmt(v.metres)} m"
        rule = Rule.KEEP_IN
    elif v.breach == "target":
        text = f"{what} is inside keep-out zone '{v.zone}' ({fmt(v.metres)} m from its edge)"
        rule = Rule.KEEP_OUT
    elif v.metres < 0.05:
        text = f"the straight path to the target touches keep-out zone '{v.zone}'"
        rule = Rule.KEEP_OUT
    else:
        text = f"the straight path to the target crosses keep-out zone '{v.zone}' for {fmt(v.metres)} m"
        rule = Rule.KEEP_OUT
    nxt = (
        "choose a point clear of the zone, or tell the user"
        if v.breach == "target"
        else "fly around the zone in legs that stay clear of it, or tell the user"
    )
    text = f"{text}; nothing was sent: {nxt}"
    return ctx.refuse(rule, text, zone=v.zone, metres=round(v.metres, 2))


class prefixed:
    """Re-raise a refusal with a prefix after the rule name (e.g. the mission item) and extra numbers."""

    def __init__(self, prefix: str, **numbers: object) -> None:
        self.prefix = prefix
        self.numbers = numbers

    def __enter__(self) -> None:
        return None

    def __exit__(
        self, exc_type: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None
    ) -> None:
        if isinstance(exc, SafetyRefusal):
            head = f"{exc.rule}: "
            body = exc.message[len(head) :] if exc.message.startswith(head) else exc.message
            details = {k: v for k, v in exc.details.items() if k != "rule"}
            raise SafetyRefusal(exc.rule, f"{head}{self.prefix}{body}", **details, **self.numbers) from None
