"""The telemetry feed: one subscription per MAVSDK stream of a vehicle, written into its TelemetryCache.

ArduCopter streams nothing until asked and mavsdk_server never asks: ``TelemetryFeed.request_rates``
sets every stream rate, one MAV_CMD_SET_MESSAGE_INTERVAL at a time through the session
(``MESSAGE_IDS``); the vehicle calls it again after every reconnect, sidecar restart or vehicle reboot.
The stream items are converted here into the cache's value types (``gateway.link.telemetry``).
"""

from __future__ import annotations

import asyncio
import logging
import math
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Protocol, TypeVar

from gateway.errors import CommandFailed
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
#: ground): MAV_CMD_SET_MESSAGE_INTERVAL for the stream's message (``MESSAGE_IDS``), sent by the session
#: as a COMMAND_LONG of its own, not through MAVSDK's set_rate_<name> (see ``MESSAGE_IDS``).
#: Each message costs the sidecar its parsing and the gateway one gRPC stream item (the most of a drone's
#: CPU at rest), so a stream gets the rate its readers need and no more. At 1 Hz what a safety or
#: readiness check reads fresh against the 3 s staleness limit (``link_lost_after_s``): the position (the
#: geofence, the read tools, the flight log's 1 Hz track), SYS_STATUS (the health: the link is ready only
#: while it is younger than the limit; the battery), the landed state (in the air or not) and the EKF
#: status (the position estimate a readiness check waits for). Every 5 s what no check reads fresh at
#: rest, each with a stale limit of five times the 3 s (``gateway.link.telemetry.SLOW_STREAM_PERIOD_S``):
#: home (the autopilot sends HOME_POSITION at once when it sets home, at arming or on DO_SET_HOME), the
#: attitude and heading, the GPS report (the fix's effect on the position estimate comes with SYS_STATUS
#: and EKF_STATUS_REPORT), the IMU and odometry. A drone that is armed or in the air gets
#: ``ACTIVE_RATES_HZ`` on top (the operations' trackers: arrival within tolerance, the climb, the
#: landing, the yaw; home and GPS for the flight log at 1 Hz).
#: Not requested and not subscribed: a heading stream (MAVSDK repeats GLOBAL_POSITION_INT's at the
#: position rate; the heading is the attitude's yaw), in_air (the same EXTENDED_SYS_STATE as the landed
#: state, from which it is taken), armed (the link reads it from the HEARTBEAT it follows anyway) and
#: LOCAL_POSITION_NED (MAVSDK's velocity stream follows GLOBAL_POSITION_INT, so the velocity comes at
#: the position rate without it). No rc_status rate either: MAVSDK takes the RC status from SYS_STATUS
#: and RC_CHANNELS and answers its set_rate_rc_status with Unsupported. On ArduPilot the battery is
#: not requested either (the dialect skips it): MAVSDK takes the battery from SYS_STATUS until a
#: BATTERY_STATUS arrives, and ArduPilot fills both from its first battery monitor, so SYS_STATUS at 1 Hz
#: brings the battery at 1 Hz with one message a second fewer.
#: MISSION_CURRENT at rest every 5 s: MAVSDK reports mission progress only when the item or the count
#: changes, and a mission item changes only in flight (armed: 1 Hz, ``ACTIVE_RATES_HZ``); an upload
#: sets the count in MAVSDK itself.
STREAM_RATES_HZ: dict[str, float] = {
    "position": 1.0,  # GLOBAL_POSITION_INT: position and velocity
    "home": 0.2,  # HOME_POSITION
    "attitude_euler": 0.2,  # ATTITUDE: attitude, and the heading (its yaw)
    "landed_state": 1.0,  # EXTENDED_SYS_STATE: landed state and in_air
    "gps_info": 0.2,  # GPS_RAW_INT
    "battery": 1.0,  # BATTERY_STATUS (PX4; ArduPilot: from SYS_STATUS)
    "health": 1.0,  # SYS_STATUS
    "imu": 0.2,  # HIGHRES_IMU (PX4)
    "raw_imu": 0.2,  # RAW_IMU (ArduPilot has no HIGHRES_IMU)
    "odometry": 0.2,  # ODOMETRY (PX4; ArduPilot answers "No ap_message for mavlink id (331)")
    "mission_current": 0.2,  # MISSION_CURRENT (only in ArduPilot's EXT_STAT stream): mission progress
    # EKF_STATUS_REPORT: when the position estimate is ready (a readiness check; arming in GUIDED needs it)
    "ekf_status": 1.0,
    # POSITION_TARGET_GLOBAL_INT: where the autopilot flies to (gateway.fleet.policy.takeover); sent only
    # in the modes that fly to a target, so nothing at rest
    "position_target": 5.0,
}

#: The message of each stream of ``STREAM_RATES_HZ``, by MAVLink message id (the ones MAVSDK's
#: set_rate_<name> asks for, where it has a setter): asked for with MAV_CMD_SET_MESSAGE_INTERVAL through the
#: session's ``set_message_rate``, one request at a time. Not through MAVSDK's setters: mavsdk_server
#: (v4) matches a COMMAND_ACK to the first queued command of the same id, sent or still waiting its
#: turn, so the ACK of an earlier request of the same command (sent again after a late answer) could
#: complete a request that was never sent: reported set, the stream never came (a simulated drone stayed
#: "connected" without SYS_STATUS, so without its health and battery, while nothing was logged).
MESSAGE_IDS: dict[str, int] = {
    "position": 33,  # GLOBAL_POSITION_INT
    "home": 242,  # HOME_POSITION
    "attitude_euler": 30,  # ATTITUDE
    "landed_state": 245,  # EXTENDED_SYS_STATE
    "gps_info": 24,  # GPS_RAW_INT
    "battery": 147,  # BATTERY_STATUS
    "health": 1,  # SYS_STATUS
    "imu": 105,  # HIGHRES_IMU
    "raw_imu": 27,  # RAW_IMU
    "odometry": 331,  # ODOMETRY
    "mission_current": 42,  # MISSION_CURRENT
    "ekf_status": 193,  # EKF_STATUS_REPORT
    "position_target": 87,  # POSITION_TARGET_GLOBAL_INT
}

#: The rates of a drone that is armed or in the air, where they differ from the rest rates: the
#: operations' trackers poll every 0.2 s and judge arrival, climb, landing and yaw from these streams; a
#: mission's progress at 1 Hz; home (set again at arming) and the GPS report at 1 Hz, as the flight log
#: records them.
ACTIVE_RATES_HZ: dict[str, float] = {
    "position": 5.0,
    "attitude_euler": 2.0,
    "landed_state": 2.0,
    "mission_current": 1.0,
    "home": 1.0,
    "gps_info": 1.0,
}

#: Asking again for a stream whose rate request got no answer: after 5 s, doubling per retry up to 60 s
UNANSWERED_RETRY_S = 5.0
UNANSWERED_RETRY_MAX_S = 60.0

#: Results that say the request never got a verdict from the vehicle (MAVSDK's and MAV_RESULT's names):
#: asked again, unlike a refusal (UNSUPPORTED, DENIED, FAILED), which stands
_NOT_ANSWERED = frozenset(
    {"TIMEOUT", "BUSY", "NO_SYSTEM", "CONNECTION_ERROR", "TEMPORARILY_REJECTED", "UNKNOWN"}
)


def not_answered(exc: Exception) -> bool:
    """Whether a failed rate request got no verdict from the vehicle: no answer in time, the sidecar
    unreachable or busy; a CommandFailed without a result is one the gateway raised for no answer."""
    if not isinstance(exc, CommandFailed):
        return True
    result = exc.details.get("result")
    return result is None or result in _NOT_ANSWERED


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
    ``set_message_rate(message_id, hz)`` asks for a stream's message (``MESSAGE_IDS``; without it no rate
    is asked for). ``use_mavsdk_flight_mode`` says whether MAVSDK's flight mode stream is wanted (None:
    not known yet, before the first HEARTBEAT); when the link names the modes from the HEARTBEAT itself it
    is never subscribed. ``armed`` is not subscribed either: the link puts it from the HEARTBEAT.

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
        set_message_rate: Callable[[int, float], Awaitable[object]] | None = None,
    ) -> None:
        self.vehicle_id = vehicle_id
        self.system = system
        self.cache = cache
        self._map_progress = mission_progress_map
        self._use_mavsdk_mode = use_mavsdk_flight_mode
        self._set_message_rate = set_message_rate
        self._tasks: list[asyncio.Task[None]] = []
        self.unsupported_rates: dict[str, str] = {}  # refused by the vehicle: never asked again
        self.unanswered_rates: dict[str, str] = {}  # no answer (a timeout on a busy link): asked again
        self._unanswered_tries = 0
        self._ask_again_at = 0.0
        self._call: Callable[[str, Awaitable[object]], Awaitable[object]] | None = None
        self._skip: frozenset[str] = frozenset()
        self._active = False  # armed or in the air: ACTIVE_RATES_HZ wanted
        self._rates_active: bool | None = None  # what the vehicle was last asked for (None: nothing yet)
        self._switch: asyncio.Task[None] | None = None
        self._requesting = False  # request_rates runs: no switch beside it (it follows the drone after)
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
        self,
        call: Callable[[str, Awaitable[object]], Awaitable[object]],
        skip: frozenset[str] = frozenset(),
        only: frozenset[str] | None = None,
    ) -> dict[str, str]:
        """Set every stream rate but ``skip`` (the rest or the active rates, whichever the drone is at), or
        only the streams ``only`` names (those that got no answer before); ``call(what, coro)`` adds the
        timeout and error mapping. Returns the streams the vehicle refused, by name.
        """
        self._call, self._skip = call, skip
        switch = self._switch
        if switch is not None and not switch.done():
            await asyncio.wait({switch})  # one rate request at a time (a switch that began first ends)
        active = self._active
        rates = {**STREAM_RATES_HZ, **ACTIVE_RATES_HZ} if active else STREAM_RATES_HZ
        if only is None:
            self.unsupported_rates, self.unanswered_rates = {}, {}
        self._requesting = True
        try:
            for name, hz in rates.items():
                if name in skip or (only is not None and name not in only):
                    continue
                request = self._rate_request(name, hz)
                if request is None:
                    continue
                self.unsupported_rates.pop(name, None)
                self.unanswered_rates.pop(name, None)
                try:
                    await call(f"set_rate_{name}", request)
                except Exception as exc:  # recorded per stream, the others still get set
                    failed = self.unanswered_rates if not_answered(exc) else self.unsupported_rates
                    failed[name] = str(exc)
        finally:
            self._requesting = False
        self._after_rates(only is not None)
        if only is None:
            self._rates_active = active
        self._follow_activity()  # the drone may have changed meanwhile
        return dict(self.unsupported_rates)

    def _after_rates(self, retried: bool) -> None:
        """Log what was not granted and when to ask again for what got no answer: 5 s after a request,
        twice as long after each retry that still got none, at most a minute."""
        self._unanswered_tries = self._unanswered_tries + 1 if retried and self.unanswered_rates else 0
        wait = min(UNANSWERED_RETRY_MAX_S, UNANSWERED_RETRY_S * 2**self._unanswered_tries)
        self._ask_again_at = time.monotonic() + wait
        if self.unsupported_rates:
            log.info("%s: streams refused: %s", self.vehicle_id, ", ".join(sorted(self.unsupported_rates)))
        if self.unanswered_rates:
            log.warning(
                "%s: no answer to the rate of %s; asked again in %g s",
                self.vehicle_id, ", ".join(sorted(self.unanswered_rates)), wait,
            )  # fmt: skip

    def rates_to_ask_again(self) -> frozenset[str]:
        """The streams whose rate request got no answer, once asking again is due (a drone missing its
        health, home or EKF stream would never be ready)."""
        if not self.unanswered_rates or time.monotonic() < self._ask_again_at:
            return frozenset()
        return frozenset(self.unanswered_rates)

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
        if self._call is None or self._requesting or self._active == self._rates_active:
            # rates not requested yet or being requested (request_rates picks the right ones and looks
            # again when it ends), or already right
            return
        if self._switch is None or self._switch.done():
            self._switch = asyncio.create_task(self._switch_rates(), name=f"tm-rates-{self.vehicle_id}")

    def _rate_request(self, name: str, hz: float) -> Awaitable[object] | None:
        """The request of one stream's rate: the session's COMMAND_LONG for its message
        (``MESSAGE_IDS``); None for a feed given no ``set_message_rate`` (nothing is asked for)."""
        if self._set_message_rate is None:
            return None
        return self._set_message_rate(MESSAGE_IDS[name], hz)

    async def _switch_rates(self) -> None:
        while (call := self._call) is not None and self._active != self._rates_active:
            active = self._active
            for name, hz in ACTIVE_RATES_HZ.items():
                if name in self._skip or name in self.unsupported_rates:
                    continue
                rate = hz if active else STREAM_RATES_HZ[name]
                request = self._rate_request(name, rate)
                if request is None:
                    continue
                try:
                    await call(f"set_rate_{name}", request)
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
