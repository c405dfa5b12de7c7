"""The store's tracked operations."""

from __future__ import annotations

import logging
from collections.abc import Sequence

from sqlalchemy import insert, select, update

from gateway.registry.models import operations
from gateway.registry.records import OperationRecord
from gateway.registry.store_audit import AuditTrail
from gateway.registry.store_core import row_by_key, rowcount
from gateway.util.json_types import JsonObject

log = logging.getLogger(__name__)

#: the one status an operation row may leave; every other is its end
RUNNING = "running"


class OperationTable(AuditTrail):
    """Tracked operations; one that has ended finishes the audit rows of the calls that left it running."""

    async def save_operation(self, op: OperationRecord) -> OperationRecord:
        """Insert or update; an operation that has ended also finishes the audit rows of the calls that
        left it running (whichever node ends it: its owner, or the node that took the drone over)."""
        data: JsonObject = {"op": op.model_dump(mode="json")}
        await self._kept(f"operation {op.id} ({op.status})", "operation", data, self._write_operation)
        return op

    async def _write_operation(self, data: JsonObject) -> None:
        """The row as ``data`` has it, unless the stored one has ended: an ended operation is final. A
        write kept while the database was down (a node's spool) reaches it late, possibly after the node
        that took the drone over ended the operation; it never brings it back to running, nor changes
        how it ended."""
        op = OperationRecord.model_validate(data["op"])
        values = op.model_dump()
        async with self.engine.begin() as conn:
            if await row_by_key(conn, operations, op.id) is None:
                await conn.execute(insert(operations).values(values))
                written = True
            else:
                changes = {key: value for key, value in values.items() if key != "id"}
                result = await conn.execute(
                    update(operations)
                    .where(operations.c.id == op.id, operations.c.status == RUNNING)
                    .values(changes)
                )
                written = rowcount(result) > 0
        if not written:
            log.info("operation %s (%s) is not written: it has ended in the database already", op.id,
                     op.status)  # fmt: skip
            return
        if op.status != RUNNING:
            await self._finish_audit_of(op.id, op.status, op.message, op.finished_at or op.updated_at)

    async def get_operation(self, operation_id: str) -> OperationRecord | None:
        async with self.engine.connect() as conn:
            row = await row_by_key(conn, operations, operation_id)
        return None if row is None else OperationRecord.model_validate(row)

    async def list_operations(
        self, vehicle_id: str | None = None, status: str | Sequence[str] | None = None, limit: int = 50
    ) -> list[OperationRecord]:
        """Operations, newest first; ``status`` may be one status or several."""
        query = select(operations)
        if vehicle_id is not None:
            query = query.where(operations.c.vehicle_id == vehicle_id)
        if isinstance(status, str):
            query = query.where(operations.c.status == status)
        elif status is not None:
            query = query.where(operations.c.status.in_(list(status)))
        query = query.order_by(operations.c.created_at.desc(), operations.c.id).limit(limit)
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query)).mappings().all()
        return [OperationRecord.model_validate(r) for r in rows]
