"""Per-link telemetry scheduling as ArduPilot does it: stream groups plus per-message intervals.

Every rate starts at 0 (ArduCopter's MAVn_*/SRn_* defaults). ``REQUEST_DATA_STREAM`` sets a whole group,
``MAV_CMD_SET_MESSAGE_INTERVAL`` one message (overriding its group). Times are simulated seconds.
"""

from __future__ import annotations

import math

# MAV_DATA_STREAM ids -> ArduPilot stream group name (the suffix of the MAVn_* parameter).
GROUP_PARAM = {
    1: "RAW_SENS",
    2: "EXT_STAT",
    3: "RC_CHAN",
    4: "RAW_CTRL",
    6: "POSITION",
    10: "EXTRA1",
    11: "EXTRA2",
    12: "EXTRA3",
}

# Messages of each group that the simulator produces (ArduPilot's copter stream tables, reduced).
GROUP_MESSAGES: dict[int, tuple[int, ...]] = {
    1: (27, 116, 129, 29, 137),  # RAW_IMU, SCALED_IMU2/3, SCALED_PRESSURE/2
    # SYS_STATUS, POWER_STATUS, MEMINFO, MISSION_CURRENT, GPS_RAW_INT, NAV_CONTROLLER_OUTPUT, FENCE_STATUS,
    # POSITION_TARGET_GLOBAL_INT (the last two only when there is something to report)
    2: (1, 125, 152, 42, 24, 62, 162, 87),
    3: (36, 65),  # SERVO_OUTPUT_RAW, RC_CHANNELS
    4: (),
    6: (33, 32),  # GLOBAL_POSITION_INT, LOCAL_POSITION_NED
    10: (30, 164, 178),  # ATTITUDE, SIMSTATE, AHRS2
    11: (74,),  # VFR_HUD
    12: (163, 2, 147, 193, 241),  # AHRS, SYSTEM_TIME, BATTERY_STATUS, EKF_STATUS_REPORT, VIBRATION
}

MESSAGE_GROUP = {msg: group for group, msgs in GROUP_MESSAGES.items() for msg in msgs}


class StreamTable:
    """Which messages one link streams and when each is due next."""

    def __init__(self) -> None:
        self.group_hz: dict[int, float] = {}
        self.intervals: dict[int, float] = {}  # msg id -> seconds; <0 disabled
        self._next_due: dict[int, float] = {}
        #: when the next message is due (simulated seconds; None: to be worked out, after a change of
        #: rates): the vehicle asks at every physics step, 25 times a second, and most steps send nothing
        self._earliest: float | None = None

    def set_group(self, group: int, hz: float) -> list[int]:
        """Set a stream group's rate (0 = off); group 0 means all groups. Returns the groups changed."""
        groups = list(GROUP_MESSAGES) if group == 0 else [group]
        changed = []
        for g in groups:
            if g in GROUP_MESSAGES:
                self.group_hz[g] = max(0.0, hz)
                changed.append(g)
        self._earliest = None
        return changed

    def set_interval(self, msg_id: int, interval_us: float) -> None:
        """-1 disables, 0 restores the group default, >0 streams at that interval."""
        if interval_us == 0:
            self.intervals.pop(msg_id, None)
        elif interval_us < 0:
            self.intervals[msg_id] = -1.0
        else:
            self.intervals[msg_id] = interval_us / 1e6
        self._next_due.pop(msg_id, None)
        self._earliest = None

    def interval(self, msg_id: int) -> float | None:
        """Current interval in seconds, or None when not streamed."""
        if msg_id in self.intervals:
            value = self.intervals[msg_id]
            return value if value > 0 else None
        group = MESSAGE_GROUP.get(msg_id)
        hz = self.group_hz.get(group, 0.0) if group is not None else 0.0
        return 1.0 / hz if hz > 0 else None

    def _asked(self) -> set[int]:
        """The message ids given an interval or in a group with a rate (some may be disabled)."""
        return set(self.intervals) | {
            m for g, hz in self.group_hz.items() if hz > 0 for m in GROUP_MESSAGES[g]
        }

    def streamed(self) -> set[int]:
        """The message ids this link streams now (by interval or by group)."""
        return {m for m in self._asked() if self.interval(m) is not None}

    def clear(self) -> None:
        self.group_hz.clear()
        self.intervals.clear()
        self._next_due.clear()
        self._earliest = None

    def due(self, now: float) -> list[int]:
        """Message ids due at ``now`` (simulated seconds); each is rescheduled one interval on.

        Like ArduPilot, a message that fell behind is sent once, not once per missed period.
        """
        if self._earliest is not None and now < self._earliest:
            return []
        out = []
        ids = self._asked()
        for msg_id in ids:
            interval = self.interval(msg_id)
            if interval is None:
                self._next_due.pop(msg_id, None)
                continue
            due = self._next_due.get(msg_id)
            if due is None:
                self._next_due[msg_id] = now + interval
                out.append(msg_id)
            elif now >= due:
                nxt = due + interval
                self._next_due[msg_id] = nxt if nxt > now else now + interval
                out.append(msg_id)
        self._earliest = min((self._next_due[m] for m in ids if m in self._next_due), default=math.inf)
        return out
