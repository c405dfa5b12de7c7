"""The audit row of a call that commands a drone is written before the command is sent (outcome running)
and finished by the call's end or by the end of the operation it started; kept on the node's disk while
the database does not answer, it reaches the database after the node is killed and started again."""

from __future__ import annotations

from datetime import UTC, datetime
from pathlib import Path

import pytest

from gateway.registry.records import AuditEntry, OperationRecord
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from gateway.registry.store_audit import SessionSeen
from tests.persist.pg import create_database, find_pg_bin, restartable_postgres


def call(action: str) -> AuditEntry:
    return AuditEntry(session_key="s1", principal="agent", source="mcp", vehicle_id="d1", action=action,
                      arguments={"alt_m": 10}, outcome="running")  # fmt: skip


async def test_a_call_row_is_stored_before_its_command_and_finished_by_its_end(store: Store) -> None:
    await store.add_vehicle(VehicleSpec(id="d1", url="tcpout://127.0.0.1:5760"))
    takeoff = store.audit_call(call("takeoff"), SessionSeen("s1", "mcp-2026", "agent"))
    assert await takeoff.written(10.0)
    # in the database before anything is sent: another reader (a new connection) sees it, running
    rows = await store.list_audit()
    assert [(r.action, r.outcome) for r in rows] == [("takeoff", "running")]
    assert (await store.get_session("s1")) is not None  # the call's session touched with it

    takeoff.operation("op-1")  # the command pass sent the operation: the row names it
    now = datetime.now(UTC)
    await store.save_operation(OperationRecord(id="op-1", vehicle_id="d1", kind="takeoff", status="succeeded",
                                               progress=1.0, created_at=now, updated_at=now,
                                               finished_at=now))  # fmt: skip
    # the call ends after its operation: the row keeps the operation's outcome
    assert await takeoff.end("running", None, 1500.0, 10.0, "op-1")
    rows = await store.list_audit()
    assert [(r.action, r.outcome, r.operation_id) for r in rows] == [("takeoff", "ok", "op-1")]
    assert rows[0].duration_ms is not None and rows[0].duration_ms >= 1500.0

    refused = store.audit_call(call("move_to_relative"))
    assert await refused.written(10.0)
    assert await refused.end("refused", "altitude_limit: above 120 m", 12.0, 10.0, None)
    newest = (await store.list_audit(limit=1))[0]
    assert (newest.action, newest.outcome, newest.error) == (
        "move_to_relative", "refused", "altitude_limit: above 120 m"
    )  # fmt: skip
    assert await store.count_audit() == 2  # one row per call, never a second one for its end


@pytest.mark.skipif(
    not (find_pg_bin("initdb") and find_pg_bin("postgres")),
    reason="PostgreSQL server binaries are not installed (apt-get install postgresql)",
)
async def test_a_call_row_kept_while_the_database_is_down_survives_the_node(tmp_path: Path) -> None:
    spool_file = tmp_path / "spool.jsonl"
    with restartable_postgres() as server:
        url = await create_database(server.url)
        store = await Store.open(url)
        await store.keep_spool_in(spool_file)
        server.stop()
        takeoff = store.audit_call(call("takeoff"))
        assert await takeoff.written(10.0)  # kept on the disk: the command may go
        assert len(store.spool) == 1 and spool_file.exists()
        assert await takeoff.end("error", "VehicleNotReady: d1 is connecting", 40.0, 10.0, None)
        await store.spool.close()  # the node dies with both writes on its disk only (no flush)
        await store.engine.dispose()

        server.start()
        again = await Store.open(url)
        try:
            assert await again.keep_spool_in(spool_file) == 2
            rows = await again.list_audit()
            assert [(r.action, r.outcome, r.error) for r in rows] == [
                ("takeoff", "error", "VehicleNotReady: d1 is connecting")
            ]
        finally:
            await again.close()
