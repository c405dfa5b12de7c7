"""A lock broadcast that arrives late, after an operator unlocked through another node, is dropped.

Two nodes on real PostgreSQL and NATS. The operator locks the fleet through node-b and unlocks it
through node-a; then node-b's lock broadcast, exactly as node-b sent it (captured on the bus), is
delivered once more, as NATS delivers a broadcast published while the bus was down at its node once that
node reconnects. No node may be locked by it. A lock made after the unlock still reaches every node.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import nats
import pytest
from nats.aio.msg import Msg

from tests.cluster.harness import Cluster, cluster, missing_engines
from tests.helpers.timing import eventually

pytestmark = pytest.mark.skipif(missing_engines() is not None, reason=str(missing_engines()))


async def _scopes(c: Cluster, name: str) -> set[str]:
    return {x["scope"] for x in (await c.node(name).get("/locks"))["items"]}


async def test_a_late_lock_broadcast_does_not_lock_the_fleet_again(tmp_path: Path) -> None:
    async with cluster(tmp_path, drones=1, nodes=2, speedup=5.0) as c:
        bus = await nats.connect(c.nats.url)
        heard: list[Msg] = []

        async def keep(msg: Msg) -> None:
            heard.append(msg)

        try:
            await bus.subscribe("fleet.event.lock", cb=keep)
            await bus.flush()
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
            await bus.flush()
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
