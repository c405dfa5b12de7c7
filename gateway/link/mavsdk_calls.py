"""Calling the vehicle through MAVSDK: one gRPC call with its timeout and its errors in words, and
COMMAND_LONG (through mavlink_direct) with its COMMAND_ACK. A refusal carries what the autopilot said
about it (its status texts, which may come just after the result), or what the vehicle was doing when
it gave no reason. The link (``gateway.link.session.Link``) offers these as its own methods."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Awaitable
from typing import Protocol, TypeVar

from grpclib.exceptions import GRPCError, StreamTerminatedError

from gateway.errors import CommandFailed
from gateway.link import refusals
from gateway.link.contract import ConnectionState, LinkRules
from gateway.link.mavsdk_rpc import MavsdkError
from gateway.link.mavsdk_system import System
from gateway.link.rawlink import MAV_RESULT, MAV_RESULT_ACCEPTED, CommandChannel, LinkFacts, NoAck
from gateway.link.telemetry import TelemetryCache
from gateway.registry.spec import VehicleSpec

T = TypeVar("T")

# gRPC call timeout (s): MAVSDK retries MAVLink commands itself; this bounds a dead sidecar.
CALL_TIMEOUT_S = 10.0


class CallsHost(Protocol):
    """What calling the vehicle needs of its link (``gateway.link.session.Link`` has all of it)."""

    spec: VehicleSpec
    facts: LinkFacts
    telemetry: TelemetryCache

    @property
    def id(self) -> str: ...

    @property
    def state(self) -> ConnectionState: ...

    @property
    def rules(self) -> LinkRules: ...

    def require_session(self) -> System: ...

    def initialising(self) -> str | None: ...


class MavsdkCalls:
    """The calls of one link; ``channel`` matches COMMAND_ACKs to COMMAND_LONGs (a new one each session)."""

    def __init__(self, link: CallsHost, gcs_sysid: int) -> None:
        self._link = link
        self._gcs_sysid = gcs_sysid
        self.channel = CommandChannel(gcs_sysid)

    def new_channel(self) -> CommandChannel:
        """A fresh command channel, for a new MAVSDK session."""
        self.channel = CommandChannel(self._gcs_sysid)
        return self.channel

    async def call(self, what: str, aw: Awaitable[T], timeout_s: float = CALL_TIMEOUT_S) -> T:
        """Await one gRPC call with a timeout; MAVSDK errors become CommandFailed with the result text
        and what the autopilot said about it (its status text, which may come just after the ACK)."""
        started = time.time()
        try:
            return await asyncio.wait_for(aw, timeout_s)
        except TimeoutError:
            raise CommandFailed(
                f"{what} on drone '{self._link.id}': no answer from its mavsdk_server within {timeout_s:g} s",
                vehicle_id=self._link.id,
            ) from None
        except asyncio.CancelledError:
            task = asyncio.current_task()
            if task is None or task.cancelling():
                raise  # the caller itself is being cancelled
            # a call whose session was closed under it (the sidecar went down mid-call) is cancelled
            raise self._session_ended(what) from None
        except (StreamTerminatedError, OSError):
            # the connection to mavsdk_server was lost or refused (its channel is never reconnected)
            raise self._session_ended(what) from None
        except GRPCError as exc:
            raise CommandFailed(
                f"{what} on drone '{self._link.id}': mavsdk_server unreachable ({exc.status.name}); "
                f"the drone is {self._link.state.value}",
                vehicle_id=self._link.id,
            ) from None
        except MavsdkError as exc:
            said = await self._complaint_since(started)
            raise CommandFailed(
                f"{what} on drone '{self._link.id}' failed: {exc.result_str} ({exc.result})" + said,
                vehicle_id=self._link.id,
                result=exc.result,
            ) from None

    def _session_ended(self, what: str) -> CommandFailed:
        return CommandFailed(
            f"{what} on drone '{self._link.id}': its mavsdk_server session ended during the call (the "
            f"gateway restarts it); the drone is {self._link.state.value}; check it and call again",
            vehicle_id=self._link.id,
        )

    async def command_long(
        self, command: int, *params: float, what: str, attempts: int = 3, wait_s: float = 1.5
    ) -> None:
        """Send COMMAND_LONG through mavlink_direct and wait for its COMMAND_ACK (MAVSDK has no call)."""
        system = self._link.require_session()
        target = self._link.facts.sysid or self._link.spec.expected_sysid or 1
        sent_at = time.time()
        try:
            result = await self.channel.send(
                system,
                lambda aw: self.call(what, aw, 5.0),
                target,
                command,
                params,
                attempts=attempts,
                wait_s=wait_s,
            )
        except NoAck as exc:
            raise CommandFailed(
                f"{what} on drone '{self._link.id}': {exc}", vehicle_id=self._link.id
            ) from None
        if result != MAV_RESULT_ACCEPTED:
            name = MAV_RESULT.get(result, str(result))
            raise CommandFailed(
                f"{what} on drone '{self._link.id}' refused by the vehicle: {name}"
                + await self._complaint_since(sent_at),
                vehicle_id=self._link.id,
                result=name,
            )

    def recent_complaint(self, within_s: float = 5.0, since: float | None = None) -> str:
        """What the autopilot said (warning or worse) in the last few seconds, or since ``since`` (wall
        clock), to explain a refusal: `` (autopilot says: 'A'; 'B')`` or "" when it said nothing."""
        said = self.said_since(time.time() - within_s if since is None else since)
        return f" (autopilot says: {refusals.quoted(said)})" if said else ""

    def said_since(self, since: float) -> list[str]:
        """The autopilot's distinct warning-or-worse texts since ``since`` (wall clock), oldest first."""
        return refusals.said_since(self._link.telemetry.status_texts, since)

    async def _complaint_since(self, since: float) -> str:
        """Why the autopilot refused what was sent at ``since``: its texts (waiting briefly for them, as
        they can follow the result), or what the vehicle was doing when it gave no reason."""
        said = await refusals.wait_said(lambda: self._link.telemetry.status_texts, since)
        return refusals.explain(said, self.describe_facts())

    def describe_facts(self) -> str:
        """The vehicle's state in a few words, for a refusal the autopilot did not explain."""
        mode = self._link.telemetry.fresh("flight_mode")
        armed = self._link.telemetry.fresh("armed")
        on_ground = self._link.rules.on_ground(self._link.telemetry)
        parts = [
            f"mode {mode}" if mode else "mode unknown",
            "armed" if armed else "disarmed" if armed is False else "armed state unknown",
            "on the ground" if on_ground else "in the air" if on_ground is False else "",
        ]
        waiting = self._link.initialising()
        if waiting:
            parts.append(waiting)
        return "it is " + ", ".join(p for p in parts if p)
