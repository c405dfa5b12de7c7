"""The link to one vehicle: its sidecar, its MAVSDK session, the connection state machine, the
telemetry cache and the telemetry rates. One ``Link`` per registered vehicle, owned by its ``Vehicle``.

The connection state is derived from facts, each time it is read:

    registered   no sidecar wanted (not connected, or disconnected)
    connecting   sidecar starting / waiting for the vehicle to be discovered / gRPC session opening
    connected    gRPC session up, heartbeats fresh, but not (yet) healthy enough to fly
    ready        connected + global position ok + home position ok + position estimate ok
                 (+ system id as expected)
    link_lost    session up but no vehicle heartbeat for ``link_lost_after_s``
    failed       the sidecar supervisor gave up (``last_error`` says why)

ArduCopter streams nothing until asked and mavsdk_server never asks: the link requests every stream
rate, and again whenever the streams stop while heartbeats go on (a reboot). What depends on the
autopilot (which streams it refuses, how its HEARTBEAT names modes, when its position estimate is
usable, whether it explains refusals in EVENT messages) comes from ``LinkRules``, chosen per autopilot
by the owner once the first HEARTBEAT says which autopilot it is.
"""

from __future__ import annotations

import asyncio
import contextlib
import enum
import json
import logging
import time
from collections.abc import Awaitable, Callable, Iterable
from datetime import UTC, datetime
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

import grpc
from mavsdk_grpc import System

from gateway.config import Settings
from gateway.errors import CommandFailed, InvalidArgument, VehicleNotReady
from gateway.link import refusals
from gateway.link.rawlink import (
    MAV_RESULT,
    MAV_RESULT_ACCEPTED,
    CommandChannel,
    LinkFacts,
    NoAck,
    autopilot_name,
)
from gateway.link.sidecar import Confine, Sidecar, SidecarState
from gateway.link.telemetry import HealthValue, MissionProgressValue, TelemetryCache
from gateway.link.telemetry_feed import TelemetryFeed
from gateway.registry.spec import VehicleSpec

if TYPE_CHECKING:
    from gateway.link.relay import Relay

log = logging.getLogger("gateway.link")
T = TypeVar("T")
OnWait = Callable[[str], Awaitable[None]]
"""Told, in words, what a vehicle still initialising is waiting for (each time that changes)."""

__all__ = ["ConnectionState", "Link", "LinkRules", "SessionJob"]

# gRPC call timeouts (s): MAVSDK retries MAVLink commands itself; these bound a dead sidecar.
CALL_TIMEOUT_S = 10.0
CONNECT_TIMEOUT_S = 10.0
READY_WAIT_S = 60.0
RATE_RETRY_S = 5.0
#: the link monitor's period (s); it also wakes when the link-lost limit is reached, ``MONITOR_LATE_S``
#: after it (so the heartbeat is then older than the limit)
MONITOR_PERIOD_S = 1.0
MONITOR_LATE_S = 0.01

MAV_CMD_SET_MESSAGE_INTERVAL = 511
MAV_CMD_REQUEST_MESSAGE = 512
MAVLINK_MSG_MISSION_CURRENT = 42
MAVLINK_MSG_EKF_STATUS_REPORT = 193
MAVLINK_MSG_POSITION_TARGET_GLOBAL_INT = 87
MAVLINK_MSG_SIMSTATE = 164


class ConnectionState(enum.StrEnum):
    REGISTERED = "registered"
    CONNECTING = "connecting"
    CONNECTED = "connected"
    READY = "ready"
    LINK_LOST = "link_lost"
    FAILED = "failed"


class LinkRules(Protocol):
    """What the link needs to know about the vehicle's autopilot (``gateway.fleet.dialects`` has them)."""

    @property
    def skipped_streams(self) -> frozenset[str]:
        """Telemetry streams not to request (the autopilot refuses them)."""
        ...

    @property
    def follows_events(self) -> bool:
        """Whether the autopilot explains refusals in EVENT messages (kept with the status texts)."""
        ...

    def mode_name(self, custom_mode: int, mav_type: int) -> str | None:
        """The flight mode a HEARTBEAT reports, or None to use MAVSDK's name for it."""
        ...

    def position_estimate_ok(self, health: HealthValue, ekf_flags: int | None) -> bool:
        """Whether the autopilot's position estimate is good enough to arm and fly."""
        ...

    def on_ground(self, telemetry: TelemetryCache) -> bool | None:
        """Whether the vehicle is on the ground (None: no fresh telemetry says)."""
        ...


class Peer(Protocol):
    """Another vehicle's link, as seen for duplicate system ids."""

    @property
    def id(self) -> str: ...

    @property
    def sysid(self) -> int | None: ...

    @property
    def state(self) -> ConnectionState: ...


#: a loop run for the whole of each MAVSDK session (resubscribed when its stream ends)
SessionJob = Callable[[System], Awaitable[None]]


class Link:
    """A registered vehicle's connection. ``connect()`` starts its sidecar; everything else follows."""

    def __init__(
        self,
        spec: VehicleSpec,
        settings: Settings,
        rules_for: Callable[[int | None], LinkRules],
        *,
        peers: Callable[[], Iterable[Peer]] | None = None,
        confine: Confine | None = None,
        on_state: Callable[[ConnectionState, ConnectionState], None] | None = None,
        mission_progress: Callable[[int, int], MissionProgressValue] | None = None,
        session_jobs: Iterable[tuple[str, SessionJob]] = (),
    ) -> None:
        self.spec = spec
        self.settings = settings
        self.telemetry = TelemetryCache(stale_after_s=settings.link_lost_after_s)
        self.facts = LinkFacts()
        self.is_simulator = False
        self.autopilot_version: str | None = None
        self.sessions = 0  # gRPC sessions opened (1 + sidecar restarts that reached serving)
        self._rules_for = rules_for
        self._peers = peers
        self._confine = confine
        self._on_state = on_state
        self._mission_progress = mission_progress
        self._jobs = list(session_jobs)
        self._sidecar: Sidecar | None = None
        self._relay: Relay | None = None  # when ground stations share the drone's MAVLink
        self._system: System | None = None
        self._session_task: asyncio.Task[None] | None = None
        self._session_started: float | None = None
        self._session_tasks: list[asyncio.Task[None]] = []
        self._feed: TelemetryFeed | None = None
        self._monitor_task: asyncio.Task[None] | None = None
        self._commands = CommandChannel(settings.gcs_sysid)
        self._last_error: str | None = None
        self._state = ConnectionState.REGISTERED
        self._state_since = time.monotonic()
        self._rates_requested_at = 0.0
        self._rates_task: asyncio.Task[None] | None = None
        self._connected_flag: bool | None = None
        self._ekf_flags: int | None = None  # EKF_STATUS_REPORT.flags (ArduPilot), None until one arrives

    # --- identity and state ---------------------------------------------------------------------------
    @property
    def id(self) -> str:
        return self.spec.id

    @property
    def rules(self) -> LinkRules:
        return self._rules_for(self.facts.autopilot)

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
        return self.facts.sysid

    @property
    def autopilot(self) -> str | None:
        """ "ardupilot", "px4" or "mav_autopilot_<n>" once a HEARTBEAT came; None before."""
        return autopilot_name(self.facts.autopilot) if self.facts.autopilot is not None else None

    @property
    def last_heartbeat_age_s(self) -> float | None:
        hb = self.facts.last_heartbeat
        return None if hb is None else max(0.0, time.monotonic() - hb)

    @property
    def sysid_mismatch(self) -> bool:
        return (
            self.spec.expected_sysid is not None
            and self.facts.sysid is not None
            and self.facts.sysid != self.spec.expected_sysid
        )

    @property
    def duplicate_sysid(self) -> list[str]:
        """Ids of other connected vehicles reporting this vehicle's system id."""
        if self.facts.sysid is None or self._peers is None:
            return []
        return sorted(
            p.id
            for p in self._peers()
            if p.id != self.id and p.sysid == self.facts.sysid and p.state != ConnectionState.REGISTERED
        )

    @property
    def state(self) -> ConnectionState:
        self._note_state()  # transitions are recorded by whoever sees them first (reader or monitor)
        return self._state

    @property
    def state_age_s(self) -> float:
        return time.monotonic() - self._state_since

    @property
    def last_error(self) -> str | None:
        return self._last_error

    @property
    def unsupported_streams(self) -> list[str]:
        return sorted(self._feed.unsupported_rates) if self._feed else []

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

    def _waiting_for(self, health: HealthValue | None) -> str | None:
        """What a connected vehicle still lacks before it can be flown, in words; None when nothing."""
        if health is None:
            return "waiting for health reports"
        if not health.global_position_ok:
            return "waiting for a GPS position"
        if not health.home_position_ok or self.telemetry.home is None:
            return "waiting for the home position"
        if not self.rules.position_estimate_ok(health, self._ekf_flags):
            return "waiting for the position estimate (the EKF is not using GPS yet)"
        return None

    def initialising(self) -> str | None:
        """While connected but not ready: what the vehicle is still waiting for (None otherwise)."""
        if self.state != ConnectionState.CONNECTED:
            return None
        sample = self.telemetry.health
        return self._waiting_for(sample.value if sample is not None else None)

    def describe_error(self) -> str | None:
        """The last failure; while connecting, what the sidecar complains about (refused, no device...)."""
        car = self._sidecar
        relay = self._relay
        if car is not None and car.state == SidecarState.STARTING:
            complaint = relay.complaint if relay is not None else car.info.complaint
            if complaint:
                return f"waiting for the vehicle on {self.spec.url}: {complaint}"
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
                f"it reports system id {self.facts.sysid} but {self.spec.expected_sysid} is expected "
                "(wrong vehicle on this link?)"
            )
        msg = f"drone '{self.id}' is {state.value}: {reason}"
        error = self.describe_error()
        if error and state in (ConnectionState.FAILED, ConnectionState.LINK_LOST, ConnectionState.CONNECTING):
            msg += f"; last error: {error}"
        raise VehicleNotReady(msg, state=state.value)

    async def wait_ready(self, within_s: float = READY_WAIT_S, on_wait: OnWait | None = None) -> bool:
        """Wait up to ``within_s`` for a vehicle that is connected and still initialising (waiting for
        its position estimate...) to become ready, telling ``on_wait`` ("alpha: waiting for ...") each
        time what it waits for changes; whether it is ready. A vehicle in any other state is not
        waited for."""
        loop = asyncio.get_running_loop()
        deadline = loop.time() + max(0.0, within_s)
        told: str | None = None
        if self.state == ConnectionState.CONNECTED and self.initialising() is not None:
            log.info("%s: %s; waiting up to %g s", self.id, self.initialising(), within_s)
        while self.state != ConnectionState.READY:
            waiting = self.initialising()
            if waiting is None or loop.time() >= deadline:
                break
            if waiting != told and on_wait is not None:
                told = waiting
                with contextlib.suppress(Exception):  # a courtesy; the wait happens regardless
                    await on_wait(f"{self.id}: {waiting}")
            await asyncio.sleep(min(0.1, max(0.0, deadline - loop.time())))
        return self.state == ConnectionState.READY

    async def wait_initialised(self, within_s: float = READY_WAIT_S, on_wait: OnWait | None = None) -> None:
        """Like require_ready, but a drone that is connected and still initialising (waiting for its
        position estimate) is waited for, up to ``within_s``: arming or taking off right after
        connecting then succeeds instead of failing."""
        await self.wait_ready(within_s, on_wait)
        self.require_ready()

    def judges_arming(self) -> bool:
        """Connected to the expected vehicle, which reports its health: an arming attempt now gets the
        autopilot's own judgement (refused, in its words, while it lacks what it needs to fly)."""
        sample = self.telemetry.health
        return (
            self.state in (ConnectionState.CONNECTED, ConnectionState.READY)
            and not self.sysid_mismatch
            and sample is not None
            and sample.age_s <= self.settings.link_lost_after_s
        )

    def require_session(self) -> System:
        """For commands that must still be tried when the vehicle is not 'ready' (land, RTL, disarm...)."""
        if self._system is None or self.state in (ConnectionState.REGISTERED, ConnectionState.FAILED):
            self.require_ready()
        return self.system

    def status(self) -> dict[str, Any]:
        car = self._sidecar
        age = self.last_heartbeat_age_s
        return {
            "id": self.id,
            "name": self.spec.name,
            "url": self.spec.url,
            "tags": list(self.spec.tags),
            "state": self.state.value,
            "state_age_s": round(self.state_age_s, 3),
            "last_heartbeat_age_s": None if age is None else round(age, 3),
            "last_heartbeat_at": _iso(self.facts.last_heartbeat_wall),
            "last_error": self.describe_error(),
            "sysid": self.facts.sysid,
            "expected_sysid": self.spec.expected_sysid,
            "sysid_mismatch": self.sysid_mismatch,
            "duplicate_sysid": self.duplicate_sysid,
            # other autopilots heard on this vehicle's link (mavsdk_server follows only the first)
            "other_sysids_on_link": sorted(self.facts.sysids_seen - {self.facts.sysid}),
            "is_simulator": self.is_simulator,
            "autopilot": self.autopilot,
            "autopilot_version": self.autopilot_version,
            "flight_mode": self.telemetry.fresh("flight_mode"),
            "armed": self.telemetry.fresh("armed"),
            "initialising": self.initialising(),
            "unsupported_streams": self.unsupported_streams,
            "sidecar": {
                "state": car.state.value if car else "stopped",
                "pid": car.pid if car else None,
                "grpc_port": car.grpc_port if car else None,
                "restarts": car.info.restarts if car else 0,
            },
            # each ground station endpoint the drone's MAVLink is relayed to, and what passed
            "ground_stations": self._relay.status() if self._relay is not None else [],
        }

    # --- lifecycle --------------------------------------------------------------------------------------
    async def connect(self) -> None:
        """Start the sidecar and everything that follows (idempotent, returns at once)."""
        if self._sidecar is not None:
            if self._sidecar.state != SidecarState.FAILED:
                return
            await self.disconnect()  # connecting a failed vehicle again starts afresh
        self._last_error = None
        url = self.spec.url
        if self.spec.gcs_endpoints:
            # the gateway holds the drone's link and relays it to the sidecar and the ground stations
            # (the relay's MAVLink dialect, about 7 MiB, is loaded only for a drone that has some)
            from gateway.link.relay import Relay

            relay = Relay(
                self.id, self.spec.url, list(self.spec.gcs_endpoints), sidecar_pid=self._sidecar_pid
            )
            await relay.start()
            self._relay = relay
            url = relay.sidecar_url
        self._sidecar = Sidecar(
            self.id,
            url,
            self.settings,
            on_serving=self._on_serving,
            on_down=self._on_sidecar_down,
            confine=self._confine,
        )
        self._sidecar.start()
        self._monitor_task = asyncio.create_task(self._monitor(), name=f"monitor-{self.id}")

    def _sidecar_pid(self) -> int | None:
        return self._sidecar.pid if self._sidecar is not None else None

    async def disconnect(self) -> None:
        """Stop everything of this link; no mavsdk_server process remains."""
        if self._monitor_task is not None:
            self._monitor_task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._monitor_task
            self._monitor_task = None
        try:
            await self._end_session()
        finally:  # the sidecar stops whatever ending the session raised
            try:
                if self._sidecar is not None:
                    car, self._sidecar = self._sidecar, None
                    await car.stop()
            finally:
                if self._relay is not None:
                    relay, self._relay = self._relay, None
                    await relay.close()
            self._note_state()

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
        self.facts = LinkFacts()
        self._commands = CommandChannel(self.settings.gcs_sysid)
        self._rates_requested_at = 0.0
        self._connected_flag = None
        self._ekf_flags = None
        feed = TelemetryFeed(
            self.id,
            system,
            self.telemetry,
            mission_progress_map=self._mission_progress,
            use_mavsdk_flight_mode=self._mavsdk_names_modes,
        )
        self._system = system
        self._feed = feed
        self._session_started = time.monotonic()
        self.sessions += 1
        feed.start()
        jobs: list[tuple[str, SessionJob, bool]] = [
            ("hb", self._heartbeats, False),
            ("ack", self._commands.pump, False),
            ("simstate", self._simstate, True),
            ("conn", self._connection_state, False),
            ("events", self._events, False),
            ("ekf", self._ekf_status, False),
            *((name, job, False) for name, job in self._jobs),
        ]
        self._session_tasks = [
            asyncio.create_task(_keep(self.id, name, fn, system, once), name=f"{name}-{self.id}")
            for name, fn, once in jobs
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

    def _mavsdk_names_modes(self) -> bool | None:
        """MAVSDK's flight mode names are used unless the dialect names the HEARTBEAT's mode itself
        (ArduCopter: MAVSDK would say OFFBOARD for GUIDED, HOLD for LOITER); None before a HEARTBEAT."""
        facts = self.facts
        if facts.autopilot is None:
            return None
        return self.rules.mode_name(facts.custom_mode or 0, facts.mav_type or 0) is None

    async def _heartbeats(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("HEARTBEAT"):
            facts = self.facts
            if not facts.heartbeat(int(msg.system_id), json.loads(msg.fields_json)):
                continue  # another ground station on the link
            if facts.sysid_changed and self.sysid_mismatch:
                self._last_error = (
                    f"system id mismatch: vehicle reports {facts.sysid}, expected {self.spec.expected_sysid}"
                )
                log.error("%s: %s", self.id, self._last_error)
            self.telemetry.put("armed", bool(facts.armed))  # the telemetry feed has no armed stream
            name = self.rules.mode_name(facts.custom_mode or 0, facts.mav_type or 0)
            if name is not None:
                self.telemetry.put("flight_mode", name)
            self._note_state()  # connected again, ready: seen with the heartbeat, not at the next check

    async def _simstate(self, system: System) -> None:
        async for _msg in system.mavlink_direct.message("SIMSTATE"):
            if not self.is_simulator:
                log.info("%s: SIMSTATE received: this vehicle is a simulator", self.id)
            self.is_simulator = True
            return  # known; stop streaming it through gRPC

    async def _ekf_status(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("EKF_STATUS_REPORT"):
            self._ekf_flags = int(json.loads(msg.fields_json).get("flags", 0))

    async def _events(self, system: System) -> None:
        """An autopilot that speaks the events protocol (PX4; MAVSDK does too) says why it refuses a
        mission or an arming in EVENT messages, not STATUSTEXT: keep them with the status texts."""
        while self.facts.autopilot is None:  # noqa: ASYNC110 - set by the HEARTBEAT loop, no event to wait on
            await asyncio.sleep(0.2)
        if not self.rules.follows_events:
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
        timeout = float(self.settings.sidecar_heartbeat_watchdog_s or 0)
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

    def request_rates_again(self, why: str) -> None:
        """Ask for every telemetry stream again (after something that resets them)."""
        self._schedule_rates(why, force=True)

    async def _request_rates(self) -> None:
        feed = self._feed
        if feed is None:
            return
        for _ in range(30):  # which streams to ask for depends on the autopilot: wait for a HEARTBEAT
            if self.facts.autopilot is not None:
                break
            await asyncio.sleep(0.1)
        skip = self.rules.skipped_streams if self.facts.autopilot is not None else frozenset()
        await feed.request_rates(lambda what, aw: self.call(what, aw, 5.0), skip)
        # MISSION_CURRENT is only in ArduPilot's EXT_STAT stream: ask for it by id (mission progress);
        # EKF_STATUS_REPORT says when the position estimate is ready (arming in GUIDED needs it);
        # POSITION_TARGET_GLOBAL_INT (EXT_STAT too) is where it flies to (gateway.fleet.policy.takeover)
        for message_id, interval_us in (
            (MAVLINK_MSG_MISSION_CURRENT, 1e6),
            (MAVLINK_MSG_EKF_STATUS_REPORT, 1e6),
            (MAVLINK_MSG_POSITION_TARGET_GLOBAL_INT, 5e5),
        ):
            with contextlib.suppress(CommandFailed):
                await self.command_long(MAV_CMD_SET_MESSAGE_INTERVAL, message_id, interval_us, what="rate")
        if not self.is_simulator:  # a simulator says so with SIMSTATE; real ArduPilot answers FAILED
            with contextlib.suppress(CommandFailed):
                await self.command_long(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_SIMSTATE, what="SIMSTATE")

    async def _monitor(self) -> None:
        """Log state changes and re-request rates when streams stopped while heartbeats go on.

        Wakes once a second (``MONITOR_PERIOD_S``), and when the last heartbeat (or, before the first, the
        session's start) reaches the link-lost limit: the one change that comes with nothing arriving.
        Changes that come with data are noted as it arrives (the HEARTBEAT loop) or when ``state`` is
        read; the health and the rate check can wait a second."""
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
            await asyncio.sleep(self._monitor_wait_s())

    def _monitor_wait_s(self) -> float:
        """Until the next check: ``MONITOR_PERIOD_S``, or less when the link-lost limit comes first."""
        wait = MONITOR_PERIOD_S
        if self._system is not None and self._session_started is not None:
            hb = self.facts.last_heartbeat
            since = hb if hb is not None else self._session_started
            until_lost = since + self.settings.link_lost_after_s - time.monotonic()
            if until_lost >= 0.0:
                wait = min(wait, until_lost + MONITOR_LATE_S)
        return max(MONITOR_LATE_S, wait)

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
                    self._on_state(old, state)
                except Exception:
                    log.exception("state listener failed")

    # --- calling MAVSDK ---------------------------------------------------------------------------------
    async def call(self, what: str, aw: Awaitable[T], timeout_s: float = CALL_TIMEOUT_S) -> T:
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

    async def command_long(
        self, command: int, *params: float, what: str, attempts: int = 3, wait_s: float = 1.5
    ) -> None:
        """Send COMMAND_LONG through mavlink_direct and wait for its COMMAND_ACK (MAVSDK has no call)."""
        system = self.require_session()
        target = self.facts.sysid or self.spec.expected_sysid or 1
        sent_at = time.time()
        try:
            result = await self._commands.send(
                system,
                lambda aw: self.call(what, aw, 5.0),
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

    def recent_complaint(self, within_s: float = 5.0, since: float | None = None) -> str:
        """What the autopilot said (warning or worse) in the last few seconds, or since ``since`` (wall
        clock), to explain a refusal: `` (autopilot says: 'A'; 'B')`` or "" when it said nothing."""
        said = self.said_since(time.time() - within_s if since is None else since)
        return f" (autopilot says: {refusals.quoted(said)})" if said else ""

    def said_since(self, since: float) -> list[str]:
        """The autopilot's distinct warning-or-worse texts since ``since`` (wall clock), oldest first."""
        return refusals.said_since(self.telemetry.status_texts, since)

    async def _complaint_since(self, since: float) -> str:
        """Why the autopilot refused what was sent at ``since``: its texts (waiting briefly for them, as
        they can follow the result), or what the vehicle was doing when it gave no reason."""
        said = await refusals.wait_said(lambda: self.telemetry.status_texts, since)
        return refusals.explain(said, self.describe_facts())

    def describe_facts(self) -> str:
        """The vehicle's state in a few words, for a refusal the autopilot did not explain."""
        mode = self.telemetry.fresh("flight_mode")
        armed = self.telemetry.fresh("armed")
        on_ground = self.rules.on_ground(self.telemetry)
        parts = [
            f"mode {mode}" if mode else "mode unknown",
            "armed" if armed else "disarmed" if armed is False else "armed state unknown",
            "on the ground" if on_ground else "in the air" if on_ground is False else "",
        ]
        waiting = self.initialising()
        if waiting:
            parts.append(waiting)
        return "it is " + ", ".join(p for p in parts if p)


async def _keep(vehicle_id: str, name: str, subscribe: SessionJob, system: System, once: bool) -> None:
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
