"""Leases on a real PostgreSQL: one owner per vehicle under races, renewal, expiry, takeover, release,
fencing epochs, the lease plan (fair shares, pinning by tag, handing over only idle vehicles), and a
node's lease keeper (``ClusterNode.tick``) carrying out the pinning by tag on the database."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator, Iterable
from datetime import UTC, datetime, timedelta
from types import SimpleNamespace
from typing import Any

import pytest

from gateway.cluster.keeper import Wanted, plan
from gateway.cluster.leases import Lease, LeaseStore, NodeRecord
from gateway.cluster.node import ClusterNode
from gateway.config import Settings
from gateway.fleet.policy.operator_locks import LockBook
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.helpers.timing import eventually
from tests.persist.pg import create_database


@pytest.fixture
async def pg_store(pg_base_url: str) -> AsyncIterator[Store]:
    store = await Store.open(await create_database(pg_base_url))
    try:
        for i in range(6):
            await store.add_vehicle(VehicleSpec(id=f"v{i}", url=f"tcpout://127.0.0.1:{5760 + i}"))
        yield store
    finally:
        await store.close()


async def test_many_nodes_racing_for_each_vehicle_get_one_owner_each(pg_store: Store) -> None:
    nodes = [LeaseStore(pg_store.engine, f"n{k}", ttl_s=30) for k in range(5)]
    results = await asyncio.gather(*(n.acquire(f"v{i}") for i in range(6) for n in nodes))
    won = [r for r in results if r is not None]
    assert sorted(r.vehicle_id for r in won) == [f"v{i}" for i in range(6)]
    leases = await nodes[0].leases()
    assert {v: lease.node_id for v, lease in leases.items()} == {r.vehicle_id: r.node_id for r in won}
    assert all(lease.epoch == 1 and lease.live for lease in leases.values())


async def test_a_live_lease_is_kept_renewed_and_not_taken(pg_store: Store) -> None:
    a, b = LeaseStore(pg_store.engine, "a", ttl_s=30), LeaseStore(pg_store.engine, "b", ttl_s=30)
    first = await a.acquire("v0")
    assert first is not None
    assert await b.acquire("v0") is None
    assert await a.acquire("v0") is None  # already held: acquiring again is not a renewal
    renewed = await a.renew(["v0", "v1"])  # v1 is not a's: not renewed
    assert list(renewed) == ["v0"]
    assert renewed["v0"].expires_at >= first.expires_at and renewed["v0"].epoch == 1
    assert await b.renew(["v0"]) == {}


async def test_an_expired_lease_is_taken_over_with_a_new_epoch_and_the_old_owner_cannot_renew(
    pg_store: Store,
) -> None:
    a, b = LeaseStore(pg_store.engine, "a", ttl_s=0.3), LeaseStore(pg_store.engine, "b", ttl_s=30)
    assert (await a.acquire("v0")) is not None
    await asyncio.sleep(0.5)  # the lease's own time passes (database clock)
    leases = await b.leases()
    assert not leases["v0"].live
    taken = await b.acquire("v0")
    assert taken is not None and taken.node_id == "b" and taken.epoch == 2
    assert await a.renew(["v0"]) == {}
    assert await a.acquire("v0") is None


async def test_two_nodes_racing_for_an_expired_lease_one_wins(pg_store: Store) -> None:
    old = LeaseStore(pg_store.engine, "old", ttl_s=0.2)
    assert await old.acquire("v0") is not None
    await asyncio.sleep(0.4)
    racers = [LeaseStore(pg_store.engine, f"r{k}", ttl_s=30) for k in range(6)]
    results = await asyncio.gather(*(r.acquire("v0") for r in racers))
    winners = [r for r in results if r is not None]
    assert len(winners) == 1 and winners[0].epoch == 2


async def test_release_frees_at_once_keeps_the_epoch_and_only_the_owner_can(pg_store: Store) -> None:
    a, b = LeaseStore(pg_store.engine, "a", ttl_s=30), LeaseStore(pg_store.engine, "b", ttl_s=30)
    await a.acquire("v0")
    assert await b.release(["v0"]) == []
    assert await a.release(["v0"]) == ["v0"]
    taken = await b.acquire("v0")
    assert taken is not None and taken.epoch == 2


async def test_no_lease_for_an_unregistered_vehicle_and_removal_drops_the_lease(pg_store: Store) -> None:
    a = LeaseStore(pg_store.engine, "a", ttl_s=30)
    assert await a.acquire("nope") is None
    await a.acquire("v1")
    await pg_store.remove_vehicle("v1")
    assert "v1" not in await a.leases()


async def test_node_heartbeats_say_who_is_alive(pg_store: Store) -> None:
    a, b = LeaseStore(pg_store.engine, "a", ttl_s=30), LeaseStore(pg_store.engine, "b", ttl_s=0.2)
    await a.heartbeat(["site-n"], "http://127.0.0.1:1")
    await b.heartbeat([], None)
    await asyncio.sleep(0.4)
    nodes = {n.node_id: n for n in await a.nodes()}
    assert nodes["a"].alive and nodes["a"].tags == ["site-n"] and not nodes["b"].alive
    await a.leave()
    assert not {n.node_id: n for n in await a.nodes()}["a"].alive


# --- pinning by tag, as a node's lease keeper carries it out on the database --------------------------


class GroundedDrone:
    """A drone of this node, on the ground and idle (the keeper may hand it over to balance)."""

    state = "ready"
    telemetry = SimpleNamespace(fresh=lambda name: False if name == "armed" else None)

    def on_ground(self, fresh: bool = True) -> bool:
        return True


class KeeperRegistry:
    """What the lease keeper asks of its node's registry: which drones it runs (no sidecars here)."""

    def __init__(self) -> None:
        self.local: set[str] = set()

    async def sync(self, records: Iterable[Any]) -> list[str]:
        return []

    def all(self) -> list[Any]:
        return []

    def is_local(self, vehicle_id: str) -> bool:
        return vehicle_id in self.local

    def get(self, vehicle_id: str) -> GroundedDrone:
        return GroundedDrone()

    async def adopt(self, vehicle_id: str) -> Any:
        self.local.add(vehicle_id)
        return SimpleNamespace(id=vehicle_id)

    async def release(self, vehicle_id: str) -> None:
        self.local.discard(vehicle_id)


class SilentBus:
    """No NATS: the keeper's calls and broadcasts go nowhere (the leases are all that is tested)."""

    connected = True

    async def serve_calls(self, vehicle_id: str, handler: Any, check: Any = None) -> Any:
        return SimpleNamespace(unsubscribe=self.broadcast)

    async def broadcast(self, *args: Any) -> None:
        return None


def keeper(store: Store, name: str, tags: str, ttl_s: float) -> ClusterNode:
    """A cluster node of ``tags`` whose lease keeper runs on ``store``'s PostgreSQL database."""
    settings = Settings(_env_file=None, cluster_nats_url="nats://127.0.0.1:4222", cluster_node_id=name,
                        cluster_node_tags=tags, cluster_lease_ttl_s=ttl_s)  # fmt: skip
    gateway = SimpleNamespace(settings=settings, store=store, require_store=lambda: store, operations=None,
                              locks=LockBook(), ready=True)  # fmt: skip
    node = ClusterNode(gateway)  # type: ignore[arg-type]
    node.registry = KeeperRegistry()  # type: ignore[assignment]
    node.bus = SilentBus()  # type: ignore[assignment]
    node.leases = LeaseStore(store.engine, name, ttl_s)
    return node


async def leases_in(store: Store) -> dict[str, Lease]:
    return await LeaseStore(store.engine, "reader", ttl_s=30).leases()


async def test_a_drone_pinned_to_a_tag_is_owned_only_by_nodes_carrying_that_tag(pg_store: Store) -> None:
    await pg_store.add_vehicle(VehicleSpec(id="pinned", url="tcpout://127.0.0.1:5770", node_tag="site-north"))
    south = keeper(pg_store, "south", "site-south", ttl_s=30)
    for _ in range(3):  # alone in the cluster, with room for every drone it may own
        await south.tick()
        assert "pinned" not in south.held and "pinned" not in south.last_plan.candidates
    assert sorted(south.held) == [f"v{i}" for i in range(6)]
    assert "pinned" not in await leases_in(pg_store)

    north = keeper(pg_store, "north", "site-north,site-west", ttl_s=1)
    await north.tick()
    assert "pinned" in north.held
    lease = (await leases_in(pg_store))["pinned"]
    assert lease.node_id == "north" and lease.epoch == 1 and lease.live

    # the north node is lost: its lease expires, and still the south node never takes the drone
    async def expired() -> bool:
        return not (await leases_in(pg_store))["pinned"].live

    await eventually(expired, "the lost north node's lease on the pinned drone expired", within_s=10)
    for _ in range(3):
        await south.tick()
        assert "pinned" not in south.held
    assert (await leases_in(pg_store))["pinned"].node_id == "north"
    # another node of the north site takes it over
    relief = keeper(pg_store, "north-2", "site-north", ttl_s=30)
    await relief.tick()
    lease = (await leases_in(pg_store))["pinned"]
    assert "pinned" in relief.held and lease.node_id == "north-2" and lease.epoch == 2 and lease.live


def test_leases_refuse_sqlite() -> None:
    from sqlalchemy.ext.asyncio import create_async_engine

    engine = create_async_engine("sqlite+aiosqlite://")
    with pytest.raises(ValueError, match="PostgreSQL"):
        LeaseStore(engine, "a", 10)


# --- the plan (pure) -------------------------------------------------------------------------------

T = datetime(2026, 1, 1, tzinfo=UTC)


def node(name: str, tags: list[str] | None = None, alive: bool = True) -> NodeRecord:
    return NodeRecord(name, tags or [], None, T, T, 5.0 if alive else -1.0)


def lease(vid: str, owner: str, live: bool = True) -> Lease:
    return Lease(vid, owner, 1, T + timedelta(seconds=5), 5.0 if live else -1.0)


def test_plan_takes_a_fair_share_of_free_vehicles() -> None:
    wanted = [Wanted(f"v{i}") for i in range(9)]
    nodes = [node("a"), node("b"), node("c")]
    p = plan("a", [], wanted, {}, nodes, held=set(), idle=set())
    assert p.room == 3 and len(p.candidates) == 9 and p.release == []
    # with two live leases held elsewhere those are not candidates
    p = plan(
        "a", [], wanted, {"v0": lease("v0", "b"), "v1": lease("v1", "c", live=False)}, nodes, set(), set()
    )
    assert "v0" not in p.candidates and "v1" in p.candidates


def test_plan_gives_back_only_idle_vehicles_beyond_the_share() -> None:
    wanted = [Wanted(f"v{i}") for i in range(9)]
    nodes = [node("a"), node("b"), node("c")]
    held = {f"v{i}" for i in range(9)}
    p = plan("a", [], wanted, {}, nodes, held=held, idle={"v0", "v1"})
    assert p.release == ["v0", "v1"] and p.room == 0  # the 7 flying ones stay
    p = plan("a", [], wanted, {}, nodes, held=held, idle=held)
    assert len(p.release) == 6


def test_plan_pins_by_tag_and_releases_what_is_no_longer_ours() -> None:
    wanted = [Wanted("n1", "north"), Wanted("n2", "north"), Wanted("s1", "south"), Wanted("off", None, False)]
    nodes = [node("a", ["north"]), node("b", ["south"])]
    p = plan("a", ["north"], wanted, {}, nodes, held={"s1", "off"}, idle=set())
    assert p.candidates == ["n1", "n2"] and p.room == 2
    assert p.release == ["off", "s1"]  # disconnected by an operator, pinned to the south site
    # a dead node's share falls to the others
    p = plan(
        "a", [], [Wanted(f"v{i}") for i in range(4)], {}, [node("a"), node("b", alive=False)], set(), set()
    )
    assert p.room == 4


# --- what a node's keeper makes of the locks and of its drones' state ---------------------------------


async def test_a_lock_heard_on_the_bus_holds_until_its_node_has_stored_it(pg_store: Store) -> None:
    """The stopping node kept its fleet lock while the database was down; the database is back here
    first: re-reading the locks must not lift the lock that node has not written yet."""
    node = keeper(pg_store, "a", "", ttl_s=30)
    body = {"scope": "*", "reason": "emergency stop", "by": "ops", "node": "b",
            "locked_at": datetime.now(UTC).isoformat()}  # fmt: skip
    await node._on_event(SimpleNamespace(subject="fleet.event.lock", data=json.dumps(body).encode()))  # type: ignore[arg-type]
    await node._sync_locks()
    assert node.gateway.locks.get("*") is not None  # not in the database yet: still holds
    await pg_store.save_lock("*", "emergency stop", "ops", datetime.now(UTC))
    await node._sync_locks()
    await pg_store.delete_lock("*")  # stored once, then removed (a missed unlock): the database decides
    await node._sync_locks()
    assert node.gateway.locks.get("*") is None


class Drone:
    def __init__(self, state: str, on_ground: bool | None, armed: bool | None) -> None:
        self.state, self._on_ground = state, on_ground
        self.telemetry = SimpleNamespace(fresh=lambda name: armed if name == "armed" else None)

    def on_ground(self, fresh: bool = True) -> bool | None:
        return self._on_ground


@pytest.mark.parametrize(
    ("drone", "idle"),
    [
        (Drone("ready", True, False), True),  # landed and disarmed
        (Drone("registered", None, None), True),  # never linked: nothing to hand over but the lease
        (Drone("connecting", None, None), False),  # may be in the air: its link is not up yet
        (Drone("link_lost", None, None), False),
        (Drone("ready", False, True), False),  # flying
        (Drone("ready", True, True), False),  # armed on the ground
    ],
)
def test_only_a_drone_known_to_be_landed_counts_as_idle(drone: Drone, idle: bool) -> None:
    settings = Settings(_env_file=None, cluster_nats_url="nats://127.0.0.1:4222", cluster_node_id="a")
    gateway = SimpleNamespace(settings=settings, operations=None, ready=True)
    node = ClusterNode(gateway)  # type: ignore[arg-type]
    node.registry = SimpleNamespace(get=lambda vehicle_id: drone)  # type: ignore[assignment]
    assert node._idle("d1") is idle


class AdoptionCutShort(KeeperRegistry):
    """Adopting starts the drone's sidecar (it is local) and then fails, as a tick cut short by its time
    limit, or a flight log that could not start, does."""

    async def adopt(self, vehicle_id: str) -> Any:
        self.local.add(vehicle_id)
        raise RuntimeError("the flight log could not start")

    def all(self) -> list[Any]:
        return [SimpleNamespace(id=v) for v in sorted(self.local)]


async def test_a_sidecar_never_runs_without_its_lease(pg_store: Store) -> None:
    node = keeper(pg_store, "a", "", ttl_s=30)
    node.registry = registry = AdoptionCutShort()  # type: ignore[assignment]
    with pytest.raises(RuntimeError, match="flight log"):
        await node.tick()
    assert not node.held and not registry.local  # nothing half adopted: no sidecar, no lease renewed
    # a local drone the node holds no lease of, however it came about, is stopped at the next tick
    registry.local.add("v5")
    registry.adopt = KeeperRegistry.adopt.__get__(registry)  # type: ignore[method-assign]
    await node.tick()
    assert registry.local == set(node.held) and len(node.held) == 5  # the one cut short expires first
