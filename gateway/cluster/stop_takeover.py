"""An operator's stop that no owner acknowledged in time: the node that took it commands the drone itself.

A stop (land, return, hold) for a drone another node owns goes to that owner over the bus
(`gateway.cluster.owner_calls`). Once the bus has not carried it, the stopping node tries, all at once
(:meth:`StopTakeover.reach`), the owner's remaining paths (PostgreSQL notifications; a fenced node's
stop-only path) and the drone's own link, opened by this node for a moment (`gateway.cluster.stoplink`):
this works at once when no process holds the link (a killed node's sidecar died with it). Nothing is sent
over it before the drone is heard on that connection: a link that serves one ground station at a time (a
TCP port) keeps a new connection waiting while another process holds it, and a command written into it
would run whenever that connection is served. The first path that takes the stop answers it.

When none has by :data:`OWNER_ACK_S` after the stop, the answer is "taking over" (:class:`StopPending`,
saying what is being done), and this node keeps at it in the background for at most :data:`TAKEOVER_S`,
every :data:`RETRY_S`: the stop once more to whichever node owns the drone now (its owner may answer
again, or another node may have taken it over), the drone's own link once more, and, once the owner's
lease has expired, the lease itself, taken as the node-loss takeover takes it (never from a live lease):
its own sidecar then reaches the drone as soon as the link is free (a frozen node lets go of it when it
runs again and finds its lease gone), and the stop is run through this node's own command path, tracked
and audited like any other.

A stop sent twice is still a stop, so a drone told by its owner and by this node lands once.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import Awaitable
from typing import TYPE_CHECKING, NoReturn, Protocol

from gateway.cluster.bus import no_progress
from gateway.cluster.forwarding import answer
from gateway.cluster.leases import Lease, LeaseStore
from gateway.cluster.node_parts import NodeWithRuntime
from gateway.cluster.remote import RemoteVehicle
from gateway.cluster.stoplink import StopTarget, direct_stop_answer, send_stop
from gateway.errors import GatewayError, NoOwner, NotRun, OwnerFenced, StopPending
from gateway.fleet.policy.caller import Caller
from gateway.link.contract import HEARD
from gateway.util.json_types import JsonObject, JsonValue

if TYPE_CHECKING:
    from gateway.fleet.vehicles.registry import Registry

log = logging.getLogger("gateway.cluster.stop_takeover")

#: the owner's acknowledgement (over the bus, then through PostgreSQL, while this node tries the drone's
#: own link beside) within this of the stop
OWNER_ACK_S = 2.2
#: the drone's own link, opened by this node, must be heard within this
DIRECT_S = 1.0
#: a drone not reached yet: this node keeps trying for this long
TAKEOVER_S = 60.0
#: between two rounds of the background attempts
RETRY_S = 0.5
#: a lease statement of the background attempts, at most (a database that hangs)
LEASE_STATEMENT_S = 2.0
#: the autopilot's answers that mean the stop was not taken
REFUSED = frozenset({"DENIED", "UNSUPPORTED", "FAILED", "TEMPORARILY_REJECTED", "CANCELLED"})


class TakeoverNode(NodeWithRuntime, Protocol):
    """What the stop takeover reads of its node beyond the core (`gateway.cluster.node.ClusterNode`)."""

    @property
    def leases(self) -> LeaseStore | None: ...

    async def take_over(self, vehicle_id: str, lease: Lease, previous: str | None, asked: float) -> None: ...

    async def forward_stop(self, drone_id: str, verb: str, caller: Caller) -> object: ...


class StopTakeover:
    """The stops this node took and commands itself, because no owner acknowledged them in time."""

    def __init__(self, node: TakeoverNode) -> None:
        self._node = node
        self._tasks: dict[str, asyncio.Task[None]] = {}

    @property
    def pending(self) -> list[str]:
        """The drones this node is still trying to reach with a stop."""
        return sorted(vid for vid, task in self._tasks.items() if not task.done())

    async def close(self) -> None:
        tasks = list(self._tasks.values())
        for task in tasks:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)
        self._tasks.clear()

    def _target(self, drone_id: str, epoch: int | None) -> StopTarget:
        registry = self._require_registry()
        vehicle = registry.get(drone_id)
        sysid = getattr(vehicle, "sysid", None) or vehicle.spec.expected_sysid
        return StopTarget(drone_id, vehicle.spec.url, sysid, epoch or 0)

    def _require_registry(self) -> Registry:
        registry = self._node.registry
        if registry is None:
            raise GatewayError("this node's registry is not running")
        return registry

    async def reach(
        self, drone_id: str, verb: str, caller: Caller, epoch: int | None, owner: str | None,
        owner_paths: list[Awaitable[JsonValue]], why: list[str], deadline: float, take_over: bool = True,
    ) -> JsonValue:  # fmt: skip
        """The stop through the owner's remaining paths (``owner_paths``: PostgreSQL, a fenced node's
        stop-only path) and, with ``take_over``, the drone's own link from this node, all at once until
        ``deadline``: the first answer. An owner's refusal is raised; with none of them through by the
        deadline, NotRun (without ``take_over``) or :class:`StopPending` (this node keeps at it)."""
        tasks: dict[asyncio.Future[JsonValue], str] = {asyncio.ensure_future(p): "owner" for p in owner_paths}
        if take_over:
            link: asyncio.Future[JsonValue] = asyncio.ensure_future(
                self._direct_until(drone_id, verb, caller, epoch, deadline)
            )
            tasks[link] = "link"
        direct = "not tried"
        try:
            while tasks:
                done, _ = await asyncio.wait(
                    tasks, timeout=max(0.0, deadline - time.monotonic()) + 0.5,
                    return_when=asyncio.FIRST_COMPLETED,
                )  # fmt: skip
                if not done:
                    break
                for task in done:
                    path = tasks.pop(task)
                    # a path that ended cancelled (a library cancelled what it awaited: a connection
                    # lost under it) failed like any other; the other paths still carry the stop
                    error = asyncio.CancelledError("cancelled") if task.cancelled() else task.exception()
                    if error is None:
                        if path == "link":
                            log.warning("%s: %s sent over its own link by node %s, no owner acknowledging "
                                        "it (%s)", drone_id, verb, self._node.node_id,
                                        "; ".join(why))  # fmt: skip
                        return task.result()
                    if path == "link":
                        direct = f"{type(error).__name__}: {error}"
                    elif isinstance(error, NotRun | NoOwner | OwnerFenced):  # the owner let go of it
                        why.append(error.message)
                    elif isinstance(error, GatewayError):
                        raise error  # the owner answered: it refused the stop
                    else:
                        why.append(repr(error))
        finally:
            _cancel_all(tasks)
        if not take_over:
            raise NotRun(
                f"no owner acknowledged {verb} for {drone_id} ({'; '.join(why)})", vehicle_id=drone_id
            )
        self.stop_pending(drone_id, verb, caller, epoch, owner, "; ".join(why), direct)

    async def _direct_until(
        self, drone_id: str, verb: str, caller: Caller, epoch: int | None, deadline: float
    ) -> JsonObject:
        """The drone's own link, tried again until ``deadline`` (it may be let go of any moment)."""
        while True:
            try:
                left = deadline - time.monotonic()
                return await self._direct(drone_id, verb, caller, epoch, min(DIRECT_S, max(0.3, left)))
            except Exception:
                if time.monotonic() > deadline - 0.3:
                    raise
                await asyncio.sleep(0.1)

    def stop_pending(
        self, drone_id: str, verb: str, caller: Caller, epoch: int | None, owner: str | None, why: str,
        direct: str,
    ) -> NoReturn:  # fmt: skip
        """Start the background attempts (unless running already) and raise :class:`StopPending`."""
        me = self._node.node_id
        owner_text = f"its owner node {owner}" if owner else "no owner"
        running = self._tasks.get(drone_id)
        if running is None or running.done():
            self._tasks[drone_id] = asyncio.create_task(
                self._keep_trying(drone_id, verb, caller, epoch, owner), name=f"stop-takeover-{drone_id}"
            )
        log.error("%s: %s not acknowledged by %s (%s) and its link is held elsewhere (%s): node %s keeps "
                  "trying for %.0f s", drone_id, verb, owner_text, why, direct, me, TAKEOVER_S)  # fmt: skip
        raise StopPending(
            f"{verb} not confirmed yet: {owner_text} did not acknowledge it within {OWNER_ACK_S:g} s "
            f"({why}), "
            f"and the drone's own link did not answer node {me} ({direct}). Node {me} keeps trying for "
            f"{TAKEOVER_S:g} s: the {verb} again to whichever node owns the drone, its own link again, and "
            f"once {owner_text}'s lease expires it takes the drone over through its own sidecar and sends "
            f"the {verb} as soon as that reaches the drone; the log and the audit say when it is sent.",
            vehicle_id=drone_id,
            action=verb,
            by_node=me,
        )

    async def _direct(
        self, drone_id: str, verb: str, caller: Caller, epoch: int | None, within_s: float = DIRECT_S
    ) -> JsonObject:
        started = time.monotonic()
        result = await send_stop(self._target(drone_id, epoch), verb, within_s, hear_first=True)
        if result in REFUSED:
            raise GatewayError(f"the autopilot refused {verb} sent over its own link: {result}")
        if result.startswith("no COMMAND_ACK"):
            raise TimeoutError(result)
        me = self._node.node_id
        took_ms = (time.monotonic() - started) * 1000
        facts = {"via": "direct link", "node": me, "autopilot": result}
        why = f"its owner not answering (autopilot: {result}, after {took_ms:.0f} ms)"
        return direct_stop_answer(drone_id, verb, me, why, facts)

    async def _keep_trying(
        self, drone_id: str, verb: str, caller: Caller, epoch: int | None, owner: str | None
    ) -> None:
        deadline = time.monotonic() + TAKEOVER_S
        attempts = 0
        while time.monotonic() < deadline:
            attempts += 1
            try:
                how = await self._round(drone_id, verb, caller, epoch, owner)
            except asyncio.CancelledError:
                raise
            except Exception as exc:
                log.info("%s: %s, attempt %d from node %s: %r", drone_id, verb, attempts,
                         self._node.node_id, exc)  # fmt: skip
                how = None
            if how is not None:
                log.warning("%s: %s sent %s, %d attempts after its owner did not acknowledge it", drone_id,
                            verb, how, attempts)  # fmt: skip
                return
            await asyncio.sleep(RETRY_S)
        log.error("%s: %s could not be sent by node %s within %.0f s: the drone keeps flying its last "
                  "command", drone_id, verb, self._node.node_id, TAKEOVER_S)  # fmt: skip

    async def _round(
        self, drone_id: str, verb: str, caller: Caller, epoch: int | None, owner: str | None
    ) -> str | None:
        """One round of attempts; how the stop was sent, or None."""
        registry = self._require_registry()
        view = registry.find(drone_id)
        me = self._node.node_id
        if view is not None and registry.is_local(drone_id):  # taken over by this node: its own sidecar
            # a stop needs the drone heard, not ready to fly (an ArduPilot drone's first EKF report can
            # be half a minute away on a new link): land, return and hold are tried when only connected
            if str(view.state) not in HEARD:
                return None
            await answer(
                self._node.gateway.commander, verb, {"drone_id": drone_id}, caller.to_dict(), no_progress
            )
            return f"through node {me}'s own sidecar, which took the drone over"
        if isinstance(view, RemoteVehicle) and view.owner is not None:  # its owner (or a new one) again
            with contextlib.suppress(NotRun, NoOwner):
                await self._node.forward_stop(drone_id, verb, caller)
                return f"to its owner node {view.owner}, which acknowledged it"
        try:
            await self._direct(drone_id, verb, caller, epoch)
            return f"over its own link by node {me}"
        except Exception as exc:
            log.debug("%s: its own link did not answer (%r)", drone_id, exc)
        leases = self._node.leases
        if leases is not None:
            asked = time.monotonic()
            lease = await asyncio.wait_for(leases.acquire(drone_id), LEASE_STATEMENT_S)
            if lease is not None:  # the owner's lease expired: the node-loss takeover, by this node
                log.warning("%s: node %s took its lease (epoch %d) to send the %s itself", drone_id, me,
                            lease.epoch, verb)  # fmt: skip
                await self._node.take_over(drone_id, lease, owner, asked)
        return None


def _cancel_all(tasks: dict[asyncio.Future[JsonValue], str]) -> None:
    """The paths still under way once one answered; a path that failed meanwhile has nothing to add."""
    for task in tasks:
        task.cancel()
        if task.done() and not task.cancelled():
            task.exception()
