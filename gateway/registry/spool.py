"""Writes the database could not take, kept in order on this node and written when it is back.

The store sends its history writes (audit rows, operations, track samples, status texts, flight ends,
operator locks) through :meth:`Spool.write`. While nothing waits, a write goes straight to the database;
when the database is unreachable (refused, reset, timed out), the write is kept here and every later one
queues behind it, so they reach the database in the order they were made, each with the time it was
made (the rows carry their own times). One task drains the queue, oldest first, retrying every
``RETRY_S`` until the database answers again. A write the database refuses for its content (a bad row)
is logged and dropped, so it cannot hold back the others. The queue is bounded: past ``limit`` the
oldest writes are dropped, and counted.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections import deque
from collections.abc import Awaitable, Callable
from typing import Any, TypeVar

import sqlalchemy.exc

log = logging.getLogger("gateway.spool")

T = TypeVar("T")
RETRY_S = 1.0
#: one write never holds its caller longer than this (a database that hangs counts as unreachable)
WRITE_TIMEOUT_S = 5.0
LIMIT = 100_000


def unreachable(exc: BaseException) -> bool:
    """The database could not be reached (as opposed to refusing what was written)."""
    seen: set[int] = set()
    todo: list[BaseException | None] = [exc]
    while todo:
        cur = todo.pop()
        if cur is None or id(cur) in seen:
            continue
        seen.add(id(cur))
        if isinstance(cur, OSError | TimeoutError | sqlalchemy.exc.TimeoutError):
            return True
        if isinstance(cur, sqlalchemy.exc.DBAPIError) and cur.connection_invalidated:
            return True
        if isinstance(cur, sqlalchemy.exc.OperationalError | sqlalchemy.exc.InterfaceError):
            return True
        module = type(cur).__module__
        if module.startswith("asyncpg") and (
            "Connection" in type(cur).__name__ or "CannotConnect" in type(cur).__name__
        ):
            return True
        if isinstance(cur, sqlalchemy.exc.DBAPIError):
            todo.append(cur.orig)
        todo.extend([cur.__cause__, cur.__context__])
    return False


class Spool:
    """The writes that wait for the database, in order."""

    def __init__(self, limit: int = LIMIT) -> None:
        self.limit = limit
        self._queue: deque[tuple[str, Callable[[], Awaitable[Any]]]] = deque()
        self._task: asyncio.Task[None] | None = None
        self.dropped = 0
        self.written_late = 0
        self._closed = False

    def __len__(self) -> int:
        return len(self._queue)

    @property
    def waiting(self) -> bool:
        return bool(self._queue)

    async def write(self, what: str, write: Callable[[], Awaitable[T]]) -> T | None:
        """``write()`` now, or (database unreachable, or earlier writes waiting) later: then None."""
        if not self._queue:
            try:
                return await asyncio.wait_for(write(), WRITE_TIMEOUT_S)
            except Exception as exc:
                if not unreachable(exc):
                    raise
                log.warning(
                    "database unreachable (%s): %s kept on this node until it is back", _short(exc), what
                )
        self._keep(what, write)
        return None

    def _keep(self, what: str, write: Callable[[], Awaitable[Any]]) -> None:
        self._queue.append((what, write))
        while len(self._queue) > self.limit:
            lost, _ = self._queue.popleft()
            self.dropped += 1
            log.error("spool full (%d writes): %s dropped", self.limit, lost)
        if not self._closed and (self._task is None or self._task.done()):
            self._task = asyncio.create_task(self._drain(), name="store-spool")

    async def _drain(self) -> None:
        while self._queue:
            what, write = self._queue[0]
            try:
                await asyncio.wait_for(write(), WRITE_TIMEOUT_S)
            except asyncio.CancelledError:
                raise
            except Exception as exc:
                if unreachable(exc):
                    await asyncio.sleep(RETRY_S)
                    continue
                log.exception("%s kept while the database was unreachable was refused by it: dropped", what)
                self.dropped += 1
            else:
                self.written_late += 1
            self._queue.popleft()
            if not self._queue:
                log.warning("database back: the writes kept on this node are written (%d)", self.written_late)

    async def flush(self, within_s: float) -> bool:
        """Wait up to ``within_s`` for the kept writes to reach the database; True when none is left."""
        loop = asyncio.get_running_loop()
        deadline = loop.time() + within_s
        while self._queue and loop.time() < deadline:  # noqa: ASYNC110 (the drain task pops the queue)
            await asyncio.sleep(0.1)
        return not self._queue

    async def close(self) -> None:
        self._closed = True
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await self._task
        if self._queue:
            log.error("%d writes kept while the database was unreachable are lost: the gateway stopped "
                      "before it came back (first: %s)", len(self._queue), self._queue[0][0])  # fmt: skip


def _short(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0][:120]}" if text else type(exc).__name__
