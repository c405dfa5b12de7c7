"""Leases on a real PostgreSQL: one owner per vehicle under races, renewal, expiry, takeover, release,
fencing epochs, and the lease plan (fair shares, pinning by tag, handing over only idle vehicles)."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from datetime import UTC, datetime, timedelta

import pytest

from gateway.cluster.keeper import Wanted, plan
from gateway.cluster.leases import Lease, LeaseStore, NodeRecord
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
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
