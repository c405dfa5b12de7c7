"""The store's operator locks and takeover locks (each written through the spool: a lock set while the
database is unreachable counts once it is back)."""

from __future__ import annotations

import logging
from collections.abc import Callable
from datetime import datetime
from typing import Any, cast

from sqlalchemy import delete, select

from gateway.registry.models import (
    LockRow,
    TakeoverRow,
)
from gateway.registry.records import LockRecord
from gateway.registry.store_core import StoreCore, rowcount

log = logging.getLogger(__name__)


#: ``superseded(family, scope, locked_at)``: whether a lock was undone since it was made (an unlock
#: newer than it is known: `gateway.cluster.lock_versions.LockVersions.superseded`); family "lock" or
#: "takeover"
Superseded = Callable[[str, str, datetime], bool]


class LockTables(StoreCore):
    """Operator locks and takeover locks (`gateway.fleet.policy.operator_locks`), kept across restarts.
    A lock written late (kept while the database was down) that was undone meanwhile is not written
    (``lock_superseded``, set by a cluster node)."""

    lock_superseded: Superseded | None = None

    def _undone(self, family: str, scope: str, locked_at: datetime) -> bool:
        if self.lock_superseded is None or not self.lock_superseded(family, scope, locked_at):
            return False
        log.warning("the %s of %s made at %s is not written: it was undone since (a newer unlock is known)",
                    family, scope, locked_at.isoformat())  # fmt: skip
        return True

    async def save_lock(self, scope: str, reason: str, by: str, locked_at: datetime) -> LockRecord | None:
        """Store (or replace) the lock of ``scope``; None when the database is unreachable (it is
        stored, in order, when the database is back)."""
        data = {"scope": scope, "reason": reason, "by": by[:200], "locked_at": locked_at.isoformat()}
        return cast(LockRecord | None, await self._kept(f"the lock of {scope}", "lock", data))

    async def _write_lock(self, data: dict[str, Any]) -> LockRecord | None:
        scope, reason, by = data["scope"], data["reason"], data["by"]
        locked_at = datetime.fromisoformat(data["locked_at"])
        if self._undone("lock", scope, locked_at):
            return None
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
            return bool(rowcount(result))

    async def list_locks(self) -> list[LockRecord]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(LockRow).order_by(LockRow.scope))).all()
            return [
                LockRecord(scope=r.scope, reason=r.reason, by=r.locked_by, locked_at=r.locked_at)
                for r in rows
            ]

    # --- takeover locks (gateway.fleet.policy.takeover) ----------------------------------------------------

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

    async def _write_takeover(self, data: dict[str, Any]) -> LockRecord | None:
        vehicle_id, reason, by = data["vehicle_id"], data["reason"], data["by"]
        locked_at = datetime.fromisoformat(data["locked_at"])
        if self._undone("takeover", vehicle_id, locked_at):
            return None
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
            return bool(rowcount(result))

    async def list_takeovers(self) -> list[LockRecord]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(TakeoverRow).order_by(TakeoverRow.vehicle_id))).all()
            return [
                LockRecord(scope=r.vehicle_id, reason=r.reason, by=r.locked_by, locked_at=r.locked_at)
                for r in rows
            ]
