"""Writes the database could not take, kept in order on this node and written when it is back.

The store sends its history writes (audit rows, operations, track samples, status texts, flight ends,
operator locks) through :meth:`Spool.write`. While nothing waits, a write goes straight to the database;
when the database is unreachable (refused, reset, timed out), the write is kept here and every later one
queues behind it, so they reach the database in the order they were made, each with the time it was
made (the rows carry their own times). One task drains the queue, oldest first, retrying every
``RETRY_S`` until the database answers again. A write the database refuses for its content (a bad row)
is logged and dropped, so it cannot hold back the others. The queue is bounded: past ``limit`` the
oldest writes are dropped, and counted.

Attached to a file (:meth:`Spool.attach`, the node's ``GATEWAY_SPOOL_PATH``), each kept write is also
appended to it as one JSON line (its kind and data, flushed to the disk before the caller is answered),
and each one written (or dropped) is marked done by another line; the file is emptied when nothing
waits. A node killed while writes wait finds them there when it starts again and writes them first, in
order, with their own times. A write made for the file carries a ``record`` (kind, JSON data) that the
spool's ``apply`` writes again after a restart.

The file belongs to one database and one running spool: its first line names the database (``owner``, a
digest of its URL), and a spool holds an exclusive lock on it while it has it open. A file kept for
another database, or in use by another running gateway (two started in one directory with one node id),
is left as it is, and this spool keeps its writes in memory only (logged): writes are never given to a
database they were not made for, nor written twice by two spools. A file of an older version, with kept
writes but no first line naming their database, is moved aside (``<name>.no-database-<time>``, logged at
ERROR) and none of its writes is made: nothing tells which database they were for.
"""

from __future__ import annotations

import asyncio
import contextlib
import fcntl
import hashlib
import json
import logging
import os
import time
from collections import deque
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import TextIO, TypeVar

import sqlalchemy.exc

from gateway.util.json_types import JsonObject

log = logging.getLogger("gateway.spool")

T = TypeVar("T")
RETRY_S = 1.0
#: one write never holds its caller longer than this (a database that hangs counts as unreachable)
WRITE_TIMEOUT_S = 5.0
LIMIT = 100_000
#: (kind, JSON data) of a write that can be made again after a restart
Record = tuple[str, JsonObject]
#: writes a kept record again (its result is not read: nobody waits for a write kept for later)
Apply = Callable[[str, JsonObject], Awaitable[object]]
#: a write as it waits in the queue
Write = Callable[[], Awaitable[object]]


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

    def __init__(self, limit: int = LIMIT, apply: Apply | None = None, owner: str | None = None) -> None:
        self.limit = limit
        self.apply = apply
        #: the database the kept writes are for (`database_tag`), named in the file's first line
        self.owner = owner
        # (what, write, its number in the file or None)
        self._queue: deque[tuple[str, Write, int | None]] = deque()
        self._task: asyncio.Task[None] | None = None
        self.dropped = 0
        self.written_late = 0
        self._closed = False
        self.path: Path | None = None
        self._file: TextIO | None = None
        self._next = 0
        # the database is known to be unreachable (its node fenced itself): writes are kept at once
        self._down = False

    async def attach(self, path: Path) -> int:
        """Keep the writes in ``path`` too; the writes a previous run left there are queued first (and
        written as soon as the database answers). Returns how many there were."""
        if self.apply is None:
            raise ValueError("a spool kept in a file needs apply (how to write a kept record again)")
        self.path = path
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            self._file = _open_locked(path)
            owner, left = self._read(self._file.read().splitlines(), path)
            if owner is not None and self.owner is not None and owner != self.owner:
                log.error(
                    "%s keeps writes for another database (%s, this one is %s): it is left as it is, and "
                    "this run keeps its writes in memory only", path, owner, self.owner,
                )  # fmt: skip
                self._close_file(unlink=False)
                self.path = None
                return 0
            if owner is None and left and self.owner is not None:
                # a file of an older version: nothing says which database its writes were made for
                aside = self._set_aside(path)
                log.error(
                    "%s holds %d kept writes but does not name their database (a file of an older version): "
                    "moved to %s, not written; this run keeps its own writes in %s", path, len(left), aside,
                    path,
                )  # fmt: skip
                return 0
            if not left:
                self._close_file(unlink=True)
                return 0
            self._file.truncate(0)  # the file again, with the pending ones only
            self._header()
        except BlockingIOError:
            log.error("%s is in use by another running gateway (same directory and node id): this run keeps "
                      "its writes in memory only", path)  # fmt: skip
            self._close_file(unlink=False)
            self.path = None
            return 0
        except OSError as exc:
            log.error("cannot keep writes in %s (%r): they are kept in memory only", path, exc)
            self._close_file(unlink=False)
            self.path = None
            return 0
        apply = self.apply
        for _n, what, kind, data in left:
            self._keep(what, _bind(apply, kind, data), (kind, data))
        log.warning("%d writes kept by this node's previous run while the database was unreachable (%s) "
                    "are written first", len(left), path)  # fmt: skip
        return len(left)

    def _set_aside(self, path: Path) -> Path:
        """Rename the open file beside itself (its writes kept for whoever can tell their database) and
        let go of it; the path is free for this spool's own writes. The new name."""
        aside = path.with_name(f"{path.name}.no-database-{int(time.time())}")
        try:
            path.rename(aside)  # under this spool's lock: no other spool reads it meanwhile
        finally:
            self._close_file(unlink=False)
        return aside

    @staticmethod
    def _read(lines: list[str], path: Path) -> tuple[str | None, list[tuple[int, str, str, JsonObject]]]:
        """The database the file's writes are for (None: not named), and its writes not marked done, in
        order."""
        owner: str | None = None
        kept: dict[int, tuple[int, str, str, JsonObject]] = {}
        for number, line in enumerate(lines, 1):
            try:
                item = json.loads(line)
                if "database" in item:
                    owner = str(item["database"])
                elif "done" in item:
                    kept.pop(int(item["done"]), None)
                else:
                    n = int(item["n"])
                    kept[n] = (n, str(item["what"]), str(item["kind"]), dict(item["data"]))
            except (ValueError, KeyError, TypeError):  # a line cut short when the node was killed
                log.error("%s line %d is not a kept write (cut short?): skipped", path, number)
        return owner, [kept[n] for n in sorted(kept)]

    def _header(self) -> None:
        """The first line of a new file: the database its writes are for."""
        if self._file is not None and self.owner is not None:
            _line(self._file, {"database": self.owner})

    def __len__(self) -> int:
        return len(self._queue)

    @property
    def waiting(self) -> bool:
        return bool(self._queue)

    @property
    def unreachable(self) -> bool:
        """Whether the database is known not to answer now: writes wait here, or its node fenced itself."""
        return self._down or bool(self._queue)

    def unreachable_now(self) -> None:
        """The database is known to be unreachable (a cluster node could not renew its leases): every
        write is kept at once, without waiting for the database first, until a kept one is written."""
        self._down = True

    async def write(
        self, what: str, write: Callable[[], Awaitable[T]], record: Record | None = None
    ) -> T | None:
        """``write()`` now, or (database unreachable, or earlier writes waiting) later: then None.
        ``record``: what to keep in the file, to write it after a restart."""
        if not self._queue and not self._down:
            try:
                return await asyncio.wait_for(write(), WRITE_TIMEOUT_S)
            except Exception as exc:
                if not unreachable(exc):
                    raise
                log.warning(
                    "database unreachable (%s): %s kept on this node until it is back", _short(exc), what
                )
        self._keep(what, write, record)
        return None

    def _keep(self, what: str, write: Write, record: Record | None = None) -> None:
        number = self._journal(what, record)
        self._queue.append((what, write, number))
        while len(self._queue) > self.limit:
            lost, _, lost_number = self._queue.popleft()
            self.dropped += 1
            self._done(lost_number)
            log.error("spool full (%d writes): %s dropped", self.limit, lost)
        if not self._closed and (self._task is None or self._task.done()):
            self._task = asyncio.create_task(self._drain(), name="store-spool")

    def _journal(self, what: str, record: Record | None) -> int | None:
        """Append the write to the file (flushed to the disk); its number there, or None."""
        if self.path is None or record is None:
            return None
        number = self._next
        self._next += 1
        kind, data = record
        try:
            if self._file is None:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                self._file = _open_locked(self.path)
                if os.fstat(self._file.fileno()).st_size == 0:
                    self._header()
            _line(self._file, {"n": number, "what": what, "kind": kind, "data": data})
        except BlockingIOError:
            log.error("%s is in use by another running gateway (same directory and node id): %s and the "
                      "writes after it are kept in memory only", self.path, what)  # fmt: skip
            self._close_file(unlink=False)
            self.path = None
            return None
        except (OSError, TypeError, ValueError) as exc:
            log.error("could not keep %s in %s (%r): it is kept in memory only", what, self.path, exc)
            return None
        return number

    def _done(self, number: int | None) -> None:
        if number is None or self._file is None:
            return
        try:
            _line(self._file, {"done": number})
        except OSError as exc:
            log.error("could not mark a kept write done in %s (%r): it may be written twice", self.path, exc)

    def _close_file(self, unlink: bool) -> None:
        """Close the file (its lock goes with it); ``unlink``: removed first, while it is still locked."""
        if unlink and self.path is not None and self._file is not None:
            with contextlib.suppress(OSError):
                self.path.unlink()
        if self._file is not None:
            with contextlib.suppress(OSError):
                self._file.close()
            self._file = None

    async def _drain(self) -> None:
        # closed: stop even when the cancel of this task was lost (asyncio.wait_for can drop a cancel that
        # lands as the write it waits for ends)
        while self._queue and not self._closed:
            what, write, number = self._queue[0]
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
                self._down = False
            self._queue.popleft()
            self._done(number)
            if not self._queue:
                self._close_file(unlink=True)  # nothing waits: the next outage starts a new file
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
        if self._queue and self._file is not None:
            log.error("%d writes kept while the database was unreachable wait in %s: they are written when "
                      "this node starts again (first: %s)", len(self._queue), self.path,
                      self._queue[0][0])  # fmt: skip
            self._close_file(unlink=False)
        elif self._queue:
            log.error("%d writes kept while the database was unreachable are lost: the gateway stopped "
                      "before it came back (first: %s)", len(self._queue), self._queue[0][0])  # fmt: skip
        else:
            self._close_file(unlink=True)


def _short(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0][:120]}" if text else type(exc).__name__


def _line(file: TextIO, item: JsonObject) -> None:
    file.write(json.dumps(item, default=str) + "\n")
    file.flush()
    os.fsync(file.fileno())


def database_tag(url: str) -> str:
    """What a spool file names its database by: a digest of its URL (which may hold a password)."""
    return hashlib.sha256(url.encode()).hexdigest()[:16]


def _open_locked(path: Path) -> TextIO:
    """``path`` opened to read and append (made when missing), locked for this spool alone;
    BlockingIOError when another spool (this process or another) holds it."""
    file = path.open("a+", encoding="utf-8")
    try:
        fcntl.flock(file.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        file.close()
        raise
    file.seek(0)
    return file


def _bind(apply: Apply, kind: str, data: JsonObject) -> Write:
    return lambda: apply(kind, data)
