"""The link to one vehicle: its sidecar, its MAVSDK sessions, the connection state machine and the
telemetry cache. One ``Link`` per registered vehicle, owned by its ``Vehicle``. Its parts: each MAVSDK
session with its loops and rate requests (``mavsdk_session``), calling the vehicle (``mavsdk_calls``),
the link monitor (``link_monitor``), its status (``link_status``), the states and the owner's hooks
(``contract``).

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
import logging
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from grpclib.exceptions import GRPCError, StreamTerminatedError

from gateway.config import Settings
from gateway.errors import VehicleNotReady
from gateway.link import pacing
from gateway.link.contract import ConnectionState, LinkRules, OnWait, Peer
from gateway.link.link_monitor import LinkMonitor
from gateway.link.mavsdk_calls import MavsdkCalls
from gateway.link.mavsdk_session import MavsdkSession, SessionJob, close_system
from gateway.link.mavsdk_system import System
from gateway.link.rawlink import LinkFacts, autopilot_name
from gateway.link.relay_endpoints import device_present
from gateway.link.sidecar import Confine, Sidecar, SidecarState
from gateway.link.telemetry import HealthValue, MissionProgressValue, TelemetryCache
from gateway.link.telemetry_feed import TelemetryFeed
from gateway.registry.spec import VehicleSpec
from gateway.util.tasks import cancel_and_wait

if TYPE_CHECKING:
    from gateway.link.relay import Relay

log = logging.getLogger("gateway.link")
__all__ = ["Link", "LinkHooks"]

# opening the gRPC session (s): bounds a dead sidecar
CONNECT_TIMEOUT_S = 10.0
#: gRPC sessions opening at once, per event loop (``gateway.link.pacing``): a session holds its slot from
#: before it connects until its rates are requested, at most 10 s; the connection's timeout counts from
#: the slot
SESSIONS = pacing.Pace(slots=8, hold_at_most_s=10.0)
READY_WAIT_S = 60.0
#: how long a session waits for its first EKF_STATUS_REPORT before MAVSDK's health decides alone (a
#: stream that never comes must not keep a drone from flying for good)
EKF_REPORT_WAIT_S = 30.0
#: how long a session waits for its first battery reading before a drone is ready without one (the safety
#: policy refuses a takeoff of unknown battery: PX4 at 3x on a loaded machine was ready, and refused to
#: arm, before its first BATTERY_STATUS)
BATTERY_REPORT_WAIT_S = 30.0
#: how far back the autopilot's words are quoted beside "waiting for the autopilot's pre-arm checks"
PREARM_WORDS_S = 30.0


@dataclass(frozen=True)
class LinkHooks:
    """What the link's owner (``gateway.fleet.vehicles.vehicle.Vehicle``) gives it: the autopilot's rules
    (``rules_for``, once the first HEARTBEAT names the autopilot), the other links (``peers``, for
    duplicate system ids), the sidecar's confinement, who hears each state change, the mission-progress
    mapping (autopilot items to the caller's numbers), the jobs each MAVSDK session runs, and who hears
    a ground station's command the relay refused."""

    rules_for: Callable[[int | None], LinkRules]
    peers: Callable[[], Iterable[Peer]] | None = None
    confine: Confine | None = None
    on_state: Callable[[ConnectionState, ConnectionState], None] | None = None
    mission_progress: Callable[[int, int], MissionProgressValue] | None = None
    session_jobs: Sequence[tuple[str, SessionJob]] = ()
    on_relay_refused: Callable[[str, str], None] | None = None


class Link:
    """A registered vehicle's connection. ``connect()`` starts its sidecar; everything else follows."""

    def __init__(self, spec: VehicleSpec, settings: Settings, hooks: LinkHooks) -> None:
        self.spec = spec
        self.settings = settings
        self.telemetry = TelemetryCache(stale_after_s=settings.link_lost_after_s)
        self.facts = LinkFacts()
        self.is_simulator = False
        self.autopilot_version: str | None = None
        self.sessions = 0  # gRPC sessions opened (1 + sidecar restarts that reached serving)
        self.hooks = hooks
        self._sidecar: Sidecar | None = None
        self._relay: Relay | None = None  # when ground stations share the drone's MAVLink or it is recorded
        self._vehicle_bytes: Callable[[bytes], None] | None = None
        self._system: System | None = None
        self._session_task: asyncio.Task[None] | None = None
        self._session_started: float | None = None
        self._prearm_passed = False  # the autopilot's pre-arm bit said "armable" in this session
        self._mavsdk: MavsdkSession | None = None  # the current (or last) MAVSDK session
        self._feed: TelemetryFeed | None = None
        self._monitor: LinkMonitor | None = None
        self._calls = calls = MavsdkCalls(self, settings.gcs_sysid)
        # calling the vehicle (gateway.link.mavsdk_calls), as the owner and the dialects call it
        self.call = calls.call
        self.command_long = calls.command_long
        self.recent_complaint = calls.recent_complaint
        self.said_since = calls.said_since
        self.describe_facts = calls.describe_facts
        self._last_error: str | None = None
        self._wanted = False  # connect() has been asked for and disconnect() has not
        self._state = ConnectionState.REGISTERED
        self._state_since = time.monotonic()

    # --- identity and state ---------------------------------------------------------------------------
    @property
    def id(self) -> str:
        return self.spec.id

    @property
    def rules(self) -> LinkRules:
        return self.hooks.rules_for(self.facts.autopilot)

    @property
    def sidecar(self) -> Sidecar | None:
        return self._sidecar

    @property
    def vehicle_bytes(self) -> Callable[[bytes], None] | None:
        """Given each read from the drone as it came while the link is relayed (the flight's raw log)."""
        return self._vehicle_bytes

    @vehicle_bytes.setter
    def vehicle_bytes(self, sink: Callable[[bytes], None] | None) -> None:
        self._vehicle_bytes = sink
        if self._relay is not None:
            self._relay.on_vehicle_bytes = sink

    @property
    def relay(self) -> Relay | None:
        """The relay of the drone's MAVLink to the sidecar, the ground stations and the flight's raw log
        (None: the sidecar holds the drone's link itself)."""
        return self._relay

    @property
    def system(self) -> System:
        """The MAVSDK System of the current session (for what the wrapper does not cover)."""
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
    def session_started(self) -> float | None:
        """When the current MAVSDK session opened (monotonic clock); None without one."""
        return self._session_started if self._system is not None else None

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
        peers = self.hooks.peers
        if self.facts.sysid is None or peers is None:
            return []
        return sorted(
            p.id
            for p in peers()
            if p.id != self.id and p.sysid == self.facts.sysid and p.state != ConnectionState.REGISTERED
        )

    @property
    def state(self) -> ConnectionState:
        self.note_state()  # transitions are recorded by whoever sees them first (reader or monitor)
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
            return ConnectionState.CONNECTING if self._wanted else ConnectionState.REGISTERED
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
        if self.telemetry.home is None or not (health.home_position_ok or self._armed()):
            return "waiting for the home position"
        ekf_flags = self._mavsdk.ekf_flags if self._mavsdk is not None else None
        if (
            ekf_flags is None
            and self.rules.estimate_from_ekf_report
            and "ekf_status" not in self.unsupported_streams
            and self._session_younger_than(EKF_REPORT_WAIT_S)
        ):
            return "waiting for the position estimate (no EKF status report yet)"
        if not self.rules.position_estimate_ok(health, ekf_flags):
            return "waiting for the position estimate (the EKF is not using GPS yet)"
        if self._awaits_first("battery", BATTERY_REPORT_WAIT_S):
            return "waiting for a battery reading"
        return self._waiting_for_prearm(health)

    def _awaits_first(self, stream: str, wait_s: float) -> bool:
        """Whether the session has had no sample of ``stream`` yet and is younger than ``wait_s`` (a
        stream that never comes must not keep a drone from flying for good)."""
        return getattr(self.telemetry, stream) is None and self._session_younger_than(wait_s)

    def _session_younger_than(self, wait_s: float) -> bool:
        return self._session_started is not None and time.monotonic() - self._session_started < wait_s

    def _waiting_for_prearm(self, health: HealthValue) -> str | None:
        """Where the dialect says so: a disarmed drone initialises until the autopilot's pre-arm bit
        has said "armable" once in this session (a drone seen armed has passed it)."""
        if not self.rules.ready_after_prearm_pass or self._prearm_passed:
            return None
        if health.is_armable or self._armed():
            self._prearm_passed = True
            return None
        return "waiting for the autopilot's pre-arm checks" + self.recent_complaint(within_s=PREARM_WORDS_S)

    def _armed(self) -> bool:
        """Armed, as the last HEARTBEAT said (raw: ``fresh`` reads the state computed from this).
        MAVSDK's health forgets the home at every reconnect (a heartbeat late on a busy link) until
        the next HOME_POSITION; that guards against the old home of a rebooted autopilot, which is
        disarmed: an armed drone keeps the home the gateway has."""
        sample = self.telemetry.armed
        return sample is not None and sample.value is True

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

    # --- lifecycle --------------------------------------------------------------------------------------
    def want(self) -> None:
        """The link is wanted from now on: it reads connecting, not registered, while what precedes its
        sidecar is awaited (a fleet stop meanwhile waits for the drone instead of skipping it)."""
        self._wanted = True
        self.note_state()

    def unwant(self) -> None:
        """A connect that failed before its sidecar started: the link is registered again."""
        if self._sidecar is None:
            self._wanted = False
            self.note_state()

    async def connect(self) -> None:
        """Start the sidecar and everything that follows (idempotent, returns at once)."""
        if self._sidecar is not None:
            if self._sidecar.state != SidecarState.FAILED:
                return
            await self.disconnect()  # connecting a failed vehicle again starts afresh
        self.want()
        try:
            await self._start_sidecar()
        except BaseException:
            self.unwant()
            raise

    async def _start_sidecar(self) -> None:
        self._last_error = None
        url = self.spec.url
        if self.spec.gcs_endpoints or (self.settings.records_flight_frames and device_present(self.spec.url)):
            # the gateway holds the drone's link and relays it to the sidecar and the ground stations,
            # and hands what the drone sends to the flight's raw log (pymavlink's MAVLink dialect,
            # about 6 MiB, is loaded only when a ground station's frame comes)
            from gateway.link.relay import Relay

            relay = Relay(
                self.id,
                self.spec.url,
                list(self.spec.gcs_endpoints),
                sidecar_pid=self._sidecar_pid,
                on_refused=self.hooks.on_relay_refused,
                on_vehicle_bytes=self._vehicle_bytes,
            )
            await relay.start()
            if relay.complaint is not None and not self.spec.gcs_endpoints:
                # relayed only for the flight's raw log, and the gateway cannot open the drone's link
                # (no such device, port taken): the sidecar opens it as without the log, and fails or
                # retries as it does then
                log.warning(
                    "%s: %s; connecting without the raw flight log (the sidecar opens the link)",
                    self.id,
                    relay.complaint,
                )
                await relay.close()
            else:
                self._relay = relay
                url = relay.sidecar_url
        self._sidecar = Sidecar(
            self.id,
            url,
            self.settings,
            on_serving=self._on_serving,
            on_down=self._on_sidecar_down,
            confine=self.hooks.confine,
        )
        self._sidecar.start()
        self._monitor = LinkMonitor(self)

    def _sidecar_pid(self) -> int | None:
        return self._sidecar.pid if self._sidecar is not None else None

    async def disconnect(self) -> None:
        """Stop everything of this link; no mavsdk_server process remains."""
        self._wanted = False
        if self._monitor is not None:
            self._monitor.stop()
            self._monitor = None
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
            self.note_state()

    # --- session (one per serving sidecar process) ---------------------------------------------------------
    def _on_serving(self, port: int) -> None:
        old = self._session_task
        address = self._sidecar.grpc_address if self._sidecar is not None else "127.0.0.1"
        self._session_task = asyncio.create_task(self._session(address, port, old), name=f"session-{self.id}")

    def _on_sidecar_down(self, reason: str) -> None:
        self._last_error = reason
        task, self._session_task = self._session_task, None
        if task is not None:
            task.cancel()
        # the session is gone now, not when its task has finished unwinding
        if self._mavsdk is not None:
            self._mavsdk.open = False
        self._system = None
        self._feed = None
        self._session_started = None
        self.note_state()

    async def _open(self, system: System, address: str, port: int) -> bool:
        """Connect the gRPC session and seal the sidecar's socket; False (the sidecar restarted) if not."""
        try:
            await asyncio.wait_for(system.connect(), CONNECT_TIMEOUT_S)
        except (TimeoutError, OSError, GRPCError, StreamTerminatedError) as exc:
            self._last_error = f"gRPC session to mavsdk_server on {address}:{port} failed: {exc!r}"
            log.warning("%s: %s; restarting the sidecar", self.id, self._last_error)
            await close_system(system)
            if self._sidecar is not None:
                self._sidecar.recycle()  # the supervisor starts a fresh process (with backoff)
            return False
        sealed = self._sidecar.seal() if self._sidecar is not None else None
        if sealed is not None:  # another process reached the sidecar first: it was restarted
            self._last_error = sealed
            await close_system(system)
            return False
        return True

    async def _end_session(self) -> None:
        task, self._session_task = self._session_task, None
        await cancel_and_wait(task)

    async def _session(self, address: str, port: int, previous: asyncio.Task[None] | None) -> None:
        if previous is not None:
            previous.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await previous
        system = System(mavsdk_server_address=address, port=port)
        slot = await SESSIONS.take()  # released once the session's rates are requested
        opened = False
        try:
            opened = await self._open(system, address, port)
        finally:
            if not opened:
                slot.release()
        if not opened:
            return
        self.telemetry.clear()
        self.facts = LinkFacts()
        commands = self._calls.new_channel()
        mavsdk = MavsdkSession(
            self, system, commands.pump, self.hooks.session_jobs, self.hooks.mission_progress
        )
        self._system = system
        self._feed = mavsdk.feed
        self._mavsdk = mavsdk
        self._session_started = time.monotonic()
        self._prearm_passed = False
        self.sessions += 1
        mavsdk.start()
        log.info("%s: MAVSDK session open on %s:%d", self.id, address, port)
        mavsdk.schedule_rates("session start", then=slot.release)
        try:
            await asyncio.Event().wait()  # lives until cancelled (sidecar down, disconnect)
        finally:
            slot.release()
            await mavsdk.stop()
            mavsdk.open = False
            if self._system is system:
                self._system = None
                self._feed = None
                self._session_started = None
            self._calls.channel.cancel_all()
            await close_system(system)

    # --- telemetry rates ---------------------------------------------------------------------------------
    def schedule_rates(self, why: str, force: bool = False, only: frozenset[str] | None = None) -> None:
        """Request every telemetry rate of the current MAVSDK session, or only the streams ``only`` names
        (unless one was requested lately; ``force``: regardless)."""
        if self._system is not None and self._mavsdk is not None:
            self._mavsdk.schedule_rates(why, force, only=only)

    def rates_to_ask_again(self) -> frozenset[str]:
        """The streams whose rate request got no answer, once asking again is due."""
        return self._feed.rates_to_ask_again() if self._feed is not None else frozenset()

    def request_rates_again(self, why: str) -> None:
        """Ask for every telemetry stream again (after something that resets them)."""
        self.schedule_rates(why, force=True)

    def note_state(self) -> None:
        """Record a change of the connection state now (whoever sees it first: a reader, the HEARTBEAT
        loop or the monitor), with its log line and the owner's listener."""
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
            if (
                state in (ConnectionState.CONNECTED, ConnectionState.READY)
                and old in (ConnectionState.LINK_LOST, ConnectionState.CONNECTING)
                and not self.sysid_mismatch
            ):
                self._last_error = None  # the link is back: what broke it is over
            on_state = self.hooks.on_state
            if on_state is not None:
                try:
                    on_state(old, state)
                except Exception:
                    log.exception("state listener failed")

    def note_error(self, message: str) -> None:
        """The link's last error, as ``last_error`` and the status say it."""
        self._last_error = message
