"""The store's tracked operations."""

from __future__ import annotations

from collections.abc import Sequence

from sqlalchemy import insert, select, update

from gateway.registry.models import operations
from gateway.registry.records import OperationRecord
from gateway.registry.store_audit import AuditTrail
from gateway.registry.store_core import row_by_key
from gateway.util.json_types import JsonObject


class OperationTable(AuditTrail):
    """Tracked operations; one that has ended finishes the audit rows of the calls that left it running."""

    async def save_operation(self, op: OperationRecord) -> OperationRecord:
        """Insert or update; an operation that has ended also finishes the audit rows of the calls that
        left it running (whichever node ends it: its owner, or the node that took the drone over)."""
        data: JsonObject = {"op": op.model_dump(mode="json")}
        await self._kept(f"operation {op.id} ({op.status})", "operation", data, self._write_operation)
        return op

    async def _write_operation(self, data: JsonObject) -> None:
        op = OperationRecord.model_validate(data["op"])
        values = op.model_dump()
        async with self.engine.begin() as conn:
            if await row_by_key(conn, operations, op.id) is None:
                await conn.execute(insert(operations).values(values))
            else:
                changes = {key: value for key, value in values.items() if key != "id"}
                await conn.execute(update(operations).where(operations.c.id == op.id).values(changes))
        if op.status != "running":
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
