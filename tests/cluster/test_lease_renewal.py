"""A node's leases are renewed apart from the work of its event loop (`gateway.cluster.renewal`): a loop
held by synchronous work for longer than the node's fence share of the lease time does not make the node
due to fence itself, and its leases stay live in the database; a lease found taken by another node
wakes the node's keeper."""

from __future__ import annotations

import asyncio
import time
from collections.abc import AsyncIterator
from types import SimpleNamespace

import pytest
from sqlalchemy import text

from gateway.cluster.leases import Lease, LeaseStore
from gateway.cluster.renewal import SELF_FENCE_SHARE, LeaseRenewal
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.helpers.timing import eventually
from tests.persist.pg import create_database

TTL_S = 2.0


@pytest.fixture
async def pg_store(pg_base_url: str) -> AsyncIterator[Store]:
    store = await Store.open(await create_database(pg_base_url))
    try:
        for i in range(2):
            await store.add_vehicle(VehicleSpec(id=f"v{i}", url=f"tcpout://127.0.0.1:{5760 + i}"))
        yield store
    finally:
        await store.close()


class Node(SimpleNamespace):
    """What the renewal reads of a `ClusterNode`: its id, settings, held leases and their renewal times,
    and its keeper's wake-up."""

    def __init__(self, held: dict[str, Lease]) -> None:
        now = time.monotonic()
        super().__init__(node_id="n1", settings=SimpleNamespace(cluster_lease_ttl_s=TTL_S), held=held,
                         _renewed_at=dict.fromkeys(held, now), kicks=0)  # fmt: skip

    def kick(self) -> None:
        self.kicks += 1

    def fence_at(self) -> float:
        return min(self._renewed_at.values()) + TTL_S * SELF_FENCE_SHARE


async def test_a_loop_held_by_other_work_does_not_starve_the_renewal(pg_store: Store) -> None:
    leases = LeaseStore(pg_store.engine, "n1", TTL_S)
    held = {vid: lease for vid in ("v0", "v1") if (lease := await leases.acquire(vid)) is not None}
    assert sorted(held) == ["v0", "v1"]
    node = Node(held)
    renewal = LeaseRenewal(node, pg_store.url)  # type: ignore[arg-type]
    renewal.start()
    try:
        blocked_at = time.monotonic()
        # the loop held by synchronous work, past the fence share and the lease (on purpose)
        time.sleep(TTL_S * 1.5)  # noqa: ASYNC251
        assert node.fence_at() > time.monotonic(), (renewal.renewals, renewal.failures)
        assert min(node._renewed_at.values()) > blocked_at  # renewed while the loop could not run
        now_live = await leases.leases()
        assert all(now_live[vid].live and now_live[vid].node_id == "n1" for vid in held), now_live
    finally:
        await renewal.stop()


async def test_a_lease_taken_by_another_node_wakes_the_keeper(pg_store: Store) -> None:
    leases = LeaseStore(pg_store.engine, "n1", TTL_S)
    lease = await leases.acquire("v0")
    assert lease is not None
    node = Node({"v0": lease})
    renewal = LeaseRenewal(node, pg_store.url)  # type: ignore[arg-type]
    renewal.start()
    try:
        await eventually(lambda: _is(renewal.renewals > 0), "a first renewal", within_s=10)
        renewed_at = node._renewed_at["v0"]
        async with pg_store.engine.begin() as conn:  # another node took it (a newer epoch)
            await conn.execute(text("UPDATE vehicle_leases SET node_id = 'n2', epoch = epoch + 1"))
        await eventually(lambda: _is(node.kicks > 0), "the keeper woken", within_s=10)
        assert node._renewed_at["v0"] <= renewed_at + TTL_S  # not moved by a lease it no longer holds
    finally:
        await renewal.stop()


async def _is(value: bool) -> bool:
    await asyncio.sleep(0)
    return value
