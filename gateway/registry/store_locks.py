"""The store's operator locks and takeover locks (each written through the spool: a lock set while the
database is unreachable counts once it is back)."""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable
from dataclasses import dataclass
from datetime import datetime

from sqlalchemy import Table, delete, insert, select, update

from gateway.registry.models import locks, takeovers
from gateway.registry.records import LockRecord
from gateway.registry.store_core import KeptWriter, StoreCore, row_by_key, rowcount
from gateway.util.json_types import JsonObject

log = logging.getLogger(__name__)


#: ``superseded(family, scope, locked_at)``: whether a lock was undone since it was made (an unlock
#: newer than it is known: `gateway.cluster.lock_versions.LockVersions.superseded`); family "lock" or
#: "takeover"
Superseded = Callable[[str, str, datetime], bool]


@dataclass(frozen=True)
class _Family:
    """One of the two kinds of lock, whose tables differ only in the name of their key (the scope, or
    the drone's id): its table, that key, the kinds of its kept writes (set, undone) and how a kept
    write of each is named in the log."""

    table: Table
    key: str
    kind: str
    undo_kind: str
    set_what: str
    undo_what: str


_LOCKS = _Family(locks, "scope", "lock", "unlock", "the lock of {}", "the unlock of {}")
_TAKEOVERS = _Family(
    takeovers, "vehicle_id", "takeover", "takeover_release", "the takeover lock of {}", "the release of {}"
)


class LockTables(StoreCore):
    """Operator locks and takeover locks (`gateway.fleet.policy.operator_locks`), kept across restarts.
    Each table is written alike: ``save_*`` stores (or replaces) a lock, ``delete_*`` removes one (False
    when there was none), and while the database is unreachable both answer None / False at once and
    are written, in order, when it is back. A lock written late that was undone meanwhile is not
    written (``lock_superseded``, set by a cluster node)."""

    lock_superseded: Superseded | None = None

    def _undone(self, family: str, scope: str, locked_at: datetime) -> bool:
        if self.lock_superseded is None or not self.lock_superseded(family, scope, locked_at):
            return False
        log.warning("the %s of %s made at %s is not written: it was undone since (a newer unlock is known)",
                    family, scope, locked_at.isoformat())  # fmt: skip
        return True

    # --- operator locks, by scope (a drone's id, or "*": the fleet) ------------------------------------

    async def save_lock(self, scope: str, reason: str, by: str, locked_at: datetime) -> LockRecord | None:
        return await self._save(_LOCKS, scope, reason, by, locked_at)

    async def delete_lock(self, scope: str) -> bool:
        return await self._delete(_LOCKS, scope)

    async def list_locks(self) -> list[LockRecord]:
        return await self._all(_LOCKS)

    # --- takeover locks, by drone (gateway.fleet.policy.takeover) ----------------------------------------

    async def save_takeover(
        self, vehicle_id: str, reason: str, by: str, locked_at: datetime
    ) -> LockRecord | None:
        return await self._save(_TAKEOVERS, vehicle_id, reason, by, locked_at)

    async def delete_takeover(self, vehicle_id: str) -> bool:
        return await self._delete(_TAKEOVERS, vehicle_id)

    async def list_takeovers(self) -> list[LockRecord]:
        return await self._all(_TAKEOVERS)

    # --- either table ----------------------------------------------------------------------------------

    def _lock_writers(self) -> dict[str, KeptWriter]:
        """How each kind of the two tables' kept writes is written (set and undone; the Store names
        them with its other tables' writers)."""
        writers: dict[str, KeptWriter] = {}
        for family in (_LOCKS, _TAKEOVERS):
            writers[family.kind] = functools.partial(self._put, family)
            writers[family.undo_kind] = functools.partial(self._remove, family)
        return writers

    async def _save(
        self, family: _Family, key: str, reason: str, by: str, locked_at: datetime
    ) -> LockRecord | None:
        """Write the lock now, or keep it (as JSON) until the database is back: then None."""
        data: JsonObject = {
            family.key: key,
            "reason": reason,
            "by": by[:200],
            "locked_at": locked_at.isoformat(),
        }
        write = self._kept_writers[family.kind]
        written = await self._kept(family.set_what.format(key), family.kind, data, write)
        return written if isinstance(written, LockRecord) else None

    async def _delete(self, family: _Family, key: str) -> bool:
        """Remove the lock now, or keep its removal until the database is back (then False)."""
        write = self._kept_writers[family.undo_kind]
        data: JsonObject = {family.key: key}
        return bool(await self._kept(family.undo_what.format(key), family.undo_kind, data, write))

    async def _put(self, family: _Family, data: JsonObject) -> LockRecord | None:
        """Insert or replace the lock ``data`` (as spooled: its key, reason, by, ISO locked_at); None
        when it was undone since it was made (not written)."""
        table, key_name = family.table, family.key
        key, reason, by, at = (_text(data, name) for name in (key_name, "reason", "by", "locked_at"))
        locked_at = datetime.fromisoformat(at)
        if self._undone(family.kind, key, locked_at):
            return None
        values = {"reason": reason, "locked_by": by, "locked_at": locked_at}
        async with self.engine.begin() as conn:
            if await row_by_key(conn, table, key) is None:
                await conn.execute(insert(table).values({key_name: key, **values}))
            else:
                await conn.execute(update(table).where(table.c[key_name] == key).values(values))
        return LockRecord(scope=key, reason=reason, by=by, locked_at=locked_at)

    async def _remove(self, family: _Family, data: JsonObject) -> bool:
        table, key_name = family.table, family.key
        key = _text(data, key_name)
        async with self.engine.begin() as conn:
            result = await conn.execute(delete(table).where(table.c[key_name] == key))
            return bool(rowcount(result))

    async def _all(self, family: _Family) -> list[LockRecord]:
        table, key_name = family.table, family.key
        async with self.engine.connect() as conn:
            rows = (await conn.execute(select(table).order_by(table.c[key_name]))).mappings().all()
        return [
            LockRecord(scope=r[key_name], reason=r["reason"], by=r["locked_by"], locked_at=r["locked_at"])
            for r in rows
        ]


def _text(data: JsonObject, name: str) -> str:
    """The text ``name`` of a kept lock's data; ValueError (the write is refused) when it holds none."""
    value = data.get(name)
    if not isinstance(value, str):
        raise ValueError(f"a kept lock holds {name} as text; got {value!r}")
    return value
