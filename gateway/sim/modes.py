"""ArduCopter flight modes (``custom_mode`` numbers) and what each one implies."""

from __future__ import annotations

from enum import IntEnum


class Mode(IntEnum):
    STABILIZE = 0
    ACRO = 1
    ALT_HOLD = 2
    AUTO = 3
    GUIDED = 4
    LOITER = 5
    RTL = 6
    CIRCLE = 7
    LAND = 9
    DRIFT = 11
    SPORT = 13
    FLIP = 14
    AUTOTUNE = 15
    POSHOLD = 16
    BRAKE = 17
    THROW = 18
    AVOID_ADSB = 19
    GUIDED_NOGPS = 20
    SMART_RTL = 21
    FLOWHOLD = 22
    FOLLOW = 23
    ZIGZAG = 24
    SYSTEMID = 25
    AUTOROTATE = 26
    AUTO_RTL = 27
    TURTLE = 28


# Modes the simulator flies; the others are refused like a firmware built without them.
SUPPORTED = frozenset(
    {
        Mode.STABILIZE,
        Mode.ACRO,
        Mode.ALT_HOLD,
        Mode.AUTO,
        Mode.GUIDED,
        Mode.LOITER,
        Mode.RTL,
        Mode.CIRCLE,
        Mode.LAND,
        Mode.POSHOLD,
        Mode.BRAKE,
        Mode.SMART_RTL,
    }
)

# Modes that need a position estimate (Mode::requires_GPS() in ArduCopter).
REQUIRES_POSITION = frozenset(
    {Mode.AUTO, Mode.GUIDED, Mode.LOITER, Mode.RTL, Mode.POSHOLD, Mode.BRAKE, Mode.SMART_RTL, Mode.CIRCLE}
)

# Heartbeat base_mode carries MAV_MODE_FLAG_GUIDED_ENABLED in these modes (measured: 89 vs 81).
GUIDED_FLAG_MODES = REQUIRES_POSITION | {Mode.LAND, Mode.AVOID_ADSB, Mode.FOLLOW, Mode.AUTO_RTL}

# Modes a GCS may arm in (Mode::allows_arming(GCS)): not AUTO (unless AUTO_OPTIONS allows), RTL, LAND,
# SMART_RTL or BRAKE.
ARMABLE_FROM_GCS = frozenset(
    {Mode.STABILIZE, Mode.ACRO, Mode.ALT_HOLD, Mode.GUIDED, Mode.LOITER, Mode.POSHOLD}
)

# Pilot-throttle modes: with the SITL RC throttle stick at its minimum they descend when flying (CIRCLE
# too, flown by gateway.sim.circle).
PILOT_THROTTLE = frozenset({Mode.STABILIZE, Mode.ACRO, Mode.ALT_HOLD, Mode.LOITER, Mode.POSHOLD})


def mode_name(number: int) -> str:
    try:
        return Mode(number).name
    except ValueError:
        return f"MODE({number})"
