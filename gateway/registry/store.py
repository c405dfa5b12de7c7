"""Persistence of the gateway: vehicles, flights and tracks, status texts, sessions, audit, operations.

``await Store.open(url)`` upgrades the schema to Alembic head and returns a ready store. Every method
returns plain pydantic records, built from Core rows (no ORM: `gateway.registry.models`). Only
portable SQL is used, so a PostgreSQL (asyncpg) URL works as well as the SQLite (aiosqlite) default;
SQLite gets WAL mode and a busy timeout.
"""

from __future__ import annotations

from datetime import datetime

from sqlalchemy import delete, select

from gateway.registry.database import create_engine_for, migrations_dir, upgrade_schema
from gateway.registry.models import audit, flights, operations, sessions, status_texts, track_samples
from gateway.registry.records import (
    AUDIT_MAX_ERROR,
    AUDIT_MAX_JSON,
    AUDIT_MAX_STRING,
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
from gateway.registry.sql_async import AsyncEngine
from gateway.registry.store_core import rowcount
from gateway.registry.store_flights import FlightTables
from gateway.registry.store_locks import LockTables
from gateway.registry.store_operations import OperationTable
from gateway.registry.store_origins import OriginTable
from gateway.registry.store_plans import PlanExtrasTable
from gateway.registry.store_vehicles import VehicleTable

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
    "StatusTextIn",
    "StatusTextRecord",
    "Store",
    "TrackSample",
    "VehicleRecord",
    "bound_arguments",
    "utcnow",
]


class Store(VehicleTable, FlightTables, LockTables, OperationTable, OriginTable, PlanExtrasTable):
    """Async persistence API over SQLAlchemy. Create with ``await Store.open(url)``.

    Its tables: `VehicleTable`, `FlightTables`, `LockTables`, `OperationTable`, `OriginTable`,
    `PlanExtrasTable` and the `AuditTrail` under
    it (the audit rows and sessions), all over `StoreCore` (the engine and the spool)."""

    def __init__(self, engine: AsyncEngine, url: str) -> None:
        super().__init__(engine, url)
        self._kept_writers.update(
            {
                "flight_end": self._write_flight_end,
                "track_samples": self._write_track_samples,
                "status_texts": self._write_status_texts,
                "audit": self._write_audit,
                "audit_batch": self._write_audit_batch_of,
                "audit_call_end": self._write_call_end,
                "operation": self._write_operation,
                "operation_end": self._write_operation_end,
                **self._lock_writers(),
            }
        )

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

    async def close(self) -> None:
        if not self._closed:
            await self.flush_audit()  # nothing queued is lost on a clean stop
            self._closed = True
            await self.spool.flush(2.0)
            await self.spool.close()
            await self.engine.dispose()

    # --- retention -------------------------------------------------------------------------------

    async def prune(self, before: datetime) -> dict[str, int]:
        """Delete history older than ``before``: flights that ended before it (with their tracks),
        status texts, audit entries, sessions last seen and operations finished before it.
        Registrations, locks, open flights and running operations are kept. Returns rows deleted."""
        old_flights = select(flights.c.id).where(flights.c.ended_at.is_not(None), flights.c.ended_at < before)
        counts: dict[str, int] = {}
        await self.flush_audit()
        async with self.engine.begin() as conn:
            steps = [
                ("track_samples", delete(track_samples).where(track_samples.c.flight_id.in_(old_flights))),
                ("status_texts", delete(status_texts).where(status_texts.c.t < before)),
                ("flights", delete(flights).where(flights.c.id.in_(old_flights))),
                ("audit", delete(audit).where(audit.c.t < before)),
                ("sessions", delete(sessions).where(sessions.c.last_seen < before)),
                (
                    "operations",
                    delete(operations).where(
                        operations.c.finished_at.is_not(None), operations.c.finished_at < before
                    ),
                ),
            ]
            for name, statement in steps:
                counts[name] = rowcount(await conn.execute(statement))
        return counts
