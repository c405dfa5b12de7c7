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
import uuid
from collections.abc import Callable
from datetime import datetime
from typing import TYPE_CHECKING, Any

from nats.aio.msg import Msg
from nats.aio.subscription import Subscription

from gateway.cluster import snapshot
from gateway.cluster.bus import Bus, CallCheck, CallHandler, ProgressSink, stop_subject, tele_subject
from gateway.cluster.forwarding import ClusterRouter, answer
from gateway.cluster.keeper import LeasePlan, Wanted, plan
from gateway.cluster.leases import Lease, LeaseStore, NodeRecord
from gateway.cluster.remote import RemoteVehicle
from gateway.cluster.stop_notify import StopRelay
from gateway.cluster.stoplink import STOP_COMMANDS, StopTarget, send_stop
from gateway.cluster.takeover import pick_up_operations
from gateway.config import Settings
from gateway.errors import CommandFailed, GatewayError, NoOwner, NotRun
from gateway.fleet.caller import Caller
from gateway.fleet.routing import OnMessage
from gateway.fleet.views import ActionResult, OperationView
from gateway.registry.spec import VehicleSpec

if TYPE_CHECKING:
    from gateway.fleet.registry import Registry
    from gateway.runtime import Gateway

log = logging.getLogger("gateway.cluster")

#: a node stops its sidecars when it could not renew for this share of the lease time (before anyone
#: else may take them over at the full lease time)
SELF_FENCE_SHARE = 0.8
CONNECT_TIMEOUT_S = 15.0
#: a stopping node gives the database and the bus this long each to hear it leave
LEAVE_TIMEOUT_S = 3.0
#: a lock heard on the bus holds this long at most while the database does not have it (its node keeps it
#: until the database is back); an unlock heard on the bus, or the lock seen stored, ends the wait
HEARD_LOCK_KEPT_S = 600.0
#: forwarded verbs that only read the drone: they get a short timeout, not the MCP wait cap
READS = frozenset({"arrival", "mission_progress", "get_param", "list_params", "download_mission"})
READ_TIMEOUT_S = 5.0
#: a stop sent over a drone's own link by its fenced node: its whole answer (open, for a hold ask where
#: the drone is, send, ack) within this (a land is sent at once; this bounds waiting for its answer)
STOP_SEND_S = 4.0
#: a stop the bus did not carry, relayed through PostgreSQL notifications: its owner's answer within this
RELAY_S = 5.0
#: an operator's stop its owner has not accepted over the bus by then goes through PostgreSQL instead (the
#: owner refuses the bus copy if it arrives later, so it runs once); the stop reaches the drone within 1 s
STOP_ACCEPT_S = 0.5


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
        self._heard_locks: dict[str, float] = {}  # scope -> when a lock of it was heard on the bus
        self._adopting_from: dict[str, str] = {}  # vehicle -> the node it was taken from, while adopting
        self._adoptions: set[asyncio.Task[None]] = set()
        # drones this node owned when it fenced itself (database unreachable): it keeps a stop-only path
        # to each (land, return, hold over the drone's own link) until a node holds a live lease of it
        self.fenced: dict[str, StopTarget] = {}
        self._stop_paths: dict[str, Subscription] = {}
        self.relay: StopRelay | None = None  # stops through PostgreSQL when the bus does not carry them
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
        self.relay = StopRelay(store.url, self.node_id, self._relayed_stop)
        await self.relay.start()
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
        if self._adoptions:  # let an adoption under way finish first: then its sidecar is stopped below
            await asyncio.wait(set(self._adoptions), timeout=LEAVE_TIMEOUT_S * 3)
        if self.relay is not None:
            relay, self.relay = self.relay, None
            await relay.close()
        held = list(self.held)
        await self._end_stop_paths(list(self.fenced), "node stopping")
        await self._drop_all(held, "node stopping")
        # neither the database nor the bus may keep a stopping node alive: its sidecars are stopped
        # already; a lease it cannot release expires on its own
        if self.leases is not None:
            try:
                await asyncio.wait_for(self._leave(held), LEAVE_TIMEOUT_S)
            except Exception as exc:
                log.warning("could not release the leases of node %s (%r): they expire on their own",
                            self.node_id, exc)  # fmt: skip
        if held and self.bus.connected:
            with contextlib.suppress(Exception):
                await self.bus.broadcast("leases", {"node": self.node_id, "released": held})
        try:
            await asyncio.wait_for(self.bus.close(), LEAVE_TIMEOUT_S)
        except Exception as exc:
            log.warning("closing the bus connection failed (%r)", exc)

    async def _leave(self, held: list[str]) -> None:
        assert self.leases is not None
        await self.leases.release(held)
        await self.leases.leave()

    async def _stop_strays(self) -> None:
        """A sidecar runs only under a lease this node holds: stop any other (none should exist)."""
        registry = self.registry
        if registry is None:
            return
        strays = [v.id for v in registry.all() if registry.is_local(v.id) and v.id not in self.held]
        for vid in strays:
            log.error("%s: its sidecar ran without this node holding its lease: stopping it", vid)
        await self._drop_all(strays, "no lease held")

    async def _drop_all(self, vehicle_ids: list[str], why: str) -> None:
        """Stop the sidecars of these vehicles, all at once (none waits behind another's flight log)."""
        results = await asyncio.gather(*(self._drop(v, why) for v in vehicle_ids), return_exceptions=True)
        for vid, result in zip(vehicle_ids, results, strict=True):
            if isinstance(result, BaseException):
                log.error("%s: stopping it raised %r", vid, result)

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
                    targets = self._stop_targets()
                    await self._drop_all(list(self.held), "leases could not be renewed")
                    await self._keep_stop_paths(targets)
                with contextlib.suppress(Exception):
                    await self._stop_strays()
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
            await self._stop_strays()
            store = self.gateway.require_store()
            records = await store.list_vehicles()
            registry = self._require_registry()
            await registry.sync(records)
            self.all_leases = await self.leases.leases()
            self.nodes = await self.leases.nodes()
            await self._end_stop_paths(
                [v for v in self.fenced if v not in self.all_leases or self.all_leases[v].live
                 or v not in {r.id for r in records}],
                "the database is back and a node holds its lease",
            )  # fmt: skip
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
                    was = previous.node_id if previous is not None else None
                    if was == self.node_id:  # our own lease of an adoption that failed: who had it before
                        was = self._adopting_from.get(vid, was)
                    # the tick's time limit is for a database that hangs, not for starting a sidecar: an
                    # adoption under way finishes (or undoes itself) even when the tick is cut short
                    adoption = asyncio.create_task(self._adopt(vid, lease, was), name=f"adopt-{vid}")
                    self._adoptions.add(adoption)
                    adoption.add_done_callback(self._adoptions.discard)
                    await asyncio.shield(adoption)
            if result.release:
                await self.bus.broadcast("leases", {"node": self.node_id, "released": result.release})
            return result

    def _note_owners(self) -> None:
        registry = self._require_registry()
        for vehicle in registry.all():
            if isinstance(vehicle, RemoteVehicle):
                lease = self.all_leases.get(vehicle.id)
                fenced = self.fenced.get(vehicle.id)
                if lease is not None and lease.live and lease.node_id != self.node_id:
                    vehicle.set_owner(lease.node_id, lease.epoch)
                elif fenced is not None:  # nobody holds its link: this node's stop-only path reaches it
                    vehicle.set_owner(self.node_id, fenced.epoch)
                else:
                    vehicle.set_owner(None)

    def _idle(self, vehicle_id: str) -> bool:
        """Known to be on the ground and disarmed, with no operation running; or not linked at all (never
        connected, or connecting is not wanted). A link that is connecting, lost or failed is not idle:
        the drone may be in the air, and is never handed over for balance."""
        registry = self._require_registry()
        try:
            vehicle = registry.get(vehicle_id)
        except GatewayError:
            return True
        ops = self.gateway.operations
        if ops is not None and ops.running(vehicle_id) is not None:
            return False
        if str(vehicle.state) == "registered":
            return True
        landed = vehicle.on_ground() is True  # the autopilot's dialect reads its landed state
        armed = vehicle.telemetry.fresh("armed")
        return landed and armed is False

    async def _adopt(self, vehicle_id: str, lease: Lease, previous: str | None) -> None:
        registry = self._require_registry()
        self.held[vehicle_id] = lease  # renewed from now on: a sidecar never runs without its lease
        try:
            vehicle = await registry.adopt(vehicle_id)
            self._served[vehicle_id] = await self.bus.serve_calls(
                vehicle_id, self._answer(vehicle_id), self._check_epoch(vehicle_id)
            )
        except BaseException:  # failed, or cut short (the node stopping): nothing half-adopted
            log.error("%s: adopting it failed: its sidecar is stopped, its lease left to expire", vehicle_id)
            if previous not in (None, self.node_id):
                self._adopting_from[vehicle_id] = previous
            await self._drop(vehicle_id, "adopting failed")
            raise
        self._adopting_from.pop(vehicle_id, None)
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

    # --- the stop-only path of a fenced node ----------------------------------------------------------
    # Fencing exists so that no two nodes command one drone. A stop (land, return, hold) is the one command
    # that is safe to send twice, so a node that fenced itself because the database was unreachable keeps
    # a way to stop the drones it owned: on the drone's stop subject, and for its own callers, it sends
    # the stop over the drone's own link (`gateway.cluster.stoplink`), opened for that moment only.
    def _stop_targets(self) -> list[StopTarget]:
        registry = self.registry
        targets = []
        for vid, lease in self.held.items():
            vehicle = None if registry is None else registry.find(vid)
            if vehicle is None:
                continue
            sysid = getattr(vehicle, "sysid", None) or vehicle.spec.expected_sysid
            targets.append(StopTarget(vid, vehicle.spec.url, sysid, lease.epoch))
        return targets

    async def _keep_stop_paths(self, targets: list[StopTarget]) -> None:
        registry = self.registry
        for target in targets:
            vid = target.vehicle_id
            self.fenced[vid] = target
            view = None if registry is None else registry.find(vid)
            if isinstance(view, RemoteVehicle):  # its stops go to this node, which answers on the side
                view.set_owner(self.node_id, target.epoch)
            if vid not in self._stop_paths:
                try:
                    self._stop_paths[vid] = await self.bus.serve_calls(
                        vid, self._stop_answer(vid), self._check_fenced(vid), subject=stop_subject(vid)
                    )
                except Exception as exc:
                    log.error("%s: cannot listen for stops on the bus (%r): only this node's own stops "
                              "reach it", vid, exc)  # fmt: skip
        if targets:
            log.warning("node %s keeps a stop-only path (land, return, hold over the drone's own link) to %s "
                        "until another node holds their leases", self.node_id,
                        ", ".join(t.vehicle_id for t in targets))  # fmt: skip

    async def _end_stop_paths(self, vehicle_ids: list[str], why: str) -> None:
        for vid in vehicle_ids:
            self.fenced.pop(vid, None)
            sub = self._stop_paths.pop(vid, None)
            if sub is not None:
                with contextlib.suppress(Exception):
                    await sub.unsubscribe()
            log.info("%s: node %s ends its stop-only path (%s)", vid, self.node_id, why)

    def _check_fenced(self, vehicle_id: str) -> CallCheck:
        def check(epoch: int | None) -> None:
            target = self.fenced.get(vehicle_id)
            if target is None:
                raise NoOwner(f"node {self.node_id} has no stop path to drone '{vehicle_id}' any more: retry")
            if epoch is not None and epoch != target.epoch:
                raise NotRun(
                    f"a stop for drone '{vehicle_id}' sent for lease epoch {epoch} reached node "
                    f"{self.node_id}, which last held epoch {target.epoch}: not run; retry"
                )

        return check

    def _stop_answer(self, vehicle_id: str) -> CallHandler:
        async def handle(
            name: str, arguments: dict[str, Any], caller: dict[str, Any], progress: ProgressSink
        ) -> Any:
            return await self.stop_directly(vehicle_id, name, Caller.from_dict(caller))

        return handle

    async def stop_directly(self, vehicle_id: str, verb: str, caller: Caller) -> dict[str, Any]:
        """An operator's land, return or hold, sent over the drone's own link by this fenced node."""
        target = self.fenced.get(vehicle_id)
        if target is None:
            raise NoOwner(f"node {self.node_id} has no stop path to drone '{vehicle_id}' any more: retry")
        if verb not in STOP_COMMANDS or not caller.is_operator:
            raise NotRun(
                f"node {self.node_id} fenced itself (the database was unreachable) and holds no link to "
                f"{vehicle_id}: it sends only an operator's land, return_to_launch or hold over the drone's "
                f"own link; {verb} was not run"
            )
        started = time.monotonic()
        try:
            answer_ = await send_stop(target, verb, STOP_SEND_S)
        except Exception as exc:
            log.error("%s: %s over its own link failed (%r): nothing sent", vehicle_id, verb, exc)
            raise NotRun(
                f"node {self.node_id} (fenced) could not open {vehicle_id}'s link ({exc}): "
                f"{verb} was not sent"
            ) from None
        log.warning("%s: %s sent over its own link by fenced node %s for %s (autopilot: %s, after %.0f ms)",
                    vehicle_id, verb, self.node_id, caller.principal, answer_,
                    (time.monotonic() - started) * 1000)  # fmt: skip
        if answer_ in ("DENIED", "UNSUPPORTED", "FAILED", "TEMPORARILY_REJECTED", "CANCELLED"):
            raise CommandFailed(f"{vehicle_id} refused {verb} sent over its own link: {answer_}")
        if verb == "hold":
            return ActionResult(
                drone_id=vehicle_id,
                action="hold",
                message=f"hold (a reposition to where it is) sent over the drone's own link by node "
                f"{self.node_id}, fenced while the database was unreachable (autopilot: {answer_})",
                facts={"via": "direct link", "node": self.node_id},
            ).model_dump(mode="json")
        return OperationView(
            operation_id=f"direct-{uuid.uuid4().hex[:12]}",
            drone_id=vehicle_id,
            kind=verb,
            status="sent",
            progress=0.0,
            message=f"{verb} sent over the drone's own link by node {self.node_id}, fenced while the "
            f"database was unreachable (autopilot: {answer_}); not tracked: its state shows when it lands",
            elapsed_s=0.0,
            params={"via": "direct link", "node": self.node_id},
        ).model_dump(mode="json")

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
            at = body.get("at") or body.get("locked_at")
            self.gateway.locks.lock(
                body["scope"], body["reason"], body["by"], at=datetime.fromisoformat(at) if at else None
            )
            self._heard_locks[body["scope"]] = time.monotonic()
        elif kind == "unlock":
            self.gateway.locks.unlock(body["scope"])
            self._heard_locks.pop(body["scope"], None)
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
        """The locks in the database are the truth: catch up with any broadcast this node missed. Not
        while this node still keeps writes the database could not take (a lock among them): until they
        are written, this node's locks are newer than the database's."""
        store = self.gateway.require_store()
        if store.spool.waiting:
            return
        stored = {lk.scope: lk for lk in await store.list_locks()}
        book = self.gateway.locks
        now = time.monotonic()
        for scope in [
            s for s, heard in self._heard_locks.items() if s in stored or now - heard > HEARD_LOCK_KEPT_S
        ]:
            del self._heard_locks[scope]
        for lock in book.all():
            # a lock heard on the bus that its node has not stored yet (the database was down there) holds
            if lock.scope not in stored and lock.scope not in self._heard_locks:
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
        forward_s = self.settings.cluster_forward_timeout_s
        if verb in READS:  # a read has nothing to wait for on the owner
            timeout = min(forward_s, READ_TIMEOUT_S)
        else:
            timeout = max(0.0, wait_s) + forward_s
        body = {**caller.to_dict(), "node": self.node_id}
        registry = self.registry
        vehicle = None if registry is None else registry.find(drone_id)
        epoch = vehicle.epoch if isinstance(vehicle, RemoteVehicle) and vehicle.epoch > 0 else None
        accept_s = min(self.settings.cluster_accept_timeout_s, timeout)
        owner_gone = None
        if isinstance(vehicle, RemoteVehicle):
            view, owner, seen_epoch = vehicle, vehicle.owner, vehicle.epoch

            def owner_gone() -> str | None:
                if view.owner == owner and view.epoch == seen_epoch:
                    return None
                if view.owner is None:
                    return f"node {owner} lost drone {drone_id}'s lease"
                return f"drone {drone_id} changed owner (node {owner} -> node {view.owner})"

        stop = verb in STOP_COMMANDS and caller.is_operator
        if stop and drone_id in self.fenced:  # no bus needed: this node sends it over the drone's link
            return await self.stop_directly(drone_id, verb, caller)
        # a stop gets a short accept time on the bus only where PostgreSQL can carry it instead
        relay = self.relay if stop else None
        short = relay is not None and relay.listening
        try:
            return await self.bus.call(
                drone_id, verb, arguments, body, timeout, on_message,
                accept_s=min(accept_s, STOP_ACCEPT_S) if short else accept_s, epoch=epoch,
                owner_gone=owner_gone,
            )  # fmt: skip
        except NotRun as exc:
            # the bus did not carry it (this node cut off, or no answer in the accept time): a stop goes
            # through PostgreSQL notifications to the owner (`gateway.cluster.stop_notify`)
            if relay is None or exc.details.get("bus") not in ("down", "no answer"):
                raise
            try:
                return await relay.send(drone_id, verb, arguments, epoch, body, RELAY_S)
            except NotRun:
                if not (short and exc.details.get("bus") == "no answer"):
                    raise
            # PostgreSQL did not carry it either while the bus is up: the bus once more, with the whole
            # accept time, for an owner slow to answer
            return await self.bus.call(
                drone_id, verb, arguments, body, timeout, on_message, accept_s=accept_s, epoch=epoch,
                owner_gone=owner_gone,
            )  # fmt: skip
        except NoOwner:
            if not stop:
                raise
        # nobody holds the drone's link: the node that last did may have fenced itself, and keep a
        # stop-only path to it (a land sent twice is still a land)
        return await self.bus.call(
            drone_id, verb, arguments, body, accept_s + STOP_SEND_S + 1.0, on_message, accept_s=accept_s,
            epoch=epoch, subject=stop_subject(drone_id),
        )  # fmt: skip

    async def _relayed_stop(self, stop: dict[str, Any]) -> Any:
        """A stop another node relayed through PostgreSQL: run it when this node owns the drone under
        that epoch (the same path as a stop over the bus), or keeps a stop-only path to it; None (silent)
        when the drone is not this node's."""
        vid, verb, epoch = str(stop.get("vehicle")), str(stop.get("command")), stop.get("epoch")
        epoch = epoch if isinstance(epoch, int) else None
        caller = dict(stop.get("by") or {})
        if vid in self.held:
            self._check_epoch(vid)(epoch)
            if verb not in STOP_COMMANDS or not Caller.from_dict(caller).is_operator:
                raise NotRun(f"only an operator's land, return_to_launch or hold crosses PostgreSQL: {verb} "
                             "was not run")  # fmt: skip
            log.warning("%s: %s relayed through PostgreSQL from node %s", vid, verb, stop.get("node"))
            return await self._answer(vid)(verb, dict(stop.get("args") or {}), caller, _no_progress)
        if vid in self.fenced:
            self._check_fenced(vid)(epoch)
            return await self.stop_directly(vid, verb, Caller.from_dict(caller))
        return None

    def _check_epoch(self, vehicle_id: str) -> CallCheck:
        def check(epoch: int | None) -> None:
            lease = self.held.get(vehicle_id)
            if lease is None:
                raise NoOwner(f"node {self.node_id} no longer owns drone '{vehicle_id}': not run; retry")
            if epoch is not None and epoch != lease.epoch:
                raise NotRun(
                    f"a call for drone '{vehicle_id}' sent for lease epoch {epoch} reached node "
                    f"{self.node_id}, which holds epoch {lease.epoch}: not run (the caller's view of its "
                    "owner was out of date); retry"
                )

        return check

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


async def _no_progress(_update: dict[str, Any]) -> None:
    return None


def remote_factory(settings: Settings) -> Callable[[VehicleSpec], RemoteVehicle]:
    return lambda spec: RemoteVehicle(spec, settings)
