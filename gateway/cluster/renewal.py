"""A cluster node's lease renewal, apart from the lease keeper's other work.

The keeper's tick (`gateway.cluster.node`) renews the node's leases among much else (the registry, the
locks, taking drones over), on the event loop that also carries every call and the telemetry, through
the store's connection pool. On a starved machine a tick ran past the moment the node must fence itself
(`SELF_FENCE_SHARE` of the lease time after its oldest renewal), and nodes with no fault fenced
themselves. So the leases are also renewed here: in a thread of their own, with their own event loop and
their own database connection, every `RENEW_SHARE` of the lease time, each attempt bounded by the time
left before the fence. Neither the loop's other work nor the pool's other statements wait in front of a
renewal (the thread takes the interpreter from the loop within its switch interval, 5 ms). An attempt
ends at its bound even when the statement it cancels does not (its rollback on a connection that does not
answer): the next one goes on a new connection, and does not wait for it. The lease statements commit as
they run (`gateway.cluster.leases`), so a renewal never waits on a row lock of the keeper's own renewal.
An attempt slower than the renewal period is logged with the time it took and the time that was left.

A renewal only moves the moment the node must fence itself (``_renewed_at``) for a lease it still holds
under the same epoch; a lease it finds lost (not renewed, or held under a newer epoch) wakes the keeper,
whose tick stops that drone's sidecar. A node whose renewals fail until that moment fences itself on the
keeper's side, as before.
"""

from __future__ import annotations

import asyncio
import logging
import threading
import time
from collections.abc import Awaitable
from typing import Protocol, TypeVar

from gateway.cluster.leases import Lease, LeaseStore
from gateway.config import Settings
from gateway.registry.sql_async import AsyncEngine, create_async_engine

log = logging.getLogger("gateway.cluster")
T = TypeVar("T")

#: a node fences itself this share of the lease time after its oldest renewal (`gateway.cluster.node`)
SELF_FENCE_SHARE = 0.8
#: the leases are renewed every this share of the lease time (several tries before the fence is due)
RENEW_SHARE = 0.2
#: a renewal attempt has at least this share of the lease time (when the fence is nearer, or past)
LEAST_ATTEMPT_SHARE = 0.1


class RenewedNode(Protocol):
    """What the renewal reads and moves of its node (`gateway.cluster.node.ClusterNode`)."""

    node_id: str
    settings: Settings
    held: dict[str, Lease]
    _renewed_at: dict[str, float]

    def kick(self) -> None: ...


class LeaseRenewal:
    """Renews a node's leases from a thread of its own (`start`, `stop`)."""

    def __init__(self, node: RenewedNode, database_url: str) -> None:
        self._node = node
        self._url = database_url
        self._ttl = node.settings.cluster_lease_ttl_s
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stopping = threading.Event()
        self._thread: threading.Thread | None = None
        self._failing = False
        #: renewals made, and attempts that failed or timed out (read by tests and benches)
        self.renewals = 0
        self.failures = 0
        #: the longest a renewal took, answered or not (seconds, from its statement sent to its end)
        self.slowest_s = 0.0

    def start(self) -> None:
        self._loop = asyncio.get_running_loop()  # the node's loop: a lost lease wakes its keeper there
        self._thread = threading.Thread(
            target=self._run, name=f"lease-renewal-{self._node.node_id}", daemon=True
        )
        self._thread.start()

    async def stop(self) -> None:
        """End the thread (an attempt under way is waited for, at most one lease time)."""
        self._stopping.set()
        thread, self._thread = self._thread, None
        if thread is not None:
            await asyncio.to_thread(thread.join, self._ttl)

    def _run(self) -> None:
        asyncio.run(self._renewing())

    async def _renewing(self) -> None:
        engine = create_async_engine(self._url, pool_size=1, max_overflow=0, pool_pre_ping=False)
        leases = LeaseStore(engine, self._node.node_id, self._ttl)
        try:
            while not self._stopping.is_set():
                began = time.monotonic()
                await self._renew_once(leases, engine)
                # this loop runs nothing else: waiting on the event blocks nobody, and a stop ends it
                self._stopping.wait(max(0.0, began + self._ttl * RENEW_SHARE - time.monotonic()))
        finally:
            await engine.dispose()

    async def _renew_once(self, leases: LeaseStore, engine: AsyncEngine) -> None:
        node = self._node
        held = {vid: lease.epoch for vid, lease in list(node.held.items())}
        if not held:
            return  # nothing to renew (the keeper's tick says the node is alive)
        asked = time.monotonic()
        # the moment the node must fence itself (`ClusterNode._valid_until`, read here from the copy: the
        # loop's thread changes the held leases meanwhile)
        fence_at = min(node._renewed_at.get(vid, 0.0) for vid in held) + self._ttl * SELF_FENCE_SHARE
        budget = max(self._ttl * LEAST_ATTEMPT_SHARE, fence_at - asked)
        try:
            renewed = await _within(leases.renew(list(held)), budget)
        except Exception as exc:
            self.failures += 1
            took = self._took(asked)
            if not self._failing:
                log.warning("renewing the leases of node %s failed after %.2f s (%r): tried again in %.1f s",
                            node.node_id, took, exc, self._ttl * RENEW_SHARE)  # fmt: skip
            self._failing = True
            await engine.dispose(close=False)  # a connection left hanging is not used again
            return
        self._failing = False
        self.renewals += 1
        took = self._took(asked)
        if took > self._ttl * RENEW_SHARE:  # slower than the renewals come: the fence is getting near
            log.warning("renewing the leases of node %s took %.2f s (%.2f s were left before the fence)",
                        node.node_id, took, fence_at - asked)  # fmt: skip
        lost = False
        for vid, epoch in held.items():
            lease = renewed.get(vid)
            if lease is None or lease.epoch != epoch:
                lost = True
                continue
            current, last = node.held.get(vid), node._renewed_at.get(vid)
            if current is not None and current.epoch == epoch and last is not None:
                node._renewed_at[vid] = max(last, asked)
        if lost and self._loop is not None:
            self._loop.call_soon_threadsafe(node.kick)

    def _took(self, asked: float) -> float:
        took = time.monotonic() - asked
        self.slowest_s = max(self.slowest_s, took)
        return took


async def _within(work: Awaitable[T], seconds: float) -> T:
    """``work``'s result within ``seconds``, else TimeoutError then, not later: a statement cancelled on a
    connection that does not answer can take as long again to end (its rollback), and the next attempt
    (on a new connection) must not wait for that. The cancelled attempt ends on its own."""
    task = asyncio.ensure_future(work)
    done, _ = await asyncio.wait({task}, timeout=seconds)
    if not done:
        task.cancel()
        task.add_done_callback(lambda t: t.cancelled() or t.exception())
        raise TimeoutError(f"no answer within {seconds:.2f} s")
    return task.result()
