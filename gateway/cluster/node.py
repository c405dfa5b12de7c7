"""A gateway as one node of a cluster: leases, telemetry fan-out, operator locks and routed calls.

The runtime (:class:`gateway.runtime.Gateway`) builds one when ``GATEWAY_CLUSTER_NATS_URL`` is set; the
registry then holds a :class:`~gateway.cluster.remote.RemoteVehicle` for every vehicle this node does not
own, and this node adopts and releases vehicles as its lease keeper wins and loses their leases.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import random
import time
from collections.abc import Callable
from datetime import datetime
from typing import TYPE_CHECKING, Any

from nats.aio.msg import Msg
from nats.aio.subscription import Subscription

from gateway.cluster import snapshot
from gateway.cluster.bus import Bus, CallHandler, ProgressSink, tele_subject
from gateway.cluster.forwarding import ClusterRouter, answer
from gateway.cluster.keeper import LeasePlan, Wanted, plan
from gateway.cluster.leases import Lease, LeaseStore, NodeRecord
from gateway.cluster.remote import RemoteVehicle
from gateway.cluster.takeover import pick_up_operations
from gateway.config import Settings
from gateway.errors import GatewayError, NoOwner
from gateway.fleet.caller import Caller
from gateway.fleet.routing import OnMessage
from gateway.registry.spec import VehicleSpec

if TYPE_CHECKING:
    from gateway.fleet.registry import Registry
    from gateway.runtime import Gateway

log = logging.getLogger("gateway.cluster")

#: a node stops its sidecars when it could not renew for this share of the lease time (before anyone
#: else may take them over at the full lease time)
SELF_FENCE_SHARE = 0.8
CONNECT_TIMEOUT_S = 15.0


class ClusterSetupError(GatewayError):
    code = "cluster_setup"
    http_status = 500


def check_settings(settings: Settings) -> None:
    """One clear line when the cluster settings cannot work together."""
    if settings.clustered and not settings.database_url.startswith("postgresql"):
        raise ClusterSetupError(
            "GATEWAY_CLUSTER_NATS_URL is set but GATEWAY_DATABASE_URL is not PostgreSQL "
            f"({settings.database_url.split(':', 1)[0]}): cluster nodes share one PostgreSQL database "
            "(postgresql+asyncpg://user:password@host/db), or unset GATEWAY_CLUSTER_NATS_URL to run alone"
        )


class ClusterNode:
    """This process as a cluster node. ``start`` after the registry has started, ``stop`` before it stops."""

    def __init__(self, gateway: Gateway) -> None:
        self.gateway = gateway
        self.settings: Settings = gateway.settings
        self.registry: Registry | None = None  # set by the runtime: the registry of this node
        self.router = ClusterRouter(self)
        self.node_id = self.settings.node_id
        self.tags = self.settings.node_tags
        self.api_url = f"http://{self.settings.host}:{self.settings.port}"
        self.bus = Bus(Bus.servers_of(self.settings.cluster_nats_url), name=f"fleet-gateway {self.node_id}")
        self.leases: LeaseStore | None = None
        self.held: dict[str, Lease] = {}
        self._served: dict[str, Subscription] = {}
        self._subs: list[Subscription] = []
        self._tasks: list[asyncio.Task[None]] = []
        self._seq = 0
        self._kick = asyncio.Event()
        self._valid_until = 0.0
        self._tick_lock = asyncio.Lock()
        self.nodes: list[NodeRecord] = []
        self.all_leases: dict[str, Lease] = {}
        self.last_plan = LeasePlan()
        self.started = False

    def _require_registry(self) -> Registry:
        if self.registry is None or not self.gateway.ready:
            raise NoOwner("this node's registry is not running (starting or stopping)")
        return self.registry

    @property
    def interval_s(self) -> float:
        return self.settings.cluster_lease_ttl_s / 3.0

    # --- lifecycle -------------------------------------------------------------------------------------
    async def start(self) -> None:
        store = self.gateway.require_store()
        self.leases = LeaseStore(store.engine, self.node_id, self.settings.cluster_lease_ttl_s)
        try:  # the client retries for ever: a server that never answers is a failed start
            await asyncio.wait_for(self.bus.connect(), CONNECT_TIMEOUT_S)
        except Exception as exc:
            raise ClusterSetupError(
                f"cannot reach NATS at {self.settings.cluster_nats_url} (GATEWAY_CLUSTER_NATS_URL): {exc!r}"
            ) from None
        self._subs.append(await self.bus.subscribe(tele_subject("*"), self._on_snapshot))
        self._subs.append(await self.bus.subscribe("fleet.event.>", self._on_event))
        await self.leases.heartbeat(self.tags, self.api_url)
        self.started = True
        log.info("cluster node %s (tags %s) joined; lease %.0f s", self.node_id, self.tags or "none",
                 self.settings.cluster_lease_ttl_s)  # fmt: skip
        self._tasks = [
            asyncio.create_task(self._keep(), name="cluster-leases"),
            asyncio.create_task(self._publish(), name="cluster-telemetry"),
        ]

    async def stop(self) -> None:
        """Hand every vehicle over: stop its sidecar, then release its lease (others take it at once)."""
        self.started = False
        for task in self._tasks:
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)
        self._tasks = []
        held = list(self.held)
        for vid in held:
            await self._drop(vid, "node stopping")
        if self.leases is not None:
            with contextlib.suppress(Exception):
                await self.leases.release(held)
                await self.leases.leave()
        if held:
            with contextlib.suppress(Exception):
                await self.bus.broadcast("leases", {"node": self.node_id, "released": held})
        await self.bus.close()

    # --- leases ----------------------------------------------------------------------------------------
    async def registrations_changed(self) -> None:
        """A registration changed through this node: every node follows at once (not at its next tick)."""
        self.kick()
        if self.started:
            await self.announce("registry", {})

    def kick(self) -> None:
        """Run the lease keeper now (registrations or leases changed)."""
        self._kick.set()

    async def _keep(self) -> None:
        first = True
        while True:
            try:
                # a database that hangs counts as one that fails: the fence below must still act
                await asyncio.wait_for(self.tick(acquire=not first), self.settings.cluster_lease_ttl_s / 2)
            except asyncio.CancelledError:
                raise
            except Exception:
                log.exception("lease keeping failed")
                if self.held and time.monotonic() > self._valid_until:
                    log.error(
                        "node %s could not renew its leases in time: stopping its sidecars", self.node_id
                    )
                    for vid in list(self.held):
                        await self._drop(vid, "leases could not be renewed")
            first = False
            self._kick.clear()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self._kick.wait(), self.interval_s)

    async def tick(self, acquire: bool = True) -> LeasePlan:
        """One round: heartbeat, renew, follow registrations, then take or give up leases."""
        assert self.leases is not None
        async with self._tick_lock:
            started = time.monotonic()
            await self.leases.heartbeat(self.tags, self.api_url)
            renewed = await self.leases.renew(list(self.held))
            self._valid_until = started + self.settings.cluster_lease_ttl_s * SELF_FENCE_SHARE
            for vid in list(self.held):
                if vid not in renewed or renewed[vid].epoch != self.held[vid].epoch:
                    log.warning("%s: lease lost (taken over or expired): stopping its sidecar", vid)
                    await self._drop(vid, "lease lost")
                else:
                    self.held[vid] = renewed[vid]
            store = self.gateway.require_store()
            records = await store.list_vehicles()
            registry = self._require_registry()
            await registry.sync(records)
            self.all_leases = await self.leases.leases()
            self.nodes = await self.leases.nodes()
            self._note_owners()
            await self._sync_locks()
            wanted = [Wanted(r.id, r.node_tag, r.auto_connect) for r in records]
            idle = {vid for vid in self.held if self._idle(vid)}
            result = plan(self.node_id, self.tags, wanted, self.all_leases, self.nodes, set(self.held), idle)
            self.last_plan = result
            for vid in result.release:
                log.info("%s: handing over (%s)", vid, "rebalancing" if vid in idle else "no longer ours")
                await self._drop(vid, "handed over")
                await self.leases.release([vid])
            if acquire and result.room > 0:
                candidates = list(result.candidates)
                random.shuffle(candidates)  # nodes racing for free leases rarely pick the same one
                taken = 0
                for vid in candidates:
                    if taken >= result.room:
                        break
                    previous = self.all_leases.get(vid)
                    lease = await self.leases.acquire(vid)
                    if lease is None:
                        continue
                    taken += 1
                    await self._adopt(vid, lease, previous.node_id if previous is not None else None)
            if result.release:
                await self.bus.broadcast("leases", {"node": self.node_id, "released": result.release})
            return result

    def _note_owners(self) -> None:
        registry = self._require_registry()
        for vehicle in registry.all():
            if isinstance(vehicle, RemoteVehicle):
                lease = self.all_leases.get(vehicle.id)
                if lease is not None and lease.live and lease.node_id != self.node_id:
                    vehicle.set_owner(lease.node_id, lease.epoch)
                else:
                    vehicle.set_owner(None)

    def _idle(self, vehicle_id: str) -> bool:
        """On the ground (or unknown: not connected) with no operation running."""
        registry = self._require_registry()
        try:
            vehicle = registry.get(vehicle_id)
        except GatewayError:
            return True
        ops = self.gateway.operations
        if ops is not None and ops.running(vehicle_id) is not None:
            return False
        flying = vehicle.on_ground() is False  # the autopilot's dialect reads its landed state
        armed = vehicle.telemetry.fresh("armed")
        return not flying and not armed

    async def _adopt(self, vehicle_id: str, lease: Lease, previous: str | None) -> None:
        registry = self._require_registry()
        vehicle = await registry.adopt(vehicle_id)
        self.held[vehicle_id] = lease
        self._served[vehicle_id] = await self.bus.serve_calls(vehicle_id, self._answer(vehicle_id))
        was = "" if previous in (None, self.node_id) else f" from node {previous}"
        log.warning("%s: now owned by node %s%s (lease epoch %d)", vehicle_id, self.node_id, was, lease.epoch)
        try:
            await pick_up_operations(self.gateway, self.node_id, vehicle, lease.epoch, previous)
        except Exception:
            log.exception("takeover of %s: picking up its operations failed", vehicle_id)

    async def _drop(self, vehicle_id: str, why: str) -> None:
        self.held.pop(vehicle_id, None)
        sub = self._served.pop(vehicle_id, None)
        if sub is not None:
            with contextlib.suppress(Exception):
                await sub.unsubscribe()
        registry = self.registry
        if registry is not None:
            await registry.release(vehicle_id)
        log.info("%s: released by node %s (%s)", vehicle_id, self.node_id, why)

    # --- telemetry fan-out ----------------------------------------------------------------------------
    async def _publish(self) -> None:
        period = 1.0 / self.settings.cluster_telemetry_hz
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
        registry = self.registry
        if registry is None or self.bus.nc is None:
            return 0
        count = 0
        for vid, lease in list(self.held.items()):
            if not registry.is_local(vid):
                continue
            self._seq += 1
            payload = snapshot.encode(
                registry.get(vid), self.node_id, lease.epoch, self._seq, self._operation(vid)
            )
            await self.bus.publish(tele_subject(vid), payload)
            count += 1
        return count

    def _operation(self, vehicle_id: str) -> dict[str, Any] | None:
        ops = self.gateway.operations
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

    async def _on_snapshot(self, msg: Msg) -> None:
        try:
            body = snapshot.decode(msg.data)
        except ValueError:
            return
        if body.get("node") == self.node_id:
            return
        registry = self.registry
        if registry is None:
            return
        try:
            vehicle = registry.get(body["id"])
        except GatewayError:
            self.kick()  # a vehicle registered on another node: pick the registration up
            return
        if isinstance(vehicle, RemoteVehicle):
            vehicle.apply(body)

    # --- broadcasts -----------------------------------------------------------------------------------
    async def announce(self, kind: str, body: dict[str, Any]) -> None:
        """Tell every node (locks, registrations); a node that misses it catches up at its next tick."""
        try:
            await self.bus.broadcast(kind, {**body, "node": self.node_id})
        except Exception:
            log.exception("could not announce %s to the cluster", kind)

    async def _on_event(self, msg: Msg) -> None:
        kind = msg.subject.rsplit(".", 1)[-1]
        try:
            body = json.loads(msg.data)
        except ValueError:
            return
        if body.get("node") == self.node_id:
            return
        if kind == "lock":
            at = body.get("at")
            self.gateway.locks.lock(
                body["scope"], body["reason"], body["by"], at=datetime.fromisoformat(at) if at else None
            )
        elif kind == "unlock":
            self.gateway.locks.unlock(body["scope"])
        elif kind == "takeover":  # a pilot or ground station took a drone owned by another node
            at = body.get("at")
            self.gateway.locks.take_over(
                body["scope"], body["reason"], at=datetime.fromisoformat(at) if at else None, by=body["by"]
            )
        elif kind == "release":
            self.gateway.locks.release(body["scope"])
        elif kind == "stop":  # an operator's emergency stop on another node: end the fleet operations
            fleet = self.gateway.fleet_operations  # this node coordinates (it stops its own drones)
            registry = self.registry
            if fleet is not None and registry is not None:
                by = f"operator stop ({body.get('action')}) on node {body.get('node')}"
                await fleet.supersede([v.id for v in registry.all()], by)
        elif kind in ("registry", "leases"):
            self.kick()

    async def _sync_locks(self) -> None:
        """The locks in the database are the truth: catch up with any broadcast this node missed."""
        store = self.gateway.require_store()
        stored = {lk.scope: lk for lk in await store.list_locks()}
        book = self.gateway.locks
        for lock in book.all():
            if lock.scope not in stored:
                book.unlock(lock.scope)
        for scope, lk in stored.items():
            current = {x.scope: x for x in book.all()}.get(scope)
            if current is None or current.reason != lk.reason or current.by != lk.by:
                book.lock(scope, lk.reason, lk.by, at=lk.locked_at)

    # --- calls routed to the owner --------------------------------------------------------------------
    async def forward(
        self,
        drone_id: str,
        verb: str,
        caller: Caller,
        arguments: dict[str, Any],
        on_message: OnMessage | None,
        wait_s: float,
    ) -> Any:
        """Run ``verb`` on the drone's owner (over NATS); its result, or its error raised here."""
        if not self.started:
            raise NoOwner(f"this node is not part of the cluster yet; cannot reach {drone_id}'s owner")
        timeout = max(0.0, wait_s) + self.settings.cluster_forward_timeout_s
        body = {**caller.to_dict(), "node": self.node_id}
        return await self.bus.call(drone_id, verb, arguments, body, timeout, on_message)

    def _answer(self, vehicle_id: str) -> CallHandler:
        async def handle(
            name: str, arguments: dict[str, Any], caller: dict[str, Any], progress: ProgressSink
        ) -> Any:
            registry = self.registry
            if registry is None or not registry.is_local(vehicle_id):
                raise NoOwner(
                    f"node {self.node_id} no longer owns drone '{vehicle_id}': retry in a few seconds"
                )
            return await answer(self.gateway.commander, name, arguments, caller, progress)

        return handle

    # --- views ----------------------------------------------------------------------------------------
    def describe(self) -> dict[str, Any]:
        return {
            "node_id": self.node_id,
            "tags": self.tags,
            "held": sorted(self.held),
            "share": round(self.last_plan.share, 3),
            "nodes": [
                {
                    "node_id": n.node_id,
                    "tags": n.tags,
                    "api_url": n.api_url,
                    "alive": n.alive,
                    "last_seen": n.last_seen.isoformat(),
                    "vehicles": sorted(
                        v for v, lease in self.all_leases.items() if lease.live and lease.node_id == n.node_id
                    ),
                }
                for n in self.nodes
            ],
        }


def remote_factory(settings: Settings) -> Callable[[VehicleSpec], RemoteVehicle]:
    return lambda spec: RemoteVehicle(spec, settings)
