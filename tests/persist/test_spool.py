"""The store while its PostgreSQL server is stopped and started again: the history it could not write
(audit rows, an operation, track samples, an operator lock) is kept on the node, answered at once, and
written when the server is back, in the order it was made and with the times it was made."""

from __future__ import annotations

import functools
from collections.abc import AsyncIterator
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any

import pytest
import pytest_asyncio

from gateway.registry.records import AuditEntry, OperationRecord, TrackSample
from gateway.registry.spec import VehicleSpec
from gateway.registry.spool import Spool
from gateway.registry.store import Store
from tests.helpers.tcpproxy import tcp_proxy
from tests.persist.pg import PostgresServer, create_database, find_pg_bin, restartable_postgres

pytestmark = pytest.mark.skipif(
    not (find_pg_bin("initdb") and find_pg_bin("postgres")),
    reason="PostgreSQL server binaries are not installed (apt-get install postgresql)",
)


@pytest_asyncio.fixture
async def server_and_store() -> AsyncIterator[tuple[PostgresServer, Store]]:
    with restartable_postgres() as server:
        store = await Store.open(await create_database(server.url))
        try:
            yield server, store
        finally:
            if not server.running:
                server.start()
            await store.close()


def entry(action: str) -> AuditEntry:
    return AuditEntry(source="rest", principal="ops", vehicle_id="d1", action=action, outcome="ok")


async def test_history_written_while_the_database_is_down_reaches_it_in_order_when_it_is_back(
    server_and_store: tuple[PostgresServer, Store],
) -> None:
    server, store = server_and_store
    await store.add_vehicle(VehicleSpec(id="d1", url="tcpout://127.0.0.1:5760"))
    started = datetime.now(UTC)
    flight = await store.open_flight("d1", started)
    assert await store.add_audit(entry("before")) is not None

    server.stop()
    made: list[datetime] = []
    for action in ("during-1", "during-2", "during-3"):
        made.append(datetime.now(UTC))
        assert await store.add_audit(entry(action)) is None  # kept, not failed
    now = datetime.now(UTC)
    op = OperationRecord(id="op-1", vehicle_id="d1", kind="land", status="succeeded", progress=1.0,
                         created_at=now, updated_at=now, finished_at=now)  # fmt: skip
    assert (await store.save_operation(op)).id == "op-1"
    samples = [
        TrackSample(flight_id=flight, t=now + timedelta(seconds=i), lat=1.0, lon=2.0) for i in range(3)
    ]
    assert await store.add_track_samples(samples) == 0  # none written yet
    assert await store.save_lock("*", "emergency stop", "ops", now) is None
    assert len(store.spool) == 6
    back = datetime.now(UTC)

    server.start()
    assert await store.spool.flush(60.0), f"{len(store.spool)} writes still kept"
    rows = sorted(await store.list_audit(limit=10), key=lambda r: r.id)
    assert [r.action for r in rows] == ["before", "during-1", "during-2", "during-3"]
    for row, t in zip(rows[1:], made, strict=True):  # the time each call was made, not when written
        assert abs((row.t.replace(tzinfo=UTC) - t).total_seconds()) < 1.0 and row.t.replace(tzinfo=UTC) < back
    stored_op = await store.get_operation("op-1")
    assert stored_op is not None and stored_op.status == "succeeded"
    assert len(await store.get_track(flight)) == 3
    assert [lk.scope for lk in await store.list_locks()] == ["*"]
    assert store.spool.dropped == 0
    # and once written, the store writes straight through again
    assert await store.add_audit(entry("after")) is not None


async def test_the_spool_file_gives_a_restarted_node_what_it_kept_and_no_more(tmp_path: Path) -> None:
    """The file alone (the database a function that refuses, then takes): kept writes are there in
    order, those written are marked done, a line cut short by a kill is skipped, and an empty spool
    leaves no file."""
    path = tmp_path / "spool.jsonl"
    down = True
    written: list[tuple[str, dict[str, Any]]] = []

    async def apply(kind: str, data: dict[str, Any]) -> None:
        if down:
            raise ConnectionRefusedError("database down")
        written.append((kind, data))

    first = Spool(apply=apply)
    assert await first.attach(path) == 0 and not path.exists()
    for i in range(3):
        data = {"i": i}
        assert (
            await first.write(f"row {i}", functools.partial(apply, "row", data), record=("row", data)) is None
        )
    assert len(path.read_text().splitlines()) == 3
    with path.open("a") as f:  # the node killed in the middle of a line
        f.write('{"n": 3, "what": "row 3", "ki')
    await first.close()  # (a kill leaves the file as it is; close cancels the retries)

    down = False
    second = Spool(apply=apply)
    assert await second.attach(path) == 3
    assert await second.flush(10.0)
    assert written == [("row", {"i": 0}), ("row", {"i": 1}), ("row", {"i": 2})]
    assert not path.exists()  # nothing waits: no file
    third = Spool(apply=apply)
    assert await third.attach(path) == 0 and len(written) == 3  # nothing is written twice


async def test_a_running_row_kept_while_the_database_was_cut_never_reopens_an_operation_ended_since(
    server_and_store: tuple[PostgresServer, Store],
) -> None:
    """Node A (its connection to the database through a proxy, cut) keeps its operation's running rows;
    node B, which took the drone over, ends the operation meanwhile. When A's link heals, its kept rows
    are written and the operation stays as B ended it, its audit row too."""
    _server, store_b = server_and_store
    port = int(store_b.url.rsplit(":", 1)[1].split("/", 1)[0])
    with tcp_proxy("127.0.0.1", port) as proxy:
        store_a = await Store.open(store_b.url.replace(f":{port}/", f":{proxy.port}/"), upgrade=False)
        try:
            made = datetime.now(UTC) - timedelta(seconds=5)
            op = OperationRecord(id="op-k", vehicle_id="d1", kind="goto", status="running", progress=0.1,
                                 created_at=made, updated_at=made)  # fmt: skip
            await store_a.save_operation(op)
            await store_a.add_audit(
                AuditEntry(source="mcp", action="goto", outcome="running", operation_id="op-k")
            )
            proxy.cut()
            store_a.spool.unreachable_now()  # as when its node fences itself
            later = datetime.now(UTC)
            assert await store_a.save_operation(
                op.model_copy(update={"progress": 0.4, "message": "300 m to go", "updated_at": later})
            )
            assert len(store_a.spool) == 1
            ended = datetime.now(UTC)
            await store_b.save_operation(
                op.model_copy(
                    update={
                        "status": "failed",
                        "message": "landed before arriving",
                        "updated_at": ended,
                        "finished_at": ended,
                    }
                )
            )
            proxy.heal()
            assert await store_a.spool.flush(60.0), f"{len(store_a.spool)} writes still kept"
            assert store_a.spool.written_late == 1 and store_a.spool.dropped == 0
        finally:
            await store_a.close()
    stored = await store_b.get_operation("op-k")
    assert stored is not None and (stored.status, stored.message) == ("failed", "landed before arriving")
    [row] = await store_b.list_audit()
    assert row.outcome == "error", row
