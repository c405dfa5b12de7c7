"""Flight mode names and numbers: ArduCopter custom modes, PX4 main/sub modes, and the common names
both dialects map (what a model or operator can say without knowing the autopilot)."""

from __future__ import annotations

from dataclasses import dataclass

from gateway.errors import InvalidArgument

ARDUCOPTER_MODES: dict[str, int] = {
    "STABILIZE": 0,
    "ACRO": 1,
    "ALT_HOLD": 2,
    "AUTO": 3,
    "GUIDED": 4,
    "LOITER": 5,
    "RTL": 6,
    "CIRCLE": 7,
    "LAND": 9,
    "DRIFT": 11,
    "SPORT": 13,
    "FLIP": 14,
    "AUTOTUNE": 15,
    "POSHOLD": 16,
    "BRAKE": 17,
    "THROW": 18,
    "AVOID_ADSB": 19,
    "GUIDED_NOGPS": 20,
    "SMART_RTL": 21,
    "FLOWHOLD": 22,
    "FOLLOW": 23,
    "ZIGZAG": 24,
    "SYSTEMID": 25,
    "AUTOROTATE": 26,
    "AUTO_RTL": 27,
    "TURTLE": 28,
}
ARDUCOPTER_MODE_NAMES = {number: name for name, number in ARDUCOPTER_MODES.items()}

#: PX4 custom mode = main_mode << 16 | sub_mode << 24; DO_SET_MODE takes them as param2 / param3.
PX4_MODES: dict[str, tuple[int, int]] = {
    "MANUAL": (1, 0),
    "ALTCTL": (2, 0),
    "POSCTL": (3, 0),
    "AUTO.TAKEOFF": (4, 2),
    "AUTO.LOITER": (4, 3),
    "AUTO.MISSION": (4, 4),
    "AUTO.RTL": (4, 5),
    "AUTO.LAND": (4, 6),
    "ACRO": (5, 0),
    "OFFBOARD": (6, 0),
    "STABILIZED": (7, 0),
}

#: Common mode names -> (ArduCopter mode, PX4 mode); None where the dialect has no such mode.
#: HOLD is a position hold that needs no pilot (ArduCopter: GUIDED at the current position, done by the
#: hold action; PX4: AUTO.LOITER). GUIDED waits for goto commands (PX4 flies those in AUTO.LOITER).
COMMON_MODES: dict[str, tuple[str | None, str | None]] = {
    "HOLD": ("GUIDED", "AUTO.LOITER"),
    "GUIDED": ("GUIDED", "AUTO.LOITER"),
    "RTL": ("RTL", "AUTO.RTL"),
    "LAND": ("LAND", "AUTO.LAND"),
    "MISSION": ("AUTO", "AUTO.MISSION"),
    "AUTO": ("AUTO", "AUTO.MISSION"),
    "TAKEOFF": (None, "AUTO.TAKEOFF"),
    "BRAKE": ("BRAKE", None),
    "SMART_RTL": ("SMART_RTL", None),
}
#: names PX4 users and MAVSDK also use for PX4 modes
PX4_ALIASES = {
    "LOITER": "AUTO.LOITER",
    "RETURN_TO_LAUNCH": "AUTO.RTL",
    "RETURN": "AUTO.RTL",
    "POSITION": "POSCTL",
    "ALTITUDE": "ALTCTL",
    "STABILIZE": "STABILIZED",
}
#: native names of the modes that fly a mission or take off by themselves (guarded like a takeoff)
LAUNCHING_MODES = frozenset({"AUTO", "AUTO.MISSION", "AUTO.TAKEOFF"})


@dataclass(frozen=True)
class ModeChoice:
    """A requested mode resolved for one autopilot: ``native`` is the autopilot's own name."""

    requested: str
    native: str
    custom_mode: int  # HEARTBEAT.custom_mode once the vehicle is in it
    params: tuple[float, ...]  # MAV_CMD_DO_SET_MODE params 1..3


def mode_names(px4: bool) -> list[str]:
    """Every name set_flight_mode accepts for this dialect: the common ones it has, then its own."""
    column = 1 if px4 else 0
    common = [name for name, pair in COMMON_MODES.items() if pair[column] is not None]
    native = list(PX4_MODES) + list(PX4_ALIASES) if px4 else list(ARDUCOPTER_MODES)
    return common + [name for name in native if name not in common]


def require_mode(name: object, px4: bool, vehicle_id: str) -> ModeChoice:
    """``resolve_mode``, or InvalidArgument naming the modes this drone has."""
    if not isinstance(name, str) or not name.strip():
        raise InvalidArgument(f"mode must be a flight mode name; got {name!r}")
    choice = resolve_mode(name, px4)
    if choice is None:
        dialect = "PX4" if px4 else "ArduCopter"
        raise InvalidArgument(
            f"mode '{name.strip()[:40]}' is not a mode of drone '{vehicle_id}' ({dialect}); "
            f"its modes: {', '.join(mode_names(px4))}"
        )
    return choice


def resolve_mode(name: str, px4: bool) -> ModeChoice | None:
    """The mode ``name`` means on this dialect, or None if the dialect has no such mode."""
    wanted = name.strip().upper()
    pair = COMMON_MODES.get(wanted)
    native = pair[1 if px4 else 0] if pair is not None else wanted
    if native is None:
        return None
    if px4:
        native = PX4_ALIASES.get(native, native)
        if native not in PX4_MODES:
            return None
        main, sub = PX4_MODES[native]
        return ModeChoice(wanted, native, (main << 16) | (sub << 24), (1.0, float(main), float(sub)))
    if native not in ARDUCOPTER_MODES:
        return None
    number = ARDUCOPTER_MODES[native]
    return ModeChoice(wanted, native, number, (1.0, float(number)))


#: MAV_TYPE values flown by ArduCopter (quad, coaxial, heli, hexa, octo, tri, dodeca, deca)
COPTER_TYPES = {2, 3, 4, 13, 14, 15, 29, 35}

MAV_AUTOPILOT_ARDUPILOTMEGA = 3
MAV_AUTOPILOT_PX4 = 12


def autopilot_name(mav_autopilot: int) -> str:
    if mav_autopilot == MAV_AUTOPILOT_ARDUPILOTMEGA:
        return "ardupilot"
    if mav_autopilot == MAV_AUTOPILOT_PX4:
        return "px4"
    return f"mav_autopilot_{mav_autopilot}"
