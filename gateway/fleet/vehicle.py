"""One registered drone: its sidecar, its MAVSDK session, its telemetry cache, and its actions.

The connection state is derived from facts, each time it is read:

    registered   no sidecar wanted (not connected, or disconnected)
    connecting   sidecar starting / waiting for the vehicle to be discovered / gRPC session opening
    connected    gRPC session up, heartbeats fresh, but not (yet) healthy enough to fly
    ready        connected + global position ok + home position ok (+ system id as expected)
    link_lost    session up but no vehicle heartbeat for ``link_lost_after_s``
    failed       the sidecar supervisor gave up (``last_error`` says why)

ArduPilot pitfalls handled here (see the reference captures): arm in GUIDED after waiting for
``is_armable``; hold is a GUIDED reposition to the current position (never MAVSDK's hold, i.e. LOITER);
missions go through ``mission_raw`` with seq 0 = home hidden (PX4 has no home slot, and its verdict on
a mission comes after the upload's ACK, in a STATUSTEXT); unknown parameter names get no reply;
telemetry rates are requested by the gateway and again whenever they are lost.
"""

from __future__ import annotations

import asyncio
import contextlib
import enum
import json
import logging
import time
from collections.abc import Awaitable, Callable, Iterable, Sequence
from datetime import UTC, datetime
from typing import TYPE_CHECKING, Any, TypeVar

import grpc
from mavsdk_grpc import System
from mavsdk_grpc import mission_raw as mavsdk_mission_raw

from gateway.config import Settings
from gateway.errors import CommandFailed, InvalidArgument, VehicleNotReady
from gateway.fleet import geo, mission, refusals
from gateway.fleet.mission import MissionItem, WirePlan
from gateway.fleet.modes import (
    ARDUCOPTER_MODE_NAMES,
    COPTER_TYPES,
    MAV_AUTOPILOT_ARDUPILOTMEGA,
    MAV_AUTOPILOT_PX4,
    ModeChoice,
    autopilot_name,
    require_mode,
)
from gateway.fleet.params import Parameters
from gateway.fleet.rawlink import MAV_RESULT, MAV_RESULT_ACCEPTED, CommandChannel, LinkFacts, NoAck
from gateway.fleet.telemetry import (
    ARDUPILOT_SKIP,
    PX4_SKIP,
    MissionProgressValue,
    TelemetryCache,
    TelemetryFeed,
)
from gateway.registry.sidecar import Confine, Sidecar, SidecarState
from gateway.registry.spec import VehicleSpec

if TYPE_CHECKING:
    from gateway.fleet.flightlog import FlightRecorder

log = logging.getLogger("gateway.vehicle")
T = TypeVar("T")

__all__ = ["ConnectionState", "MissionItem", "Vehicle"]

# gRPC call timeouts (s): MAVSDK retries MAVLink commands itself; these bound a dead sidecar.
CALL_TIMEOUT_S = 10.0
MISSION_TIMEOUT_S = 30.0
CONNECT_TIMEOUT_S = 10.0
ARMABLE_WAIT_S = 60.0
MODE_CONFIRM_S = 4.0
RATE_RETRY_S = 5.0

MAV_CMD_CONDITION_YAW = 115
MAV_CMD_DO_SET_MODE = 176
MAV_CMD_MISSION_START = 300
MAV_CMD_SET_MESSAGE_INTERVAL = 511
MAV_CMD_REQUEST_MESSAGE = 512
MAVLINK_MSG_MISSION_CURRENT = 42
MAVLINK_MSG_EKF_STATUS_REPORT = 193
EKF_POS_HORIZ_ABS = 16
EKF_CONST_POS_MODE = 128
#: arming refusals that go away by themselves while the autopilot initialises (retried within the cap)
ARM_WAIT_TEXTS = ("position estimate", "ekf", "gps", "waiting", "initialis", "initializ", "heading", "gyros",
                  "accels", "ahrs", "home", "alt estimate")  # fmt: skip
ARM_RETRY_S = 1.0
MAVLINK_MSG_SIMSTATE = 164
MISSION_STATE_COMPLETE = 5
#: PX4 checks an uploaded mission after acknowledging it and says so in STATUSTEXT within this time
MISSION_VERDICT_S = 1.5
#: how PX4's mission feasibility checks start their STATUSTEXT when they reject a mission
PX4_MISSION_REJECTIONS = ("mission rejected", "geofence violation for waypoint", "waypoint above maximum")


class ConnectionState(enum.StrEnum):
    REGISTERED = "registered"
    CONNECTING = "connecting"
    CONNECTED = "connected"
    READY = "ready"
    LINK_LOST = "link_lost"
    FAILED = "failed"


class Vehicle:
    """A registered drone. Created by the Registry; ``connect()`` starts its sidecar."""

    def __init__(
        self,
        spec: VehicleSpec,
        settings: Settings,
        *,
        store: Any | None = None,
        peers: Callable[[], Iterable[Vehicle]] | None = None,
        confine: Confine | None = None,
        on_state: Callable[[Vehicle, ConnectionState, ConnectionState], None] | None = None,
    ) -> None:
        self.spec = spec
        self.settings = settings
        self.store = store
        self.telemetry = TelemetryCache(stale_after_s=settings.link_lost_after_s)
        self._peers = peers
        self._confine = confine
        self._on_state = on_state
        self._sidecar: Sidecar | None = None
        self._system: System | None = None
        self._session_task: asyncio.Task[None] | None = None
        self._session_started: float | None = None
        self._session_tasks: list[asyncio.Task[Any]] = []
        self._feed: TelemetryFeed | None = None
        self._monitor_task: asyncio.Task[None] | None = None
        self._recorder: FlightRecorder | None = None
        self._link = LinkFacts()
        self._commands = CommandChannel(settings.gcs_sysid)
        self._last_error: str | None = None
        self._state = ConnectionState.REGISTERED
        self._state_since = time.monotonic()
        self._rates_requested_at: float = 0.0
        self._rates_task: asyncio.Task[None] | None = None
        self._connected_flag: bool | None = None
        self.is_simulator = False
        self.autopilot_version: str | None = None
        self._mission_plan: WirePlan | None = None
        self._mission_state: int | None = None  # MISSION_CURRENT.mission_state (5 = COMPLETE)
        self._mission_rejection: str | None = None  # the autopilot's words when it refused the mission
        self._ekf_flags: int | None = None  # EKF_STATUS_REPORT.flags (ArduPilot), None until one arrives
        self.params = Parameters(spec.id, self._call, self._require_session)
        self.sessions = 0  # gRPC sessions opened (1 + sidecar restarts that reached serving)

    # --- identity and state ---------------------------------------------------------------------------
    @property
    def id(self) -> str:
        return self.spec.id

    @property
    def sidecar(self) -> Sidecar | None:
        return self._sidecar

    @property
    def system(self) -> System:
        """The raw ``mavsdk_grpc.System`` of the current session (for what the wrapper does not cover)."""
        if self._system is None:
            raise VehicleNotReady(
                f"drone '{self.id}' has no MAVSDK session (state {self.state.value})", state=self.state.value
            )
        return self._system

    @property
    def sysid(self) -> int | None:
        return self._link.sysid

    @property
    def autopilot(self) -> str | None:
        return autopilot_name(self._link.autopilot) if self._link.autopilot is not None else None

    @property
    def current_flight_id(self) -> int | None:
        """The id of the flight being recorded (armed now), None on the ground or while not connected."""
        recorder = self._recorder
        return recorder.flight.id if recorder is not None and recorder.flight is not None else None

    @property
    def last_heartbeat_age_s(self) -> float | None:
        hb = self._link.last_heartbeat
        return None if hb is None else max(0.0, time.monotonic() - hb)

    @property
    def sysid_mismatch(self) -> bool:
        return (
            self.spec.expected_sysid is not None
            and self._link.sysid is not None
            and self._link.sysid != self.spec.expected_sysid
        )

    @property
    def duplicate_sysid(self) -> list[str]:
        """Ids of other connected vehicles reporting this vehicle's system id."""
        if self._link.sysid is None or self._peers is None:
            return []
        return sorted(
            p.id
            for p in self._peers()
            if p is not self and p.sysid == self._link.sysid and p.state != ConnectionState.REGISTERED
        )

    @property
    def state(self) -> ConnectionState:
        self._note_state()  # transitions are recorded by whoever sees them first (reader or monitor)
        return self._state

    @property
    def last_error(self) -> str | None:
        return self._last_error

    def _compute_state(self) -> ConnectionState:
        car = self._sidecar
        if car is None:
            return ConnectionState.REGISTERED
        if car.state == SidecarState.FAILED:
            return ConnectionState.FAILED
        if self._system is None or self._session_started is None:
            return ConnectionState.CONNECTING
        limit = self.settings.link_lost_after_s
        age = self.last_heartbeat_age_s
        if age is None:
            since = time.monotonic() - self._session_started
            return ConnectionState.LINK_LOST if since > limit else ConnectionState.CONNECTED
        if age > limit:
            return ConnectionState.LINK_LOST
        sample = self.telemetry.health  # raw age: fresh() depends on the state computed here
        health = sample.value if sample is not None and sample.age_s <= limit else None
        if self._waiting_for(health) is None and not self.sysid_mismatch:
            return ConnectionState.READY
        return ConnectionState.CONNECTED

    def _waiting_for(self, health: Any) -> str | None:
        """What a connected vehicle still lacks before it can be flown, in words; None when nothing."""
        if health is None:
            return "waiting for health reports"
        if not health.global_position_ok:
            return "waiting for a GPS position"
        if not health.home_position_ok or self.telemetry.home is None:
            return "waiting for the home position"
        if not self._position_estimate_ok(health):
            return "waiting for the position estimate (the EKF is not using GPS yet)"
        return None

    def _position_estimate_ok(self, health: Any) -> bool:
        """ArduPilot says "Need Position Estimate" until its EKF uses GPS, well after GPS and home are
        fine: EKF_STATUS_REPORT tells (absolute horizontal position, not constant-position mode).
        Without that report, MAVSDK's local position health."""
        flags = self._ekf_flags
        if flags is not None and self._link.autopilot == MAV_AUTOPILOT_ARDUPILOTMEGA:
            return bool(flags & EKF_POS_HORIZ_ABS) and not flags & EKF_CONST_POS_MODE
        return bool(health.local_position_ok)

    def initialising(self) -> str | None:
        """While connected but not ready: what the vehicle is still waiting for (None otherwise)."""
        if self.state != ConnectionState.CONNECTED:
            return None
        sample = self.telemetry.health
        return self._waiting_for(sample.value if sample is not None else None)

    def status(self) -> dict[str, Any]:
        car = self._sidecar
        age = self.last_heartbeat_age_s
        mode = self.telemetry.fresh("flight_mode")
        armed = self.telemetry.fresh("armed")
        return {
            "id": self.id,
            "name": self.spec.name,
            "url": self.spec.url,
            "tags": list(self.spec.tags),
            "state": self.state.value,
            "state_age_s": round(time.monotonic() - self._state_since, 3),
            "last_heartbeat_age_s": None if age is None else round(age, 3),
            "last_heartbeat_at": _iso(self._link.last_heartbeat_wall),
            "last_error": self._describe_error(),
            "sysid": self._link.sysid,
            "expected_sysid": self.spec.expected_sysid,
            "sysid_mismatch": self.sysid_mismatch,
            "duplicate_sysid": self.duplicate_sysid,
            # other autopilots heard on this vehicle's link (mavsdk_server follows only the first)
            "other_sysids_on_link": sorted(self._link.sysids_seen - {self._link.sysid}),
            "is_simulator": self.is_simulator,
            "autopilot": self.autopilot,
            "autopilot_version": self.autopilot_version,
            "flight_mode": mode,
            "armed": armed,
            "initialising": self.initialising(),
            "unsupported_streams": sorted(self._feed.unsupported_rates) if self._feed else [],
            "sidecar": {
                "state": car.state.value if car else "stopped",
                "pid": car.pid if car else None,
                "grpc_port": car.grpc_port if car else None,
                "restarts": car.info.restarts if car else 0,
            },
        }

    def _describe_error(self) -> str | None:
        """The last failure; while connecting, what the sidecar complains about (refused, no device...)."""
        car = self._sidecar
        if car is not None and car.state == SidecarState.STARTING and car.info.complaint:
            return f"waiting for the vehicle on {self.spec.url}: {car.info.complaint}"
        return self._last_error

    def require_ready(self) -> None:
        """Raise VehicleNotReady naming the state (and why) unless the vehicle is ready to fly."""
        state = self.state
        if state == ConnectionState.READY:
            return
        reason = {
            ConnectionState.REGISTERED: "it is not connected (connect it first)",
            ConnectionState.CONNECTING: "its link is still being established",
            ConnectionState.CONNECTED: "it is connected but not ready (still initialising)",
            ConnectionState.LINK_LOST: "its link is lost (no heartbeat)",
            ConnectionState.FAILED: "its sidecar failed",
        }[state]
        waiting = self.initialising()
        if waiting is not None:
            reason = f"it is connected but not ready: {waiting}"
        if self.sysid_mismatch:
            reason = (
                f"it reports system id {self._link.sysid} but {self.spec.expected_sysid} is expected "
                "(wrong vehicle on this link?)"
            )
        msg = f"drone '{self.id}' is {state.value}: {reason}"
        error = self._describe_error()
        if error and state in (ConnectionState.FAILED, ConnectionState.LINK_LOST, ConnectionState.CONNECTING):
            msg += f"; last error: {error}"
        raise VehicleNotReady(msg, state=state.value)

    async def wait_initialised(self, within_s: float = ARMABLE_WAIT_S) -> None:
        """Like require_ready, but a drone that is connected and still initialising (waiting for its
        position estimate) is waited for, up to ``within_s``: arming or taking off right after
        connecting then succeeds instead of failing."""
        if self.state == ConnectionState.CONNECTED and self.initialising() is not None:
            log.info("%s: %s; waiting up to %g s before arming", self.id, self.initialising(), within_s)
            with contextlib.suppress(VehicleNotReady):
                await self.wait_for_state(ConnectionState.READY, within_s=within_s)
        self.require_ready()

    def _require_session(self) -> System:
        """For commands that must still be tried when the vehicle is not 'ready' (land, RTL, disarm...)."""
        if self._system is None or self.state in (ConnectionState.REGISTERED, ConnectionState.FAILED):
            self.require_ready()
        return self.system

    # --- lifecycle --------------------------------------------------------------------------------------
    async def connect(self) -> None:
        """Start the sidecar and everything that follows (idempotent, returns at once)."""
        if self._sidecar is not None:
            if self._sidecar.state != SidecarState.FAILED:
                return
            await self.disconnect()  # connecting a failed vehicle again starts afresh
        self._last_error = None
        self._sidecar = Sidecar(
            self.id,
            self.spec.url,
            self.settings,
            on_serving=self._on_serving,
            on_down=self._on_sidecar_down,
            confine=self._confine,
        )
        self._sidecar.start()
        self._monitor_task = asyncio.create_task(self._monitor(), name=f"monitor-{self.id}")
        if self.store is not None:
            from gateway.fleet.flightlog import FlightRecorder

            self._recorder = FlightRecorder(self, self.store, self.settings)
            await self._recorder.start()

    async def disconnect(self) -> None:
        """Stop everything of this vehicle; no mavsdk_server process remains."""
        if self._recorder is not None:
            recorder, self._recorder = self._recorder, None
            await recorder.stop()
        if self._monitor_task is not None:
            self._monitor_task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._monitor_task
            self._monitor_task = None
        await self._end_session()
        if self._sidecar is not None:
            car, self._sidecar = self._sidecar, None
            await car.stop()
        self._note_state()

    async def wait_for_state(self, *states: ConnectionState | str, within_s: float = 60.0) -> ConnectionState:
        """Wait until the state is one of ``states``; raise VehicleNotReady naming the state otherwise."""
        wanted = {ConnectionState(s) for s in states}
        loop = asyncio.get_running_loop()
        deadline = loop.time() + within_s
        while (state := self.state) not in wanted:
            if loop.time() > deadline:
                raise VehicleNotReady(
                    f"drone '{self.id}' did not reach {'/'.join(sorted(s.value for s in wanted))} within "
                    f"{within_s:g} s; it is {state.value}"
                    + (f" ({self._last_error})" if self._last_error else ""),
                    state=state.value,
                )
            await asyncio.sleep(0.1)
        return state

    # --- session (one per serving sidecar process) ---------------------------------------------------------
    def _on_serving(self, port: int) -> None:
        old = self._session_task
        self._session_task = asyncio.create_task(self._session(port, old), name=f"session-{self.id}")

    def _on_sidecar_down(self, reason: str) -> None:
        self._last_error = reason
        task, self._session_task = self._session_task, None
        if task is not None:
            task.cancel()
        # the session is gone now, not when its task has finished unwinding
        self._system = None
        self._feed = None
        self._session_started = None
        self._note_state()

    async def _end_session(self) -> None:
        task, self._session_task = self._session_task, None
        if task is not None:
            task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await task

    async def _session(self, port: int, previous: asyncio.Task[None] | None) -> None:
        if previous is not None:
            previous.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await previous
        system = System(mavsdk_server_address="127.0.0.1", port=port)
        try:
            await asyncio.wait_for(system.connect(), CONNECT_TIMEOUT_S)
        except (TimeoutError, grpc.aio.AioRpcError) as exc:
            self._last_error = f"gRPC session to mavsdk_server on port {port} failed: {exc!r}"
            log.warning("%s: %s; restarting the sidecar", self.id, self._last_error)
            await _close_system(system)
            if self._sidecar is not None:
                self._sidecar.recycle()  # the supervisor starts a fresh process (with backoff)
            return
        self.telemetry.clear()
        self._link = LinkFacts()
        self._commands = CommandChannel(self.settings.gcs_sysid)
        self._rates_requested_at = 0.0
        self._connected_flag = None
        self._ekf_flags = None
        feed = TelemetryFeed(
            self.id,
            system,
            self.telemetry,
            mission_progress_map=self._map_progress,
            use_mavsdk_flight_mode=self._mavsdk_names_modes,
        )
        self._system = system
        self._feed = feed
        self._session_started = time.monotonic()
        self.sessions += 1
        feed.start()
        self._session_tasks = [
            asyncio.create_task(_keep(self.id, name, fn, system, once), name=f"{name}-{self.id}")
            for name, fn, once in (
                ("hb", self._heartbeats, False),
                ("ack", self._commands.pump, False),
                ("simstate", self._simstate, True),
                ("conn", self._connection_state, False),
                ("mission", self._mission_current, False),
                ("events", self._px4_events, False),
                ("ekf", self._ekf_status, False),
            )
        ]
        self._session_tasks.append(asyncio.create_task(self._identify(system), name=f"ident-{self.id}"))
        if self.settings.sidecar_heartbeat_watchdog_s:
            self._session_tasks.append(
                asyncio.create_task(self._feed_watchdog(system), name=f"watchdog-{self.id}")
            )
        log.info("%s: MAVSDK session open on gRPC port %d", self.id, port)
        self._schedule_rates("session start")
        try:
            await asyncio.Event().wait()  # lives until cancelled (sidecar down, disconnect)
        finally:
            tasks = [*self._session_tasks, *([self._rates_task] if self._rates_task else [])]
            self._session_tasks = []
            self._rates_task = None
            for t in tasks:
                t.cancel()
            await asyncio.gather(*tasks, return_exceptions=True)
            await feed.stop()
            if self._system is system:
                self._system = None
                self._feed = None
                self._session_started = None
            self._commands.cancel_all()
            await _close_system(system)

    def _mavsdk_names_modes(self) -> bool:
        """MAVSDK's flight mode names are used for non-ArduCopter autopilots only (ArduCopter's real mode
        comes from HEARTBEAT.custom_mode; MAVSDK would say OFFBOARD for GUIDED, HOLD for LOITER)."""
        return self._link.autopilot is not None and not self._is_arducopter()

    def _is_arducopter(self) -> bool:
        return self._link.autopilot == MAV_AUTOPILOT_ARDUPILOTMEGA and self._link.mav_type in COPTER_TYPES

    async def _heartbeats(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("HEARTBEAT"):
            link = self._link
            if not link.heartbeat(int(msg.system_id), json.loads(msg.fields_json)):
                continue  # another ground station on the link
            if link.sysid_changed and self.sysid_mismatch:
                self._last_error = (
                    f"system id mismatch: vehicle reports {link.sysid}, expected {self.spec.expected_sysid}"
                )
                log.error("%s: %s", self.id, self._last_error)
            if self._is_arducopter():
                mode = link.custom_mode or 0
                self.telemetry.put("flight_mode", ARDUCOPTER_MODE_NAMES.get(mode, f"MODE_{mode}"))

    async def _simstate(self, system: System) -> None:
        async for _msg in system.mavlink_direct.message("SIMSTATE"):
            if not self.is_simulator:
                log.info("%s: SIMSTATE received: this vehicle is a simulator", self.id)
            self.is_simulator = True
            return  # known; stop streaming it through gRPC

    async def _ekf_status(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("EKF_STATUS_REPORT"):
            self._ekf_flags = int(json.loads(msg.fields_json).get("flags", 0))

    async def _px4_events(self, system: System) -> None:
        """PX4 tells a ground station that speaks the events protocol (MAVSDK does) why it refuses a
        mission or an arming as EVENT messages, not STATUSTEXT: keep them with the status texts."""
        while self._link.autopilot is None:  # noqa: ASYNC110 - set by the HEARTBEAT loop, no event to wait on
            await asyncio.sleep(0.2)
        if self._link.autopilot != MAV_AUTOPILOT_PX4:
            await asyncio.Event().wait()  # nothing to follow on this link until the session ends
        async for event in system.events.events():
            severity = getattr(event.log_level, "name", "info").lower()
            self.telemetry.add_status_text(severity, " ".join(str(event.message).split()))

    async def _connection_state(self, system: System) -> None:
        async for cs in system.core.connection_state():
            was = self._connected_flag
            self._connected_flag = bool(cs.is_connected)
            if was is False and cs.is_connected:
                self._schedule_rates("vehicle reconnected", force=True)

    async def _identify(self, system: System) -> None:
        for _ in range(10):
            try:
                v = await asyncio.wait_for(system.info.get_version(), 5.0)
            except Exception:  # AUTOPILOT_VERSION may not have arrived yet
                await asyncio.sleep(2.0)
                continue
            kind = getattr(v.flight_sw_version_type, "name", "")
            self.autopilot_version = (
                f"{v.flight_sw_major}.{v.flight_sw_minor}.{v.flight_sw_patch} {kind}".strip()
            )
            return

    async def _feed_watchdog(self, system: System) -> None:
        """Enable mavsdk_server's heartbeat watchdog for this session and keep feeding it: if the gateway
        hangs, the GCS heartbeat stops and the autopilot's own GCS failsafe can act."""
        timeout = float(self.settings.sidecar_heartbeat_watchdog_s)
        period = max(0.5, timeout / 3)
        while True:
            try:
                await asyncio.wait_for(system.core.set_heartbeat_watchdog_timeout(timeout), 5.0)
                break
            except Exception as exc:  # retried: a session without its watchdog is not what was configured
                log.warning("%s: cannot enable the heartbeat watchdog: %r", self.id, exc)
                await asyncio.sleep(1.0)
        while True:
            with contextlib.suppress(Exception):
                await asyncio.wait_for(system.core.feed_heartbeat_watchdog(), period)
            await asyncio.sleep(period)

    # --- telemetry rates ---------------------------------------------------------------------------------
    def _schedule_rates(self, why: str, force: bool = False) -> None:
        if self._system is None or (self._rates_task is not None and not self._rates_task.done()):
            return
        if not force and time.monotonic() - self._rates_requested_at < RATE_RETRY_S:
            return
        self._rates_requested_at = time.monotonic()
        log.info("%s: requesting telemetry rates (%s)", self.id, why)
        self._rates_task = asyncio.create_task(self._request_rates(), name=f"rates-{self.id}")

    async def _request_rates(self) -> None:
        feed = self._feed
        if feed is None:
            return
        for _ in range(30):  # which streams to ask for depends on the autopilot: wait for a HEARTBEAT
            if self._link.autopilot is not None:
                break
            await asyncio.sleep(0.1)
        skip = {MAV_AUTOPILOT_ARDUPILOTMEGA: ARDUPILOT_SKIP, MAV_AUTOPILOT_PX4: PX4_SKIP}.get(
            self._link.autopilot or 0, frozenset()
        )
        await feed.request_rates(lambda what, aw: self._call(what, aw, 5.0), skip)
        # MISSION_CURRENT is only in ArduPilot's EXT_STAT stream: ask for it by id (mission progress);
        # EKF_STATUS_REPORT says when the position estimate is ready (arming in GUIDED needs it)
        for message_id in (MAVLINK_MSG_MISSION_CURRENT, MAVLINK_MSG_EKF_STATUS_REPORT):
            with contextlib.suppress(CommandFailed):
                await self._command_long(MAV_CMD_SET_MESSAGE_INTERVAL, message_id, 1e6, what="rate")
        if not self.is_simulator:  # a simulator says so with SIMSTATE; real ArduPilot answers FAILED
            with contextlib.suppress(CommandFailed):
                await self._command_long(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_SIMSTATE, what="SIMSTATE")

    async def _monitor(self) -> None:
        """Every 0.25 s: log state changes, re-request rates when streams stopped while heartbeats go on."""
        while True:
            self._note_state()
            if self._system is not None:
                hb = self.last_heartbeat_age_s
                heartbeats_fresh = hb is not None and hb < self.settings.link_lost_after_s
                limit = max(2.0, self.settings.link_lost_after_s * 0.66)
                # both requested streams silent (a vehicle without GPS may never send a position)
                streams_silent = all(
                    sample is None or sample.age_s > limit
                    for sample in (self.telemetry.position, self.telemetry.attitude)
                )
                if heartbeats_fresh and streams_silent:
                    self._schedule_rates("telemetry streams silent while heartbeats continue (reboot?)")
            await asyncio.sleep(0.25)

    def _note_state(self) -> None:
        state = self._compute_state()
        self.telemetry.live = state in (ConnectionState.CONNECTED, ConnectionState.READY)
        if state != self._state:
            old, self._state = self._state, state
            self._state_since = time.monotonic()
            log.info("%s: %s -> %s", self.id, old.value, state.value)
            if state == ConnectionState.FAILED and self._sidecar is not None:
                self._last_error = self._sidecar.info.last_error
            if state == ConnectionState.LINK_LOST:
                self._last_error = f"no heartbeat for more than {self.settings.link_lost_after_s:g} s"
            if self._on_state is not None:
                try:
                    self._on_state(self, old, state)
                except Exception:
                    log.exception("state listener failed")

    # --- calling MAVSDK ---------------------------------------------------------------------------------
    async def _call(self, what: str, aw: Awaitable[T], timeout_s: float = CALL_TIMEOUT_S) -> T:
        """Await one gRPC call with a timeout; MAVSDK errors become CommandFailed with the result text
        and what the autopilot said about it (its status text, which may come just after the ACK)."""
        started = time.time()
        try:
            return await asyncio.wait_for(aw, timeout_s)
        except TimeoutError:
            raise CommandFailed(
                f"{what} on drone '{self.id}': no answer from its mavsdk_server within {timeout_s:g} s",
                vehicle_id=self.id,
            ) from None
        except grpc.aio.AioRpcError as exc:
            raise CommandFailed(
                f"{what} on drone '{self.id}': mavsdk_server unreachable ({exc.code().name}); "
                f"the drone is {self.state.value}",
                vehicle_id=self.id,
            ) from None
        except (CommandFailed, VehicleNotReady, InvalidArgument):
            raise
        except Exception as exc:
            result = getattr(exc, "_result", None)
            if result is None:
                raise
            name = getattr(result.result, "name", str(result.result))
            said = await self._complaint_since(started)
            raise CommandFailed(
                f"{what} on drone '{self.id}' failed: {result.result_str} ({name})" + said,
                vehicle_id=self.id,
                result=name,
            ) from None

    async def _command_long(
        self, command: int, *params: float, what: str, attempts: int = 3, wait_s: float = 1.5
    ) -> None:
        """Send COMMAND_LONG through mavlink_direct and wait for its COMMAND_ACK (MAVSDK has no call)."""
        system = self._require_session()
        target = self._link.sysid or self.spec.expected_sysid or 1
        sent_at = time.time()
        try:
            result = await self._commands.send(
                system,
                lambda aw: self._call(what, aw, 5.0),
                target,
                command,
                params,
                attempts=attempts,
                wait_s=wait_s,
            )
        except NoAck as exc:
            raise CommandFailed(f"{what} on drone '{self.id}': {exc}", vehicle_id=self.id) from None
        if result != MAV_RESULT_ACCEPTED:
            name = MAV_RESULT.get(result, str(result))
            raise CommandFailed(
                f"{what} on drone '{self.id}' refused by the vehicle: {name}"
                + await self._complaint_since(sent_at),
                vehicle_id=self.id,
                result=name,
            )

    def _recent_complaint(self, within_s: float = 5.0, since: float | None = None) -> str:
        """What the autopilot said (warning or worse) in the last few seconds, or since ``since`` (wall
        clock), to explain a refusal; "" when it said nothing."""
        said = self._said_since(time.time() - within_s if since is None else since)
        return f" (autopilot says: {refusals.quoted(said)})" if said else ""

    async def _complaint_since(self, since: float) -> str:
        """Why the autopilot refused what was sent at ``since``: its texts (waiting briefly for them, as
        they can follow the result), or what the vehicle was doing when it gave no reason."""
        said = await refusals.wait_said(lambda: self.telemetry.status_texts, since)
        return refusals.explain(said, self._facts())

    def _said_since(self, since: float) -> list[str]:
        return refusals.said_since(self.telemetry.status_texts, since)

    def _facts(self) -> str:
        """The vehicle's state in a few words, for a refusal the autopilot did not explain."""
        mode = self.telemetry.fresh("flight_mode")
        armed = self.telemetry.fresh("armed")
        in_air = self.telemetry.fresh("in_air")
        parts = [
            f"mode {mode}" if mode else "mode unknown",
            "armed" if armed else "disarmed" if armed is False else "armed state unknown",
            "in the air" if in_air else "on the ground" if in_air is False else "",
        ]
        waiting = self.initialising()
        if waiting:
            parts.append(waiting)
        return "it is " + ", ".join(p for p in parts if p)

    # --- modes ------------------------------------------------------------------------------------------
    def resolve_mode(self, name: str) -> ModeChoice:
        """The requested mode on this drone's autopilot; InvalidArgument listing its modes otherwise."""
        return require_mode(name, self._link.autopilot == MAV_AUTOPILOT_PX4, self.id)

    async def set_flight_mode(self, name: str) -> None:
        """Switch flight mode by a common name (HOLD, RTL, LAND, MISSION, ...) or the autopilot's own;
        done once the HEARTBEAT reports the new mode."""
        choice = self.resolve_mode(name)
        self._require_session()
        if self._link.custom_mode == choice.custom_mode:
            return
        await self._command_long(MAV_CMD_DO_SET_MODE, *choice.params, what=f"set mode {choice.native}")
        loop = asyncio.get_running_loop()
        deadline = loop.time() + MODE_CONFIRM_S
        while self._link.custom_mode != choice.custom_mode:
            if loop.time() > deadline:
                now = self.telemetry.fresh("flight_mode") or f"custom mode {self._link.custom_mode}"
                raise CommandFailed(
                    f"set mode {choice.native} on drone '{self.id}' was accepted "
                    f"but the vehicle still reports {now}" + self._recent_complaint(),
                    vehicle_id=self.id,
                )
            await asyncio.sleep(0.05)

    # --- actions ----------------------------------------------------------------------------------------
    async def arm(self) -> None:
        """Arm (ArduPilot: in GUIDED, switched to first). The arming attempt itself is the check: its
        refusal carries the autopilot's reason. A reason the autopilot lifts by itself while it
        initialises ("Need Position Estimate": SYS_STATUS's pre-arm bit lags a mode change by up to a
        second) is retried for up to ARMABLE_WAIT_S; any other comes back at once, in its words."""
        await self.wait_initialised()
        if self.telemetry.fresh("armed"):
            return
        system = self.system
        loop = asyncio.get_running_loop()
        deadline = loop.time() + ARMABLE_WAIT_S
        if self._link.autopilot != MAV_AUTOPILOT_PX4:
            await self.set_flight_mode("GUIDED")
        while True:
            attempt_at = time.time()
            try:
                await self._call("arm", system.action.arm())
                return
            except CommandFailed as exc:
                said = self._said_since(attempt_at)
                passing = bool(said) and all(_lifts_by_itself(text) for text in said)
                if not passing or loop.time() + ARM_RETRY_S > deadline:
                    raise self._arm_refusal(exc, said, waited=passing) from None
            log.info("%s: arming refused while initialising (%s); retrying", self.id, "; ".join(said))
            await asyncio.sleep(ARM_RETRY_S)

    def _arm_refusal(self, exc: CommandFailed, said: list[str], waited: bool) -> CommandFailed:
        if not said:
            return exc
        gps = self.telemetry.fresh("gps_info")
        facts = f"GPS {gps.fix_type}, {gps.num_satellites} satellites" if gps is not None else "no GPS report"
        words = refusals.quoted(said)
        if waited:
            return CommandFailed(
                f"drone '{self.id}' cannot arm yet: autopilot says {words} ({facts}; still refused after "
                f"{ARMABLE_WAIT_S:g} s); call again in a few seconds or check fleet_status",
                vehicle_id=self.id,
                result=exc.details.get("result"),
            )
        return CommandFailed(
            f"drone '{self.id}' refused to arm: autopilot says {words} ({facts})",
            vehicle_id=self.id,
            result=exc.details.get("result"),
        )

    async def disarm(self) -> None:
        await self._call("disarm", self._require_session().action.disarm())

    async def kill(self) -> None:
        """Stop the motors at once, even in the air (the policy decides who may call this)."""
        await self._call("kill", self._require_session().action.kill())

    async def takeoff(self, alt_rel_m: float) -> None:
        """Arm if needed, then take off to ``alt_rel_m`` metres above home. Returns once accepted."""
        geo.check_finite("takeoff altitude", alt_rel_m)
        if alt_rel_m <= 0:
            raise InvalidArgument(f"takeoff altitude must be above 0 m; got {alt_rel_m:g}")
        await self.wait_initialised()
        system = self.system
        if self.telemetry.fresh("in_air"):
            raise CommandFailed(f"drone '{self.id}' is already flying; use goto to change altitude")
        await self.arm()
        await self._call("set takeoff altitude", system.action.set_takeoff_altitude(float(alt_rel_m)))
        await self._call("takeoff", system.action.takeoff())

    def home_amsl_m(self) -> float:
        home = self.telemetry.home
        if home is None:
            raise VehicleNotReady(f"drone '{self.id}' has no home position yet", state=self.state.value)
        return home.value.abs_alt_m

    async def goto(self, lat: float, lon: float, alt_rel_m: float, yaw_deg: float | None = None) -> None:
        """Fly to lat/lon at ``alt_rel_m`` above home (converted to AMSL with the cached home)."""
        geo.check_lat_lon(lat, lon)
        geo.check_finite("altitude", alt_rel_m)
        if yaw_deg is not None:
            geo.check_finite("yaw", yaw_deg)
        self.require_ready()
        amsl = geo.relative_to_amsl(float(alt_rel_m), self.home_amsl_m())
        yaw = float("nan") if yaw_deg is None else float(yaw_deg) % 360.0
        await self._call("goto", self.system.action.goto_location(float(lat), float(lon), amsl, yaw))

    async def hold(self) -> None:
        """Hold position: GUIDED reposition to where the vehicle is now (never LOITER/ALT_HOLD, in
        which a copter without RC throttle descends). On the ground there is nothing to hold."""
        system = self._require_session()
        if not self.telemetry.fresh("in_air"):
            return
        pos = self.telemetry.fresh("position")
        if pos is None:
            raise CommandFailed(f"cannot hold drone '{self.id}': no current position", vehicle_id=self.id)
        await self._call(
            "hold", system.action.goto_location(pos.lat_deg, pos.lon_deg, pos.abs_alt_m, float("nan"))
        )

    async def land(self) -> None:
        await self._call("land", self._require_session().action.land())

    async def return_to_launch(self) -> None:
        await self._call("return to launch", self._require_session().action.return_to_launch())

    async def set_yaw(self, heading_deg: float) -> None:
        """Turn to a heading (degrees from true north) in place."""
        geo.check_finite("heading", heading_deg)
        self.require_ready()
        heading = float(heading_deg) % 360.0
        if self._link.autopilot == MAV_AUTOPILOT_PX4:
            pos = self.telemetry.fresh("position")
            if pos is None:
                raise CommandFailed(f"cannot yaw drone '{self.id}': no current position", vehicle_id=self.id)
            await self._call(
                "set yaw", self.system.action.goto_location(pos.lat_deg, pos.lon_deg, pos.abs_alt_m, heading)
            )
            return
        # CONDITION_YAW: p1 angle, p2 rate (0 = default), p3 direction (0 = shortest), p4 0 = absolute
        await self._command_long(MAV_CMD_CONDITION_YAW, heading, 0, 0, 0, what="set yaw")

    async def set_max_speed(self, mps: float) -> None:
        geo.check_finite("speed", mps)
        if mps <= 0:
            raise InvalidArgument(f"speed must be above 0 m/s; got {mps:g}")
        await self._call("set speed", self._require_session().action.set_current_speed(float(mps)))

    # --- missions ---------------------------------------------------------------------------------------
    def _map_progress(self, current: int, total: int) -> MissionProgressValue:
        """Wire progress (seq incl. home) in user numbers. "Finished" comes from MISSION_CURRENT's
        mission_state COMPLETE (ArduPilot >= 4.5): MAVSDK's progress never reaches current == total
        against ArduPilot, whose MISSION_CURRENT.total leaves out home."""
        finished = self._mission_state == MISSION_STATE_COMPLETE
        plan = self._mission_plan
        first = 1 if self._home_slot() else 0  # the wire seq of user item 1
        if plan is None:
            user_total = max(0, total - first)
            user = min(max(0, current - first + 1), user_total)
        else:
            user_total = len(plan.user_to_wire)
            user = plan.user_index(current) if current >= first and user_total else 0
        return MissionProgressValue(user_total if finished else user, user_total, finished)

    def _home_slot(self) -> bool:
        """ArduPilot keeps home at mission seq 0; PX4 has no such slot (see gateway.fleet.mission)."""
        return self._link.autopilot != MAV_AUTOPILOT_PX4

    async def _mission_current(self, system: System) -> None:
        """MISSION_CURRENT (requested at 1 Hz): current seq and the mission state."""
        async for msg in system.mavlink_direct.message("MISSION_CURRENT"):
            fields = json.loads(msg.fields_json)
            state = int(fields.get("mission_state", 0))
            if state != self._mission_state:
                self._mission_state = state
                total = int(fields.get("total", 0))
                # ArduPilot's MISSION_CURRENT.total excludes home; wire counts include it
                wire_total = total + 1 if self._home_slot() else total
                progress = self._map_progress(int(fields.get("seq", 0)), wire_total)
                self.telemetry.put("mission_progress", progress)

    async def upload_mission(self, items: Sequence[MissionItem | dict[str, Any]]) -> int:
        """Upload user items 1..N (on ArduPilot, home at seq 0 is added and hidden). Returns N.

        Raises CommandFailed with the autopilot's words when it refuses the mission, in the MISSION_ACK
        or (PX4) in the STATUSTEXT of its feasibility check; such a mission is never started."""
        if not isinstance(items, list | tuple) or not items:
            raise InvalidArgument("a mission needs at least one item")
        if len(items) > mission.MAX_ITEMS:
            raise InvalidArgument(f"a mission holds at most {mission.MAX_ITEMS} items; got {len(items)}")
        parsed: list[MissionItem] = []
        for k, item in enumerate(items, start=1):
            try:
                parsed.append(item if isinstance(item, MissionItem) else MissionItem.model_validate(item))
            except Exception as exc:
                raise InvalidArgument(f"mission item {k}: {exc}") from None
        system = self._require_session()
        home = self.telemetry.home
        plan = mission.encode(
            parsed,
            (home.value.lat_deg, home.value.lon_deg, home.value.abs_alt_m) if home else None,
            home_slot=self._home_slot(),
        )
        raw = [
            mavsdk_mission_raw.MissionItem(
                w.seq, w.frame, w.command, 1 if w.seq == 0 else 0, 1,
                w.param1, w.param2, w.param3, w.param4, w.x, w.y, w.z, 0,
            )
            for w in plan.items
        ]  # fmt: skip
        self._mission_plan = None  # whatever was on board is being replaced
        self._mission_state = None
        rejection = await self._upload_checked(system, raw)
        self._mission_plan = plan
        self._mission_rejection = rejection
        if rejection is not None:
            raise CommandFailed(
                f"drone '{self.id}' rejected the mission ({len(parsed)} items): {rejection}. "
                "It will not be started; change the items and upload again.",
                vehicle_id=self.id,
                result="MISSION_REJECTED",
            )
        return len(parsed)

    async def _upload_checked(self, system: System, raw: list[Any]) -> str | None:
        """Upload; return the autopilot's rejection text if its feasibility check refused the mission."""
        heard: list[str] = []
        verdict = asyncio.Event()

        def listen(item: Any) -> None:
            text = str(item.text).strip()
            if text.lower().startswith(PX4_MISSION_REJECTIONS):
                heard.append(text)
                verdict.set()

        self.telemetry.on_status_text(listen)
        try:
            try:
                await self._call("upload mission", system.mission_raw.upload_mission(raw), MISSION_TIMEOUT_S)
            except CommandFailed as exc:  # a MISSION_ACK error: add what the autopilot said, if anything
                raise CommandFailed(
                    exc.message + self._recent_complaint(), vehicle_id=self.id, **exc.details
                ) from None
            if not self._home_slot():
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(verdict.wait(), MISSION_VERDICT_S)
        finally:
            self.telemetry.remove_status_listener(listen)
        return heard[0] if heard else None

    async def download_mission(self) -> list[MissionItem]:
        """The vehicle's mission as user items 1..N (home, seq 0, hidden)."""
        system = self._require_session()
        raw = await self._call("download mission", system.mission_raw.download_mission(), MISSION_TIMEOUT_S)
        items, plan = mission.decode(list(raw), home_slot=self._home_slot())
        self._mission_plan = plan
        return items

    async def clear_mission(self) -> None:
        await self._call(
            "clear mission", self._require_session().mission_raw.clear_mission(), MISSION_TIMEOUT_S
        )
        self._mission_plan = WirePlan(items=[], user_to_wire=[])
        self._mission_state = None
        self._mission_rejection = None

    async def start_mission(self) -> None:
        """Run the uploaded mission. ArduPilot on the ground: arm in GUIDED, then MISSION_START (which
        takes off; mission_raw.start_mission only switches to AUTO). PX4 on the ground: switch to
        MISSION first, so that a mission PX4 refuses stops before the motors are armed. In the air:
        switch to AUTO / MISSION."""
        self.require_ready()
        system = self.system
        if self._mission_rejection is not None:
            raise CommandFailed(
                f"drone '{self.id}' rejected its uploaded mission ({self._mission_rejection}); "
                "upload a corrected mission first",
                vehicle_id=self.id,
                result="MISSION_REJECTED",
            )
        if self._mission_plan is None:
            await self.download_mission()
        if self._mission_plan is None or not self._mission_plan.user_to_wire:
            raise CommandFailed(
                f"drone '{self.id}' has no mission to start; upload one first", vehicle_id=self.id
            )
        self._mission_state = None  # a COMPLETE from an earlier run is not this run's
        if self.telemetry.fresh("in_air"):
            await self._call("start mission", system.mission_raw.start_mission())
            return
        if self._link.autopilot == MAV_AUTOPILOT_PX4:
            await self._call("start mission", system.mission_raw.start_mission())
            await self.arm()
            return
        await self.arm()
        await self._command_long(MAV_CMD_MISSION_START, 0, 0, what="start mission")

    async def set_current_mission_item(self, user_index: int) -> None:
        if not isinstance(user_index, int) or isinstance(user_index, bool):
            raise InvalidArgument(f"mission item index must be an integer; got {user_index!r}")
        system = self._require_session()
        if self._mission_plan is None:
            await self.download_mission()
        plan = self._mission_plan
        count = len(plan.user_to_wire) if plan else 0
        if plan is None or not 1 <= user_index <= count:
            raise InvalidArgument(f"mission item index must be 1..{count}; got {user_index}")
        await self._call(
            "set current mission item", system.mission_raw.set_current_mission_item(plan.wire_seq(user_index))
        )

    async def is_mission_finished(self) -> bool:
        if self._mission_state == MISSION_STATE_COMPLETE:
            return True
        return bool(
            await self._call("mission finished", self._require_session().mission_raw.is_mission_finished())
        )

    def return_altitude_param(self) -> tuple[str, float]:
        """The parameter that sets the altitude RTL flies home at, and its units per metre: ArduPilot's
        RTL_ALT is in centimetres, PX4's RTL_RETURN_ALT in metres."""
        if self._link.autopilot == MAV_AUTOPILOT_PX4:
            return "RTL_RETURN_ALT", 1.0
        return "RTL_ALT", 100.0

    # --- parameters (gateway.fleet.params) ---------------------------------------------------------------
    async def get_param(self, name: str) -> tuple[float | int, str]:
        """Value and type ('int' | 'float'); tries the other ArduPilot name if the parameter was renamed."""
        return await self.params.get(name)

    async def set_param(self, name: str, value: float | int) -> tuple[float | int, str]:
        """Write a parameter with the vehicle's own type for it; returns (stored value, type)."""
        return await self.params.set(name, value)

    async def list_params(self, max_age_s: float | None = None) -> dict[str, float | int]:
        """All parameters, fetched once and cached; ``max_age_s`` forces a refetch of an older copy."""
        return await self.params.all(max_age_s)

    @property
    def params_fetched_age_s(self) -> float | None:
        return self.params.list_age_s


def _lifts_by_itself(text: str) -> bool:
    """An arming refusal that goes away while the autopilot initialises (EKF, GPS, sensors settling)."""
    return any(word in text.lower() for word in ARM_WAIT_TEXTS)


async def _keep(
    vehicle_id: str, name: str, subscribe: Callable[[Any], Awaitable[None]], system: Any, once: bool
) -> None:
    """Run one subscription loop for the session; resubscribe when its gRPC stream ends or breaks
    (``once``: a loop that returns by itself is done, e.g. SIMSTATE seen)."""
    delay = 0.5
    while True:
        try:
            await subscribe(system)
            if once:
                return
            log.debug("%s: %s subscription ended; resubscribing", vehicle_id, name)
        except asyncio.CancelledError:
            raise
        except Exception as exc:
            log.debug("%s: %s subscription failed (%r); resubscribing", vehicle_id, name, exc)
        await asyncio.sleep(delay)
        delay = min(delay * 2, 5.0)


def _iso(epoch_s: float | None) -> str | None:
    return None if epoch_s is None else datetime.fromtimestamp(epoch_s, UTC).isoformat()


async def _close_system(system: System) -> None:
    """Close the gRPC channel of a System (mavsdk_grpc keeps it private: reach it through a stub)."""
    try:
        stub = system._plugins["core"]._stub
        channel = stub.SubscribeConnectionState._references[0]
        await channel.close(grace=None)
    except Exception:  # best effort; the channel is also closed when collected
        pass
