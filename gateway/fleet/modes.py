"""Flight mode names and numbers: ArduCopter custom modes and PX4 main/sub modes."""

from __future__ import annotations

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
