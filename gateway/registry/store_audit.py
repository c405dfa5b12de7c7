"""The store's audit trail: every call's audit row (written at once, or queued by the MCP door and
written in batches by a writer task within AUDIT_BATCH_S, or, for a call that commands a drone, written
before the command is sent and finished when the call ends: `AuditCall`), the sessions the calls came
in, the live listeners of written rows, and the finishing of rows left running once their operation
ends."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import uuid
from collections.abc import Awaitable, Callable
from datetime import UTC, datetime
from typing import get_args

from sqlalchemy import Insert, RowMapping, func, insert, or_, select, update
from sqlalchemy.exc import IntegrityError
from sqlalchemy.sql.elements import ColumnElement

from gateway.errors import InvalidArgument
from gateway.registry.audit_kept import (
    CallRowChanges,
    KeptAudit,
    KeptAuditBatch,
    KeptCallEnd,
    KeptCallRow,
    KeptOperationEnd,
    SessionSeen,
)
from gateway.registry.models import audit, operations, sessions
from gateway.registry.records import (
    AUDIT_MAX_ERROR,
    AUDIT_OUTCOME_OF_OPERATION,
    AuditEntry,
    AuditRecord,
    SessionKind,
    SessionRecord,
    bound_arguments,
    utcnow,
)
from gateway.registry.sql_async import AsyncConnection, AsyncEngine
from gateway.registry.store_core import StoreCore, row_by_key, rowcount
from gateway.util.json_types import JsonObject
from gateway.util.text import printable

log = logging.getLogger(__name__)

#: Called with each audit row this store writes, and again when a row's outcome is finished.
AuditListener = Callable[[AuditRecord], None]
AUDIT_BATCH_S = 0.05
"""The longest a queued audit row waits for others to share its transaction (`Store.queue_audit`);
readers and `close` cut it short."""

ENDED_ELSEWHERE_KEPT = 500
"""Outcomes of operations kept only in memory (fleet operations) remembered for audit rows written late."""


class AuditTrail(StoreCore):
    """The audit rows of the calls, written at once or queued, and the sessions the calls came in; a row
    left running is finished when its operation ends."""

    def __init__(self, engine: AsyncEngine, url: str) -> None:
        super().__init__(engine, url)
        self._audit_listeners: list[AuditListener] = []
        # operation id -> (status, message) of ended operations this store does not keep (fleet ones)
        self._ended_elsewhere: dict[str, tuple[str, str | None, datetime]] = {}
        # audit rows (with the session each call touched) waiting for the writer task (queue_audit)
        self._audit_queue: list[tuple[AuditEntry, SessionSeen | None]] = []
        self._audit_writer: asyncio.Task[None] | None = None
        self._audit_flush: asyncio.Event | None = None
        # the writes of calls' rows under way (`AuditCall`): readers and `close` wait for them too
        self._call_writes: set[asyncio.Task[None]] = set()

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
                async with self.engine.begin() as conn:
                    row = await row_by_key(conn, sessions, key)
                    if row is None:
                        values: dict[str, object] = {
                            "key": key,
                            "kind": kind,
                            "principal": principal,
                            "client_name": (client_name or None) and client_name[:200],
                            "client_version": (client_version or None) and client_version[:100],
                            "first_seen": now,
                            "last_seen": now,
                            "request_count": 1,
                        }
                        await conn.execute(insert(sessions).values(values))
                    else:
                        changes: dict[str, object] = {
                            "last_seen": now,
                            "request_count": (row["request_count"] or 0) + 1,
                            "kind": kind,
                        }
                        if principal is not None:
                            changes["principal"] = principal
                        if client_name:
                            changes["client_name"] = client_name[:200]
                        if client_version:
                            changes["client_version"] = client_version[:100]
                        await conn.execute(update(sessions).where(sessions.c.key == key).values(changes))
                        values = {**row, **changes}
                return SessionRecord.model_validate(values)
            except IntegrityError:
                if attempt:  # a concurrent insert won twice: give up loudly
                    raise
        raise AssertionError("unreachable")

    async def get_session(self, key: str) -> SessionRecord | None:
        await self.flush_audit()
        async with self.engine.connect() as conn:
            row = await row_by_key(conn, sessions, key)
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
        query = select(sessions)
        if kind is not None:
            query = query.where(sessions.c.kind == kind)
        if principal is not None:
            query = query.where(sessions.c.principal == principal)
        if since is not None:
            query = query.where(sessions.c.last_seen >= since)
        query = query.order_by(sessions.c.last_seen.desc(), sessions.c.key).limit(limit).offset(offset)
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query)).mappings().all()
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

    def _audit_written(self, row: RowMapping | AuditRecord) -> None:
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
        bounded = AuditEntry(
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
        data = KeptAudit(values=bounded).model_dump(mode="json")
        return await self._kept(f"the audit row of {bounded.action}", "audit", data, self._write_audit)

    async def _write_audit(self, data: JsonObject) -> int:
        kept = KeptAudit.model_validate(data)
        values, call_id = kept.values.model_dump(), kept.call_id
        statement = self._insert_once().returning(audit.c.id)
        async with self.engine.begin() as conn:
            row_id = (await conn.execute(statement, [{**values, "call_id": call_id}])).scalars().first()
            if row_id is None:  # written by an earlier try (its answer lost): that row, not a second one
                query = select(audit.c.id).where(audit.c.call_id == call_id)
                return int((await conn.execute(query)).scalars().one())
        self._audit_written(AuditRecord.model_validate({**values, "id": row_id}))
        if kept.values.outcome == "running" and kept.values.operation_id is not None:
            await self._finish_if_ended(kept.values.operation_id)
        return int(row_id)

    def _insert_once(self) -> Insert:
        """An insert of audit rows that skips a row whose call id is already stored: a write tried again
        (its first try timed out after its commit, or the spool wrote it again) adds no row."""
        # each dialect's insert is imported for the database in use only (a SQLite gateway never loads
        # PostgreSQL's: tests/test_lean_start.py)
        if self.engine.dialect.name == "postgresql":
            from sqlalchemy.dialects import postgresql

            return postgresql.insert(audit).on_conflict_do_nothing(index_elements=[audit.c.call_id])
        if self.engine.dialect.name == "sqlite":
            from sqlalchemy.dialects import sqlite

            return sqlite.insert(audit).on_conflict_do_nothing(index_elements=[audit.c.call_id])
        name = self.engine.dialect.name
        raise ValueError(f"the audit trail needs PostgreSQL or SQLite; the database is {name}")

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
        """Wait until every queued audit row is written (at once: the batching pause is cut short), and
        every call row's write under way (`AuditCall`) has ended."""
        while self._audit_writer is not None and not self._audit_writer.done():
            if self._audit_flush is not None:
                self._audit_flush.set()
            await asyncio.shield(self._audit_writer)
        current = asyncio.current_task()
        pending = [t for t in self._call_writes if t is not current and not t.done()]
        if pending:
            await asyncio.wait(pending)

    def audit_call(self, entry: AuditEntry, seen: SessionSeen | None = None) -> AuditCall:
        """Start writing the row of a call that is about to command a drone (outcome running), with the
        touch of its session; the call's handle, to wait for that write and to finish the row."""
        if self._closed:
            raise RuntimeError("the store is closed")
        if entry.t is None:  # the row's time is the moment the call was taken
            entry = entry.model_copy(update={"t": utcnow()})
        return AuditCall(self, entry, seen)

    def _call_write(self, write: Awaitable[None], after: asyncio.Task[None] | None) -> asyncio.Task[None]:
        """A call row's write, run after the one before it (``after``) has ended."""

        async def ordered() -> None:
            if after is not None:
                await asyncio.wait({after})
            await write

        task = asyncio.get_running_loop().create_task(ordered(), name="audit-call")
        self._call_writes.add(task)
        task.add_done_callback(self._call_writes.discard)
        return task

    async def _begin_call_row(self, call_id: str, entry: AuditEntry, seen: SessionSeen | None) -> None:
        data = KeptAuditBatch(rows=[KeptCallRow(entry=entry, seen=seen, call_id=call_id)])
        try:  # the database unreachable: kept in the spool (on disk too), in order, with its time
            await self._kept_batch(f"the audit row of {entry.action}", data)
        except Exception:
            log.exception("could not write the audit row of %s", entry.action)

    async def _change_call_row(self, call_id: str, what: str, changes: CallRowChanges) -> None:
        data = KeptCallEnd(call_id=call_id, changes=changes).model_dump(mode="json", exclude_unset=True)
        try:
            await self._kept(f"the audit row's end of {what}", "audit_call_end", data, self._write_call_end)
        except Exception:
            log.exception("could not finish the audit row of %s", what)

    async def _write_call_end(self, data: JsonObject) -> None:
        """A call row's later write: its outcome, error, duration and operation; a row left running with
        an operation that has already ended takes that operation's outcome."""
        kept = KeptCallEnd.model_validate(data)
        changes = kept.changes.model_dump(exclude_unset=True)
        if isinstance(changes.get("error"), str):
            changes["error"] = changes["error"][:AUDIT_MAX_ERROR]
        written: list[AuditRecord] = []
        async with self.engine.begin() as conn:
            query = select(audit).where(audit.c.call_id == kept.call_id)
            for row in (await conn.execute(query)).mappings().all():
                finished = row["outcome"] != "running" and changes.get("outcome") == "running"
                # one its operation's end finished keeps that outcome
                kept_changes = {
                    key: value
                    for key, value in changes.items()
                    if not (finished and key in ("outcome", "error"))
                }
                if kept_changes:
                    await conn.execute(update(audit).where(audit.c.id == row["id"]).values(kept_changes))
                written.append(AuditRecord.model_validate({**row, **kept_changes}))
        for record in written:
            self._audit_written(record)
        operation_id = changes.get("operation_id")
        if written and isinstance(operation_id, str) and written[0].outcome == "running":
            await self._finish_if_ended(operation_id)

    async def _write_queued(self, flush: asyncio.Event) -> None:
        while self._audit_queue:
            if not flush.is_set():  # calls arriving meanwhile share the transaction
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(flush.wait(), AUDIT_BATCH_S)
            batch, self._audit_queue = self._audit_queue, []
            data = self._batch_data(batch)
            try:  # the database unreachable: kept in the spool, in order, with their times
                await self._kept_batch(f"{len(batch)} audit rows", data)
            except Exception:
                log.exception("could not write %d audit rows at once; writing them one by one", len(batch))
                for (entry, _seen), row in zip(batch, data.rows, strict=True):
                    try:
                        await self._write_kept_batch(KeptAuditBatch(rows=[row]))
                    except Exception:
                        log.exception("could not write the audit row of %s", entry.action)

    @staticmethod
    def _batch_data(batch: list[tuple[AuditEntry, SessionSeen | None]]) -> KeptAuditBatch:
        """The rows as the spool keeps them, each with a fresh call id (its row is written once, however
        often the write is tried)."""
        return KeptAuditBatch(rows=[KeptCallRow(entry=e, seen=s) for e, s in batch])

    async def _kept_batch(self, what: str, batch: KeptAuditBatch) -> None:
        data = batch.model_dump(mode="json")
        await self._kept(what, "audit_batch", data, self._write_audit_batch_of)

    async def _write_audit_batch_of(self, data: JsonObject) -> None:
        await self._write_kept_batch(KeptAuditBatch.model_validate(data))

    async def _write_kept_batch(self, kept: KeptAuditBatch) -> None:
        batch = [(r.entry, r.seen) for r in kept.rows]
        await self._write_audit_batch(batch, [r.call_id for r in kept.rows])

    async def _write_audit_batch(
        self, batch: list[tuple[AuditEntry, SessionSeen | None]], call_ids: list[str]
    ) -> None:
        """Insert the rows whose call id is not stored yet, and touch their sessions, in one transaction.
        A row already stored (an earlier try of this write committed, and its answer was lost to a
        timeout, or the spool wrote it again) is neither inserted nor counted again."""
        values = [self._audit_values(entry) for entry, _ in batch]
        rows = [{**v, "call_id": call_id} for v, call_id in zip(values, call_ids, strict=True)]
        statement = self._insert_once().returning(audit.c.id, audit.c.call_id)
        async with self.engine.begin() as conn:
            inserted = {c: i for i, c in (await conn.execute(statement, rows)).all()}
            seen: dict[str, tuple[SessionSeen, int]] = {}
            for (_entry, s), call_id in zip(batch, call_ids, strict=True):
                if s is not None and call_id in inserted:
                    seen[s.key[:200]] = (s, seen.get(s.key[:200], (s, 0))[1] + 1)
            for key, (s, count) in seen.items():
                await self._touch_in(conn, key, s, count)
        for (entry, _s), row, call_id in zip(batch, values, call_ids, strict=True):
            if self._audit_listeners and call_id in inserted:
                self._audit_written(AuditRecord.model_validate({**row, "id": inserted[call_id]}))
            if entry.outcome == "running" and entry.operation_id is not None:
                await self._finish_if_ended(entry.operation_id)

    @staticmethod
    async def _touch_in(conn: AsyncConnection, key: str, s: SessionSeen, count: int) -> None:
        """Last seen now and ``count`` more requests (the row is made when it is new)."""
        now = utcnow()
        changes: dict[str, object] = {
            "last_seen": now,
            "request_count": func.coalesce(sessions.c.request_count, 0) + count,
            "kind": s.kind,
        }
        if s.principal is not None:
            changes["principal"] = s.principal
        if s.client_name:
            changes["client_name"] = s.client_name[:200]
        if s.client_version:
            changes["client_version"] = s.client_version[:100]
        result = await conn.execute(update(sessions).where(sessions.c.key == key).values(**changes))
        if not rowcount(result):
            await conn.execute(
                insert(sessions).values(
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
    def _audit_values(entry: AuditEntry) -> dict[str, object]:
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
        async with self.engine.connect() as conn:
            op = await row_by_key(conn, operations, operation_id)
        if op is not None and op["status"] != "running":
            await self._finish_audit_rows(
                operation_id, op["status"], op["message"], op["finished_at"] or op["updated_at"]
            )

    def _audit_conditions(
        self,
        vehicle_id: str | None,
        session_key: str | None,
        since: datetime | None = None,
        until: datetime | None = None,
        include_fleet: bool = False,
    ) -> list[ColumnElement[bool]]:
        conditions: list[ColumnElement[bool]] = []
        if vehicle_id is not None:
            same = audit.c.vehicle_id == vehicle_id
            conditions.append(or_(same, audit.c.vehicle_id.is_(None)) if include_fleet else same)
        if session_key is not None:
            conditions.append(audit.c.session_key == session_key)
        if since is not None:
            conditions.append(audit.c.t >= since)
        if until is not None:
            conditions.append(audit.c.t <= until)
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
            select(audit)
            .where(*self._audit_conditions(vehicle_id, session_key, since, until, include_fleet))
            .order_by(audit.c.t.desc(), audit.c.id.desc())
            .limit(limit)
            .offset(offset)
        )
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query)).mappings().all()
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
        query = select(func.count()).select_from(audit)
        query = query.where(*self._audit_conditions(vehicle_id, session_key, since, until, include_fleet))
        async with self.engine.connect() as conn:
            return int((await conn.execute(query)).scalar_one())

    async def finish_audit_of(self, operation_id: str, status: str, message: str | None) -> None:
        """An operation this store does not keep (a fleet operation, held in memory by its node) ended:
        finish the audit rows of the calls that left it running, and remember how it ended so that a
        row written after this (the call's row is written once its answer is sent) is finished too."""
        ended_at = utcnow()
        self._ended_elsewhere[operation_id] = (status, message, ended_at)
        while len(self._ended_elsewhere) > ENDED_ELSEWHERE_KEPT:
            del self._ended_elsewhere[next(iter(self._ended_elsewhere))]
        end = KeptOperationEnd(operation_id=operation_id, status=status, message=message, ended_at=ended_at)
        data = end.model_dump(mode="json")
        await self._kept(
            f"the end of operation {operation_id}", "operation_end", data, self._write_operation_end
        )

    async def _write_operation_end(self, data: JsonObject) -> None:
        end = KeptOperationEnd.model_validate(data)
        ended_at = end.ended_at or utcnow()  # a kept write of an older version has none: now is the nearest
        await self._finish_audit_of(end.operation_id, end.status, end.message, ended_at)

    async def _finish_audit_of(
        self, operation_id: str, status: str, message: str | None, ended_at: datetime
    ) -> None:
        await self.flush_audit()  # a row still queued is finished too
        await self._finish_audit_rows(operation_id, status, message, ended_at)

    async def _finish_audit_rows(
        self, operation_id: str, status: str, message: str | None, ended_at: datetime
    ) -> None:
        """The rows of the calls that left ``operation_id`` running take its outcome, and its whole
        duration (from the call to the operation's end) rather than the time the call took to answer."""
        outcome = AUDIT_OUTCOME_OF_OPERATION.get(status, "error")
        error = None if outcome == "ok" else (message or status)[:AUDIT_MAX_ERROR]
        finished: list[AuditRecord] = []
        async with self.engine.begin() as conn:
            query = select(audit).where(audit.c.operation_id == operation_id, audit.c.outcome == "running")
            for row in (await conn.execute(query)).mappings().all():
                took_ms = (_aware(ended_at) - _aware(row["t"])).total_seconds() * 1000.0
                duration_ms = max(took_ms, row["duration_ms"] or 0.0)
                changes = {"outcome": outcome, "error": error, "duration_ms": duration_ms}
                await conn.execute(update(audit).where(audit.c.id == row["id"]).values(changes))
                finished.append(AuditRecord.model_validate({**row, **changes}))
        for record in finished:  # the console's audit stream shows the row again, finished
            self._audit_written(record)


class AuditCall:
    """The audit row of one call that commands a drone: written before the command is sent (outcome
    running), so a node killed while the call runs keeps it (the database has it, or the node's spool file
    until the database does); then the operation the call started, and the call's end, each written after
    the write before it. A row whose operation is named stays running until that operation ends, on
    whichever node, and takes its outcome (`AuditTrail.finish_audit_of`, `Store.save_operation`)."""

    def __init__(self, trail: AuditTrail, entry: AuditEntry, seen: SessionSeen | None) -> None:
        self.id = uuid.uuid4().hex
        self._trail = trail
        self._what = entry.action
        self._last = trail._call_write(trail._begin_call_row(self.id, entry, seen), None)
        self._operation: str | None = None

    async def written(self, within_s: float) -> bool:
        """Wait up to ``within_s`` for the row (in the database, or kept on this node's disk); True when
        it is. The write goes on past that (a database that hangs is waited on for the spool's time)."""
        done, _ = await asyncio.wait({self._last}, timeout=within_s)
        return bool(done)

    def operation(self, operation_id: str) -> None:
        """The call started ``operation_id``: the row names it (its end finishes the row), at once."""
        if operation_id == self._operation:
            return
        self._operation = operation_id
        change = self._trail._change_call_row(self.id, self._what, CallRowChanges(operation_id=operation_id))
        self._last = self._trail._call_write(change, self._last)

    async def end(
        self, outcome: str, error: str | None, duration_ms: float, within_s: float, operation_id: str | None
    ) -> bool:
        """The call ended: its outcome (running, naming its operation, while that still runs), error and
        duration; waited for up to ``within_s`` (True when written)."""
        changes = CallRowChanges(outcome=outcome, error=error, duration_ms=duration_ms)
        if operation_id is not None:
            changes.operation_id = self._operation = operation_id
        change = self._trail._change_call_row(self.id, self._what, changes)
        self._last = self._trail._call_write(change, self._last)
        return await self.written(within_s)


def _aware(t: datetime) -> datetime:
    """SQLite gives back naive datetimes; the store writes UTC."""
    return t if t.tzinfo is not None else t.replace(tzinfo=UTC)
