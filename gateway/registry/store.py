"""Persistence of the gateway: vehicles, flights and tracks, status texts, sessions, audit, operations.

``await Store.open(url)`` upgrades the schema to Alembic head and returns a ready store. Every method
returns plain pydantic records, never live ORM objects. Only portable SQL is used, so a PostgreSQL
(asyncpg) URL works as well as the SQLite (aiosqlite) default; SQLite gets WAL mode and a busy timeout.
"""

from __future__ import annotations

import asyncio
import contextlib
import dataclasses
import functools
import logging
import weakref
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from datetime import datetime
from pathlib import Path
from typing import Any, cast, get_args

from sqlalchemy import CursorResult, delete, event, func, insert, or_, select, text, update
from sqlalchemy.exc import IntegrityError
from sqlalchemy.ext.asyncio import AsyncEngine, async_sessionmaker, create_async_engine

from gateway.errors import DuplicateVehicle, InvalidArgument, NotFound
from gateway.registry.models import (
    AuditRow,
    FlightRow,
    LockRow,
    OperationRow,
    SessionRow,
    StatusTextRow,
    TakeoverRow,
    TrackSampleRow,
    VehicleRow,
)
from gateway.registry.records import (
    AUDIT_MAX_ERROR,
    AUDIT_MAX_JSON,
    AUDIT_MAX_STRING,
    AUDIT_OUTCOME_OF_OPERATION,
    SEVERITY_NAMES,
    AuditEntry,
    AuditOutcome,
    AuditRecord,
    AuditSource,
    FlightRecord,
    LockRecord,
    OperationRecord,
    OperationStatus,
    SessionKind,
    SessionRecord,
    StatusTextIn,
    StatusTextRecord,
    TrackSample,
    VehicleRecord,
    bound_arguments,
    utcnow,
)
from gateway.registry.schema_check import schema_is_current
from gateway.registry.spec import VehicleSpec
from gateway.registry.spool import Spool
from gateway.util.text import printable

# The records are part of the store's API: import them from here or from gateway.registry.records.
__all__ = [
    "AUDIT_MAX_ERROR",
    "AUDIT_MAX_JSON",
    "AUDIT_MAX_STRING",
    "SEVERITY_NAMES",
    "AuditEntry",
    "AuditOutcome",
    "AuditRecord",
    "AuditSource",
    "FlightRecord",
    "LockRecord",
    "OperationRecord",
    "OperationStatus",
    "SessionKind",
    "SessionRecord",
    "SessionSeen",
    "StatusTextIn",
    "StatusTextRecord",
    "Store",
    "TrackSample",
    "VehicleRecord",
    "bound_arguments",
    "create_engine_for",
    "current_revision",
    "head_revision",
    "upgrade_schema",
    "utcnow",
]

log = logging.getLogger(__name__)

#: Called with each audit row this store writes, and again when a row's outcome is finished.
AuditListener = Callable[[AuditRecord], None]
AUDIT_BATCH_S = 0.05
"""The longest a queued audit row waits for others to share its transaction (`Store.queue_audit`);
readers and `close` cut it short."""

ENDED_ELSEWHERE_KEPT = 500
"""Outcomes of operations kept only in memory (fleet operations) remembered for audit rows written late."""


#: how long a start waits for the writes its previous run kept to reach the database
KEPT_REPLAY_S = 30.0


@dataclass(frozen=True)
class SessionSeen:
    """A session seen by one audited call: written with the call's audit row (`Store.queue_audit`)."""

    key: str
    kind: SessionKind
    principal: str | None = None
    client_name: str | None = None
    client_version: str | None = None


# The Alembic scripts ship inside the package (package data, ``gateway/migrations``), so they are found
# wherever pip puts the package: a virtual environment, ``--user``, a distribution's system pip, a
# ``--target`` directory or an editable checkout.
MIGRATIONS_DIR = Path(__file__).resolve().parents[1] / "migrations"


def migrations_dir() -> Path:
    if (MIGRATIONS_DIR / "env.py").is_file():
        return MIGRATIONS_DIR
    raise RuntimeError(
        f"the database migrations are missing: {MIGRATIONS_DIR} has no env.py (a damaged install? "
        "reinstall fleet-gateway)"
    )


SQLITE_BUSY_TIMEOUT_MS = 10_000


def _is_sqlite(url: str) -> bool:
    return url.startswith("sqlite")


def _install_sqlite_pragmas(engine: AsyncEngine) -> None:
    @event.listens_for(engine.sync_engine, "connect")
    def _on_connect(dbapi_connection: Any, _record: Any) -> None:
        cursor = dbapi_connection.cursor()
        cursor.execute(f"PRAGMA busy_timeout={SQLITE_BUSY_TIMEOUT_MS}")
        cursor.execute("PRAGMA journal_mode=WAL")
        cursor.execute("PRAGMA synchronous=NORMAL")
        cursor.execute("PRAGMA foreign_keys=ON")
        cursor.close()


def create_engine_for(url: str) -> AsyncEngine:
    """An async engine for ``url``, with SQLite's pragmas installed when it is SQLite."""
    kwargs: dict[str, Any] = {"pool_pre_ping": not _is_sqlite(url)}
    if _is_sqlite(url):
        kwargs["connect_args"] = {"timeout": SQLITE_BUSY_TIMEOUT_MS / 1000}
    engine = create_async_engine(url, **kwargs)
    if _is_sqlite(url):
        _install_sqlite_pragmas(engine)
    return engine


def alembic_config(url: str) -> Any:
    """An Alembic Config pointing at the project's migrations and ``url``."""
    from alembic.config import Config

    cfg = Config()
    cfg.set_main_option("script_location", str(migrations_dir()))
    cfg.set_main_option("sqlalchemy.url", url.replace("%", "%%"))
    return cfg


# Alembic keeps its migration context in module globals: two upgrades interleaving in one event loop
# would clobber each other, so they take turns (one lock per loop; tests run many loops).
MIGRATION_LOCK_KEY = 0x666C6565  # PostgreSQL advisory lock id of schema upgrades ("flee")
_MIGRATION_LOCKS: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, asyncio.Lock] = (
    weakref.WeakKeyDictionary()
)


async def upgrade_schema(engine: AsyncEngine, url: str, revision: str = "head") -> None:
    """Run Alembic migrations up to ``revision`` on ``engine`` (sharing its connection).

    Across processes, the whole upgrade is one transaction holding the database's write lock (SQLite:
    ``BEGIN IMMEDIATE``; PostgreSQL: an advisory lock): a second gateway or ``db upgrade`` starting at
    the same time waits, then finds the schema current.
    """
    from alembic import command

    cfg = alembic_config(url)

    def _run(connection: Any) -> None:
        cfg.attributes["connection"] = connection
        command.upgrade(cfg, revision)

    lock = _MIGRATION_LOCKS.setdefault(asyncio.get_running_loop(), asyncio.Lock())
    async with lock, engine.begin() as conn:
        if conn.dialect.name == "sqlite":
            await conn.exec_driver_sql("BEGIN IMMEDIATE")
        elif conn.dialect.name == "postgresql":  # held until this transaction ends
            await conn.execute(text("SELECT pg_advisory_xact_lock(:key)"), {"key": MIGRATION_LOCK_KEY})
        await conn.run_sync(_run)


def head_revision() -> str:
    """The newest schema revision among the project's migrations."""
    from alembic.script import ScriptDirectory

    head = ScriptDirectory.from_config(alembic_config("sqlite://")).get_current_head()
    assert head is not None, "no migrations found"
    return head


async def current_revision(engine: AsyncEngine) -> str | None:
    from alembic.runtime.migration import MigrationContext

    def _get(connection: Any) -> str | None:
        return MigrationContext.configure(connection).get_current_revision()

    async with engine.connect() as conn:
        return await conn.run_sync(_get)


class Store:
    """Async persistence API over SQLAlchemy. Create with ``await Store.open(url)``."""

    def __init__(self, engine: AsyncEngine, url: str) -> None:
        self.engine = engine
        self.url = url
        self._sessions = async_sessionmaker(engine, expire_on_commit=False)
        self._closed = False
        self._audit_listeners: list[AuditListener] = []
        # operation id -> (status, message) of ended operations this store does not keep (fleet ones)
        self._ended_elsewhere: dict[str, tuple[str, str | None]] = {}
        #: history writes the database could not take (it was unreachable), written when it is back
        self.spool = Spool(apply=self._apply_kept)
        self._kept_writers: dict[str, Callable[[dict[str, Any]], Awaitable[Any]]] = {
            "flight_end": self._write_flight_end,
            "track_samples": self._write_track_samples,
            "status_texts": self._write_status_texts,
            "audit": self._write_audit,
            "audit_batch": self._write_audit_batch_of,
            "operation": self._write_operation,
            "operation_end": self._write_operation_end,
            "lock": self._write_lock,
            "unlock": self._write_unlock,
            "takeover": self._write_takeover,
            "takeover_release": self._write_takeover_release,
        }
        # audit rows (with the session each call touched) waiting for the writer task (queue_audit)
        self._audit_queue: list[tuple[AuditEntry, SessionSeen | None]] = []
        self._audit_writer: asyncio.Task[None] | None = None
        self._audit_flush: asyncio.Event | None = None

    @classmethod
    async def open(cls, url: str, upgrade: bool = True) -> Store:
        engine = create_engine_for(url)
        try:
            if upgrade and not await schema_is_current(engine, migrations_dir()):
                await upgrade_schema(engine, url)
        except BaseException:
            await engine.dispose()
            raise
        return cls(engine, url)

    async def keep_spool_in(self, path: Path) -> int:
        """Keep the writes the database cannot take in ``path`` (JSON lines) as well as in memory, so a
        node killed during an outage writes them after its restart; returns how many a previous run of
        this node left there (they are written, in order, before any new write)."""
        left = await self.spool.attach(path)
        if left and not await self.spool.flush(KEPT_REPLAY_S):  # the locks among them count at once
            log.error(
                "%d writes of the previous run are not written yet: they wait in %s", len(self.spool), path
            )
        return left

    async def _kept(self, what: str, kind: str, data: dict[str, Any]) -> Any:
        """Write now, or keep (``kind``, ``data``: JSON) until the database is back."""
        write = functools.partial(self._apply_kept, kind, data)
        return await self.spool.write(what, write, record=(kind, data))

    async def _apply_kept(self, kind: str, data: dict[str, Any]) -> Any:
        writer = self._kept_writers.get(kind)
        if writer is None:
            kinds = ", ".join(sorted(self._kept_writers))
            raise ValueError(f"unknown kind of kept write {kind!r}; kinds: {kinds}")
        return await writer(data)

    @property
    def is_open(self) -> bool:
        return not self._closed

    async def close(self) -> None:
        if not self._closed:
            await self.flush_audit()  # nothing queued is lost on a clean stop
            self._closed = True
            await self.spool.flush(2.0)
            await self.spool.close()
            await self.engine.dispose()

    async def ping(self) -> bool:
        """True when the database answers a trivial query."""
        try:
            async with self._sessions() as session:
                await session.execute(select(1))
            return True
        except Exception:
            log.exception("database ping failed")
            return False

    # --- vehicles --------------------------------------------------------------------------------

    async def add_vehicle(self, spec: VehicleSpec, auto_connect: bool = True) -> VehicleRecord:
        spec = VehicleSpec.model_validate(spec.model_dump())
        now = utcnow()
        row = VehicleRow(
            id=spec.id,
            url=spec.url,
            name=spec.name,
            tags=list(spec.tags),
            expected_sysid=spec.expected_sysid,
            node_tag=spec.node_tag,
            gcs_endpoints=list(spec.gcs_endpoints),
            auto_connect=auto_connect,
            created_at=now,
            updated_at=now,
        )
        try:
            async with self._sessions.begin() as session:
                if await session.get(VehicleRow, spec.id) is not None:
                    raise DuplicateVehicle(f"a drone with id '{spec.id}' is already registered", id=spec.id)
                session.add(row)
        except IntegrityError as exc:
            raise DuplicateVehicle(f"a drone with id '{spec.id}' is already registered", id=spec.id) from exc
        return VehicleRecord.model_validate(row)

    _UPDATABLE = frozenset(
        {"name", "tags", "expected_sysid", "node_tag", "url", "gcs_endpoints", "auto_connect"}
    )

    async def update_vehicle(self, vehicle_id: str, **changes: Any) -> VehicleRecord:
        unknown = sorted(set(changes) - self._UPDATABLE)
        if unknown:
            raise InvalidArgument(
                f"cannot update field(s) {unknown}; updatable: {sorted(self._UPDATABLE)}", fields=unknown
            )
        async with self._sessions.begin() as session:
            row = await session.get(VehicleRow, vehicle_id)
            if row is None:
                raise NotFound(f"no drone with id '{vehicle_id}' is registered", id=vehicle_id)
            merged = VehicleRecord.model_validate(row).model_dump()
            merged.update(changes)
            if not isinstance(merged["auto_connect"], bool):
                raise InvalidArgument("auto_connect must be true or false", field="auto_connect")
            auto_connect = merged.pop("auto_connect")
            for key in ("created_at", "updated_at"):
                merged.pop(key)
            try:
                spec = VehicleSpec.model_validate(merged)
            except ValueError as exc:
                raise InvalidArgument(f"invalid vehicle update: {exc}", fields=sorted(changes)) from exc
            row.url = spec.url
            row.name = spec.name
            row.tags = list(spec.tags)
            row.expected_sysid = spec.expected_sysid
            row.node_tag = spec.node_tag
            row.gcs_endpoints = list(spec.gcs_endpoints)
            row.auto_connect = auto_connect
            row.updated_at = utcnow()
        return VehicleRecord.model_validate(row)

    async def remove_vehicle(self, vehicle_id: str) -> None:
        async with self._sessions.begin() as session:
            result = await session.execute(delete(VehicleRow).where(VehicleRow.id == vehicle_id))
            if _rowcount(result) == 0:
                raise NotFound(f"no drone with id '{vehicle_id}' is registered", id=vehicle_id)

    async def get_vehicle(self, vehicle_id: str) -> VehicleRecord | None:
        async with self._sessions() as session:
            row = await session.get(VehicleRow, vehicle_id)
            return None if row is None else VehicleRecord.model_validate(row)

    async def list_vehicles(self) -> list[VehicleRecord]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(VehicleRow).order_by(VehicleRow.id))).all()
            return [VehicleRecord.model_validate(r) for r in rows]

    # --- flights ---------------------------------------------------------------------------------

    async def open_flight(
        self,
        vehicle_id: str,
        started_at: datetime,
        home_lat: float | None = None,
        home_lon: float | None = None,
        home_alt_amsl: float | None = None,
    ) -> int:
        row = FlightRow(
            vehicle_id=vehicle_id,
            started_at=started_at,
            home_lat=home_lat,
            home_lon=home_lon,
            home_alt_amsl=home_alt_amsl,
        )
        async with self._sessions.begin() as session:
            session.add(row)
            await session.flush()
            return int(row.id)

    async def close_flight(
        self,
        flight_id: int,
        ended_at: datetime,
        duration_s: float | None = None,
        distance_m: float | None = None,
        max_alt_rel_m: float | None = None,
        battery_used_pct: float | None = None,
    ) -> FlightRecord | None:
        """End a flight; None when the database is unreachable (the end is written when it is back)."""
        data = {
            "flight_id": flight_id, "ended_at": ended_at.isoformat(), "duration_s": duration_s,
            "distance_m": distance_m, "max_alt_rel_m": max_alt_rel_m, "battery_used_pct": battery_used_pct,
        }  # fmt: skip
        kept = await self._kept(f"the end of flight {flight_id}", "flight_end", data)
        return cast(FlightRecord | None, kept)

    async def _write_flight_end(self, data: dict[str, Any]) -> FlightRecord:
        flight_id = int(data["flight_id"])
        async with self._sessions.begin() as session:
            row = await session.get(FlightRow, flight_id)
            if row is None:
                raise NotFound(f"no flight with id {flight_id}", id=flight_id)
            row.ended_at = datetime.fromisoformat(data["ended_at"])
            row.duration_s = data["duration_s"]
            row.distance_m = data["distance_m"]
            row.max_alt_rel_m = data["max_alt_rel_m"]
            row.battery_used_pct = data["battery_used_pct"]
        return FlightRecord.model_validate(row)

    async def list_open_flights(self, vehicle_id: str | None = None) -> list[FlightRecord]:
        query = select(FlightRow).where(FlightRow.ended_at.is_(None))
        if vehicle_id is not None:
            query = query.where(FlightRow.vehicle_id == vehicle_id)
        async with self._sessions() as session:
            rows = (await session.scalars(query.order_by(FlightRow.started_at))).all()
            return [FlightRecord.model_validate(r) for r in rows]

    async def add_track_samples(self, samples: Sequence[TrackSample]) -> int:
        """Insert a batch of track samples in one transaction; returns how many were written (0: kept
        until the database is back)."""
        if not samples:
            return 0
        data = {"rows": [s.model_dump(mode="json") for s in samples]}
        return await self._kept(f"{len(samples)} track samples", "track_samples", data) or 0

    async def _write_track_samples(self, data: dict[str, Any]) -> int:
        rows = [TrackSample.model_validate(r).model_dump() for r in data["rows"]]
        async with self._sessions.begin() as session:
            await session.execute(insert(TrackSampleRow), rows)
        return len(rows)

    async def add_status_texts(self, items: Sequence[StatusTextIn]) -> int:
        if not items:
            return 0
        data = {"rows": [i.model_dump(mode="json") for i in items]}
        return await self._kept(f"{len(items)} status texts", "status_texts", data) or 0

    async def _write_status_texts(self, data: dict[str, Any]) -> int:
        rows = [StatusTextIn.model_validate(r).model_dump() for r in data["rows"]]
        async with self._sessions.begin() as session:
            await session.execute(insert(StatusTextRow), rows)
        return len(rows)

    async def list_flights(
        self,
        vehicle_id: str | None = None,
        since: datetime | None = None,
        until: datetime | None = None,
        limit: int = 50,
        offset: int = 0,
    ) -> tuple[list[FlightRecord], int]:
        """Flights overlapping [since, until], newest first, with the total count for paging."""
        conditions = []
        if vehicle_id is not None:
            conditions.append(FlightRow.vehicle_id == vehicle_id)
        if since is not None:
            conditions.append(or_(FlightRow.ended_at.is_(None), FlightRow.ended_at >= since))
        if until is not None:
            conditions.append(FlightRow.started_at <= until)
        query = select(FlightRow).where(*conditions)
        count = select(func.count()).select_from(FlightRow).where(*conditions)
        async with self._sessions() as session:
            total = int((await session.execute(count)).scalar_one())
            rows = (
                await session.scalars(
                    query.order_by(FlightRow.started_at.desc(), FlightRow.id.desc())
                    .limit(limit)
                    .offset(offset)
                )
            ).all()
            return [FlightRecord.model_validate(r) for r in rows], total

    async def get_flight(self, flight_id: int) -> FlightRecord | None:
        async with self._sessions() as session:
            row = await session.get(FlightRow, flight_id)
            return None if row is None else FlightRecord.model_validate(row)

    async def get_track(self, flight_id: int) -> list[TrackSample]:
        columns = [getattr(TrackSampleRow, name) for name in TrackSample.model_fields]
        query = (
            select(*columns)
            .where(TrackSampleRow.flight_id == flight_id)
            .order_by(TrackSampleRow.t, TrackSampleRow.id)
        )
        async with self._sessions() as session:
            rows = (await session.execute(query)).all()
        # Plain rows, no ORM objects; validated when written, so built without re-validation (long tracks).
        return [TrackSample.model_construct(**row._asdict()) for row in rows]

    async def list_status_texts(
        self, vehicle_id: str, limit: int = 100, since: datetime | None = None
    ) -> list[StatusTextRecord]:
        """The newest ``limit`` status texts of a vehicle, oldest first."""
        query = select(StatusTextRow).where(StatusTextRow.vehicle_id == vehicle_id)
        if since is not None:
            query = query.where(StatusTextRow.t >= since)
        query = query.order_by(StatusTextRow.t.desc(), StatusTextRow.id.desc()).limit(limit)
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [StatusTextRecord.model_validate(r) for r in reversed(rows)]

    async def list_flight_status_texts(self, flight_id: int, limit: int = 500) -> list[StatusTextRecord]:
        """The status texts received during a flight, oldest first (at most ``limit``, the first ones)."""
        query = (
            select(StatusTextRow)
            .where(StatusTextRow.flight_id == flight_id)
            .order_by(StatusTextRow.t, StatusTextRow.id)
            .limit(limit)
        )
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [StatusTextRecord.model_validate(r) for r in rows]

    # --- sessions --------------------------------------------------------------------------------

    async def touch_session(
        self,
        key: str,
        kind: SessionKind,
        principal: str | None = None,
        client_name: str | None = None,
        client_version: str | None = None,
    ) -> SessionRecord:
        """Record that a session was seen now (insert or update; portable, no dialect upsert)."""
        if kind not in get_args(SessionKind):
            raise InvalidArgument(f"unknown session kind '{kind}'", field="kind")
        key = key[:200]
        for attempt in range(2):
            now = utcnow()
            try:
                async with self._sessions.begin() as session:
                    row = await session.get(SessionRow, key)
                    if row is None:
                        row = SessionRow(
                            key=key,
                            kind=kind,
                            principal=principal,
                            client_name=(client_name or None) and client_name[:200],
                            client_version=(client_version or None) and client_version[:100],
                            first_seen=now,
                            last_seen=now,
                            request_count=1,
                        )
                        session.add(row)
                    else:
                        row.last_seen = now
                        row.request_count = (row.request_count or 0) + 1
                        row.kind = kind
                        if principal is not None:
                            row.principal = principal
                        if client_name:
                            row.client_name = client_name[:200]
                        if client_version:
                            row.client_version = client_version[:100]
                return SessionRecord.model_validate(row)
            except IntegrityError:
                if attempt:  # a concurrent insert won twice: give up loudly
                    raise
        raise AssertionError("unreachable")

    async def get_session(self, key: str) -> SessionRecord | None:
        await self.flush_audit()
        async with self._sessions() as session:
            row = await session.get(SessionRow, key)
            return None if row is None else SessionRecord.model_validate(row)

    async def list_sessions(
        self,
        kind: str | None = None,
        principal: str | None = None,
        since: datetime | None = None,
        limit: int = 100,
        offset: int = 0,
    ) -> list[SessionRecord]:
        """Sessions, most recently seen first."""
        await self.flush_audit()
        query = select(SessionRow)
        if kind is not None:
            query = query.where(SessionRow.kind == kind)
        if principal is not None:
            query = query.where(SessionRow.principal == principal)
        if since is not None:
            query = query.where(SessionRow.last_seen >= since)
        query = query.order_by(SessionRow.last_seen.desc(), SessionRow.key).limit(limit).offset(offset)
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [SessionRecord.model_validate(r) for r in rows]

    # --- audit -----------------------------------------------------------------------------------

    def on_audit(self, listener: AuditListener) -> Callable[[], None]:
        """Call ``listener`` with every audit row written (or finished) through this store, after it is
        committed; returns the function that removes it. Listeners run in the writer's task: keep them
        quick and non-blocking (the live event stream queues the row and returns)."""
        self._audit_listeners.append(listener)

        def remove() -> None:
            if listener in self._audit_listeners:
                self._audit_listeners.remove(listener)

        return remove

    def _audit_written(self, row: AuditRow | AuditRecord) -> None:
        if not self._audit_listeners:
            return
        record = row if isinstance(row, AuditRecord) else AuditRecord.model_validate(row)
        for listener in list(self._audit_listeners):
            try:
                listener(record)
            except Exception:  # a broken listener must not fail the audited call
                log.exception("audit listener failed")

    async def add_audit(self, entry: AuditEntry) -> int | None:
        """Write an audit row; its id, or None when the database is unreachable: the row is kept on this
        node, with its time, and written in order when the database is back."""
        values = dict(
            t=entry.t or utcnow(),
            session_key=entry.session_key and printable(entry.session_key, 200),
            principal=entry.principal and printable(entry.principal, 200),
            source=entry.source,
            vehicle_id=entry.vehicle_id and printable(entry.vehicle_id, 32),
            action=printable(entry.action, 100),
            arguments=bound_arguments(entry.arguments),
            outcome=entry.outcome,
            error=entry.error and entry.error[:AUDIT_MAX_ERROR],
            duration_ms=entry.duration_ms,
            operation_id=entry.operation_id,
        )

        t = values["t"]
        data = {"values": {**values, "t": t.isoformat() if isinstance(t, datetime) else t}}
        return cast(int | None, await self._kept(f"the audit row of {values['action']}", "audit", data))

    async def _write_audit(self, data: dict[str, Any]) -> int:
        values = {**data["values"], "t": datetime.fromisoformat(data["values"]["t"])}
        row = AuditRow(**values)  # a fresh row for each attempt
        async with self._sessions.begin() as session:
            session.add(row)
            await session.flush()
            row_id = int(row.id)
        self._audit_written(row)
        if values["outcome"] == "running" and values["operation_id"] is not None:
            await self._finish_if_ended(values["operation_id"])
        return row_id

    def queue_audit(self, entry: AuditEntry, seen: SessionSeen | None = None) -> None:
        """Record one call without waiting for the database (the MCP door's path, per tool call).

        The row, and the touch of the session the call came in (``seen``: last seen, one more request),
        are written by the store's writer task together with the calls queued within ``AUDIT_BATCH_S``,
        in one transaction. Every reader of audit rows or sessions, the finishing of a running row and
        `close` wait for the queue first, so no reader misses a row and a clean stop loses none; a
        batch the database refuses is written again row by row, and a row that still fails is logged
        with its call, as `add_audit`'s callers do."""
        if self._closed:
            raise RuntimeError("the store is closed")
        if entry.t is None:  # the row's time is the call's end, not the batch's write
            entry = entry.model_copy(update={"t": utcnow()})
        self._audit_queue.append((entry, seen))
        if self._audit_writer is None or self._audit_writer.done():
            self._audit_flush = asyncio.Event()
            self._audit_writer = asyncio.get_running_loop().create_task(
                self._write_queued(self._audit_flush), name="audit-writer"
            )

    async def flush_audit(self) -> None:
        """Wait until every queued audit row is written (at once: the batching pause is cut short)."""
        while self._audit_writer is not None and not self._audit_writer.done():
            if self._audit_flush is not None:
                self._audit_flush.set()
            await asyncio.shield(self._audit_writer)

    async def _write_queued(self, flush: asyncio.Event) -> None:
        while self._audit_queue:
            if not flush.is_set():  # calls arriving meanwhile share the transaction
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(flush.wait(), AUDIT_BATCH_S)
            batch, self._audit_queue = self._audit_queue, []
            data = {
                "rows": [
                    {"entry": e.model_dump(mode="json"), "seen": None if s is None else dataclasses.asdict(s)}
                    for e, s in batch
                ]
            }
            try:  # the database unreachable: kept in the spool, in order, with their times
                await self._kept(f"{len(batch)} audit rows", "audit_batch", data)
            except Exception:
                log.exception("could not write %d audit rows at once; writing them one by one", len(batch))
                for item in batch:
                    try:
                        await self._write_audit_batch([item])
                    except Exception:
                        log.exception("could not write the audit row of %s", item[0].action)

    async def _write_audit_batch_of(self, data: dict[str, Any]) -> None:
        await self._write_audit_batch(
            [
                (AuditEntry.model_validate(r["entry"]), SessionSeen(**r["seen"]) if r["seen"] else None)
                for r in data["rows"]
            ]
        )

    async def _write_audit_batch(self, batch: list[tuple[AuditEntry, SessionSeen | None]]) -> None:
        seen: dict[str, tuple[SessionSeen, int]] = {}
        for _entry, s in batch:
            if s is not None:
                seen[s.key[:200]] = (s, seen.get(s.key[:200], (s, 0))[1] + 1)
        values = [self._audit_values(entry) for entry, _ in batch]
        async with self._sessions.begin() as session:
            for key, (s, count) in seen.items():
                await self._touch_in(session, key, s, count)
            statement = insert(AuditRow).returning(AuditRow.id, sort_by_parameter_order=True)
            ids = (await session.scalars(statement, values)).all()
        for (entry, _s), row, row_id in zip(batch, values, ids, strict=True):
            if self._audit_listeners:
                self._audit_written(AuditRecord.model_validate({**row, "id": row_id}))
            if entry.outcome == "running" and entry.operation_id is not None:
                await self._finish_if_ended(entry.operation_id)

    @staticmethod
    async def _touch_in(session: Any, key: str, s: SessionSeen, count: int) -> None:
        """Last seen now and ``count`` more requests (the row is made when it is new)."""
        now = utcnow()
        changes: dict[str, Any] = {
            "last_seen": now,
            "request_count": func.coalesce(SessionRow.request_count, 0) + count,
            "kind": s.kind,
        }
        if s.principal is not None:
            changes["principal"] = s.principal
        if s.client_name:
            changes["client_name"] = s.client_name[:200]
        if s.client_version:
            changes["client_version"] = s.client_version[:100]
        result = await session.execute(update(SessionRow).where(SessionRow.key == key).values(**changes))
        if not _rowcount(result):
            await session.execute(
                insert(SessionRow).values(
                    key=key,
                    kind=s.kind,
                    principal=s.principal,
                    client_name=(s.client_name or None) and s.client_name[:200],
                    client_version=(s.client_version or None) and s.client_version[:100],
                    first_seen=now,
                    last_seen=now,
                    request_count=count,
                )
            )

    @staticmethod
    def _audit_values(entry: AuditEntry) -> dict[str, Any]:
        return {
            "t": entry.t or utcnow(),
            "session_key": entry.session_key and entry.session_key[:200],
            "principal": entry.principal and entry.principal[:200],
            "source": entry.source,
            "vehicle_id": entry.vehicle_id and entry.vehicle_id[:32],
            "action": entry.action[:100],
            "arguments": bound_arguments(entry.arguments),
            "outcome": entry.outcome,
            "error": entry.error and entry.error[:AUDIT_MAX_ERROR],
            "duration_ms": entry.duration_ms,
            "operation_id": entry.operation_id,
        }

    async def _finish_if_ended(self, operation_id: str) -> None:
        """A running row was just written: the operation may have ended before, and then nobody else
        finishes the row."""
        ended = self._ended_elsewhere.get(operation_id)
        if ended is not None:
            await self._finish_audit_rows(operation_id, *ended)
            return
        op = await self.get_operation(operation_id)
        if op is not None and op.status != "running":
            await self._finish_audit_rows(operation_id, op.status, op.message)

    def _audit_conditions(
        self,
        vehicle_id: str | None,
        session_key: str | None,
        since: datetime | None = None,
        until: datetime | None = None,
        include_fleet: bool = False,
    ) -> list[Any]:
        conditions: list[Any] = []
        if vehicle_id is not None:
            same = AuditRow.vehicle_id == vehicle_id
            conditions.append(or_(same, AuditRow.vehicle_id.is_(None)) if include_fleet else same)
        if session_key is not None:
            conditions.append(AuditRow.session_key == session_key)
        if since is not None:
            conditions.append(AuditRow.t >= since)
        if until is not None:
            conditions.append(AuditRow.t <= until)
        return conditions

    async def list_audit(
        self,
        vehicle_id: str | None = None,
        session_key: str | None = None,
        limit: int = 100,
        offset: int = 0,
        *,
        since: datetime | None = None,
        until: datetime | None = None,
        include_fleet: bool = False,
    ) -> list[AuditRecord]:
        """Audit entries, newest first; ``since``/``until`` bound their time (inclusive).
        ``include_fleet`` adds, to a ``vehicle_id`` filter, the rows that name no single vehicle
        (fleet-wide calls)."""
        await self.flush_audit()
        query = (
            select(AuditRow)
            .where(*self._audit_conditions(vehicle_id, session_key, since, until, include_fleet))
            .order_by(AuditRow.t.desc(), AuditRow.id.desc())
            .limit(limit)
            .offset(offset)
        )
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [AuditRecord.model_validate(r) for r in rows]

    async def count_audit(
        self,
        vehicle_id: str | None = None,
        session_key: str | None = None,
        *,
        since: datetime | None = None,
        until: datetime | None = None,
        include_fleet: bool = False,
    ) -> int:
        await self.flush_audit()
        query = select(func.count()).select_from(AuditRow)
        query = query.where(*self._audit_conditions(vehicle_id, session_key, since, until, include_fleet))
        async with self._sessions() as session:
            return int((await session.execute(query)).scalar_one())

    # --- operations ------------------------------------------------------------------------------

    async def save_operation(self, op: OperationRecord) -> OperationRecord:
        """Insert or update; an operation that has ended also finishes the audit rows of the calls that
        left it running (whichever node ends it: its owner, or the node that took the drone over)."""
        await self._kept(f"operation {op.id} ({op.status})", "operation", {"op": op.model_dump(mode="json")})
        return op

    async def _write_operation(self, data: dict[str, Any]) -> None:
        op = OperationRecord.model_validate(data["op"])
        values = op.model_dump()
        async with self._sessions.begin() as session:
            row = await session.get(OperationRow, op.id)
            if row is None:
                session.add(OperationRow(**values))
            else:
                for key, value in values.items():
                    if key != "id":
                        setattr(row, key, value)
        if op.status != "running":
            await self._finish_audit_of(op.id, op.status, op.message)

    async def finish_audit_of(self, operation_id: str, status: str, message: str | None) -> None:
        """An operation this store does not keep (a fleet operation, held in memory by its node) ended:
        finish the audit rows of the calls that left it running, and remember how it ended so that a
        row written after this (the call's row is written once its answer is sent) is finished too."""
        self._ended_elsewhere[operation_id] = (status, message)
        while len(self._ended_elsewhere) > ENDED_ELSEWHERE_KEPT:
            del self._ended_elsewhere[next(iter(self._ended_elsewhere))]
        data = {"operation_id": operation_id, "status": status, "message": message}
        await self._kept(f"the end of operation {operation_id}", "operation_end", data)

    async def _write_operation_end(self, data: dict[str, Any]) -> None:
        await self._finish_audit_of(data["operation_id"], data["status"], data["message"])

    async def _finish_audit_of(self, operation_id: str, status: str, message: str | None) -> None:
        await self.flush_audit()  # a row still queued is finished too
        await self._finish_audit_rows(operation_id, status, message)

    async def _finish_audit_rows(self, operation_id: str, status: str, message: str | None) -> None:
        outcome = AUDIT_OUTCOME_OF_OPERATION.get(status, "error")
        async with self._sessions.begin() as session:
            query = select(AuditRow).where(
                AuditRow.operation_id == operation_id, AuditRow.outcome == "running"
            )
            rows = (await session.scalars(query)).all()
            for row in rows:
                row.outcome = outcome
                row.error = None if outcome == "ok" else (message or status)[:AUDIT_MAX_ERROR]
        for row in rows:  # the console's audit stream shows the row again, finished
            self._audit_written(row)

    async def get_operation(self, operation_id: str) -> OperationRecord | None:
        async with self._sessions() as session:
            row = await session.get(OperationRow, operation_id)
            return None if row is None else OperationRecord.model_validate(row)

    async def list_operations(
        self, vehicle_id: str | None = None, status: str | Sequence[str] | None = None, limit: int = 50
    ) -> list[OperationRecord]:
        """Operations, newest first; ``status`` may be one status or several."""
        query = select(OperationRow)
        if vehicle_id is not None:
            query = query.where(OperationRow.vehicle_id == vehicle_id)
        if isinstance(status, str):
            query = query.where(OperationRow.status == status)
        elif status is not None:
            query = query.where(OperationRow.status.in_(list(status)))
        query = query.order_by(OperationRow.created_at.desc(), OperationRow.id).limit(limit)
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [OperationRecord.model_validate(r) for r in rows]

    # --- operator locks --------------------------------------------------------------------------

    async def save_lock(self, scope: str, reason: str, by: str, locked_at: datetime) -> LockRecord | None:
        """Store (or replace) the lock of ``scope``; None when the database is unreachable (it is
        stored, in order, when the database is back)."""
        data = {"scope": scope, "reason": reason, "by": by[:200], "locked_at": locked_at.isoformat()}
        return cast(LockRecord | None, await self._kept(f"the lock of {scope}", "lock", data))

    async def _write_lock(self, data: dict[str, Any]) -> LockRecord:
        scope, reason, by = data["scope"], data["reason"], data["by"]
        locked_at = datetime.fromisoformat(data["locked_at"])
        async with self._sessions.begin() as session:
            row = await session.get(LockRow, scope)
            if row is None:
                session.add(LockRow(scope=scope, reason=reason, locked_by=by, locked_at=locked_at))
            else:
                row.reason, row.locked_by, row.locked_at = reason, by, locked_at
        return LockRecord(scope=scope, reason=reason, by=by, locked_at=locked_at)

    async def delete_lock(self, scope: str) -> bool:
        """Remove the lock of ``scope``; False when there was none (or the database is unreachable:
        then it is removed when the database is back)."""
        return bool(await self._kept(f"the unlock of {scope}", "unlock", {"scope": scope}))

    async def _write_unlock(self, data: dict[str, Any]) -> bool:
        async with self._sessions.begin() as session:
            result = await session.execute(delete(LockRow).where(LockRow.scope == data["scope"]))
            return bool(_rowcount(result))

    async def list_locks(self) -> list[LockRecord]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(LockRow).order_by(LockRow.scope))).all()
            return [
                LockRecord(scope=r.scope, reason=r.reason, by=r.locked_by, locked_at=r.locked_at)
                for r in rows
            ]

    # --- takeover locks (gateway.fleet.takeover) ----------------------------------------------------

    async def save_takeover(
        self, vehicle_id: str, reason: str, by: str, locked_at: datetime
    ) -> LockRecord | None:
        """Store (or replace) the takeover lock of a drone; None when the database is unreachable (it is
        stored, in order, when the database is back)."""
        data = {"vehicle_id": vehicle_id, "reason": reason, "by": by[:200]} | {
            "locked_at": locked_at.isoformat()
        }
        kept = await self._kept(f"the takeover lock of {vehicle_id}", "takeover", data)
        return cast(LockRecord | None, kept)

    async def _write_takeover(self, data: dict[str, Any]) -> LockRecord:
        vehicle_id, reason, by = data["vehicle_id"], data["reason"], data["by"]
        locked_at = datetime.fromisoformat(data["locked_at"])
        async with self._sessions.begin() as session:
            row = await session.get(TakeoverRow, vehicle_id)
            if row is None:
                session.add(
                    TakeoverRow(vehicle_id=vehicle_id, reason=reason, locked_by=by, locked_at=locked_at)
                )
            else:
                row.reason, row.locked_by, row.locked_at = reason, by, locked_at
        return LockRecord(scope=vehicle_id, reason=reason, by=by, locked_at=locked_at)

    async def delete_takeover(self, vehicle_id: str) -> bool:
        """Remove a drone's takeover lock; False when there was none (or the database is unreachable:
        then it is removed when the database is back)."""
        data = {"vehicle_id": vehicle_id}
        return bool(await self._kept(f"the release of {vehicle_id}", "takeover_release", data))

    async def _write_takeover_release(self, data: dict[str, Any]) -> bool:
        async with self._sessions.begin() as session:
            result = await session.execute(
                delete(TakeoverRow).where(TakeoverRow.vehicle_id == data["vehicle_id"])
            )
            return bool(_rowcount(result))

    async def list_takeovers(self) -> list[LockRecord]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(TakeoverRow).order_by(TakeoverRow.vehicle_id))).all()
            return [
                LockRecord(scope=r.vehicle_id, reason=r.reason, by=r.locked_by, locked_at=r.locked_at)
                for r in rows
            ]

    # --- retention -------------------------------------------------------------------------------

    async def prune(self, before: datetime) -> dict[str, int]:
        """Delete history older than ``before``: flights that ended before it (with their tracks),
        status texts, audit entries, sessions last seen and operations finished before it.
        Registrations, locks, open flights and running operations are kept. Returns rows deleted."""
        old_flights = select(FlightRow.id).where(FlightRow.ended_at.is_not(None), FlightRow.ended_at < before)
        counts: dict[str, int] = {}
        await self.flush_audit()
        async with self._sessions.begin() as session:
            steps = [
                ("track_samples", delete(TrackSampleRow).where(TrackSampleRow.flight_id.in_(old_flights))),
                ("status_texts", delete(StatusTextRow).where(StatusTextRow.t < before)),
                ("flights", delete(FlightRow).where(FlightRow.id.in_(old_flights))),
                ("audit", delete(AuditRow).where(AuditRow.t < before)),
                ("sessions", delete(SessionRow).where(SessionRow.last_seen < before)),
                (
                    "operations",
                    delete(OperationRow).where(
                        OperationRow.finished_at.is_not(None), OperationRow.finished_at < before
                    ),
                ),
            ]
            for name, statement in steps:
                result = await session.execute(statement.execution_options(synchronize_session=False))
                counts[name] = _rowcount(result)
        return counts


def _rowcount(result: object) -> int:
    """Rows a DELETE/UPDATE touched (``Session.execute`` is typed as returning a plain ``Result``)."""
    return int(result.rowcount or 0) if isinstance(result, CursorResult) else 0
