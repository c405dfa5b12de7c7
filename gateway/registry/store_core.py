"""What every table of the store writes through: the engine's connections (Core statements, no ORM),
and the spool that keeps a write the database cannot take (it is unreachable) and writes it, in order,
once the database is back."""

from __future__ import annotations

import functools
import logging
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import TypeVar

from sqlalchemy import CursorResult, RowMapping, Table, select

from gateway.registry.spool import Spool, database_tag
from gateway.registry.sql_async import AsyncConnection, AsyncEngine
from gateway.util.json_types import JsonObject

log = logging.getLogger(__name__)

#: how long a start waits for the writes its previous run kept to reach the database
KEPT_REPLAY_S = 30.0

T = TypeVar("T")
#: writes one kind of kept write from its JSON data; what it returns reaches the call that made the write
#: when it is written at once (a write kept for later returns nothing to anyone)
KeptWriter = Callable[[JsonObject], Awaitable[object]]


class StoreCore:
    """The engine and the spool; the tables of `gateway.registry.store.Store` build on it. A read runs on
    ``self.engine.connect()``, a write on ``self.engine.begin()`` (one transaction, committed at its end
    unless it raises)."""

    def __init__(self, engine: AsyncEngine, url: str) -> None:
        self.engine = engine
        self.url = url
        self._closed = False
        #: history writes the database could not take (it was unreachable), written when it is back
        self.spool = Spool(apply=self._apply_kept, owner=database_tag(url))
        #: how each kind of kept write is written (the Store names its tables' writers)
        self._kept_writers: dict[str, KeptWriter] = {}

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

    async def _kept(
        self, what: str, kind: str, data: JsonObject, write: Callable[[JsonObject], Awaitable[T]]
    ) -> T | None:
        """Write now (``write``, the writer of ``kind``), or keep (``kind``, ``data``: JSON) until the
        database is back: then None."""
        if self._kept_writers.get(kind) != write:  # a restart writes it again through the writer of kind
            raise ValueError(f"a kept write of kind {kind!r} is written by {self._kept_writers.get(kind)!r}, "
                             f"not by {write!r}")  # fmt: skip
        return await self.spool.write(what, functools.partial(write, data), record=(kind, data))

    async def _apply_kept(self, kind: str, data: JsonObject) -> object:
        writer = self._kept_writers.get(kind)
        if writer is None:
            kinds = ", ".join(sorted(self._kept_writers))
            raise ValueError(f"unknown kind of kept write {kind!r}; kinds: {kinds}")
        return await writer(data)

    @property
    def is_open(self) -> bool:
        return not self._closed

    async def ping(self) -> bool:
        """True when the database answers a trivial query."""
        try:
            async with self.engine.connect() as conn:
                await conn.execute(select(1))
            return True
        except Exception:
            log.exception("database ping failed")
            return False


def rowcount(result: object) -> int:
    """Rows a DELETE/UPDATE touched."""
    return int(result.rowcount or 0) if isinstance(result, CursorResult) else 0


async def row_by_key(conn: AsyncConnection, table: Table, key: object) -> RowMapping | None:
    """The row of ``table`` whose (one-column) primary key is ``key``, by column name, or None.

    Rows are read as mappings throughout the store: a column named like one of ``Row``'s own
    attributes (``t``, ``count``, ``index``) would read as that attribute."""
    (column,) = table.primary_key.columns
    return (await conn.execute(select(table).where(column == key))).mappings().first()
