"""A lock broadcast that arrives late, after an operator unlocked through another node, is dropped.

Two nodes on real PostgreSQL and NATS. The operator locks the fleet through node-b and unlocks it
through node-a; then node-b's lock broadcast, exactly as node-b sent it (captured on the bus), is
delivered once more, as NATS delivers a broadcast published while the bus was down at its node once that
node reconnects. No node may be locked by it. A lock made after the unlock still reaches every node.
"""

from __future__ import annotations

import json
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import nats
import pytest
from nats.aio.msg import Msg

from gateway.cluster.lock_versions import LockVersions
from gateway.registry.store import Store
from tests.cluster.harness import Cluster, cluster, missing_engines, server_has_all_sent
from tests.helpers.timing import eventually
from tests.persist.pg import create_database, find_pg_bin, restartable_postgres


async def _scopes(c: Cluster, name: str) -> set[str]:
    return {x["scope"] for x in (await c.node(name).get("/locks"))["items"]}


@pytest.mark.skipif(missing_engines() is not None, reason=str(missing_engines()))
async def test_a_late_lock_broadcast_does_not_lock_the_fleet_again(tmp_path: Path) -> None:
    async with cluster(tmp_path, drones=1, nodes=2, speedup=5.0) as c:
        bus = await nats.connect(c.nats.url)
        heard: list[Msg] = []

        async def keep(msg: Msg) -> None:
            heard.append(msg)

        try:
            await bus.subscribe("fleet.event.lock", cb=keep)
            await server_has_all_sent(bus)
            response = await c.node("node-b").post("/fleet/lock", {"reason": "weather"})
            assert response.status_code == 200, response.text

            async def locked_everywhere() -> bool:
                scopes = [await _scopes(c, n) for n in ("node-a", "node-b")]
                return all("*" in s for s in scopes) and bool(heard)

            await eventually(locked_everywhere, "the fleet lock on both nodes, and its broadcast heard")
            late = heard[0]
            sent: dict[str, Any] = json.loads(late.data)
            assert sent["scope"] == "*" and sent["node"] == "node-b", sent
            assert isinstance(sent["version"], int), sent

            response = await c.node("node-a").delete("/fleet/lock")
            assert response.status_code == 200, response.text

            async def unlocked_everywhere() -> bool:
                scopes = [await _scopes(c, n) for n in ("node-a", "node-b")]
                return not any("*" in s for s in scopes)

            await eventually(unlocked_everywhere, "the fleet unlocked on both nodes")

            # node-b's lock broadcast, delivered again after the unlock; then a lock of the drone through
            # node-b, which every node hears after it (one server, in the order it received them)
            await bus.publish(late.subject, late.data)
            await server_has_all_sent(bus)
            response = await c.node("node-b").post(f"/vehicles/{c.drone_ids[0]}/lock", {"reason": "check"})
            assert response.status_code == 200, response.text

            async def drone_lock_heard() -> set[str] | None:
                scopes = await _scopes(c, "node-a")
                return scopes if c.drone_ids[0] in scopes else None

            scopes = await eventually(drone_lock_heard, "node-a hears the drone's lock")
            assert "*" not in scopes, f"node-a applied the late lock broadcast: {scopes}"
            assert "*" not in await _scopes(c, "node-b")
            assert "dropped a late lock broadcast of * from node node-b" in c.node("node-a").log.read_text()

            # a lock made after the unlock is newer than it: every node applies it
            response = await c.node("node-b").post("/fleet/lock", {"reason": "again"})
            assert response.status_code == 200, response.text
            await eventually(locked_everywhere, "a new fleet lock on both nodes")
        finally:
            await bus.close()


@pytest.mark.skipif(
    not (find_pg_bin("initdb") and find_pg_bin("postgres")),
    reason="PostgreSQL server binaries are not installed (apt-get install postgresql)",
)
async def test_a_lock_kept_while_the_database_was_down_does_not_override_a_newer_unlock() -> None:
    """A node's store, its PostgreSQL stopped: the node's stop locks the fleet (kept in its spool); the
    operator unlocks the fleet through another node, whose unlock broadcast this node hears; the database
    returns and the spool is written: the kept lock is not, since a newer unlock is known. A lock kept
    with no unlock after it is written as before."""
    with restartable_postgres() as server:
        store = await Store.open(await create_database(server.url))
        try:
            versions = LockVersions()  # this node's, as its cluster node gives them to its store
            store.lock_superseded = versions.superseded
            other = LockVersions()  # the other node's
            server.stop()
            stopped_at = datetime.now(UTC)
            versions.stamp("lock", {"scope": "*", "locked_at": stopped_at.isoformat()})  # announced
            assert await store.save_lock("*", "emergency stop", "ops", stopped_at) is None  # kept
            other.fresh("lock", versions.stamp("lock", {"scope": "*", "locked_at": stopped_at.isoformat()}))
            unlock = other.stamp("unlock", {"scope": "*"})  # through the other node, after it heard the lock
            assert versions.fresh("unlock", unlock)  # heard here
            drone_at = datetime.now(UTC)  # and a lock of a drone, never unlocked
            versions.stamp("lock", {"scope": "d1", "locked_at": drone_at.isoformat()})
            assert await store.save_lock("d1", "check", "ops", drone_at) is None

            server.start()
            assert await store.spool.flush(60.0), f"{len(store.spool)} writes still kept"
            assert [lk.scope for lk in await store.list_locks()] == ["d1"]
        finally:
            if not server.running:
                server.start()
            await store.close()
