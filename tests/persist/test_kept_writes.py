"""The store's kept writes as the spool keeps them: JSON read back through its kind's model. A record kept
by an older version (no call id, no end time, a change the row does not take) is still written; a write
whose writer is not its kind's is refused before anything is written (a restart would write it through
its kind's writer)."""

from __future__ import annotations

from datetime import UTC, datetime

import pytest

from gateway.registry.records import AuditEntry
from gateway.registry.store import Store


def entry(action: str, outcome: str = "ok", operation_id: str | None = None) -> AuditEntry:
    return AuditEntry.model_validate({"session_key": "s1", "principal": "agent", "source": "mcp",
                                      "vehicle_id": "d1", "action": action, "arguments": {"alt_m": 10},
                                      "outcome": outcome, "operation_id": operation_id})  # fmt: skip


async def test_records_an_older_version_kept_are_written(sqlite_store: Store) -> None:
    store = sqlite_store
    t = "2026-11-29T12:00:00+00:00"
    await store._apply_kept("audit", {"values": {**entry("rest.land").model_dump(mode="json"), "t": t}})
    row = {"entry": {**entry("takeoff", "running", "op-1").model_dump(mode="json"), "t": t},
           "seen": {"key": "s1", "kind": "mcp-2025", "principal": "agent"}}  # fmt: skip
    await store._apply_kept("audit_batch", {"rows": [row]})
    rows = {r.action: r for r in await store.list_audit()}
    assert set(rows) == {"rest.land", "takeoff"} and rows["takeoff"].outcome == "running"
    session = await store.get_session("s1")
    assert session is not None and session.request_count == 1

    # an operation's end without its time (taken as now) finishes the row left running by its call
    await store._apply_kept("operation_end", {"operation_id": "op-1", "status": "succeeded", "message": None})
    finished = {r.action: r for r in await store.list_audit()}["takeoff"]
    assert finished.outcome == "ok"


async def test_a_call_rows_end_changes_only_the_fields_it_names(sqlite_store: Store) -> None:
    store = sqlite_store
    call = store.audit_call(entry("goto", "running"))
    assert await call.written(10.0)
    [before] = await store.list_audit()
    # kept by hand as the spool keeps it: an error over the row's limit, a field the row does not take
    end = {"call_id": call.id, "changes": {"outcome": "error", "error": "x" * 5000, "t": "ignored"}}
    await store._apply_kept("audit_call_end", end)
    [row] = await store.list_audit()
    assert row.outcome == "error" and row.error is not None and len(row.error) < 5000
    assert row.duration_ms is None and row.t == before.t


async def test_a_write_through_another_kinds_writer_is_refused(sqlite_store: Store) -> None:
    store = sqlite_store
    data = {"scope": "d1", "reason": "maintenance", "by": "op", "locked_at": "2026-11-29T12:00:00+00:00"}
    with pytest.raises(ValueError, match="kind 'unlock'"):
        await store._kept("the lock of d1", "unlock", data, store._kept_writers["lock"])
    assert await store.list_locks() == []
    assert await store.save_lock("d1", "maintenance", "op", datetime.now(UTC)) is not None
    assert [lock.scope for lock in await store.list_locks()] == ["d1"]
