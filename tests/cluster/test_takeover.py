"""What a node does with the operations a lost node left running (gateway.cluster.takeover), on the real
Gateway (store, operations, Commander) over a fake drone: the newest one it can follow is tracked again
under the same id and keeps saying what happened until it ends; every other one is recorded as
interrupted, saying so."""

from __future__ import annotations

import copy
from collections.abc import AsyncIterator
from datetime import timedelta
from pathlib import Path
from typing import Any

import pytest

from gateway.cluster.takeover import pick_up_late_operations, pick_up_operations
from gateway.fleet import geo
from gateway.fleet.operations import operations as operations_module
from gateway.fleet.operations.operation_state import Operation
from gateway.fleet.policy.caller import Caller
from gateway.registry.records import OperationRecord, utcnow
from gateway.runtime import Gateway
from tests.fakes import HOME, fake, fake_gateway, position_value, spread, unit_settings
from tests.helpers.timing import eventually

AGENT = Caller(via="mcp", principal="agent-1", session="s1")
LOST = "node node-c was lost while this"


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=10.0), spread(1)) as gw:
        drone = fake(gw, "d1")
        drone.set(armed=True, in_air=True, landed_state="IN_AIR", flight_mode="GUIDED",
                  position=position_value(HOME[0], HOME[1], 10.0))  # fmt: skip
        yield gw


async def left_running(gateway: Gateway, op_id: str, kind: str, age_s: float, **params: float) -> None:
    """An operation the lost node wrote as running ``age_s`` ago and never finished."""
    at = utcnow() - timedelta(seconds=age_s)
    record = OperationRecord(id=op_id, vehicle_id="d1", kind=kind, params=params, status="running",
                             progress=0.3, message="command sent", session_key="s1", created_at=at,
                             updated_at=at)  # fmt: skip
    await gateway.require_store().save_operation(record)


async def followed_far_north(gateway: Gateway, op_id: str) -> tuple[Any, tuple[float, float]]:
    """A goto 300 m north the lost node left running, followed here; the drone and the goto's target."""
    vehicle = gateway.require_registry().get("d1")
    lat, lon = geo.offset_position(HOME[0], HOME[1], 300.0, 0.0)
    await left_running(gateway, op_id, "goto", 5.0, lat_deg=lat, lon_deg=lon, alt_m=10.0)
    assert await pick_up_operations(gateway, "node-a", vehicle, 2, "node-c") == 1
    return vehicle, (lat, lon)


async def test_a_taken_over_goto_says_its_node_was_lost_until_it_ends_and_an_older_one_is_interrupted(
    gateway: Gateway,
) -> None:
    store = gateway.require_store()
    lat, lon = geo.offset_position(HOME[0], HOME[1], 30.0, 0.0)
    await left_running(gateway, "older-takeoff", "takeoff", 20.0, alt_m=10.0)
    await left_running(gateway, "newer-goto", "goto", 5.0, lat_deg=lat, lon_deg=lon, alt_m=10.0)
    vehicle = gateway.require_registry().get("d1")

    assert await pick_up_operations(gateway, "node-a", vehicle, 2, "node-c") == 2

    # the older one: interrupted, and the record says why and what the drone does now
    older = await store.get_operation("older-takeoff")
    assert older is not None and older.status == "interrupted" and older.finished_at is not None
    assert older.message is not None
    assert older.message.startswith(f"{LOST} takeoff ran; node node-a took d1 over"), older.message
    assert "(a newer operation was running)" in older.message
    assert "keeps flying its last command on its own" in older.message
    # the newer one: followed again under its id; its progress messages keep the note
    ops = gateway.commander.operations
    resumed = ops.get("newer-goto")
    note = f"{LOST} goto ran; node node-a took d1 over (lease epoch 2) and has tracked it since"

    async def tracked() -> str | None:
        return resumed.message if "m to go" in resumed.message else None

    assert (await eventually(tracked, "a progress message of the resumed goto", within_s=10)).endswith(note)
    # the drone arrives on its own (it flew its last command): what monitor_flight answers says it all
    fake(gateway, "d1").set(position=position_value(lat, lon, 10.0))
    view = await gateway.commander.monitor(AGENT, "d1")
    assert view.operation_id == "newer-goto" and view.status == "succeeded", view
    assert view.message.startswith("arrived (") and view.message.endswith(note), view.message

    async def stored_as_answered() -> OperationRecord | None:  # the store writes behind the answer
        record = await store.get_operation("newer-goto")
        return record if record is not None and record.status == "succeeded" else None

    stored = await eventually(stored_as_answered, "the resumed goto stored as succeeded", within_s=10)
    assert stored.message == view.message


async def test_an_operation_that_cannot_be_followed_again_is_interrupted_saying_so(gateway: Gateway) -> None:
    await left_running(gateway, "no-target", "goto", 5.0, alt_m=10.0)  # its stored target is incomplete
    vehicle = gateway.require_registry().get("d1")

    assert await pick_up_operations(gateway, "node-b", vehicle, 3, "node-c") == 1

    record = await gateway.require_store().get_operation("no-target")
    assert record is not None and record.status == "interrupted", record
    assert record.message == (
        f"{LOST} goto ran; node node-b took d1 over and stopped tracking it (it cannot be followed again); "
        "the drone keeps flying its last command on its own: check get_telemetry before the next command"
    )
    assert gateway.commander.operations.latest("d1") is None  # nothing is tracked on this node


async def test_a_drone_given_up_leaves_its_operation_to_the_next_owner_which_picks_up_a_late_row(
    gateway: Gateway,
) -> None:
    """A node that gives a drone up (it fenced itself) stops following its operation and writes nothing
    about it; a running row that reaches the database after the drone's next owner took it over (kept in
    the previous owner's spool) is picked up at that owner's next tick; one older than the operation the
    owner runs is closed, not resumed over it."""
    store, ops = gateway.require_store(), gateway.commander.operations
    vehicle, (lat, lon) = await followed_far_north(gateway, "followed")
    assert ops.running("d1") is not None and ops.knows("followed")

    assert ops.let_go("d1") == ["followed"]
    assert ops.running("d1") is None and ops.latest("d1") is None and not ops.knows("followed")
    record = await store.get_operation("followed")
    assert record is not None and record.status == "running"  # left to the node that holds it next

    # this node holds the drone again: the row nobody follows is followed again
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 1
    assert ops.running("d1") is not None and ops.running("d1").id == "followed"  # type: ignore[union-attr]
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 0  # followed now

    # a row older than the operation it runs, written late: closed, the running one kept
    await left_running(gateway, "late-older", "goto", 30.0, lat_deg=lat, lon_deg=lon, alt_m=10.0)
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 1
    late = await store.get_operation("late-older")
    assert late is not None and late.status == "interrupted", late
    assert late.message is not None and "(a newer operation was running)" in late.message, late.message
    assert ops.running("d1").id == "followed"  # type: ignore[union-attr]
    # drones this node does not hold are not looked at
    await left_running(gateway, "elsewhere", "goto", 1.0, lat_deg=lat, lon_deg=lon, alt_m=10.0)
    assert await pick_up_late_operations(gateway, "node-a", {}) == 0


async def test_a_followed_operation_the_database_still_holds_as_running_is_ended_there_at_the_next_tick(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The node follows the operation, but the database holds it as running: its end here never reached
    the database (written again), or nothing follows it any more (its monitor is gone: ended as failed).
    Either way the row does not stay running for ever."""
    monkeypatch.setattr(operations_module, "RESTATE_AFTER_S", 0.0)
    store, ops = gateway.require_store(), gateway.commander.operations
    vehicle, (lat, lon) = await followed_far_north(gateway, "lost-end")
    saved = store.save_operation

    async def lost(record: OperationRecord) -> OperationRecord:  # the end's write never arrives
        return record

    monkeypatch.setattr(store, "save_operation", lost)
    fake(gateway, "d1").set(position=position_value(lat, lon, 10.0))
    await eventually(lambda: _ended(ops.get("lost-end")), "the goto ended here", within_s=10)
    monkeypatch.setattr(store, "save_operation", saved)
    before = await store.get_operation("lost-end")
    assert before is not None and before.status == "running"

    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 0
    after = await store.get_operation("lost-end")
    assert after is not None and after.status == "succeeded", after

    # a running operation whose monitor is gone: nothing would ever end it
    lat2, lon2 = geo.offset_position(HOME[0], HOME[1], 0.0, 300.0)
    await left_running(gateway, "unfollowed", "goto", 1.0, lat_deg=lat2, lon_deg=lon2, alt_m=10.0)
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 1
    task = ops._monitors.pop("unfollowed")
    task.cancel()
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 0
    record = await store.get_operation("unfollowed")
    assert record is not None and record.status == "failed", record
    assert record.message is not None and "monitoring stopped" in record.message, record.message

    # followed over a link the node no longer holds (it holds the drone over a new one): let go there and
    # followed again over the new one, under the same id
    await left_running(gateway, "old-link", "goto", 1.0, lat_deg=lat2, lon_deg=lon2, alt_m=10.0)
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (vehicle, 4)}) == 1
    new_link = copy.copy(vehicle)
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (new_link, 5)}) == 1
    assert ops._followed_on["old-link"] is new_link and ops.running("d1") is ops.get("old-link")
    assert await pick_up_late_operations(gateway, "node-a", {"d1": (new_link, 5)}) == 0


async def _ended(op: Operation) -> bool:
    return op.finished
