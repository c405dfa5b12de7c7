"""What reached one simulated autopilot and what it then did, for judging a safety rule by its effect.

A ``FlightRecord`` keeps, since its last reset: every MAVLink message that could change the vehicle (commands,
parameter writes, mission uploads, mode and position targets) with the system id that sent it, each mission
the vehicle stored, its mode changes, a track sampled every 0.25 simulated seconds, and the extremes of the
true state (altitude above the first home, distance from the first home, speeds, a disarm in the air, the
speed it hit the ground at). The first home is kept across resets: it is the one the autopilot reported
first, which a later arming moves on ArduCopter. Read through the control API (``GET
/vehicles/{i}/record``), reset with ``POST /vehicles/{i}/record``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.modes import mode_name

if TYPE_CHECKING:
    from gateway.sim.host import SimHost
    from gateway.sim.mission import Item

#: messages that only read or keep the link alive: not recorded
_READS = frozenset(
    {
        "HEARTBEAT", "TIMESYNC", "REQUEST_DATA_STREAM", "PARAM_REQUEST_LIST", "PARAM_REQUEST_READ",
        "MISSION_REQUEST_LIST", "MISSION_REQUEST_INT", "MISSION_REQUEST", "MISSION_ACK", "SYSTEM_TIME",
        "AUTOPILOT_VERSION_REQUEST",
    }
)  # fmt: skip
#: commands that only ask for messages (stream rates, versions): not recorded
_READ_COMMANDS = frozenset({510, 511, 512, 519, 520, 521, 525})
TRACK_EVERY_S = 0.25
MAX_ENTRIES = 5000


class FlightRecord:
    def __init__(self) -> None:
        self.first_home: tuple[float, float, float] | None = None
        self._first_home_ne: tuple[float, float] | None = None
        self.reset()

    def reset(self) -> None:
        self.received: list[dict[str, object]] = []
        self.missions_stored: list[list[dict[str, object]]] = []
        self.modes: list[tuple[float, str]] = []
        self.track: list[tuple[float, float, float, float]] = []
        self.disarmed_in_air: list[dict[str, float]] = []
        self.max_rel_alt_m = -math.inf
        self.max_alt_above_first_home_m = -math.inf
        self.max_distance_first_home_m = 0.0
        self.max_ground_speed_mps = 0.0
        self.max_climb_mps = 0.0
        self.max_descent_mps = 0.0
        self.hit_ground_mps = 0.0
        self._last_track = -math.inf
        self._last_descent = 0.0
        self._was: tuple[bool, bool, str] | None = None

    # -- input ----------------------------------------------------------------------------------------
    def message(self, t: float, msg: mav.MAVLink_message) -> None:
        kind = msg.get_type()
        if kind in _READS or len(self.received) >= MAX_ENTRIES:
            return
        entry: dict[str, object] = {"t": round(t, 3), "kind": kind, "src": msg.get_srcSystem()}
        if kind in ("COMMAND_LONG", "COMMAND_INT"):
            if msg.command in _READ_COMMANDS:
                return
            entry["command"] = msg.command
            params = [_num(getattr(msg, f"param{i}")) for i in range(1, 5)]
            if kind == "COMMAND_INT":
                params += [msg.x, msg.y, _num(msg.z)]
            else:
                params += [_num(msg.param5), _num(msg.param6), _num(msg.param7)]
            entry["params"] = params
        elif kind == "PARAM_SET":
            raw = msg.param_id
            name = raw.decode("ascii", "replace") if isinstance(raw, bytes) else raw
            entry["name"] = name.split("\0", 1)[0]
            entry["value"] = _num(msg.param_value)
        elif kind in ("MISSION_ITEM", "MISSION_ITEM_INT"):
            entry["seq"] = msg.seq
            entry["command"] = msg.command
        elif kind == "SET_MODE":
            entry["custom_mode"] = msg.custom_mode
        self.received.append(entry)

    def mission_stored(self, items: list[Item]) -> None:
        """The mission the vehicle now holds (home excluded), as stored."""
        self.missions_stored.append([_item(i) for i in items])

    def sample(self, v: SimHost) -> None:
        """Once per simulation step: the extremes, transitions and (every TRACK_EVERY_S) the track."""
        b = v.body
        if self.first_home is None and v.home is not None:
            self.first_home = v.home
            self._first_home_ne = v.frame.to_ne(v.home[0], v.home[1])
        mode = mode_name(v.mode)
        was = self._was
        if was is not None:
            armed_before, landed_before, mode_before = was
            if armed_before and not v.armed and not landed_before:
                self.disarmed_in_air.append({"t": round(v.t, 3), "rel_alt_m": round(v.rel_alt(), 2)})
            if not landed_before and v.landed:
                self.hit_ground_mps = max(self.hit_ground_mps, self._last_descent)
            if mode != mode_before:
                self.modes.append((round(v.t, 3), mode))
        self._was = (v.armed, v.landed, mode)
        self._last_descent = max(0.0, -b.vu)
        if v.landed and not v.armed:
            return
        self.max_rel_alt_m = max(self.max_rel_alt_m, v.rel_alt())
        self.max_ground_speed_mps = max(self.max_ground_speed_mps, b.ground_speed)
        self.max_climb_mps = max(self.max_climb_mps, b.vu)
        self.max_descent_mps = max(self.max_descent_mps, -b.vu)
        if self.first_home is not None and self._first_home_ne is not None:
            n0, e0 = self._first_home_ne
            self.max_distance_first_home_m = max(
                self.max_distance_first_home_m, math.hypot(b.north - n0, b.east - e0)
            )
            above = v.frame.alt0 + b.up - self.first_home[2]
            self.max_alt_above_first_home_m = max(self.max_alt_above_first_home_m, above)
        if v.t - self._last_track >= TRACK_EVERY_S and len(self.track) < MAX_ENTRIES:
            self._last_track = v.t
            lat, lon, _alt = v.position()
            self.track.append((round(v.t, 3), lat, lon, round(v.rel_alt(), 2)))

    # -- output ---------------------------------------------------------------------------------------
    def describe(self, v: SimHost) -> dict[str, object]:
        home = self.first_home
        return {
            "first_home": None if home is None else {"lat": home[0], "lon": home[1], "alt": home[2]},
            "received": self.received,
            "missions_stored": self.missions_stored,
            "mission_now": [_item(v.mission.item(s)) for s in range(1, v.mission.count())],
            "modes": self.modes,
            "track": self.track,
            "disarmed_in_air": self.disarmed_in_air,
            "max_rel_alt_m": _finite(self.max_rel_alt_m),
            "max_alt_above_first_home_m": _finite(self.max_alt_above_first_home_m),
            "max_distance_first_home_m": round(self.max_distance_first_home_m, 2),
            "max_ground_speed_mps": round(self.max_ground_speed_mps, 3),
            "max_climb_mps": round(self.max_climb_mps, 3),
            "max_descent_mps": round(self.max_descent_mps, 3),
            "hit_ground_mps": round(self.hit_ground_mps, 3),
        }


def _item(item: Item) -> dict[str, object]:
    return {
        "command": item.command,
        "frame": item.frame,
        "params": [_num(item.param1), _num(item.param2), _num(item.param3), _num(item.param4)],
        "lat": item.lat,
        "lon": item.lon,
        "z": _num(item.z),
    }


def _num(x: float) -> float | str:
    """JSON has no NaN or infinity: those are written as text."""
    return x if math.isfinite(x) else str(x)


def _finite(x: float) -> float | None:
    return round(x, 2) if math.isfinite(x) else None
