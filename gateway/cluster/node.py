"""A gateway as one node of a cluster: leases, telemetry fan-out, operator locks and routed calls.

The runtime (:class:`gateway.runtime.Gateway`) builds one when ``GATEWAY_CLUSTER_NATS_URL`` is set and hands
it itself, which the node reads as a `gateway.cluster.runtime_view.NodeRuntime`; the
registry then holds a :class:`~gateway.cluster.remote.RemoteVehicle` for every vehicle this node does not
own, and this node adopts and releases vehicles as its lease keeper wins and loses their leases.
Beside it: `gateway.cluster.owner_calls` (calls routed to a drone's owner), `gateway.cluster.fenced_stops`
(the stop-only path of a fenced node) and `gateway.cluster.telemetry_fanout` (snapshots between nodes).
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
from typing import TYPE_CHECKING

from nats.aio.msg import Msg
from nats.aio.subscription import Subscription
from sqlalchemy.exc import DBAPIError

from gateway.cluster.bus import Bus, tele_subject
from gateway.cluster.fenced_stops import FencedStops
from gateway.cluster.forwarding import ClusterRouter
from gateway.cluster.keeper import LeasePlan, Wanted, plan
from gateway.cluster.leases import Lease, LeaseStore, NodeRecord
from gateway.cluster.lock_versions import FAMILIES, LockVersions
from gateway.cluster.owner_calls import OwnerCalls
from gateway.cluster.remote import RemoteVehicle
from gateway.cluster.renewal import SELF_FENCE_SHARE, LeaseRenewal
from gateway.cluster.runtime_view import NodeRuntime
from gateway.cluster.stop_notify import StopRelay
from gateway.cluster.stop_takeover import StopTakeover
from gateway.cluster.stoplink import StopTarget
from gateway.cluster.takeover import pick_up_late, pick_up_operations
from gateway.cluster.telemetry_fanout import TelemetryFanout
from gateway.config import Settings
from gateway.errors import GatewayError, NoOwner
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.geofence import FLEET
from gateway.registry.spec import VehicleSpec
from gateway.util.json_types import JsonObject

if TYPE_CHECKING:
    from gateway.fleet.vehicles.registry import Registry

log = logging.getLogger("gateway.cluster")

#: a node stops its sidecars when it could not renew for this share of the lease time (before anyone
#: else may take them over at the full lease time): `gateway.cluster.renewal.SELF_FENCE_SHARE`
CONNECT_TIMEOUT_S = 15.0
#: a tick may run past the moment the fence is due by this share of the lease time (half the time
#: between that moment and the leases' expiry), so that a renewal under way can still finish
TICK_GRACE_SHARE = 0.1
#: a stopping node gives the database and the bus this long each to hear it leave
LEAVE_TIMEOUT_S = 3.0
#: a lock heard on the bus holds this long at most while the database does not have it (its node keeps it
#: until the database is back); an unlock heard on the bus, or the lock seen stored, ends the wait
HEARD_LOCK_KEPT_S = 600.0


#: why a fenced node gives its drones up
FENCED_WHY = "leases could not be renewed"


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


#: what a slow or unreachable database raises: one line each, not a traceback (under load every
#: overrunning tick would print one, and the fence's own ERROR line says what it did)
_DATABASE_FAULTS: tuple[type[BaseException], ...] = (TimeoutError, OSError, DBAPIError)


def _log_keeping_failure(failure: Exception) -> None:
    if isinstance(failure, _DATABASE_FAULTS):
        first_line = next(iter(str(failure).splitlines()), "")
        log.warning("lease keeping failed: %s: %s", type(failure).__name__, first_line)
    else:
        log.error("lease keeping failed", exc_info=failure)


class ClusterNode:
    """This process as a cluster node. ``start`` after the registry has started, ``stop`` before it stops."""

    def __init__(self, gateway: NodeRuntime) -> None:
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
        self._kick = asyncio.Event()
        # vehicle -> when its lease was last renewed or taken (monotonic, before the statement)
        self._renewed_at: dict[str, float] = {}
        self._tick_lock = asyncio.Lock()
        self._heard_locks: dict[str, float] = {}  # scope -> when a lock of it was heard on the bus
        self.lock_versions = LockVersions()  # a lock broadcast older than what this node knows is dropped
        self._adopting_from: dict[str, str] = {}  # vehicle -> the node it was taken from, while adopting
        self._adoptions: set[asyncio.Task[None]] = set()
        self._adopting: set[str] = set()  # the vehicles whose adoption has not picked up their operations
        self.stops = FencedStops(self)  # the stop-only path of this node once it fenced itself
        self.fanout = TelemetryFanout(self)
        # calls routed to a drone's owner, and answered for this node's; annotated, so that mypy checks
        # ClusterRouter(self) above against RouterNode (an attribute inferred later is unknown there)
        self.calls: OwnerCalls = OwnerCalls(self)
        self.relay: StopRelay | None = None  # stops through PostgreSQL when the bus does not carry them
        self.renewal: LeaseRenewal | None = None  # the leases renewed apart from the keeper's other work
        self.takeover = StopTakeover(self)  # stops no owner acknowledged: this node commands the drone
        self.nodes: list[NodeRecord] = []
        self.all_leases: dict[str, Lease] = {}
        self.last_plan = LeasePlan()
        self.started = False

    @property
    def fenced(self) -> dict[str, StopTarget]:
        """The drones this node owned when it fenced itself, to which it keeps a stop-only path."""
        return self.stops.fenced

    def _require_registry(self) -> Registry:
        if self.registry is None or not self.gateway.ready:
            raise NoOwner("this node's registry is not running (starting or stopping)")
        return self.registry

    @property
    def _valid_until(self) -> float:
        """The moment this node must fence itself unless it renews: the share of the lease time after the
        oldest renewal (or taking) of a lease it holds."""
        oldest = min((self._renewed_at.get(vid, 0.0) for vid in self.held), default=time.monotonic())
        return oldest + self.settings.cluster_lease_ttl_s * SELF_FENCE_SHARE

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
        self._subs.append(await self.bus.subscribe(tele_subject("*"), self.fanout.on_snapshot))
        self._subs.append(await self.bus.subscribe("fleet.event.>", self._on_event))
        await self.leases.heartbeat(self.tags, self.api_url)
        # a lock this node kept while the database was down is not written once it is back if an unlock
        # newer than it is known by then (made through another node meanwhile)
        store.lock_superseded = self.lock_versions.superseded
        self.relay = StopRelay(store.url, self.node_id, self.calls.relayed_stop)
        await self.relay.start()
        self.renewal = LeaseRenewal(self, store.url)
        self.renewal.start()
        self.started = True
        log.info("cluster node %s (tags %s) joined; lease %.0f s", self.node_id, self.tags or "none",
                 self.settings.cluster_lease_ttl_s)  # fmt: skip
        self._tasks = [
            asyncio.create_task(self._keep(), name="cluster-leases"),
            asyncio.create_task(self.fanout.run(), name="cluster-telemetry"),
        ]

    async def stop(self) -> None:
        """Hand every vehicle over: stop its sidecar, then release its lease (others take it at once)."""
        self.started = False
        for task in self._tasks:
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)
        self._tasks = []
        if self.renewal is not None:
            await self.renewal.stop()
        if self._adoptions:  # let an adoption under way finish first: then its sidecar is stopped below
            await asyncio.wait(set(self._adoptions), timeout=LEAVE_TIMEOUT_S * 3)
        await self.takeover.close()
        if self.relay is not None:
            relay, self.relay = self.relay, None
            await relay.close()
        held = list(self.held)
        await self.stops.end(list(self.fenced), "node stopping")
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

    async def _drop_all(self, vehicle_ids: list[str], why: str, fenced: bool = False) -> None:
        """Stop the sidecars of these vehicles, all at once (none waits behind another's flight log)."""
        results = await asyncio.gather(
            *(self._drop(v, why, fenced) for v in vehicle_ids), return_exceptions=True
        )
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
        ticking: asyncio.Task[LeasePlan] | None = None
        began = time.monotonic()
        while True:
            try:
                if ticking is None or ticking.done():
                    ticking = asyncio.create_task(self.tick(acquire=not first), name="cluster-tick")
                    began = time.monotonic()
                await self._tick_done(ticking)
            except asyncio.CancelledError:
                if ticking is not None:
                    ticking.cancel()
                raise
            except Exception as failure:
                _log_keeping_failure(failure)
                if self.held and time.monotonic() > self._valid_until:
                    log.error(
                        "node %s could not renew its leases in time: stopping its sidecars", self.node_id
                    )
                    # nothing it writes now (a flight log closing) waits on the database: the sidecars
                    # let go of the drones' links at once, for the node that takes them over
                    self.gateway.require_store().spool.unreachable_now()
                    targets = self.stops.targets()
                    # the stop-only path listens before the sidecars are stopped: stopping one can take
                    # seconds (its flight log closing), and a stop meanwhile goes through it
                    await self.stops.keep(targets)
                    try:
                        await self._drop_all(list(self.held), FENCED_WHY, fenced=True)
                    finally:
                        self.stops.left()
                    await self.stops.keep(targets)
                with contextlib.suppress(Exception):
                    await self._stop_strays()
            first = False
            self._kick.clear()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self._kick.wait(), self._next_tick_s(began))

    async def _tick_done(self, ticking: asyncio.Task[LeasePlan]) -> None:
        """Wait for a tick within its limit (half the lease time); its failure raised, or TimeoutError.
        While this node holds leases, a tick that has not renewed them shortly after the moment it must
        fence itself is cut then (a database that hangs counts as one that fails, and the fence must act
        on time); one that renewed them goes on (adopting a drone can take a while). A tick cut short is
        cancelled but not waited for (a statement on a connection that hangs can hold its cancellation,
        a rollback that never answers); the next round waits for it again rather than start another."""
        ttl = self.settings.cluster_lease_ttl_s
        limit_at = time.monotonic() + ttl / 2
        while True:
            fence_at = self._valid_until + ttl * TICK_GRACE_SHARE if self.held else limit_at
            done, _ = await asyncio.wait(
                {ticking}, timeout=max(0.0, min(limit_at, fence_at) - time.monotonic())
            )
            if done:
                break
            now = time.monotonic()
            if now >= limit_at or (self.held and now >= self._valid_until + ttl * TICK_GRACE_SHARE):
                ticking.cancel()
                raise TimeoutError("the lease tick did not finish in time (the database does not answer)")
        if ticking.cancelled():
            raise TimeoutError("the lease tick was cut short (the database did not answer)")
        ticking.result()

    def _next_tick_s(self, began: float) -> float:
        """Until the next tick: ``ttl/3`` after the last one began (a slow tick does not push the next
        renewal towards the fence), or less when this node's leases are valid for less (after a tick
        that failed), so that it fences itself when they are no longer valid, not up to a tick later."""
        wait = max(0.0, began + self.interval_s - time.monotonic())
        if self.held:
            wait = min(wait, max(0.0, self._valid_until - time.monotonic()))
        return wait

    async def tick(self, acquire: bool = True) -> LeasePlan:
        """One round: heartbeat, renew, follow registrations, then take or give up leases."""
        assert self.leases is not None
        async with self._tick_lock:
            started = time.monotonic()
            await self.leases.heartbeat(self.tags, self.api_url)
            renewed = await self.leases.renew(list(self.held))
            for vid in list(self.held):
                if vid not in renewed or renewed[vid].epoch != self.held[vid].epoch:
                    log.warning("%s: lease lost (taken over or expired): stopping its sidecar", vid)
                    self.calls.cut_short(vid, "its lease was lost")
                    await self._drop(vid, "lease lost")
                else:
                    self.held[vid] = renewed[vid]
                    self._renewed_at[vid] = started
            await self._stop_strays()
            store = self.gateway.require_store()
            records = await store.list_vehicles()
            registry = self._require_registry()
            await registry.sync(records)
            self.all_leases = await self.leases.leases()
            self.nodes = await self.leases.nodes()
            await self.stops.end(
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
                    asked = time.monotonic()
                    lease = await self.leases.acquire(vid)
                    if lease is None:
                        continue
                    taken += 1
                    was = previous.node_id if previous is not None else None
                    if was == self.node_id:  # our own lease of an adoption that failed: who had it before
                        was = self._adopting_from.get(vid, was)
                    await self.take_over(vid, lease, was, asked)
            if result.release:
                await self.bus.broadcast("leases", {"node": self.node_id, "released": result.release})
            await self._pick_up_late()
            return result

    async def _pick_up_late(self) -> None:
        epochs = {vid: lease.epoch for vid, lease in self.held.items() if vid not in self._adopting}
        await pick_up_late(self.gateway, self.node_id, self._require_registry(), epochs)

    async def take_over(self, vehicle_id: str, lease: Lease, previous: str | None, asked: float) -> None:
        """Adopt a vehicle whose lease this node has just taken (the statement sent at ``asked``,
        monotonic): its own sidecar, the calls on its subject, the operations ``previous`` left running.
        The caller's time limit (a tick's, for a database that hangs) does not cut an adoption short: it
        finishes, or undoes itself."""
        self._renewed_at[vehicle_id] = asked
        adoption = asyncio.create_task(self._adopt(vehicle_id, lease, previous), name=f"adopt-{vehicle_id}")
        self._adoptions.add(adoption)
        adoption.add_done_callback(self._adoptions.discard)
        await asyncio.shield(adoption)

    async def forward_stop(self, drone_id: str, verb: str, caller: Caller) -> object:
        """An operator's stop to the drone's current owner (`OwnerCalls.forward_stop`)."""
        return await self.calls.forward_stop(drone_id, verb, caller)

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
        self._adopting.add(vehicle_id)
        try:
            await self._adopt_and_pick_up(vehicle_id, lease, previous)
        finally:
            self._adopting.discard(vehicle_id)

    async def _adopt_and_pick_up(self, vehicle_id: str, lease: Lease, previous: str | None) -> None:
        registry = self._require_registry()
        self.held[vehicle_id] = lease  # renewed from now on: a sidecar never runs without its lease
        try:
            vehicle = await registry.adopt(vehicle_id)
            self._served[vehicle_id] = await self.bus.serve_calls(
                vehicle_id, self.calls.answer(vehicle_id), self.calls.check_epoch(vehicle_id)
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

    async def _drop(self, vehicle_id: str, why: str, fenced: bool = False) -> None:
        """Stop the vehicle's sidecar; ``fenced``: this node fenced itself, so the forwarded calls it runs
        for the vehicle are answered at once (their operations are left to the node that takes the drone
        over next, which follows them under the same ids, as after a node loss)."""
        if fenced:
            self.calls.cut_short(vehicle_id, why)
        ops = self.gateway.operations
        let_go = [] if ops is None else ops.let_go(vehicle_id)
        if let_go:  # the node that holds the drone next follows them, or closes them
            log.warning("%s: node %s no longer follows its operation(s) %s (%s)", vehicle_id, self.node_id,
                        ", ".join(let_go), why)  # fmt: skip
        self.held.pop(vehicle_id, None)
        self._renewed_at.pop(vehicle_id, None)
        sub = self._served.pop(vehicle_id, None)
        if sub is not None:
            with contextlib.suppress(Exception):
                await sub.unsubscribe()
        registry = self.registry
        if registry is not None:
            await registry.release(vehicle_id)
        log.info("%s: released by node %s (%s)", vehicle_id, self.node_id, why)

    # --- broadcasts -----------------------------------------------------------------------------------
    async def announce(self, kind: str, body: JsonObject) -> None:
        """Tell every node (locks, registrations); a node that misses it catches up at its next tick. A
        lock, an unlock, a takeover lock and its release carry their version
        (`gateway.cluster.lock_versions`)."""
        body = self.lock_versions.stop_stamp(body) if kind == "stop" else self.lock_versions.stamp(kind, body)
        if kind == "unlock":
            self._heard_locks.pop(str(body.get("scope")), None)
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
        if not self.lock_versions.fresh(kind, body):  # sent before a change this node already knows
            log.warning("dropped a late %s broadcast of %s from node %s (version %s; this node knows "
                        "version %d)", kind, body.get("scope"), body.get("node"), body.get("version"),
                        self.lock_versions.newest(FAMILIES[kind], str(body.get("scope"))))  # fmt: skip
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
            if self.lock_versions.stop_is_late(body):
                log.warning("dropped a late stop broadcast from node %s (fleet lock version %s; this node "
                            "knows version %d)", body.get("node"), body.get("version"),
                            self.lock_versions.newest("lock", FLEET))  # fmt: skip
            elif fleet is not None and registry is not None:
                by = f"operator stop ({body.get('action')}) on node {body.get('node')}"
                made = body.get("at")  # only the fleet operations started before the stop was made
                before = datetime.fromisoformat(made) if isinstance(made, str) else None
                await fleet.supersede([v.id for v in registry.all()], by, before=before)
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
            self.lock_versions.saw("lock", scope, lk.locked_at)
            current = {x.scope: x for x in book.all()}.get(scope)
            if current is None or current.reason != lk.reason or current.by != lk.by:
                book.lock(scope, lk.reason, lk.by, at=lk.locked_at)

    # --- views ----------------------------------------------------------------------------------------
    def describe(self) -> dict[str, object]:
        """This node, the live nodes and the drones each holds (the REST API's cluster view)."""
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
