"""One MAVSDK session of a vehicle's link: the gRPC session to one serving mavsdk_server process, with
the loops it runs for as long as it lives (the HEARTBEAT, SIMSTATE, EKF status and EVENT messages, the
connection state, the autopilot's version, the heartbeat watchdog, the owner's jobs), its telemetry
feed and the telemetry rates it requests. The link (``gateway.link.session.Link``) opens one each time
its sidecar serves and stops it when the sidecar goes down or the link disconnects.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import time
from collections.abc import Awaitable, Callable, Iterable
from typing import Protocol, TypeVar

from gateway.config import Settings
from gateway.errors import CommandFailed
from gateway.link.contract import LinkRules
from gateway.link.mavsdk_system import System
from gateway.link.rawlink import LinkFacts
from gateway.link.telemetry import MissionProgressValue, TelemetryCache
from gateway.link.telemetry_feed import TelemetryFeed
from gateway.registry.spec import VehicleSpec

log = logging.getLogger("gateway.link")
T = TypeVar("T")

#: a loop run for the whole of each MAVSDK session (resubscribed when its stream ends)
SessionJob = Callable[[System], Awaitable[None]]

RATE_RETRY_S = 5.0
MAV_CMD_SET_MESSAGE_INTERVAL = 511
MAV_CMD_REQUEST_MESSAGE = 512
MAVLINK_MSG_SIMSTATE = 164
MAVLINK_MSG_HOME_POSITION = 242


class SessionHost(Protocol):
    """What a session needs of its link (``gateway.link.session.Link`` has all of it)."""

    spec: VehicleSpec
    settings: Settings
    telemetry: TelemetryCache
    facts: LinkFacts
    is_simulator: bool
    autopilot_version: str | None

    @property
    def id(self) -> str: ...

    @property
    def rules(self) -> LinkRules: ...

    @property
    def sysid_mismatch(self) -> bool: ...

    def note_state(self) -> None: ...

    def note_error(self, message: str) -> None: ...

    async def call(self, what: str, aw: Awaitable[T], timeout_s: float = ...) -> T: ...

    async def command_long(
        self, command: int, *params: float, what: str, attempts: int = ..., wait_s: float = ...
    ) -> None: ...


class MavsdkSession:
    """One gRPC session to the vehicle's mavsdk_server: ``start()`` runs its loops and asks for the
    telemetry rates, ``stop()`` ends them and closes the channel."""

    def __init__(
        self,
        link: SessionHost,
        system: System,
        ack_pump: SessionJob,
        jobs: Iterable[tuple[str, SessionJob]] = (),
        mission_progress: Callable[[int, int], MissionProgressValue] | None = None,
    ) -> None:
        self._link = link
        self.id = link.id
        self.system = system
        self.feed = TelemetryFeed(
            link.id,
            system,
            link.telemetry,
            mission_progress_map=mission_progress,
            use_mavsdk_flight_mode=self.mavsdk_names_modes,
            set_message_rate=self._set_message_rate,
        )
        self.open = True  # False once the link dropped it (its loops may still be unwinding)
        self.ekf_flags: int | None = None  # EKF_STATUS_REPORT.flags (ArduPilot), None until one arrives
        self._ack_pump = ack_pump
        self._jobs = list(jobs)
        self._tasks: list[asyncio.Task[None]] = []
        self._rates_requested_at = 0.0
        self._rates_task: asyncio.Task[None] | None = None
        self._connected: bool | None = None

    def start(self) -> None:
        system = self.system
        self.feed.start()
        jobs: list[tuple[str, SessionJob, bool]] = [
            ("hb", self._heartbeats, False),
            ("ack", self._ack_pump, False),
            ("simstate", self._simstate, True),
            ("conn", self._connection_state, False),
            ("events", self._events, False),
            ("ekf", self._ekf_status, False),
            *((name, job, False) for name, job in self._jobs),
        ]
        self._tasks = [
            asyncio.create_task(keep(self.id, name, fn, system, once), name=f"{name}-{self.id}")
            for name, fn, once in jobs
        ]
        self._tasks.append(asyncio.create_task(self._identify(system), name=f"ident-{self.id}"))
        if self._link.settings.sidecar_heartbeat_watchdog_s:
            self._tasks.append(asyncio.create_task(self._feed_watchdog(system), name=f"watchdog-{self.id}"))

    async def stop(self) -> None:
        """End the loops, the rates request and the feed (the caller closes the channel)."""
        tasks = [*self._tasks, *([self._rates_task] if self._rates_task else [])]
        self._tasks = []
        self._rates_task = None
        for t in tasks:
            t.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)
        await self.feed.stop()

    # --- telemetry rates ---------------------------------------------------------------------------------
    def schedule_rates(
        self,
        why: str,
        force: bool = False,
        then: Callable[[], None] | None = None,
        only: frozenset[str] | None = None,
    ) -> None:
        """Request every telemetry rate (again), or only the streams ``only`` names, unless a request runs
        or one was made less than ``RATE_RETRY_S`` ago (``force``: regardless of when); ``then`` is called
        once the request has ended, or at once when none was made."""
        if not self.open or (self._rates_task is not None and not self._rates_task.done()):
            if then is not None:
                then()
            return
        if not force and time.monotonic() - self._rates_requested_at < RATE_RETRY_S:
            if then is not None:
                then()
            return
        self._rates_requested_at = time.monotonic()
        log.info("%s: requesting telemetry rates (%s)", self.id, why)
        self._rates_task = asyncio.create_task(self._request_rates(only), name=f"rates-{self.id}")
        if then is not None:
            self._rates_task.add_done_callback(lambda _task: then())

    async def _request_rates(self, only: frozenset[str] | None = None) -> None:
        feed = self.feed
        for _ in range(30):  # which streams to ask for depends on the autopilot: wait for a HEARTBEAT
            if self._link.facts.autopilot is not None:
                break
            await asyncio.sleep(0.1)
        skip = self._link.rules.skipped_streams if self._link.facts.autopilot is not None else frozenset()
        await feed.request_rates(lambda what, aw: self._link.call(what, aw, 5.0), skip, only)
        if only is not None:
            return  # a retry of streams that got no answer: SIMSTATE and home were asked for at the start
        if not self._link.is_simulator:  # a simulator says so with SIMSTATE; real ArduPilot answers FAILED
            with contextlib.suppress(CommandFailed):
                await self._link.command_long(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_SIMSTATE, what="SIMSTATE")
        # home comes every 5 s at rest and a drone is ready only once it has one: asked for once now, so
        # that a (re)connected drone is not kept waiting for the next one (sent only once home is set);
        # after SIMSTATE, so that a simulator is known as one by the time it is ready
        with contextlib.suppress(CommandFailed):
            await self._link.command_long(MAV_CMD_REQUEST_MESSAGE, MAVLINK_MSG_HOME_POSITION, what="home")

    async def _set_message_rate(self, message_id: int, hz: float) -> None:
        """MAV_CMD_SET_MESSAGE_INTERVAL for a stream's message (the feed's ``MESSAGE_IDS``), answered
        within the 5 s the feed gives each rate request."""
        await self._link.command_long(
            MAV_CMD_SET_MESSAGE_INTERVAL, message_id, 1e6 / hz, what="rate", attempts=3, wait_s=1.5
        )

    # --- the session's loops ----------------------------------------------------------------------------
    def mavsdk_names_modes(self) -> bool | None:
        """MAVSDK's flight mode names are used unless the dialect names the HEARTBEAT's mode itself
        (ArduCopter: MAVSDK would say OFFBOARD for GUIDED, HOLD for LOITER); None before a HEARTBEAT."""
        facts = self._link.facts
        if facts.autopilot is None:
            return None
        return self._link.rules.mode_name(facts.custom_mode or 0, facts.mav_type or 0) is None

    async def _heartbeats(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("HEARTBEAT"):
            facts = self._link.facts
            if not facts.heartbeat(int(msg.system_id), json.loads(msg.fields_json)):
                continue  # another ground station on the link
            if facts.sysid_changed and self._link.sysid_mismatch:
                expected = self._link.spec.expected_sysid
                error = f"system id mismatch: vehicle reports {facts.sysid}, expected {expected}"
                self._link.note_error(error)
                log.error("%s: %s", self.id, error)
            self._link.telemetry.put("armed", bool(facts.armed))  # the telemetry feed has no armed stream
            name = self._link.rules.mode_name(facts.custom_mode or 0, facts.mav_type or 0)
            if name is not None:
                self._link.telemetry.put("flight_mode", name)
            self._link.note_state()  # connected again, ready: seen with the heartbeat, not at the next check

    async def _simstate(self, system: System) -> None:
        async for _msg in system.mavlink_direct.message("SIMSTATE"):
            if not self._link.is_simulator:
                log.info("%s: SIMSTATE received: this vehicle is a simulator", self.id)
            self._link.is_simulator = True
            return  # known; stop streaming it through gRPC

    async def _ekf_status(self, system: System) -> None:
        async for msg in system.mavlink_direct.message("EKF_STATUS_REPORT"):
            self.ekf_flags = int(json.loads(msg.fields_json).get("flags", 0))

    async def _events(self, system: System) -> None:
        """An autopilot that speaks the events protocol (PX4; MAVSDK does too) says why it refuses a
        mission or an arming in EVENT messages, not STATUSTEXT: keep them with the status texts."""
        while self._link.facts.autopilot is None:  # noqa: ASYNC110 - set by the HEARTBEAT loop, no event to wait on
            await asyncio.sleep(0.2)
        if not self._link.rules.follows_events:
            await asyncio.Event().wait()  # nothing to follow on this link until the session ends
        async for event in system.events.events():
            severity = getattr(event.log_level, "name", "info").lower()
            self._link.telemetry.add_status_text(severity, " ".join(str(event.message).split()))

    async def _connection_state(self, system: System) -> None:
        async for cs in system.core.connection_state():
            was = self._connected
            self._connected = bool(cs.is_connected)
            if was is False and cs.is_connected:
                self.schedule_rates("vehicle reconnected", force=True)

    async def _identify(self, system: System) -> None:
        for _ in range(10):
            try:
                v = await asyncio.wait_for(system.info.get_version(), 5.0)
            except Exception:  # AUTOPILOT_VERSION may not have arrived yet
                await asyncio.sleep(2.0)
                continue
            kind = getattr(v.flight_sw_version_type, "name", "")
            self._link.autopilot_version = (
                f"{v.flight_sw_major}.{v.flight_sw_minor}.{v.flight_sw_patch} {kind}".strip()
            )
            return

    async def _feed_watchdog(self, system: System) -> None:
        """Enable mavsdk_server's heartbeat watchdog for this session and keep feeding it: if the gateway
        hangs, the GCS heartbeat stops and the autopilot's own GCS failsafe can act."""
        timeout = float(self._link.settings.sidecar_heartbeat_watchdog_s or 0)
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


async def keep(vehicle_id: str, name: str, subscribe: SessionJob, system: System, once: bool) -> None:
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


async def close_system(system: System) -> None:
    """Close the gRPC channel of a System (best effort: a channel not closed is closed when collected)."""
    with contextlib.suppress(Exception):
        await system.close()
