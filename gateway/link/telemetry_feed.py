"""The telemetry feed: one subscription per MAVSDK stream of a vehicle, written into its TelemetryCache.

ArduCopter streams nothing until asked and mavsdk_server never asks: ``TelemetryFeed.request_rates``
sets every stream rate through ``telemetry.set_rate_*``; the vehicle calls it again after every
reconnect, sidecar restart or vehicle reboot. The stream items are converted here into the cache's
value types (``gateway.link.telemetry``).
"""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Protocol, TypeVar

from gateway.link.mavsdk_system import System
from gateway.link.telemetry import (
    AttitudeValue,
    BatteryValue,
    GpsInfoValue,
    HealthValue,
    ImuValue,
    MissionProgressValue,
    OdometryValue,
    PositionValue,
    RcStatusValue,
    TelemetryCache,
    VelocityNedValue,
)

log = logging.getLogger("gateway.telemetry")

Item = TypeVar("Item")

#: Streams and the rate (Hz) the gateway requests for each while the drone rests (disarmed on the
#: ground); MAVSDK's set_rate_<name>, which sends MAV_CMD_SET_MESSAGE_INTERVAL for the stream's message.
#: Each message costs the sidecar its parsing and the gateway one gRPC stream item (the most of a drone's
#: CPU at rest), so a stream gets the rate its readers need and no more. The position at 1 Hz: the read
#: tools and the flight log's 1 Hz track. SYS_STATUS (health) at 1 Hz: the link is ready only while its
#: health is younger than the staleness limit (3 s). Every stream the policy or a readiness check reads
#: fresh (home, attitude, landed state, GPS, battery) stays at 1 Hz too: at one message every 2 s, one
#: message lost on the radio or late on a busy machine makes the reading older than the 3 s limit, and a
#: takeoff is refused for an "unknown" battery. Only what no check reads fresh (the IMU and odometry)
#: comes every 2 s. A drone that is armed or in the air gets ``ACTIVE_RATES_HZ`` on top (the
#: operations' trackers: arrival within tolerance, the climb, the landing, the yaw).
#: Not requested and not subscribed: a heading stream (MAVSDK repeats GLOBAL_POSITION_INT's at the
#: position rate; the heading is the attitude's yaw), in_air (the same EXTENDED_SYS_STATE as the landed
#: state, from which it is taken), armed (the link reads it from the HEARTBEAT it follows anyway) and
#: LOCAL_POSITION_NED (MAVSDK's velocity stream follows GLOBAL_POSITION_INT, so the velocity comes at
#: the position rate without it). No rc_status rate either: MAVSDK takes the RC status from SYS_STATUS
#: and RC_CHANNELS and answers its set_rate_rc_status with Unsupported.
STREAM_RATES_HZ: dict[str, float] = {
    "position": 1.0,  # GLOBAL_POSITION_INT: position and velocity
    "home": 1.0,  # HOME_POSITION
    "attitude_euler": 1.0,  # ATTITUDE: attitude, and the heading (its yaw)
    "landed_state": 1.0,  # EXTENDED_SYS_STATE: landed state and in_air
    "gps_info": 1.0,  # GPS_RAW_INT
    "battery": 1.0,  # BATTERY_STATUS
    "health": 1.0,  # SYS_STATUS
    "imu": 0.5,  # HIGHRES_IMU (PX4)
    "raw_imu": 0.5,  # RAW_IMU (ArduPilot has no HIGHRES_IMU)
    "odometry": 0.5,  # ODOMETRY (PX4; ArduPilot answers "No ap_message for mavlink id (331)")
}

#: The rates of a drone that is armed or in the air, where they differ from the rest rates: the
#: operations' trackers poll every 0.2 s and judge arrival, climb and landing from these streams.
ACTIVE_RATES_HZ: dict[str, float] = {
    "position": 5.0,
    "attitude_euler": 2.0,
    "landed_state": 2.0,
}

#: MAVSDK's landed states that say whether the drone is in the air (MAVSDK's own in_air stream says
#: the same from the same message; any other state keeps the last answer, as MAVSDK's does)
_IN_AIR_BY_LANDED_STATE = {"ON_GROUND": False, "IN_AIR": True, "TAKING_OFF": True, "LANDING": True}


# --- what the gateway reads of MAVSDK's stream items (mavsdk_grpc ships no type hints) ------------


class _Named(Protocol):
    """An enum value of MAVSDK's (landed state, flight mode, GPS fix type, status text type)."""

    name: str


class _GeoPoint(Protocol):
    latitude_deg: float
    longitude_deg: float
    absolute_altitude_m: float
    relative_altitude_m: float


class _Battery(Protocol):
    remaining_percent: float | None
    voltage_v: float | None


class _Frd(Protocol):
    forward_m_s2: float
    right_m_s2: float
    down_m_s2: float


class _AngularFrd(Protocol):
    forward_rad_s: float
    right_rad_s: float
    down_rad_s: float


class _Imu(Protocol):
    acceleration_frd: _Frd
    angular_velocity_frd: _AngularFrd
    temperature_degc: float | None


class _Xyz(Protocol):
    x_m: float
    y_m: float
    z_m: float


class _XyzRate(Protocol):
    x_m_s: float
    y_m_s: float
    z_m_s: float


class _Odometry(Protocol):
    position_body: _Xyz
    velocity_body: _XyzRate


class _Attitude(Protocol):
    roll_deg: float
    pitch_deg: float
    yaw_deg: float


class _StatusText(Protocol):
    type: _Named
    text: str


class _MissionProgress(Protocol):
    current: int
    total: int


def _finite(value: float | None) -> float | None:
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


# --- converting MAVSDK stream items ----------------------------------------------------------------


def _position(p: _GeoPoint) -> PositionValue:
    return PositionValue(
        float(p.latitude_deg),
        float(p.longitude_deg),
        float(p.absolute_altitude_m),
        float(p.relative_altitude_m),
    )


def has_global_position(p: _GeoPoint) -> bool:
    """Whether a position (or home) item is a real fix: while an autopilot boots it streams latitude and
    longitude 0, 0 (ArduPilot before its EKF origin) or NaN, which must never be reported as fresh."""
    lat, lon = float(p.latitude_deg), float(p.longitude_deg)
    return math.isfinite(lat) and math.isfinite(lon) and not (lat == 0.0 and lon == 0.0)


def _battery(b: _Battery) -> BatteryValue:
    remaining = _finite(b.remaining_percent)
    if remaining is not None and remaining < 0:  # -1 / NaN: the autopilot does not know
        remaining = None
    return BatteryValue(remaining, _finite(b.voltage_v))


def _imu(i: _Imu) -> ImuValue:
    a, g = i.acceleration_frd, i.angular_velocity_frd
    return ImuValue(
        (a.forward_m_s2, a.right_m_s2, a.down_m_s2),
        (g.forward_rad_s, g.right_rad_s, g.down_rad_s),
        _finite(i.temperature_degc),
    )


MILLI_G_TO_MPS2 = 9.80665 / 1000.0


def _raw_imu(i: _Imu) -> ImuValue:
    """RAW_IMU (ArduPilot's IMU stream) carries its raw units, milli-g and milli-rad/s, which MAVSDK
    passes through unconverted; the cache holds m/s^2 and rad/s like HIGHRES_IMU's."""
    a, g = i.acceleration_frd, i.angular_velocity_frd
    return ImuValue(
        (a.forward_m_s2 * MILLI_G_TO_MPS2, a.right_m_s2 * MILLI_G_TO_MPS2, a.down_m_s2 * MILLI_G_TO_MPS2),
        (g.forward_rad_s / 1000.0, g.right_rad_s / 1000.0, g.down_rad_s / 1000.0),
        _finite(i.temperature_degc),
    )


def _odometry(o: _Odometry) -> OdometryValue:
    p, v = o.position_body, o.velocity_body
    return OdometryValue((p.x_m, p.y_m, p.z_m), (v.x_m_s, v.y_m_s, v.z_m_s))


#: MAVSDK's Health fields, in the order of `HealthValue`'s (gyro_ok, accel_ok, mag_ok, ...)
HEALTH_FIELDS = (
    "is_gyrometer_calibration_ok",
    "is_accelerometer_calibration_ok",
    "is_magnetometer_calibration_ok",
    "is_local_position_ok",
    "is_global_position_ok",
    "is_home_position_ok",
    "is_armable",
)


def _health(h: object) -> HealthValue:
    return HealthValue(*(bool(getattr(h, name)) for name in HEALTH_FIELDS))


class TelemetryFeed:
    """Subscribes the streams of one mavsdk_grpc System once and writes into a TelemetryCache.

    ``mission_progress_map`` turns MAVSDK's wire progress (current seq, total incl. home) into user
    item numbers; the vehicle owns that mapping because it knows how its mission was uploaded.
    ``use_mavsdk_flight_mode`` says whether MAVSDK's flight mode stream is wanted (None: not known yet,
    before the first HEARTBEAT); when the link names the modes from the HEARTBEAT itself it is never
    subscribed. ``armed`` is not subscribed either: the link puts it from the HEARTBEAT.

    The rates follow the drone: ``STREAM_RATES_HZ`` while it rests, ``ACTIVE_RATES_HZ`` from the first
    item that shows it armed or in the air until one shows it disarmed on the ground.
    """

    def __init__(
        self,
        vehicle_id: str,
        system: System,
        cache: TelemetryCache,
        *,
        mission_progress_map: Callable[[int, int], MissionProgressValue] | None = None,
        use_mavsdk_flight_mode: Callable[[], bool | None] = lambda: True,
    ) -> None:
        self.vehicle_id = vehicle_id
        self.system = system
        self.cache = cache
        self._map_progress = mission_progress_map
        self._use_mavsdk_mode = use_mavsdk_flight_mode
        self._tasks: list[asyncio.Task[None]] = []
        self.unsupported_rates: dict[str, str] = {}
        self._call: Callable[[str, Awaitable[object]], Awaitable[object]] | None = None
        self._skip: frozenset[str] = frozenset()
        self._active = False  # armed or in the air: ACTIVE_RATES_HZ wanted
        self._rates_active: bool | None = None  # what the vehicle was last asked for (None: nothing yet)
        self._switch: asyncio.Task[None] | None = None
        self._in_air: bool | None = None

    def _put_fixed(self, name: str, item: _GeoPoint) -> None:
        if has_global_position(item):
            self.cache.put(name, _position(item))

    def start(self) -> None:
        t = self.system.telemetry
        put = self.cache.put
        self._subscribe("position", t.position, self._position)
        self._subscribe("home", t.home, lambda p: self._put_fixed("home", p))
        # the heading is the attitude's yaw: no stream of its own (MAVSDK's heading stream repeats
        # GLOBAL_POSITION_INT's at the position rate, one more gRPC item per position)
        self._subscribe("attitude", t.attitude_euler, self._attitude)
        self._subscribe(
            "velocity_ned",
            t.velocity_ned,
            lambda v: put("velocity_ned", VelocityNedValue(v.north_m_s, v.east_m_s, v.down_m_s)),
        )
        self._subscribe("battery", t.battery, lambda b: put("battery", _battery(b)))
        self._subscribe(
            "gps_info",
            t.gps_info,
            lambda g: put("gps_info", GpsInfoValue(int(g.num_satellites), g.fix_type.name)),
        )
        self._subscribe("flight_mode", self._flight_modes, self._flight_mode)
        self._subscribe("landed_state", t.landed_state, self._landed_state)
        self._subscribe("health", t.health, lambda h: put("health", _health(h)))
        self._subscribe(
            "rc_status",
            t.rc_status,
            lambda r: put(
                "rc_status",
                RcStatusValue(r.was_available_once, r.is_available, _finite(r.signal_strength_percent)),
            ),
        )
        self._subscribe("imu", t.imu, lambda i: put("imu", _imu(i)))
        self._subscribe("raw_imu", t.raw_imu, lambda i: put("imu", _raw_imu(i)))
        self._subscribe("odometry", t.odometry, lambda o: put("odometry", _odometry(o)))
        self._subscribe("status_text", t.status_text, self._status_text)
        self._subscribe("mission_progress", self.system.mission_raw.mission_progress, self._mission_progress)

    def _subscribe(
        self, name: str, subscribe: Callable[[], AsyncIterator[Item]], handle: Callable[[Item], None]
    ) -> None:
        self._tasks.append(
            asyncio.create_task(self._pump(name, subscribe, handle), name=f"tm-{self.vehicle_id}-{name}")
        )

    async def stop(self) -> None:
        tasks, self._tasks = self._tasks, []
        if self._switch is not None:
            tasks.append(self._switch)
            self._switch = None
        for task in tasks:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)

    async def request_rates(
        self, call: Callable[[str, Awaitable[object]], Awaitable[object]], skip: frozenset[str] = frozenset()
    ) -> dict[str, str]:
        """Set every stream rate but ``skip`` (the rest or the active rates, whichever the drone is at);
        ``call(what, coro)`` adds the timeout and error mapping. Returns the streams the vehicle refused,
        by name.
        """
        self._call, self._skip = call, skip
        t = self.system.telemetry
        refused: dict[str, str] = {}
        active = self._active
        rates = {**STREAM_RATES_HZ, **ACTIVE_RATES_HZ} if active else STREAM_RATES_HZ
        for name, hz in rates.items():
            if name in skip:
                continue
            setter = getattr(t, f"set_rate_{name}")
            try:
                await call(f"set_rate_{name}", setter(hz))
            except Exception as exc:  # recorded per stream, the others still get set
                refused[name] = str(exc)
        self.unsupported_rates = refused
        self._rates_active = active
        self._follow_activity()  # the drone may have changed meanwhile
        if refused:
            log.info("%s: streams not granted: %s", self.vehicle_id, ", ".join(sorted(refused)))
        return refused

    # --- rest and active rates --------------------------------------------------------------------------
    @property
    def active(self) -> bool:
        """Whether the drone is armed or in the air, as last seen (the active rates are wanted)."""
        return self._active

    def _follow_activity(self) -> None:
        """Ask for the active or the rest rates when the drone changed between the two (armed or in the
        air vs disarmed on the ground); called with every position and landed state item."""
        cache = self.cache
        armed = cache.armed.value if cache.armed is not None else False
        self._active = bool(armed) or bool(self._in_air)
        if self._call is None or self._active == self._rates_active:
            return  # rates not requested yet (request_rates picks the right ones), or already right
        if self._switch is None or self._switch.done():
            self._switch = asyncio.create_task(self._switch_rates(), name=f"tm-rates-{self.vehicle_id}")

    async def _switch_rates(self) -> None:
        t = self.system.telemetry
        while (call := self._call) is not None and self._active != self._rates_active:
            active = self._active
            for name, hz in ACTIVE_RATES_HZ.items():
                if name in self._skip or name in self.unsupported_rates:
                    continue
                rate = hz if active else STREAM_RATES_HZ[name]
                try:
                    await call(f"set_rate_{name}", getattr(t, f"set_rate_{name}")(rate))
                except Exception as exc:  # tried again with the next item that shows the change
                    log.info("%s: setting the %s rate to %g Hz failed: %s", self.vehicle_id, name, rate, exc)
                    return
            self._rates_active = active
            log.debug("%s: %s telemetry rates", self.vehicle_id, "active" if active else "rest")

    # --- stream items ---------------------------------------------------------------------------------
    def _position(self, p: _GeoPoint) -> None:
        self._put_fixed("position", p)
        self._follow_activity()

    def _landed_state(self, state: _Named) -> None:
        name = state.name
        self.cache.put("landed_state", name)
        in_air = _IN_AIR_BY_LANDED_STATE.get(name, self._in_air)
        if in_air is not None:
            self._in_air = in_air
            self.cache.put("in_air", in_air)
        self._follow_activity()

    async def _flight_modes(self) -> AsyncIterator[_Named]:
        """MAVSDK's flight mode stream, once the first HEARTBEAT has shown the link needs it."""
        while (wanted := self._use_mavsdk_mode()) is None:  # noqa: ASYNC110 - set by the HEARTBEAT loop
            await asyncio.sleep(0.2)
        if not wanted:
            await asyncio.Event().wait()  # the link names the modes itself: nothing to stream
        async for mode in self.system.telemetry.flight_mode():
            yield mode

    def _attitude(self, a: _Attitude) -> None:
        self.cache.put("attitude", AttitudeValue(a.roll_deg, a.pitch_deg, a.yaw_deg))
        yaw = float(a.yaw_deg)
        if math.isfinite(yaw):
            self.cache.put("heading_deg", yaw % 360.0)

    def _status_text(self, text: _StatusText) -> None:
        self.cache.add_status_text(text.type.name.lower(), str(text.text))

    def _flight_mode(self, mode: _Named) -> None:
        if self._use_mavsdk_mode():
            self.cache.put("flight_mode", mode.name)

    def _mission_progress(self, progress: _MissionProgress) -> None:
        current, total = int(progress.current), int(progress.total)
        value = (
            self._map_progress(current, total)
            if self._map_progress is not None
            else MissionProgressValue(current, total, total > 0 and current >= total)
        )
        self.cache.put("mission_progress", value)

    async def _pump(
        self, name: str, subscribe: Callable[[], AsyncIterator[Item]], handle: Callable[[Item], None]
    ) -> None:
        """Keep one stream flowing into the cache; resubscribe after errors (the channel may blip)."""
        delay = 0.5
        while True:
            try:
                async for item in subscribe():
                    handle(item)
                    delay = 0.5
            except asyncio.CancelledError:
                raise
            except Exception as exc:  # logged; the stream is retried
                log.debug("%s: telemetry stream %s ended: %s", self.vehicle_id, name, exc)
            await asyncio.sleep(delay)
            delay = min(delay * 2, 5.0)
