"""Store on a real SQLite file: schema, every method, bad input, batching, concurrency."""

from __future__ import annotations

import asyncio
import math
import sys
from datetime import UTC, datetime, timedelta

import pytest
from sqlalchemy import event, text, update
from sqlalchemy.exc import IntegrityError

from gateway.errors import DuplicateVehicle, InvalidArgument, NotFound
from gateway.registry.database import current_revision, head_revision
from gateway.registry.models import sessions
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import (
    AUDIT_MAX_STRING,
    AuditEntry,
    AuditRecord,
    OperationRecord,
    StatusTextIn,
    Store,
    TrackSample,
    bound_arguments,
)
from gateway.registry.store_audit import SessionSeen
from tests.helpers.timing import scaled

T0 = datetime(2026, 5, 1, 12, 0, tzinfo=UTC)


def spec(vid: str = "alpha", port: int = 5760, **kw) -> VehicleSpec:
    return VehicleSpec(id=vid, url=f"tcpout://127.0.0.1:{port}", **kw)


# --- schema ------------------------------------------------------------------------------------


async def test_open_upgrades_to_head(store: Store) -> None:
    assert await current_revision(store.engine) == head_revision() == "0010"
    assert await store.ping()


async def test_sqlite_runs_in_wal_mode_with_a_busy_timeout(sqlite_store: Store) -> None:
    store = sqlite_store
    async with store.engine.connect() as conn:
        assert (await conn.execute(text("PRAGMA journal_mode"))).scalar_one() == "wal"
        assert (await conn.execute(text("PRAGMA busy_timeout"))).scalar_one() > 0
        tables = {r[0] for r in await conn.execute(text("SELECT name FROM sqlite_master WHERE type='table'"))}
    assert {
        "vehicles",
        "sessions",
        "audit",
        "flights",
        "track_samples",
        "status_texts",
        "operations",
        "locks",
    } <= tables


async def test_reopen_keeps_data_and_schema(db_url: str) -> None:
    first = await Store.open(db_url)
    await first.add_vehicle(spec())
    await first.close()
    assert not first.is_open
    second = await Store.open(db_url)
    try:
        assert [v.id for v in await second.list_vehicles()] == ["alpha"]
        assert await current_revision(second.engine) == head_revision()
    finally:
        await second.close()


async def test_upgrade_from_the_first_revision_keeps_data(db_url: str) -> None:
    """A database made by an older gateway (revision 0001) is upgraded in place on open."""
    from gateway.registry.database import create_engine_for, upgrade_schema

    engine = create_engine_for(db_url)
    try:
        await upgrade_schema(engine, db_url, "0001")
        assert await current_revision(engine) == "0001"
    finally:
        await engine.dispose()
    old = create_engine_for(db_url)  # the old schema, written with the old columns only
    try:
        async with old.begin() as conn:
            now = datetime.now(UTC)
            await conn.execute(
                text(
                    "INSERT INTO vehicles (id, url, tags, auto_connect, created_at, updated_at) "
                    "VALUES ('alpha', 'tcpout://127.0.0.1:5760', '[]', true, :now, :now)"
                ),
                {"now": now},
            )
    finally:
        await old.dispose()
    store = await Store.open(db_url)
    try:
        assert await current_revision(store.engine) == head_revision()
        assert [v.id for v in await store.list_vehicles()] == ["alpha"]
        assert await store.list_locks() == []
    finally:
        await store.close()


async def test_concurrent_opens_of_a_fresh_database(db_url: str) -> None:
    """Several stores opening (and migrating) one new database at once all succeed."""
    stores = await asyncio.gather(*(Store.open(db_url) for _ in range(3)))
    try:
        for store in stores:
            assert await current_revision(store.engine) == head_revision()
        await stores[0].add_vehicle(spec("alpha"))
        assert [v.id for v in await stores[2].list_vehicles()] == ["alpha"]
    finally:
        for store in stores:
            await store.close()


async def test_concurrent_upgrades_from_several_processes(db_url: str) -> None:
    """`fleet-gateway db upgrade` in four processes at once on a new database: all succeed."""
    command = [sys.executable, "-m", "gateway.server_cli", "db", "upgrade", "--database-url", db_url]
    procs = [
        await asyncio.create_subprocess_exec(
            *command, stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE
        )
        for _ in range(4)
    ]
    try:
        results = [await asyncio.wait_for(p.communicate(), scaled(120)) for p in procs]
    finally:
        for p in procs:
            if p.returncode is None:
                p.kill()
                await p.wait()
    for p, (out, err) in zip(procs, results, strict=True):
        assert p.returncode == 0, err.decode()[-2000:]
        assert f"database at revision {head_revision()}".encode() in out


async def test_migrations_match_the_models(store: Store) -> None:
    """Autogenerate against the migrated database finds nothing to change."""
    from alembic.autogenerate import compare_metadata
    from alembic.runtime.migration import MigrationContext

    from gateway.registry.models import metadata

    def diff(connection):
        ctx = MigrationContext.configure(connection, opts={"compare_type": True})
        return compare_metadata(ctx, metadata)

    async with store.engine.connect() as conn:
        assert await conn.run_sync(diff) == []


# --- vehicles ----------------------------------------------------------------------------------


async def test_gcs_endpoints_are_stored_and_changed(store: Store) -> None:
    endpoints = ["udpout://127.0.0.1:14550", "tcpin://127.0.0.1:5790"]
    rec = await store.add_vehicle(spec("alpha", gcs_endpoints=endpoints))
    assert rec.gcs_endpoints == endpoints and rec.spec.gcs_endpoints == endpoints
    assert (await store.get_vehicle("alpha")).gcs_endpoints == endpoints  # type: ignore[union-attr]
    changed = await store.update_vehicle("alpha", gcs_endpoints=endpoints[1:])
    assert changed.gcs_endpoints == endpoints[1:]
    with pytest.raises(InvalidArgument, match="is not accepted"):
        await store.update_vehicle("alpha", gcs_endpoints=["serial:///dev/ttyUSB0"])
    assert (await store.get_vehicle("alpha")).gcs_endpoints == endpoints[1:]  # type: ignore[union-attr]
    await store.add_vehicle(spec("bravo", 5770))
    assert (await store.get_vehicle("bravo")).gcs_endpoints == []  # type: ignore[union-attr]


async def test_vehicle_crud(store: Store) -> None:
    rec = await store.add_vehicle(spec("alpha", name="Alpha", tags=["survey"], expected_sysid=1))
    assert rec.auto_connect is True
    assert rec.created_at.tzinfo is not None and rec.created_at == rec.updated_at
    await store.add_vehicle(spec("bravo", 5770))
    assert [v.id for v in await store.list_vehicles()] == ["alpha", "bravo"]

    updated = await store.update_vehicle("alpha", name="A", tags=["x", "y"], auto_connect=False)
    assert (updated.name, updated.tags, updated.auto_connect) == ("A", ["x", "y"], False)
    assert updated.updated_at >= rec.updated_at
    got = await store.get_vehicle("alpha")
    assert got == updated
    assert got.spec == VehicleSpec(id="alpha", url=rec.url, name="A", tags=["x", "y"], expected_sysid=1)

    await store.remove_vehicle("bravo")
    assert await store.get_vehicle("bravo") is None
    with pytest.raises(NotFound):
        await store.remove_vehicle("bravo")


async def test_duplicate_vehicle_is_refused_and_changes_nothing(store: Store) -> None:
    await store.add_vehicle(spec("alpha", name="first"))
    with pytest.raises(DuplicateVehicle, match="alpha"):
        await store.add_vehicle(spec("alpha", 5999, name="second"))
    [only] = await store.list_vehicles()
    assert only.name == "first" and only.url.endswith(":5760")


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"url": "http://example.com"}, "scheme"),
        ({"expected_sysid": 0}, "expected_sysid"),
        ({"tags": ["bad tag!"]}, "tag"),
        ({"auto_connect": "yes"}, "auto_connect"),
        ({"id": "other"}, "cannot update"),
        ({"created_at": T0}, "cannot update"),
    ],
)
async def test_bad_vehicle_update_changes_nothing(store: Store, changes: dict, match: str) -> None:
    before = await store.add_vehicle(spec("alpha", name="Alpha"))
    with pytest.raises(InvalidArgument, match=match):
        await store.update_vehicle("alpha", **changes)
    assert await store.get_vehicle("alpha") == before


async def test_update_unknown_vehicle(store: Store) -> None:
    with pytest.raises(NotFound, match="ghost"):
        await store.update_vehicle("ghost", name="x")


# --- flights, tracks, status texts ------------------------------------------------------------


async def test_flight_lifecycle_and_track(store: Store) -> None:
    fid = await store.open_flight("alpha", T0, 47.39, 8.54, 488.0)
    assert [f.id for f in await store.list_open_flights()] == [fid]
    assert await store.list_open_flights("bravo") == []

    samples = [
        TrackSample(
            flight_id=fid,
            t=T0 + timedelta(seconds=i),
            lat=47.39 + i * 1e-5,
            lon=8.54,
            alt_rel_m=float(i),
            heading_deg=90.0,
            ground_speed_mps=5.0,
            battery_pct=100 - i,
        )
        for i in range(10)
    ]
    assert await store.add_track_samples(samples[5:]) == 5
    assert await store.add_track_samples(samples[:5]) == 5
    assert await store.add_track_samples([]) == 0
    track = await store.get_track(fid)
    assert track == samples  # ordered by time, whatever the insert order

    closed = await store.close_flight(fid, T0 + timedelta(seconds=10), 10.0, 11.1, 9.0, 9.0)
    assert not closed.is_open and closed.duration_s == 10.0
    assert await store.list_open_flights() == []
    flight = await store.get_flight(fid)
    assert flight == closed and flight.home_alt_amsl == 488.0
    assert await store.get_flight(fid + 100) is None
    with pytest.raises(NotFound):
        await store.close_flight(fid + 100, T0)


async def test_track_sample_accepts_unix_time_and_rejects_bad_coordinates() -> None:
    sample = TrackSample(flight_id=1, t=T0.timestamp(), lat=1, lon=2)
    assert sample.t == T0
    with pytest.raises(ValueError, match="lat"):
        TrackSample(flight_id=1, t=T0, lat=91, lon=2)
    with pytest.raises(ValueError, match="lon"):
        TrackSample(flight_id=1, t=T0, lat=1, lon=math.nan)
    odd = TrackSample(flight_id=1, t=T0, lat=1, lon=2, alt_rel_m=math.nan, battery_pct=math.inf)
    assert odd.alt_rel_m is None and odd.battery_pct is None


async def test_track_batch_is_one_transaction(store: Store) -> None:
    fid = await store.open_flight("alpha", T0)
    commits: list[int] = []
    event.listen(store.engine.sync_engine, "commit", lambda conn: commits.append(1))
    batch = [TrackSample(flight_id=fid, t=T0 + timedelta(seconds=i), lat=1, lon=2) for i in range(200)]
    await store.add_track_samples(batch)
    assert len(commits) == 1
    assert len(await store.get_track(fid)) == 200


async def test_track_batch_for_unknown_flight_is_refused_whole(store: Store) -> None:
    fid = await store.open_flight("alpha", T0)
    batch = [
        TrackSample(flight_id=fid, t=T0, lat=1, lon=2),
        TrackSample(flight_id=fid + 1, t=T0, lat=1, lon=2),
    ]
    with pytest.raises(IntegrityError):
        await store.add_track_samples(batch)
    assert await store.get_track(fid) == []


async def test_list_flights_filters_and_pages(store: Store) -> None:
    ids = []
    for i in range(5):
        vid = "alpha" if i % 2 == 0 else "bravo"
        start = T0 + timedelta(hours=i)
        fid = await store.open_flight(vid, start)
        if i < 4:
            await store.close_flight(fid, start + timedelta(minutes=10))
        ids.append(fid)

    flights, total = await store.list_flights()
    assert total == 5 and [f.id for f in flights] == ids[::-1]  # newest first
    flights, total = await store.list_flights(vehicle_id="alpha")
    assert total == 3 and {f.vehicle_id for f in flights} == {"alpha"}
    flights, total = await store.list_flights(limit=2, offset=1)
    assert total == 5 and [f.id for f in flights] == [ids[3], ids[2]]
    # overlap with [T0+1h05, T0+2h05]: flight 1 (1:00-1:10) and flight 2 (2:00-2:10)
    flights, total = await store.list_flights(
        since=T0 + timedelta(hours=1, minutes=5), until=T0 + timedelta(hours=2, minutes=5)
    )
    assert total == 2 and {f.id for f in flights} == {ids[1], ids[2]}
    # the open flight (started 4:00) overlaps any later window
    flights, _ = await store.list_flights(since=T0 + timedelta(days=1))
    assert [f.id for f in flights] == [ids[4]]


async def test_status_texts(store: Store) -> None:
    fid = await store.open_flight("alpha", T0)
    items = [
        StatusTextIn(vehicle_id="alpha", flight_id=fid, t=T0 + timedelta(seconds=i), severity=6, text=f"m{i}")
        for i in range(5)
    ]
    items.append(
        StatusTextIn(vehicle_id="alpha", t=T0 + timedelta(seconds=9), severity="warning", text="x" * 999)
    )
    items.append(StatusTextIn(vehicle_id="bravo", t=T0, severity=4, text="other"))
    assert await store.add_status_texts(items) == 7

    texts = await store.list_status_texts("alpha", limit=3)
    assert [t.text[:2] for t in texts] == ["m3", "m4", "xx"]  # newest three, oldest first
    assert texts[0].severity == "INFO" and texts[-1].severity == "WARNING"
    assert len(texts[-1].text) == 255 and texts[-1].flight_id is None
    since = await store.list_status_texts("alpha", since=T0 + timedelta(seconds=4))
    assert [t.text[:2] for t in since] == ["m4", "xx"]
    assert [t.text for t in await store.list_status_texts("bravo")] == ["other"]


# --- sessions ----------------------------------------------------------------------------------


async def test_touch_session_upserts(store: Store) -> None:
    first = await store.touch_session("sess-1", "mcp-2025", principal="agent-a", client_name="claude")
    assert first.request_count == 1 and first.first_seen == first.last_seen
    await asyncio.sleep(0.01)
    second = await store.touch_session("sess-1", "mcp-2025", client_version="1.2")
    assert second.first_seen == first.first_seen and second.last_seen > first.last_seen
    assert second.request_count == 2
    assert (second.principal, second.client_name, second.client_version) == ("agent-a", "claude", "1.2")
    await store.touch_session("op:alice", "rest", principal="alice")

    sessions = await store.list_sessions()
    assert [s.key for s in sessions] == ["op:alice", "sess-1"]  # most recently seen first
    assert [s.key for s in await store.list_sessions(kind="mcp-2025")] == ["sess-1"]
    assert [s.key for s in await store.list_sessions(principal="alice")] == ["op:alice"]
    assert (await store.get_session("sess-1")) == second


async def test_touch_session_rejects_unknown_kind(store: Store) -> None:
    with pytest.raises(InvalidArgument, match="kind"):
        await store.touch_session("k", "telnet")  # type: ignore[arg-type]
    assert await store.list_sessions() == []


async def test_concurrent_touches_of_one_session(store: Store) -> None:
    await asyncio.gather(*(store.touch_session("same", "mcp-2026") for _ in range(20)))
    [only] = await store.list_sessions()
    assert only.request_count >= 1 and only.key == "same"


# --- audit -------------------------------------------------------------------------------------


def test_bound_arguments_truncates() -> None:
    args = {
        "long": "x" * 2000,
        "nan": math.nan,
        "nested": {"list": [1, "y" * 600], "obj": object()},
        "ok": 1.5,
    }
    bounded = bound_arguments(args)
    assert bounded["long"].startswith("x" * AUDIT_MAX_STRING) and "1500 more chars" in bounded["long"]
    assert bounded["nan"] == "nan" and bounded["ok"] == 1.5
    assert len(bounded["nested"]["list"][1]) < 600
    assert bounded["nested"]["obj"].startswith("<object")
    huge = bound_arguments({f"k{i}": "z" * 400 for i in range(100)})
    assert huge["_truncated"] is True and huge["_size"] > 8000


async def test_audit_add_and_list(store: Store) -> None:
    for i in range(5):
        await store.add_audit(
            AuditEntry(
                session_key="s1" if i < 3 else "s2",
                principal="agent",
                source="mcp",
                vehicle_id="alpha" if i % 2 == 0 else "bravo",
                action="takeoff",
                arguments={"alt": i, "note": "n" * 5000},
                outcome="ok" if i else "refused",
                error=None if i else "altitude limit",
                duration_ms=12.5,
                t=T0 + timedelta(seconds=i),
            )
        )
    entries = await store.list_audit()
    assert [e.arguments["alt"] for e in entries] == [4, 3, 2, 1, 0]  # newest first
    assert len(entries[0].arguments["note"]) < 600
    assert entries[-1].outcome == "refused" and entries[-1].error == "altitude limit"
    assert [e.arguments["alt"] for e in await store.list_audit(vehicle_id="alpha")] == [4, 2, 0]
    assert [e.arguments["alt"] for e in await store.list_audit(session_key="s2")] == [4, 3]
    assert [e.arguments["alt"] for e in await store.list_audit(limit=2, offset=1)] == [3, 2]
    assert await store.count_audit() == 5 and await store.count_audit(vehicle_id="bravo") == 2


async def test_queued_audit_rows_are_written_in_batches_and_seen_by_every_reader(store: Store) -> None:
    seen: list[AuditRecord] = []
    store.on_audit(seen.append)
    batches: list[int] = []
    writes = store._write_audit_batch

    async def counted(batch: list, call_ids: list[str]) -> None:  # type: ignore[type-arg]
        batches.append(len(batch))
        await writes(batch, call_ids)

    store._write_audit_batch = counted  # type: ignore[method-assign]
    who = SessionSeen("s1", "mcp-2026", principal="agent", client_name="bench", client_version="1")
    for i in range(5):
        store.queue_audit(
            AuditEntry(
                source="mcp", action="get_position", vehicle_id="alpha", arguments={"i": i}, outcome="ok"
            ),
            who,
        )
    # a reader does not wait for the batching pause, and misses nothing
    assert [e.arguments["i"] for e in await store.list_audit()] == [4, 3, 2, 1, 0]
    assert batches == [5]
    session = await store.get_session("s1")
    assert session is not None and session.request_count == 5 and session.client_name == "bench"
    assert [r.arguments["i"] for r in seen] == [0, 1, 2, 3, 4]  # listeners see each row once written
    store.queue_audit(AuditEntry(source="mcp", action="land", outcome="ok"), who)
    assert await store.count_audit() == 6
    assert (await store.get_session("s1")).request_count == 6  # type: ignore[union-attr]


async def test_a_queued_running_row_of_an_operation_that_already_ended_is_finished(store: Store) -> None:
    op = OperationRecord(id="op-q", vehicle_id="alpha", kind="goto", status="running")
    await store.save_operation(op)
    await store.save_operation(op.model_copy(update={"status": "succeeded", "message": "arrived"}))
    store.queue_audit(
        AuditEntry(source="mcp", action="go_to_location", outcome="running", operation_id="op-q")
    )
    [row] = await store.list_audit()
    assert row.outcome == "ok" and row.operation_id == "op-q"


async def test_a_finished_row_took_as_long_as_its_operation(store: Store) -> None:
    """The call answered in 7 ms; the landing it started took 20 s: the row says 20 s."""
    op = OperationRecord(id="op-t", vehicle_id="alpha", kind="land", status="running", created_at=T0)
    await store.save_operation(op)
    await store.add_audit(
        AuditEntry(
            source="rest", action="land", outcome="running", operation_id="op-t", t=T0, duration_ms=7.0
        )
    )
    ended = T0 + timedelta(seconds=20)
    await store.save_operation(
        op.model_copy(update={"status": "succeeded", "finished_at": ended, "updated_at": ended})
    )
    [row] = await store.list_audit()
    assert row.outcome == "ok" and row.duration_ms == pytest.approx(20_000.0)


async def test_a_row_finished_by_another_node_took_until_that_end(store: Store) -> None:
    started = datetime.now(UTC) - timedelta(seconds=12)
    await store.add_audit(
        AuditEntry(
            source="mcp",
            action="fleet_land",
            outcome="running",
            operation_id="f-1",
            t=started,
            duration_ms=5.0,
        )
    )
    await store.finish_audit_of("f-1", "succeeded", None)
    [row] = await store.list_audit()
    assert row.outcome == "ok" and row.duration_ms is not None and row.duration_ms >= 12_000.0


async def test_close_writes_what_is_queued(db_url: str) -> None:
    store = await Store.open(db_url)
    store.queue_audit(AuditEntry(source="mcp", action="takeoff", outcome="ok"))
    await store.close()
    reopened = await Store.open(db_url)
    try:
        assert [e.action for e in await reopened.list_audit()] == ["takeoff"]
    finally:
        await reopened.close()


def test_audit_entry_rejects_unknown_outcome() -> None:
    with pytest.raises(ValueError, match="outcome"):
        AuditEntry(source="mcp", action="x", outcome="maybe")


# --- operations --------------------------------------------------------------------------------


async def test_an_ended_operation_is_final(store: Store) -> None:
    """A running row written after the operation ended (kept by a node while the database was down)
    does not bring it back, nor does a second end change how it ended."""
    op = OperationRecord(id="op-e", vehicle_id="alpha", kind="goto", status="running", created_at=T0)
    await store.save_operation(op)
    ended = T0 + timedelta(seconds=30)
    await store.save_operation(
        op.model_copy(
            update={"status": "succeeded", "message": "arrived", "updated_at": ended, "finished_at": ended}
        )
    )
    await store.save_operation(op.model_copy(update={"progress": 0.5, "message": "20 m to go"}))
    later = ended + timedelta(seconds=5)
    await store.save_operation(
        op.model_copy(
            update={
                "status": "interrupted",
                "message": "gateway stopped",
                "updated_at": later,
                "finished_at": later,
            }
        )
    )
    got = await store.get_operation("op-e")
    assert got is not None and (got.status, got.message) == ("succeeded", "arrived")
    assert got.finished_at is not None and got.finished_at.replace(tzinfo=UTC) == ended
    assert [r.id for r in await store.list_operations(status="running")] == []


async def test_operations_upsert_and_list(store: Store) -> None:
    op = OperationRecord(id="op-1", vehicle_id="alpha", kind="takeoff", params={"alt": 10}, status="running")
    await store.save_operation(op)
    await store.save_operation(
        OperationRecord(id="op-2", vehicle_id="bravo", kind="goto", status="running", created_at=T0)
    )
    done = op.model_copy(
        update={
            "status": "succeeded",
            "progress": 1.0,
            "finished_at": datetime.now(UTC),
            "result": {"alt": 10},
        }
    )
    await store.save_operation(done)
    got = await store.get_operation("op-1")
    assert got.status == "succeeded" and got.progress == 1.0 and got.result == {"alt": 10}
    assert got.params == {"alt": 10} and got.finished_at is not None
    assert await store.get_operation("nope") is None
    assert [o.id for o in await store.list_operations()] == ["op-1", "op-2"]
    assert [o.id for o in await store.list_operations(status="running")] == ["op-2"]
    assert [o.id for o in await store.list_operations("alpha", status=["succeeded", "failed"])] == ["op-1"]
    with pytest.raises(ValueError, match="status"):
        OperationRecord(id="x", vehicle_id="a", kind="k", status="weird")
    with pytest.raises(ValueError, match="progress"):
        OperationRecord(id="x", vehicle_id="a", kind="k", status="running", progress=1.5)


# --- time and concurrency ----------------------------------------------------------------------


async def test_naive_datetimes_are_refused(store: Store) -> None:
    with pytest.raises(Exception, match="naive datetime"):
        await store.open_flight("alpha", datetime(2026, 1, 1))
    assert (await store.list_flights())[1] == 0


async def test_two_stores_on_one_file_write_concurrently(db_url: str) -> None:
    """Two engines (as gateway + CLI) writing at once: the busy timeout serialises them."""
    a, b = await Store.open(db_url), await Store.open(db_url)
    try:

        async def writer(store: Store, name: str) -> None:
            for i in range(30):
                await store.add_audit(AuditEntry(source="rest", action=f"{name}{i}", outcome="ok"))

        await asyncio.gather(writer(a, "a"), writer(b, "b"))
        assert await a.count_audit() == 60
    finally:
        await a.close()
        await b.close()


# --- operator locks ----------------------------------------------------------------------------


async def test_locks_are_stored_replaced_and_deleted(store: Store) -> None:
    await store.save_lock("*", "battery swap", "alice", T0)
    await store.save_lock("alpha", "maintenance", "bob", T0 + timedelta(minutes=1))
    await store.save_lock("alpha", "props changed", "carol", T0 + timedelta(minutes=2))
    locks = await store.list_locks()
    assert [(lk.scope, lk.reason, lk.by) for lk in locks] == [
        ("*", "battery swap", "alice"),
        ("alpha", "props changed", "carol"),
    ]
    assert locks[1].locked_at == T0 + timedelta(minutes=2)
    assert await store.delete_lock("alpha") is True
    assert await store.delete_lock("alpha") is False
    assert [lk.scope for lk in await store.list_locks()] == ["*"]


# --- retention ---------------------------------------------------------------------------------


async def test_prune_deletes_old_history_only(store: Store) -> None:
    old, new = T0, T0 + timedelta(days=40)
    cutoff = T0 + timedelta(days=30)
    await store.add_vehicle(spec("alpha"))
    await store.save_lock("alpha", "kept", "op", old)
    old_flight = await store.open_flight("alpha", old)
    await store.add_track_samples([TrackSample(flight_id=old_flight, t=old, lat=1, lon=2)])
    await store.close_flight(old_flight, old + timedelta(minutes=5))
    open_flight = await store.open_flight("alpha", old)  # still open: kept with its track
    await store.add_track_samples([TrackSample(flight_id=open_flight, t=old, lat=1, lon=2)])
    new_flight = await store.open_flight("alpha", new)
    await store.add_track_samples([TrackSample(flight_id=new_flight, t=new, lat=1, lon=2)])
    await store.close_flight(new_flight, new + timedelta(minutes=5))
    await store.add_status_texts(
        [
            StatusTextIn(vehicle_id="alpha", flight_id=old_flight, t=old, severity=6, text="old"),
            StatusTextIn(vehicle_id="alpha", flight_id=new_flight, t=new, severity=6, text="new"),
        ]
    )
    for t in (old, new):
        await store.add_audit(AuditEntry(source="rest", action="x", outcome="ok", t=t))
    await store.save_operation(
        OperationRecord(
            id="old", vehicle_id="alpha", kind="goto", status="succeeded", created_at=old, finished_at=old
        )
    )
    await store.save_operation(
        OperationRecord(id="run", vehicle_id="alpha", kind="goto", status="running", created_at=old)
    )
    await store.touch_session("s-old", "mcp-2025")
    async with store.engine.begin() as conn:  # make that session old
        await conn.execute(update(sessions).values(last_seen=old))
    await store.touch_session("s-new", "mcp-2026")

    counts = await store.prune(cutoff)
    assert counts == {
        "track_samples": 1,
        "status_texts": 1,
        "flights": 1,
        "audit": 1,
        "sessions": 1,
        "operations": 1,
    }
    flights, total = await store.list_flights()
    assert total == 2 and {f.id for f in flights} == {open_flight, new_flight}
    assert len(await store.get_track(open_flight)) == 1 and len(await store.get_track(new_flight)) == 1
    assert [t.text for t in await store.list_status_texts("alpha")] == ["new"]
    assert await store.count_audit() == 1
    assert [s.key for s in await store.list_sessions()] == ["s-new"]
    assert [o.id for o in await store.list_operations()] == ["run"]
    assert [v.id for v in await store.list_vehicles()] == ["alpha"] and len(await store.list_locks()) == 1
    assert (await store.prune(cutoff)) == dict.fromkeys(counts, 0)
