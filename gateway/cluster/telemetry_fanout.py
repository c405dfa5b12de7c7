"""Telemetry fan-out between cluster nodes: this node publishes a snapshot of each drone it owns
(``cluster_telemetry_hz`` a second, with the drone's latest operation) and applies the snapshots other
nodes publish to its `RemoteVehicle` views of their drones."""

from __future__ import annotations

import asyncio
import logging
import time
from typing import TYPE_CHECKING, Protocol

from nats.aio.msg import Msg

from gateway.cluster import snapshot
from gateway.cluster.bus import tele_subject
from gateway.cluster.node_parts import NodeWithRuntime
from gateway.cluster.remote import RemoteVehicle
from gateway.errors import GatewayError
from gateway.util.json_types import JsonObject

if TYPE_CHECKING:
    pass

log = logging.getLogger("gateway.cluster")


class FanoutNode(NodeWithRuntime, Protocol):
    """What the fan-out reads of its node beyond the core (`gateway.cluster.node_parts`)."""

    def kick(self) -> None:
        """Run the lease keeper now (a vehicle registered on another node)."""
        ...


class TelemetryFanout:
    """Publishes this node's drones' snapshots; applies the other nodes'."""

    def __init__(self, node: FanoutNode) -> None:
        self._node = node
        self._seq = 0

    async def run(self) -> None:
        period = 1.0 / self._node.settings.cluster_telemetry_hz
        while True:
            started = time.monotonic()
            try:
                await self.publish_snapshots()
            except asyncio.CancelledError:
                raise
            except Exception:
                log.exception("publishing telemetry snapshots failed")
            await asyncio.sleep(max(0.0, period - (time.monotonic() - started)))

    async def publish_snapshots(self) -> int:
        registry = self._node.registry
        if registry is None or self._node.bus.nc is None:
            return 0
        count = 0
        for vid, lease in list(self._node.held.items()):
            if not registry.is_local(vid):
                continue
            self._seq += 1
            payload = snapshot.encode(
                registry.get(vid), self._node.node_id, lease.epoch, self._seq, self._operation(vid)
            )
            await self._node.bus.publish(tele_subject(vid), payload)
            count += 1
        return count

    def _operation(self, vehicle_id: str) -> JsonObject | None:
        ops = self._node.gateway.operations
        op = None if ops is None else ops.latest(vehicle_id)
        if op is None:
            return None
        target = op.params.get("alt_m")
        return {
            "id": op.id,
            "kind": op.kind,
            "status": op.status.value,
            "progress": round(float(op.progress), 3),
            "message": op.message,
            "target_alt_m": float(target) if isinstance(target, int | float) else None,
            "eta_s": None if op.eta_s is None else round(op.eta_s, 1),
            "elapsed_s": round(op.elapsed_s(), 1),
            "params": op.params,
        }

    async def on_snapshot(self, msg: Msg) -> None:
        try:
            body = snapshot.decode(msg.data)
        except ValueError:
            return
        if body.get("node") == self._node.node_id:
            return
        registry = self._node.registry
        if registry is None:
            return
        try:
            vehicle = registry.get(str(body["id"]))
        except GatewayError:
            self._node.kick()  # a vehicle registered on another node: pick the registration up
            return
        if isinstance(vehicle, RemoteVehicle):
            vehicle.apply(body)
