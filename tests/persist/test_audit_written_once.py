"""An audit row is written once however often its write is tried: a try whose commit went through but
whose answer was lost (timed out) and the spool's later try of the same write, a kept write replayed
after it was written, or a write applied twice, leave one row and one request on its session."""

from __future__ import annotations

from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Any

import pytest_asyncio

from gateway.registry.audit_kept import SessionSeen
from gateway.registry.records import AuditEntry
from gateway.registry.store import Store

SEEN = SessionSeen("s1", "mcp-2025", "agent", "client", "1.0")


def entry(action: str) -> AuditEntry:
    return AuditEntry(session_key="s1", principal="agent", source="mcp", vehicle_id="d1", action=action,
                      arguments={"alt_m": 10}, outcome="ok")  # fmt: skip


@pytest_asyncio.fixture
async def store(db_url: str) -> AsyncIterator[Store]:
    opened = await Store.open(db_url)
    try:
        yield opened
    finally:
        await opened.close()


def answer_lost_once(store: Store, kind: str) -> list[str]:
    """The writer of ``kind`` commits, then its first try raises a timeout (as a database whose answer
    comes after the spool's time does): the spool keeps the write and tries it again. The tries, logged."""
    writer: Callable[[dict[str, Any]], Awaitable[Any]] = store._kept_writers[kind]
    tries: list[str] = []

    async def late(data: dict[str, Any]) -> Any:
        result = await writer(data)
        tries.append("committed")
        if len(tries) == 1:
            raise TimeoutError("the commit's answer came too late")
        return result

    store._kept_writers[kind] = late  # the spool's later tries
    setattr(store, writer.__name__, late)  # the first try (the store names its writer for each kept write)
    return tries


async def test_a_batch_tried_again_after_its_commit_is_one_row_each(store: Store) -> None:
    tries = answer_lost_once(store, "audit_batch")
    for action in ("get_telemetry", "list_drones"):
        store.queue_audit(entry(action), SEEN)
    await store.flush_audit()
    assert await store.spool.flush(10.0)
    assert tries == ["committed", "committed"]  # tried twice, committed twice
    assert sorted(r.action for r in await store.list_audit()) == ["get_telemetry", "list_drones"]
    session = await store.get_session("s1")
    assert session is not None and session.request_count == 2


async def test_a_rest_row_tried_again_after_its_commit_is_one_row(store: Store) -> None:
    tries = answer_lost_once(store, "audit")
    assert await store.add_audit(entry("rest.fleet_stop")) is None  # kept: its first answer was lost
    assert await store.spool.flush(10.0)
    assert tries == ["committed", "committed"]
    assert [r.action for r in await store.list_audit()] == ["rest.fleet_stop"]


async def test_a_kept_write_applied_twice_adds_nothing_the_second_time(store: Store) -> None:
    """A node killed after a kept write reached the database but before the spool file marked it done
    writes it again when it starts: the rows are there once, the session counted once."""
    data = store._batch_data([(entry("takeoff"), SEEN), (entry("land"), SEEN)]).model_dump(mode="json")
    await store._apply_kept("audit_batch", data)
    await store._apply_kept("audit_batch", data)
    rest = {"values": {**store._audit_values(entry("rest.fleet_stop")), "t": "2026-11-29T12:00:00+00:00"},
            "call_id": "f" * 32}  # fmt: skip
    first = await store._apply_kept("audit", rest)
    assert await store._apply_kept("audit", rest) == first  # the row already written, by its id
    assert sorted(r.action for r in await store.list_audit()) == ["land", "rest.fleet_stop", "takeoff"]
    session = await store.get_session("s1")
    assert session is not None and session.request_count == 2


async def test_a_call_row_begun_twice_is_one_row_finished_by_its_end(store: Store) -> None:
    """A call's row written before its command (`AuditCall`) whose first try's answer was lost: one row,
    which the call's end finishes."""
    tries = answer_lost_once(store, "audit_batch")
    call = store.audit_call(entry("takeoff").model_copy(update={"outcome": "running"}), SEEN)
    assert await call.written(10.0)
    assert await call.end("ok", None, 120.0, 10.0, None)
    assert await store.spool.flush(10.0)
    assert tries == ["committed", "committed"]
    rows = await store.list_audit()
    assert [(r.action, r.outcome) for r in rows] == [("takeoff", "ok")]
