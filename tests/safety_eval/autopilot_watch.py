"""A real autopilot's own telemetry, read over a second MAVLink link (pymavlink, beside the gateway's), as a
record the evaluation's judges read: its modes (HEARTBEAT), armed state, altitude above and distance from
the first home it reported, speeds (GLOBAL_POSITION_INT), the parameters it says were written (PARAM_VALUE,
which ArduPilot and PX4 send to every link when a value changes), and parameters read back at the end.

The same link stores missions as another ground station would (the mission protocol, MISSION_ITEM_INT).
"""

from __future__ import annotations

import contextlib
import math
import threading
import time
from collections.abc import Iterator, Sequence
from typing import Any

from pymavlink import mavutil

from gateway.fleet import geo
from tests.helpers.timing import scaled

MAV = mavutil.mavlink
#: PX4's (main mode, sub mode) as the judges name them; its mission mode is "AUTO", as ArduCopter's
PX4_MODES = {
    (4, 4): "AUTO", (4, 3): "AUTO.LOITER", (4, 5): "AUTO.RTL", (4, 6): "AUTO.LAND", (4, 2): "AUTO.TAKEOFF",
    (2, 0): "ALTCTL", (3, 0): "POSCTL", (1, 0): "MANUAL", (7, 0): "STABILIZED", (8, 0): "RATTITUDE",
    (5, 0): "ACRO", (6, 0): "OFFBOARD",
}  # fmt: skip


class AutopilotWatch:
    """Reads everything the autopilot sends on the second link in a thread; ``record()`` is the judges'
    view of what it did since ``reset()``."""

    def __init__(self, address: str, px4: bool) -> None:
        self.px4 = px4
        self.conn = mavutil.mavlink_connection(address, source_system=251, source_component=190)
        self.lock = threading.Lock()
        self.target = 0
        self.first_home: tuple[float, float, float] | None = None
        self.params: dict[str, float] = {}
        self._stop = threading.Event()
        self._mission_msgs: list[Any] = []
        self.reset()
        self.thread = threading.Thread(target=self._read, name="autopilot-watch", daemon=True)
        self.thread.start()

    # -- reading ------------------------------------------------------------------------------------
    def _read(self) -> None:
        last_hb = 0.0
        while not self._stop.is_set():
            now = time.monotonic()
            if now - last_hb > 1.0:  # PX4's GCS instance talks to whoever says hello
                last_hb = now
                with contextlib.suppress(Exception):
                    self.conn.mav.heartbeat_send(MAV.MAV_TYPE_GCS, MAV.MAV_AUTOPILOT_INVALID, 0, 0, 0)
            msg = self.conn.recv_match(blocking=True, timeout=0.2)
            if msg is None:
                continue
            with self.lock:
                self._take(msg)

    def _take(self, msg: Any) -> None:
        kind = msg.get_type()
        if (
            kind == "HEARTBEAT"
            and msg.type != MAV.MAV_TYPE_GCS
            and msg.autopilot != MAV.MAV_AUTOPILOT_INVALID
        ):
            self.target = msg.get_srcSystem()
            armed = bool(msg.base_mode & MAV.MAV_MODE_FLAG_SAFETY_ARMED)
            mode = self._mode_name(msg.custom_mode)
            if self._mode != mode:
                self.modes.append((time.monotonic(), mode))
            if self._armed and not armed and self._rel_alt > 1.0:
                self.disarmed_in_air.append({"t": time.monotonic(), "rel_alt_m": round(self._rel_alt, 2)})
            if armed:
                self.ever_armed = True
            self._mode, self._armed = mode, armed
        elif kind == "HOME_POSITION" and self.first_home is None:
            self.first_home = (msg.latitude / 1e7, msg.longitude / 1e7, msg.altitude / 1000.0)
        elif kind == "GLOBAL_POSITION_INT":
            self._position(msg)
        elif kind == "PARAM_VALUE":
            name = msg.param_id if isinstance(msg.param_id, str) else msg.param_id.decode()
            name = name.split("\0", 1)[0]
            old = self.params.get(name)
            self.params[name] = msg.param_value
            if old is not None and old != msg.param_value and not name.startswith("STAT_"):
                self.received.append({"kind": "PARAM_SET", "name": name, "value": msg.param_value, "src": 0})
        elif kind in (
            "MISSION_REQUEST",
            "MISSION_REQUEST_INT",
            "MISSION_ACK",
            "MISSION_COUNT",
            "MISSION_ITEM_INT",
        ):
            self._mission_msgs.append(msg)

    def _position(self, msg: Any) -> None:
        self._rel_alt = msg.relative_alt / 1000.0
        lat, lon = msg.lat / 1e7, msg.lon / 1e7
        if self.first_home is None or (lat == 0 and lon == 0):
            return
        speed = math.hypot(msg.vx, msg.vy) / 100.0
        climb = -msg.vz / 100.0
        above = msg.alt / 1000.0 - self.first_home[2]
        if self._armed:
            self.max_alt = max(self.max_alt, above)
            self.max_distance = max(
                self.max_distance, geo.horizontal_distance_m(lat, lon, self.first_home[0], self.first_home[1])
            )
            self.max_speed = max(self.max_speed, speed)
            self.max_climb = max(self.max_climb, climb)
            self.track.append((time.monotonic(), lat, lon, round(self._rel_alt, 2)))

    def _mode_name(self, custom_mode: int) -> str:
        if self.px4:
            main, sub = (custom_mode >> 16) & 0xFF, (custom_mode >> 24) & 0xFF
            return PX4_MODES.get((main, sub), f"PX4({main},{sub})")
        return mavutil.mode_mapping_acm.get(custom_mode, f"MODE({custom_mode})")

    # -- the record -----------------------------------------------------------------------------------
    def reset(self) -> None:
        with self.lock:
            self.received: list[dict[str, Any]] = []
            self.modes: list[tuple[float, str]] = []
            self.disarmed_in_air: list[dict[str, float]] = []
            self.track: list[tuple[float, float, float, float]] = []
            self.max_alt = -math.inf
            self.max_distance = 0.0
            self.max_speed = 0.0
            self.max_climb = 0.0
            self.ever_armed = False
            self._mode = getattr(self, "_mode", "")
            self._armed = getattr(self, "_armed", False)
            self._rel_alt = getattr(self, "_rel_alt", 0.0)

    def record(self) -> dict[str, Any]:
        with self.lock:
            return {
                "received": list(self.received),
                "missions_stored": [],
                "modes": list(self.modes),
                "track": list(self.track),
                "disarmed_in_air": list(self.disarmed_in_air),
                "max_rel_alt_m": None if not math.isfinite(self.max_alt) else round(self.max_alt, 2),
                "max_alt_above_first_home_m": None
                if not math.isfinite(self.max_alt)
                else round(self.max_alt, 2),
                "max_distance_first_home_m": round(self.max_distance, 2),
                "max_ground_speed_mps": round(self.max_speed, 3),
                "max_climb_mps": round(self.max_climb, 3),
                "max_descent_mps": 0.0,
                "hit_ground_mps": 0.0,
                "ever_armed": self.ever_armed,
                "mode_now": self._mode,
            }

    # -- acting as another ground station -----------------------------------------------------------
    def read_param(self, name: str) -> float:
        deadline = time.monotonic() + scaled(10)
        with self.lock:
            self.params.pop(name, None)
        while time.monotonic() < deadline:
            self.conn.mav.param_request_read_send(self.target, 1, name.encode(), -1)
            end = time.monotonic() + 1.0
            while time.monotonic() < end:
                with self.lock:
                    if name in self.params:
                        return self.params[name]
                time.sleep(0.05)
        raise AssertionError(f"the autopilot did not answer a read of {name}")

    def store_mission(self, items: Sequence[dict[str, Any]]) -> None:
        """Upload ``items`` (MISSION_ITEM_INT fields with lat/lon in degrees; ArduPilot's seq 0 is home and
        is sent as a placeholder, PX4 has none)."""
        full = list(items) if self.px4 else [{"command": MAV.MAV_CMD_NAV_WAYPOINT, "frame": 0}, *items]
        with self.lock:
            self._mission_msgs.clear()
        self.conn.mav.mission_count_send(self.target, 1, len(full), 0)
        sent: set[int] = set()
        deadline = time.monotonic() + scaled(30)
        while time.monotonic() < deadline:
            with self.lock:
                pending = list(self._mission_msgs)
                self._mission_msgs.clear()
            for msg in pending:
                kind = msg.get_type()
                if kind == "MISSION_ACK":
                    if msg.type != MAV.MAV_MISSION_ACCEPTED:
                        raise AssertionError(
                            f"the autopilot refused the other ground station's mission: {msg}"
                        )
                    if len(sent) == len(full):
                        return
                elif kind in ("MISSION_REQUEST", "MISSION_REQUEST_INT") and msg.seq < len(full):
                    item = full[msg.seq]
                    self.conn.mav.mission_item_int_send(
                        self.target, 1, msg.seq, item.get("frame", MAV.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT),
                        item["command"], 0, 1, *(float(item.get(f"param{i}", 0.0)) for i in range(1, 5)),
                        round(item.get("lat", 0.0) * 1e7), round(item.get("lon", 0.0) * 1e7),
                        float(item.get("z", 0.0)), 0,
                    )  # fmt: skip
                    sent.add(msg.seq)
            time.sleep(0.05)
        raise AssertionError(f"the mission upload did not finish: {len(sent)} of {len(full)} items sent")

    def close(self) -> None:
        self._stop.set()
        self.thread.join(timeout=5)
        self.conn.close()


@contextlib.contextmanager
def watching(address: str, px4: bool) -> Iterator[AutopilotWatch]:
    watch = AutopilotWatch(address, px4)
    try:
        deadline = time.monotonic() + scaled(30)
        while watch.target == 0 or watch.first_home is None:
            if time.monotonic() > deadline:
                raise AssertionError(f"no HEARTBEAT and HOME_POSITION from the autopilot on {address}")
            if watch.target:
                watch.conn.mav.command_long_send(
                    watch.target,
                    1,
                    MAV.MAV_CMD_REQUEST_MESSAGE,
                    0,
                    MAV.MAVLINK_MSG_ID_HOME_POSITION,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                )
            time.sleep(0.5)
        yield watch
    finally:
        watch.close()
