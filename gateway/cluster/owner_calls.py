"""Calls routed to a drone's owner: a command on a drone another node owns goes to that node over the
bus (an operator's stop also through PostgreSQL, or to a fenced node's stop-only path), and this node
answers the calls for the drones it owns."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import Awaitable, Callable, Mapping
from typing import TYPE_CHECKING, Protocol

from gateway.cluster.bus import (
    CallCheck,
    CallHandler,
    ProgressSink,
    epoch_check,
    no_progress,
    stop_subject,
)
from gateway.cluster.fenced_stops import STOP_SEND_S, FencedStops
from gateway.cluster.forwarding import answer
from gateway.cluster.node_parts import NodeWithRuntime
from gateway.cluster.remote import RemoteVehicle
from gateway.cluster.stop_notify import StopRelay
from gateway.cluster.stop_takeover import OWNER_ACK_S, StopTakeover
from gateway.cluster.stoplink import STOP_COMMANDS, StopTarget
from gateway.errors import NoOwner, NotRun, OwnerFenced
from gateway.fleet.operations.routing import OnMessage, RoutedCall
from gateway.fleet.policy.caller import Caller
from gateway.util.cancelling import cancelled_here
from gateway.util.json_types import JsonObject, JsonValue

if TYPE_CHECKING:
    pass

log = logging.getLogger("gateway.cluster")

#: forwarded verbs that only read the drone: they get a short timeout, not the MCP wait cap
READS = frozenset({"arrival", "mission_progress", "get_param", "list_params", "download_mission"})
READ_TIMEOUT_S = 5.0
#: an operator's stop its owner has not accepted over the bus by then is refused by the owner if it arrives
#: later (the caller knows it as not run once the bus's clock margin has passed too)
STOP_ACCEPT_S = 0.5
#: an operator's stop its owner has not accepted over the bus by then also goes through PostgreSQL, beside
#: the bus (a stop that runs twice is still a stop): a bus that does not answer (a frozen server) costs this,
#: not the accept time and its clock margin (1 s), of the 3 s in which every drone must be told
STOP_BUS_HEAD_START_S = 0.3
#: a fenced node asks again this often for a node serving the drone's calls (one taking it over)
NEW_OWNER_RETRY_S = 0.2


class CallsNode(NodeWithRuntime, Protocol):
    """What the routed calls read of their node beyond the core (`gateway.cluster.node_parts`)."""

    @property
    def started(self) -> bool: ...

    @property
    def fenced(self) -> dict[str, StopTarget]: ...

    @property
    def stops(self) -> FencedStops: ...

    @property
    def relay(self) -> StopRelay | None: ...

    @property
    def takeover(self) -> StopTakeover: ...


#: what a call's check says when this node no longer owns the drone, or the call was sent for another
#: lease epoch
LEASE_WORDS = (
    "node {node} no longer owns drone '{vehicle}': not run; retry",
    "a call for drone '{vehicle}' sent for lease epoch {sent} reached node {node}, which holds epoch "
    "{held}: not run (the caller's view of its owner was out of date); retry",
)


class OwnerCalls:
    """Forwards this node's calls on other nodes' drones; answers the calls on its own."""

    def __init__(self, node: CallsNode) -> None:
        self._node = node
        # vehicle -> the forwarded calls this node runs for it now (each its verb's task)
        self._running: dict[str, set[asyncio.Task[object]]] = {}
        # a call cut short -> why (`cut_short`)
        self._cut: dict[asyncio.Task[object], str] = {}

    def cut_short(self, vehicle_id: str, why: str) -> int:
        """This node gives the drone up without handing it over (it fenced itself, or its lease was
        lost): every forwarded call it runs for the drone ends now, its caller answered at once that it
        was not finished (`OwnerFenced`) rather than when its wait runs out; how many."""
        running = self._running.pop(vehicle_id, set())
        for task in running:
            self._cut[task] = why
            task.cancel()
        if running:
            log.warning("%s: %d forwarded call(s) cut short (%s)", vehicle_id, len(running), why)
        return len(running)

    async def forward(self, routed: RoutedCall) -> JsonValue:
        """Run the verb on the drone's owner (over NATS); its result, or its error raised here."""
        drone_id, verb, caller, wait_s = routed.drone_id, routed.verb, routed.caller, routed.wait_s
        arguments, on_message = dict(routed.arguments), routed.on_message
        if not self._node.started:
            raise NoOwner(f"this node is not part of the cluster yet; cannot reach {drone_id}'s owner")
        forward_s = self._node.settings.cluster_forward_timeout_s
        if verb in READS:  # a read has nothing to wait for on the owner
            timeout = min(forward_s, READ_TIMEOUT_S)
        else:
            timeout = max(0.0, wait_s) + forward_s
        body = {**caller.to_dict(), "node": self._node.node_id}
        registry = self._node.registry
        vehicle = None if registry is None else registry.find(drone_id)
        epoch = vehicle.epoch if isinstance(vehicle, RemoteVehicle) and vehicle.epoch > 0 else None
        accept_s = min(self._node.settings.cluster_accept_timeout_s, timeout)
        owner_gone = None
        if isinstance(vehicle, RemoteVehicle):
            view, owner, seen_epoch = vehicle, vehicle.owner, vehicle.epoch

            def owner_gone() -> str | None:
                if view.owner == owner and view.epoch == seen_epoch:
                    return None
                if view.owner is None:
                    return f"node {owner} lost drone {drone_id}'s lease"
                return f"drone {drone_id} changed owner (node {owner} -> node {view.owner})"

        if verb in STOP_COMMANDS and caller.is_operator:
            return await self._stop(drone_id, verb, caller, arguments, on_message, timeout, accept_s,
                                    epoch, owner_gone)  # fmt: skip
        return await self._node.bus.call(
            drone_id, verb, arguments, body, timeout, on_message, accept_s=accept_s, epoch=epoch,
            owner_gone=owner_gone,
        )  # fmt: skip

    async def forward_stop(self, drone_id: str, verb: str, caller: Caller) -> object:
        """An operator's stop to the drone's owner as it is now (bus, then PostgreSQL), without this
        node commanding the drone itself when no owner acknowledges it: NotRun or NoOwner then."""
        registry = self._node.registry
        vehicle = None if registry is None else registry.find(drone_id)
        epoch = vehicle.epoch if isinstance(vehicle, RemoteVehicle) and vehicle.epoch > 0 else None
        accept_s = self._node.settings.cluster_accept_timeout_s
        return await self._stop(drone_id, verb, caller, {}, None, accept_s + STOP_SEND_S, accept_s, epoch,
                                None, take_over=False)  # fmt: skip

    async def _stop(
        self, drone_id: str, verb: str, caller: Caller, arguments: JsonObject,
        on_message: OnMessage | None, call_s: float, accept_s: float, epoch: int | None,
        owner_gone: Callable[[], str | None] | None, take_over: bool = True,
    ) -> JsonValue:  # fmt: skip
        """An operator's stop (land, return, hold) on a drone another node owns: over the bus, through
        PostgreSQL when the bus does not carry it (each sent again until its owner answers), to a fenced
        node's stop-only path when nobody holds the drone's link; and when no owner acknowledged it
        within OWNER_ACK_S, commanded by this node itself (`gateway.cluster.stop_takeover`)."""
        body = {**caller.to_dict(), "node": self._node.node_id}
        if drone_id in self._node.fenced:
            # no bus needed: this node sends it over the drone's link; but this node cannot read the
            # leases, and another node may have taken the drone over meanwhile (its sidecar holding the
            # link): the stop goes to whoever serves the drone's calls too, and the first to take it answers
            until = time.monotonic() + STOP_SEND_S
            direct = self._node.stops.stop_directly(drone_id, verb, caller)
            new_owner = self._to_new_owner(drone_id, verb, arguments, body, call_s, accept_s, until)
            try:
                return await self._node.takeover.reach(
                    drone_id, verb, caller, epoch, None, [direct, new_owner], ["this node fenced itself"],
                    until, take_over=False,
                )  # fmt: skip
            except NotRun as exc:
                if not take_over:
                    raise
                # the node that took the drone over is still bringing its link up: keep at it
                self._node.takeover.stop_pending(
                    drone_id, verb, caller, epoch, None, exc.message, "held by another process"
                )
        deadline = time.monotonic() + OWNER_ACK_S
        registry = self._node.registry
        vehicle = None if registry is None else registry.find(drone_id)
        owner = vehicle.owner if isinstance(vehicle, RemoteVehicle) else None
        relay = self._node.relay
        # a stop gets a short accept time on the bus where PostgreSQL can carry it instead
        short = relay is not None and relay.listening
        bus = self._node.bus
        why: list[str] = []
        owner_paths: list[Awaitable[JsonValue]] = []
        heard = asyncio.Event()
        over_bus = asyncio.ensure_future(bus.call(
            drone_id, verb, arguments, body, call_s, on_message,
            accept_s=min(accept_s, STOP_ACCEPT_S if short else OWNER_ACK_S), epoch=epoch,
            owner_gone=owner_gone, accepted_event=heard,
        ))  # fmt: skip
        if short:
            await _head_start(over_bus, heard)
        try:
            if short and not heard.is_set():
                # the owner has not taken it over the bus yet: the bus stays one of its paths, and
                # PostgreSQL notifications carry it beside (`gateway.cluster.stop_notify`)
                why.append(f"bus: not accepted within {STOP_BUS_HEAD_START_S:g} s")
                log.info("%s: %s not accepted over the bus within %.1f s: through PostgreSQL beside it",
                         drone_id, verb, STOP_BUS_HEAD_START_S)  # fmt: skip
                owner_paths.append(over_bus)
                self._relay(relay, drone_id, verb, arguments, epoch, body, deadline, owner_paths, why)
            else:
                return await over_bus
        except asyncio.CancelledError:
            if cancelled_here():
                raise
            # the bus call ended cancelled under it (not this stop): PostgreSQL carries the stop instead
            why.append("bus: its call was cancelled")
            self._relay(relay, drone_id, verb, arguments, epoch, body, deadline, owner_paths, why)
        except NotRun as exc:
            # the bus did not carry it (this node cut off, or no answer in the accept time): through
            # PostgreSQL notifications to the owner
            if exc.details.get("bus") not in ("down", "no answer"):
                raise
            why.append(f"bus: {exc.details.get('bus')}")
            self._relay(relay, drone_id, verb, arguments, epoch, body, deadline, owner_paths, why)
        except (NoOwner, OwnerFenced) as exc:
            # nobody holds the drone's link on the bus, or its owner fenced itself while it ran the stop
            # (whether the stop reached the drone then is not known): the node that last held it keeps a
            # stop-only path to it (a land sent twice is still a land), and this node takes the link over
            why.append(f"bus: {exc.message}")
            left = max(0.2, deadline - time.monotonic())
            fenced_path = bus.call(
                drone_id, verb, arguments, body, left + STOP_SEND_S + 1.0, on_message,
                accept_s=left, epoch=epoch, subject=stop_subject(drone_id),
            )  # fmt: skip
            owner_paths.append(fenced_path)
        # the owner's paths, and (unless told not to) the drone's own link from this node, at once: the
        # first that takes the stop answers it
        return await self._node.takeover.reach(
            drone_id, verb, caller, epoch, owner, owner_paths, why, deadline, take_over=take_over
        )

    @staticmethod
    def _relay(
        relay: StopRelay | None, drone_id: str, verb: str, arguments: JsonObject, epoch: int | None,
        body: Mapping[str, object], deadline: float, owner_paths: list[Awaitable[JsonValue]], why: list[str],
    ) -> None:  # fmt: skip
        """The stop through PostgreSQL notifications, as one more of the owner's paths (until
        ``deadline``), or why not."""
        left = deadline - time.monotonic()
        if relay is None:
            why.append("PostgreSQL: not listening")
        elif left > 0.1:
            owner_paths.append(relay.send(drone_id, verb, arguments, epoch, body, left))

    async def _to_new_owner(
        self, drone_id: str, verb: str, arguments: JsonObject, body: Mapping[str, object], call_s: float,
        accept_s: float, until: float,
    ) -> JsonValue:  # fmt: skip
        """A fenced node's stop to whichever node serves the drone's calls, asked again until ``until``
        while none does (a node taking the drone over serves them once its link is up)."""
        while True:
            try:
                return await self._node.bus.call(
                    drone_id, verb, arguments, body, call_s, None, accept_s=min(accept_s, OWNER_ACK_S)
                )
            except NoOwner:
                if time.monotonic() > until - NEW_OWNER_RETRY_S:
                    raise
                await asyncio.sleep(NEW_OWNER_RETRY_S)

    async def relayed_stop(self, stop: JsonObject) -> object:
        """A stop another node relayed through PostgreSQL: run it when this node owns the drone under
        that epoch (the same path as a stop over the bus), or keeps a stop-only path to it; None (silent)
        when the drone is not this node's."""
        vid, verb, epoch = str(stop.get("vehicle")), str(stop.get("command")), stop.get("epoch")
        epoch = epoch if isinstance(epoch, int) else None
        by, args = stop.get("by"), stop.get("args")
        caller = dict(by) if isinstance(by, dict) else {}
        if vid in self._node.held:
            self.check_epoch(vid)(epoch)
            if verb not in STOP_COMMANDS or not Caller.from_dict(caller).is_operator:
                raise NotRun(f"only an operator's land, return_to_launch or hold crosses PostgreSQL: {verb} "
                             "was not run")  # fmt: skip
            log.warning("%s: %s relayed through PostgreSQL from node %s", vid, verb, stop.get("node"))
            arguments = dict(args) if isinstance(args, dict) else {}
            return await self.answer(vid)(verb, arguments, caller, no_progress)
        if vid in self._node.fenced:
            self._node.stops.check(vid)(epoch)
            return await self._node.stops.stop_directly(vid, verb, Caller.from_dict(caller))
        return None

    def check_epoch(self, vehicle_id: str) -> CallCheck:
        return epoch_check(self._node.held, vehicle_id, self._node.node_id, LEASE_WORDS)

    def answer(self, vehicle_id: str) -> CallHandler:
        async def handle(
            name: str, arguments: JsonObject, caller: Mapping[str, object], progress: ProgressSink
        ) -> object:
            registry = self._node.registry
            if registry is None or not registry.is_local(vehicle_id):
                raise NoOwner(
                    f"node {self._node.node_id} no longer owns drone '{vehicle_id}': retry in a few seconds"
                )
            commander = self._node.gateway.commander
            run = asyncio.ensure_future(answer(commander, name, arguments, caller, progress))
            self._running.setdefault(vehicle_id, set()).add(run)
            try:
                await asyncio.wait({run})  # this handler cancelled: the verb is cancelled with it
            except asyncio.CancelledError:
                run.cancel()
                raise
            finally:
                self._running.get(vehicle_id, set()).discard(run)
                why = self._cut.pop(run, None)
            if why is not None and run.cancelled():
                raise OwnerFenced(
                    f"not finished: node {self._node.node_id} gave drone '{vehicle_id}' up while it ran "
                    f"{name} ({why}) and does not command it any further; the drone flies its last command "
                    "on its own: check get_telemetry before the next command",
                    vehicle_id=vehicle_id,
                )
            return run.result()

        return handle


async def _head_start(over_bus: asyncio.Future[JsonValue], heard: asyncio.Event) -> None:
    """Until the stop's bus call has ended or its owner accepted it (``heard`` is set then), at most
    STOP_BUS_HEAD_START_S."""
    over_bus.add_done_callback(lambda _call: heard.set())
    with contextlib.suppress(TimeoutError):
        await asyncio.wait_for(heard.wait(), STOP_BUS_HEAD_START_S)
