"""The emergency stop's broadcast carries the fleet lock's version and the time it was made, as the lock
broadcasts carry theirs (`gateway.cluster.lock_versions`): a stop delivered late (NATS sends a broadcast
published while the bus was down at its node once that node reconnects) never ends a fleet operation
started after it, and one heard in time ends only the fleet operations started before it. Two nodes'
event handling, the bus replaced by handing each broadcast to the other node as NATS would."""

from __future__ import annotations

import json
from datetime import UTC, datetime, timedelta
from types import SimpleNamespace
from typing import Any

from gateway.cluster.lock_versions import LockVersions
from gateway.cluster.node import ClusterNode
from gateway.config import Settings
from gateway.fleet.operations.fleet_operation import FleetOperation
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.policy.operator_locks import LockBook


def node_a() -> tuple[ClusterNode, FleetOperations]:
    settings = Settings(_env_file=None, cluster_nats_url="nats://127.0.0.1:4222", cluster_node_id="node-a")
    fleet = FleetOperations(SimpleNamespace())  # type: ignore[arg-type]
    gateway = SimpleNamespace(settings=settings, operations=None, ready=True, locks=LockBook(),
                              fleet_operations=fleet)  # fmt: skip
    node = ClusterNode(gateway)  # type: ignore[arg-type]
    node.registry = SimpleNamespace(all=lambda: [SimpleNamespace(id="d1"), SimpleNamespace(id="d2")])  # type: ignore[assignment]
    return node, fleet


def formation(fleet: FleetOperations, op_id: str, created_at: datetime) -> FleetOperation:
    fop = FleetOperation(id=op_id, kind="formation", drone_ids=["d1", "d2"], params={}, members={},
                         phase_names=["goto"], created_at=created_at)  # fmt: skip
    fleet._ops[op_id] = fop
    return fop


def heard(kind: str, body: dict[str, Any]) -> Any:
    """A broadcast of node-b as node-a's subscription gets it."""
    data = json.dumps({**body, "node": "node-b"}).encode()
    return SimpleNamespace(subject=f"fleet.event.{kind}", data=data)


async def test_a_stop_delivered_after_an_unlock_ends_no_fleet_operation_started_after_it() -> None:
    node, fleet = node_a()
    b = LockVersions()  # node-b's versions, as its announce stamps them
    lock = b.stamp("lock", {"scope": "*", "reason": "emergency stop", "by": "ops",
                            "locked_at": datetime.now(UTC).isoformat()})  # fmt: skip
    stop = b.stop_stamp({"action": "land", "by": "ops"})
    await node._on_event(heard("lock", lock))  # the stop's lock reaches node-a; its stop is held up
    unlock = b.stamp("unlock", {"scope": "*"})  # the operator unlocks through node-b
    await node._on_event(heard("unlock", unlock))
    assert node.gateway.locks.get("*") is None
    after = formation(fleet, "f-after", datetime.now(UTC) + timedelta(seconds=1))  # started after the unlock

    await node._on_event(heard("stop", stop))  # the stop's broadcast, delivered late
    assert after.status == "running", after.message


async def test_a_stop_heard_in_time_ends_the_fleet_operations_started_before_it_only() -> None:
    node, fleet = node_a()
    b = LockVersions()
    before = formation(fleet, "f-before", datetime.now(UTC) - timedelta(seconds=5))
    lock = b.stamp("lock", {"scope": "*", "reason": "emergency stop", "by": "ops",
                            "locked_at": datetime.now(UTC).isoformat()})  # fmt: skip
    stop = b.stop_stamp({"action": "land", "by": "ops"})
    # a fleet operation node-a started after the stop was made (the lock not heard yet)
    after = formation(fleet, "f-after", datetime.fromisoformat(stop["at"]) + timedelta(milliseconds=200))
    await node._on_event(heard("lock", lock))
    await node._on_event(heard("stop", stop))
    assert before.status == "superseded" and "operator stop (land) on node node-b" in before.message
    assert after.status == "running", after.message
