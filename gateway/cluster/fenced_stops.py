"""The stop-only path of a fenced node.

Fencing exists so that no two nodes command one drone. A stop (land, return, hold) is the one command
that is safe to send twice, so a node that fenced itself because the database was unreachable keeps
a way to stop the drones it owned: on the drone's stop subject, and for its own callers, it sends
the stop over the drone's own link (`gateway.cluster.stoplink`), opened for that moment only.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import time
from collections.abc import Mapping

from nats.aio.subscription import Subscription

from gateway.cluster.bus import CallCheck, CallHandler, ProgressSink, epoch_check, stop_subject
from gateway.cluster.node_parts import NodeCore
from gateway.cluster.remote import RemoteVehicle
from gateway.cluster.stoplink import STOP_COMMANDS, StopTarget, direct_stop_answer, send_stop
from gateway.errors import CommandFailed, NoOwner, NotRun
from gateway.fleet.policy.caller import Caller
from gateway.fleet.vehicles.protocols import FlyingVehicle
from gateway.util.json_types import JsonObject

log = logging.getLogger("gateway.cluster")

#: a stop sent over a drone's own link by its fenced node: its whole answer (open, for a hold ask where
#: the drone is, send, ack) within this (a land is sent at once; this bounds waiting for its answer)
STOP_SEND_S = 4.0
#: one try at the drone's own link within that (its sidecar may still be letting go of it)
LINK_TRY_S = 1.0


#: what a stop's check says when this node has no stop path to the drone, or the stop was sent for
#: another lease epoch
STOP_PATH_WORDS = (
    "node {node} has no stop path to drone '{vehicle}' any more: retry",
    "a stop for drone '{vehicle}' sent for lease epoch {sent} reached node {node}, which last held epoch "
    "{held}: not run; retry",
)


class FencedStops:
    """The drones this node owned when it fenced itself, and the stop-only path it keeps to each."""

    def __init__(self, node: NodeCore) -> None:
        self._node = node
        # drones this node owned when it fenced itself (database unreachable): it keeps a stop-only path
        # to each (land, return, hold over the drone's own link) until a node holds a live lease of it
        self.fenced: dict[str, StopTarget] = {}
        self._paths: dict[str, Subscription] = {}
        # the vehicles whose sidecars are being stopped as this node fences itself, while they are
        self._leaving: dict[str, FlyingVehicle] = {}

    def targets(self) -> list[StopTarget]:
        registry = self._node.registry
        targets = []
        for vid, lease in self._node.held.items():
            vehicle = None if registry is None else registry.find(vid)
            if vehicle is None:
                continue
            sysid = getattr(vehicle, "sysid", None) or vehicle.spec.expected_sysid
            targets.append(StopTarget(vid, vehicle.spec.url, sysid, lease.epoch))
            flown = vehicle.flown_here()  # None: a view of a drone another node flew
            if flown is not None:
                self._leaving[vid] = flown
        return targets

    def left(self) -> None:
        """Its sidecars are stopped: a stop goes over the drones' own links only."""
        self._leaving.clear()

    async def keep(self, targets: list[StopTarget]) -> None:
        registry = self._node.registry
        for target in targets:
            vid = target.vehicle_id
            self.fenced[vid] = target
            view = None if registry is None else registry.find(vid)
            if isinstance(view, RemoteVehicle):  # its stops go to this node, which answers on the side
                view.set_owner(self._node.node_id, target.epoch)
            if vid not in self._paths:
                try:
                    self._paths[vid] = await self._node.bus.serve_calls(
                        vid, self._answer(vid), self.check(vid), subject=stop_subject(vid)
                    )
                except Exception as exc:
                    log.error("%s: cannot listen for stops on the bus (%r): only this node's own stops "
                              "reach it", vid, exc)  # fmt: skip
        if targets:
            log.warning("node %s keeps a stop-only path (land, return, hold over the drone's own link) to %s "
                        "until another node holds their leases", self._node.node_id,
                        ", ".join(t.vehicle_id for t in targets))  # fmt: skip

    async def end(self, vehicle_ids: list[str], why: str) -> None:
        for vid in vehicle_ids:
            self.fenced.pop(vid, None)
            sub = self._paths.pop(vid, None)
            if sub is not None:
                with contextlib.suppress(Exception):
                    await sub.unsubscribe()
            log.info("%s: node %s ends its stop-only path (%s)", vid, self._node.node_id, why)

    def check(self, vehicle_id: str) -> CallCheck:
        return epoch_check(self.fenced, vehicle_id, self._node.node_id, STOP_PATH_WORDS)

    def _answer(self, vehicle_id: str) -> CallHandler:
        async def handle(
            name: str, arguments: JsonObject, caller: Mapping[str, object], progress: ProgressSink
        ) -> object:
            return await self.stop_directly(vehicle_id, name, Caller.from_dict(caller))

        return handle

    async def stop_directly(self, vehicle_id: str, verb: str, caller: Caller) -> JsonObject:
        """An operator's land, return or hold, sent over the drone's own link by this fenced node."""
        target = self.fenced.get(vehicle_id)
        if target is None:
            raise NoOwner(
                f"node {self._node.node_id} has no stop path to drone '{vehicle_id}' any more: retry"
            )
        if verb not in STOP_COMMANDS or not caller.is_operator:
            raise NotRun(
                f"node {self._node.node_id} fenced itself (the database was unreachable) and holds no link "
                f"to {vehicle_id}: it sends only an operator's land, return_to_launch or hold over the "
                f"drone's own link; {verb} was not run"
            )
        started = time.monotonic()
        deadline = started + STOP_SEND_S
        answer_: str | None = None
        while answer_ is None:
            leaving = self._leaving.get(vehicle_id)
            if leaving is not None and str(leaving.state) == "ready":
                # its sidecar is still being stopped (its flight log closing): while its link is up, the
                # stop goes through it
                try:
                    stops = {"land": leaving.land, "return_to_launch": leaving.return_to_launch,
                             "hold": leaving.hold}  # fmt: skip
                    await stops[verb]()
                except Exception as exc:
                    log.info("%s: %s through its stopping sidecar failed (%r)", vehicle_id, verb, exc)
                else:
                    answer_ = "ACCEPTED (through its sidecar, still being stopped)"
                    break
            try:
                left = max(0.3, deadline - time.monotonic())
                answer_ = await send_stop(target, verb, min(left, LINK_TRY_S), hear_first=True)
            except Exception as exc:
                if time.monotonic() < deadline - 0.3:  # the link may be freed any moment (sidecar stopping)
                    await asyncio.sleep(0.1)
                    continue
                log.error("%s: %s over its own link failed (%r): nothing sent", vehicle_id, verb, exc)
                raise NotRun(
                    f"node {self._node.node_id} (fenced) could not open {vehicle_id}'s link ({exc}): "
                    f"{verb} was not sent"
                ) from None
        log.warning("%s: %s sent over its own link by fenced node %s for %s (autopilot: %s, after %.0f ms)",
                    vehicle_id, verb, self._node.node_id, caller.principal, answer_,
                    (time.monotonic() - started) * 1000)  # fmt: skip
        if answer_ in ("DENIED", "UNSUPPORTED", "FAILED", "TEMPORARILY_REJECTED", "CANCELLED"):
            raise CommandFailed(f"{vehicle_id} refused {verb} sent over its own link: {answer_}")
        facts = {"via": "direct link", "node": self._node.node_id}
        why = f"fenced while the database was unreachable (autopilot: {answer_})"
        return direct_stop_answer(vehicle_id, verb, self._node.node_id, why, facts)
