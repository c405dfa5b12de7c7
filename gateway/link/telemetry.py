"""Per-vehicle telemetry: the latest value of every stream, cached with the time it arrived.

Readers answer from the cache at once (never waiting for the next stream item) and see each value's
age; a value older than its stream's limit (``TelemetryCache.stale_limit_s``: ``link_lost_after_s``, or
that times ``SLOW_STREAM_PERIOD_S`` for a stream asked for slower at rest) is reported as stale, never as
current. The vehicle's ``TelemetryFeed`` (``gateway.link.telemetry_feed``) fills it from the MAVSDK
streams.
"""

from __future__ import annotations

import contextlib
import logging
import math
import time
from collections import deque
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, is_dataclass
from typing import ClassVar, Generic, Literal, TypeVar, get_args, get_origin, get_type_hints, overload

from gateway.util.json_types import JsonObject, JsonValue

log = logging.getLogger("gateway.telemetry")

#: a sample only hands its value out: a Sample[bool] is a Sample[object]
Value_co = TypeVar("Value_co", covariant=True)


@dataclass(frozen=True)
class Sample(Generic[Value_co]):
    """A cached value and when it arrived (monotonic clock)."""

    value: Value_co
    received_at: float

    @property
    def age_s(self) -> float:
        return max(0.0, time.monotonic() - self.received_at)


@dataclass(frozen=True)
class PositionValue:
    lat_deg: float
    lon_deg: float
    abs_alt_m: float
    rel_alt_m: float


@dataclass(frozen=True)
class AttitudeValue:
    roll_deg: float
    pitch_deg: float
    yaw_deg: float


@dataclass(frozen=True)
class VelocityNedValue:
    north_mps: float
    east_mps: float
    down_mps: float

    @property
    def ground_speed_mps(self) -> float:
        return math.hypot(self.north_mps, self.east_mps)


@dataclass(frozen=True)
class BatteryValue:
    remaining_pct: float | None  # 0..100 (MAVSDK's remaining_percent is already a percentage)
    voltage_v: float | None


@dataclass(frozen=True)
class GpsInfoValue:
    num_satellites: int
    fix_type: str


@dataclass(frozen=True)
class HealthValue:
    gyro_ok: bool
    accel_ok: bool
    mag_ok: bool
    local_position_ok: bool
    global_position_ok: bool
    home_position_ok: bool
    is_armable: bool


@dataclass(frozen=True)
class RcStatusValue:
    was_available_once: bool
    is_available: bool
    signal_strength_pct: float | None  # None: unknown (MAVSDK says NaN)


@dataclass(frozen=True)
class ImuValue:
    accel_frd_mps2: tuple[float, float, float]
    gyro_frd_rads: tuple[float, float, float]
    temperature_degc: float | None


@dataclass(frozen=True)
class OdometryValue:
    position_body_m: tuple[float, float, float]
    velocity_body_mps: tuple[float, float, float]


@dataclass(frozen=True)
class MissionProgressValue:
    current: int  # user item 1..N being flown (0: not started); N once finished
    total: int
    finished: bool = False  # the last item was reached (MAVSDK reports current == total)


@dataclass(frozen=True)
class StatusTextValue:
    t: float  # wall clock (epoch seconds)
    severity: str  # "info", "warning", "critical", ...
    text: str


#: The period (s) at rest of the streams the feed asks for slower than once a second while the drone
#: rests (``gateway.link.telemetry_feed.STREAM_RATES_HZ``; every other stream's is 1 s). A stream's stale
#: limit is ``stale_after_s`` (``link_lost_after_s``, 3 s: three periods of a 1 Hz stream) times its
#: period, so that one message lost on the radio or late on a busy machine does not make it stale; every
#: value is stale while the link is lost (``live``). No safety check reads these streams fresh at rest:
#: home (the geofence, the return distance) changes only when the autopilot sets it, which it announces
#: at once (ArduPilot's ``set_home`` sends HOME_POSITION: at arming, on DO_SET_HOME), and an armed drone
#: gets home at 1 Hz again (``ACTIVE_RATES_HZ``); the attitude, heading, GPS report, IMU and odometry are
#: read by the read tools, the console and the flight log, and by the yaw tracker in flight (attitude at
#: 2 Hz there).
SLOW_STREAM_PERIOD_S: dict[str, float] = {
    "home": 5.0,  # HOME_POSITION
    "attitude": 5.0,  # ATTITUDE
    "heading_deg": 5.0,  # the attitude's yaw
    "gps_info": 5.0,  # GPS_RAW_INT
    "imu": 5.0,  # RAW_IMU (ArduPilot) or HIGHRES_IMU (PX4)
    "odometry": 5.0,  # ODOMETRY (PX4)
}


@dataclass
class TelemetryCache:
    """Latest value of every stream, each with its arrival time; None until first received.

    Its ``Sample[...] | None`` fields are the one list of streams: `STREAM_TYPES`, ``FIELDS`` and
    `VALUE_TYPES` are read from them (``fresh``'s overloads type the same names for mypy)."""

    stale_after_s: float = 3.0
    #: False while the vehicle's link is lost or its session is down: then every value counts as stale,
    #: even one that arrived a moment after the last heartbeat (the owner keeps this up to date)
    live: bool = True
    position: Sample[PositionValue] | None = None
    home: Sample[PositionValue] | None = None
    attitude: Sample[AttitudeValue] | None = None
    velocity_ned: Sample[VelocityNedValue] | None = None
    heading_deg: Sample[float] | None = None
    battery: Sample[BatteryValue] | None = None
    gps_info: Sample[GpsInfoValue] | None = None
    flight_mode: Sample[str] | None = None
    armed: Sample[bool] | None = None
    in_air: Sample[bool] | None = None
    landed_state: Sample[str] | None = None
    health: Sample[HealthValue] | None = None
    rc_status: Sample[RcStatusValue] | None = None
    imu: Sample[ImuValue] | None = None
    odometry: Sample[OdometryValue] | None = None
    mission_progress: Sample[MissionProgressValue] | None = None
    status_texts: deque[StatusTextValue] = field(default_factory=lambda: deque(maxlen=50))
    #: updates received per stream since the vehicle was created (monotonic counters, for /metrics)
    message_counts: dict[str, int] = field(default_factory=dict)
    _status_listeners: list[Callable[[StatusTextValue], None]] = field(default_factory=list, repr=False)

    #: the streams' names, in the fields' order (set below from `STREAM_TYPES`)
    FIELDS: ClassVar[tuple[str, ...]]

    def put(self, name: str, value: object) -> None:
        if name not in self.FIELDS:
            raise KeyError(name)
        setattr(self, name, Sample(value, time.monotonic()))
        self.message_counts[name] = self.message_counts.get(name, 0) + 1

    def stale_limit_s(self, name: str) -> float:
        """The age past which ``name``'s sample is stale: ``stale_after_s``, times the stream's period at
        rest for a stream asked for slower than once a second (``SLOW_STREAM_PERIOD_S``)."""
        return self.stale_after_s * SLOW_STREAM_PERIOD_S.get(name, 1.0)

    def is_stale(self, name: str, age_s: float) -> bool:
        """Whether a sample of ``name`` this old is stale (every sample is while the link is lost)."""
        return age_s > self.stale_limit_s(name) or not self.live

    def add_status_text(self, severity: str, text: str, t: float | None = None) -> StatusTextValue:
        item = StatusTextValue(t if t is not None else time.time(), severity, text)
        self.status_texts.append(item)
        self.message_counts["status_text"] = self.message_counts.get("status_text", 0) + 1
        for listener in list(self._status_listeners):
            try:
                listener(item)
            except Exception:  # a broken listener must not stop telemetry
                log.exception("status text listener failed")
        return item

    def on_status_text(self, listener: Callable[[StatusTextValue], None]) -> None:
        self._status_listeners.append(listener)

    def remove_status_listener(self, listener: Callable[[StatusTextValue], None]) -> None:
        with contextlib.suppress(ValueError):
            self._status_listeners.remove(listener)

    @overload
    def fresh(
        self, name: Literal["position", "home"], max_age_s: float | None = None
    ) -> PositionValue | None: ...
    @overload
    def fresh(self, name: Literal["attitude"], max_age_s: float | None = None) -> AttitudeValue | None: ...
    @overload
    def fresh(
        self, name: Literal["velocity_ned"], max_age_s: float | None = None
    ) -> VelocityNedValue | None: ...
    @overload
    def fresh(self, name: Literal["heading_deg"], max_age_s: float | None = None) -> float | None: ...
    @overload
    def fresh(self, name: Literal["battery"], max_age_s: float | None = None) -> BatteryValue | None: ...
    @overload
    def fresh(self, name: Literal["gps_info"], max_age_s: float | None = None) -> GpsInfoValue | None: ...
    @overload
    def fresh(
        self, name: Literal["flight_mode", "landed_state"], max_age_s: float | None = None
    ) -> str | None: ...
    @overload
    def fresh(self, name: Literal["armed", "in_air"], max_age_s: float | None = None) -> bool | None: ...
    @overload
    def fresh(self, name: Literal["health"], max_age_s: float | None = None) -> HealthValue | None: ...
    @overload
    def fresh(self, name: Literal["rc_status"], max_age_s: float | None = None) -> RcStatusValue | None: ...
    @overload
    def fresh(self, name: Literal["imu"], max_age_s: float | None = None) -> ImuValue | None: ...
    @overload
    def fresh(self, name: Literal["odometry"], max_age_s: float | None = None) -> OdometryValue | None: ...
    @overload
    def fresh(
        self, name: Literal["mission_progress"], max_age_s: float | None = None
    ) -> MissionProgressValue | None: ...
    @overload
    def fresh(self, name: str, max_age_s: float | None = None) -> object: ...
    def fresh(self, name: str, max_age_s: float | None = None) -> object:
        """The value of ``name`` if it is younger than ``max_age_s`` (default: the stream's stale limit,
        ``stale_limit_s``), else None (typed by the stream's name, one overload per type of value; a name
        not known until run time reads as an object)."""
        sample: Sample[object] | None = getattr(self, name)
        limit = self.stale_limit_s(name) if max_age_s is None else max_age_s
        if sample is None or sample.age_s > limit or not self.live:
            return None
        return sample.value

    def clear(self) -> None:
        """Forget every value (a new vehicle session must not inherit the previous one's state)."""
        for name in self.FIELDS:
            setattr(self, name, None)

    def snapshot(self) -> JsonObject:
        """Everything, each part with ``age_s`` and ``stale``; never-received parts are None.

        ``stale`` is true for a part older than its limit (``stale_limit_s``) and for every part while not
        ``live``."""
        out: JsonObject = {}
        for name in self.FIELDS:
            sample: Sample[object] | None = getattr(self, name)
            if sample is None:
                out[name] = None
                continue
            value = sample.value
            plain = asdict(value) if is_dataclass(value) and not isinstance(value, type) else {"value": value}
            body = {key: _json_safe(part) for key, part in plain.items()}
            age = round(sample.age_s, 3)
            body["age_s"] = age
            body["stale"] = self.is_stale(name, age)
            out[name] = body
        out["status_texts"] = [asdict(item) for item in list(self.status_texts)[-10:]]
        return out


def _stream_types() -> dict[str, type]:
    """Each field of the cache typed ``Sample[X] | None`` (a stream), with ``X``, in the fields' order."""
    streams: dict[str, type] = {}
    for name, hint in get_type_hints(TelemetryCache).items():
        for part in get_args(hint):
            if get_origin(part) is Sample:
                (streams[name],) = get_args(part)
    return streams


#: every stream the cache keeps and the type of its value
STREAM_TYPES: dict[str, type] = _stream_types()
TelemetryCache.FIELDS = tuple(STREAM_TYPES)
#: the dataclass of each structured stream; the others carry a plain value (bool, float, str)
VALUE_TYPES: dict[str, type] = {name: kind for name, kind in STREAM_TYPES.items() if is_dataclass(kind)}


def _json_safe(value: object) -> JsonValue:
    """NaN / inf (MAVSDK's "unknown") become None: results must be strict JSON; a value of no JSON type
    (an enum) its text."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_safe(v) for v in value]
    if value is None or isinstance(value, str | int):
        return value
    return str(value)
