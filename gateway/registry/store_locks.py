"""The store's operator locks and takeover locks (each written through the spool: a lock set while the
database is unreachable counts once it is back)."""

from __future__ import annotations

import logging
from collections.abc import Callable
from datetime import datetime
from typing import TypeVar

from sqlalchemy import delete, select

from gateway.registry.models import (
    LockRow,
    TakeoverRow,
)
from gateway.registry.records import LockRecord
from gateway.registry.store_core import StoreCore, rowcount
from gateway.util.json_types import JsonObject

log = logging.getLogger(__name__)


#: ``superseded(family, scope, locked_at)``: whether a lock was undone since it was made (an unlock
#: newer than it is known: `gateway.cluster.lock_versions.LockVersions.superseded`); family "lock" or
#: "takeover"
Superseded = Callable[[str, str, datetime], bool]

#: the two tables of locks, which differ only in the name of their key (the scope, or the drone's id)
_Row = TypeVar("_Row", LockRow, TakeoverRow)
_KEY: dict[type[LockRow] | type[TakeoverRow], str] = {LockRow: "scope", TakeoverRow: "vehicle_id"}


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
        data: JsonObject = {
            "scope": scope,
            "reason": reason,
            "by": by[:200],
            "locked_at": locked_at.isoformat(),
        }
        return await self._kept(f"the lock of {scope}", "lock", data, self._write_lock)

    async def _write_lock(self, data: JsonObject) -> LockRecord | None:
        return await self._put(LockRow, "lock", data)

    async def delete_lock(self, scope: str) -> bool:
        """Remove the lock of ``scope``; False when there was none (or the database is unreachable:
        then it is removed when the database is back)."""
        return bool(
            await self._kept(f"the unlock of {scope}", "unlock", {"scope": scope}, self._write_unlock)
        )

    async def _write_unlock(self, data: JsonObject) -> bool:
        return await self._remove(LockRow, data)

    async def list_locks(self) -> list[LockRecord]:
        return await self._all(LockRow)

    # --- takeover locks (gateway.fleet.policy.takeover) ----------------------------------------------------

    async def save_takeover(
        self, vehicle_id: str, reason: str, by: str, locked_at: datetime
    ) -> LockRecord | None:
        """Store (or replace) the takeover lock of a drone; None when the database is unreachable (it is
        stored, in order, when the database is back)."""
        data: JsonObject = {
            "vehicle_id": vehicle_id,
            "reason": reason,
            "by": by[:200],
            "locked_at": locked_at.isoformat(),
        }
        return await self._kept(f"the takeover lock of {vehicle_id}", "takeover", data, self._write_takeover)

    async def _write_takeover(self, data: JsonObject) -> LockRecord | None:
        return await self._put(TakeoverRow, "takeover", data)

    async def delete_takeover(self, vehicle_id: str) -> bool:
        """Remove a drone's takeover lock; False when there was none (or the database is unreachable:
        then it is removed when the database is back)."""
        data: JsonObject = {"vehicle_id": vehicle_id}
        kept = await self._kept(
            f"the release of {vehicle_id}", "takeover_release", data, self._write_takeover_release
        )
        return bool(kept)

    async def _write_takeover_release(self, data: JsonObject) -> bool:
        return await self._remove(TakeoverRow, data)

    async def list_takeovers(self) -> list[LockRecord]:
        return await self._all(TakeoverRow)

    # --- either table ----------------------------------------------------------------------------------

    async def _put(self, table: type[_Row], family: str, data: JsonObject) -> LockRecord | None:
        """Insert or replace the lock ``data`` (as spooled: its key, reason, by, ISO locked_at); None
        when it was undone since it was made (not written)."""
        key, reason, by, at = (_text(data, name) for name in (_KEY[table], "reason", "by", "locked_at"))
        key_name, locked_at = _KEY[table], datetime.fromisoformat(at)
        if self._undone(family, key, locked_at):
            return None
        async with self._sessions.begin() as session:
            row = await session.get(table, key)
            if row is None:
                session.add(table(**{key_name: key}, reason=reason, locked_by=by, locked_at=locked_at))
            else:
                row.reason, row.locked_by, row.locked_at = reason, by, locked_at
        return LockRecord(scope=key, reason=reason, by=by, locked_at=locked_at)

    async def _remove(self, table: type[_Row], data: JsonObject) -> bool:
        key_name = _KEY[table]
        key = _text(data, key_name)
        async with self._sessions.begin() as session:
            result = await session.execute(delete(table).where(getattr(table, key_name) == key))
            return bool(rowcount(result))

    async def _all(self, table: type[_Row]) -> list[LockRecord]:
        key_name = _KEY[table]
        async with self._sessions() as session:
            rows = (await session.scalars(select(table).order_by(getattr(table, key_name)))).all()
            return [
                LockRecord(scope=getattr(r, key_name), reason=r.reason, by=r.locked_by, locked_at=r.locked_at)
                for r in rows
            ]


def _text(data: JsonObject, name: str) -> str:
    """The text ``name`` of a kept lock's data; ValueError (the write is refused) when it holds none."""
    value = data.get(name)
    if not isinstance(value, str):
        raise ValueError(f"a kept lock holds {name} as text; got {value!r}")
    return value
