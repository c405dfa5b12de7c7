"""A spool told that the database is unreachable (its cluster node fenced itself) keeps every write at
once instead of waiting for the database first, until a kept write reaches it again."""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable

from gateway.registry.spool import Spool
from tests.helpers.timing import eventually


async def test_writes_are_kept_at_once_while_the_database_is_known_unreachable() -> None:
    spool = Spool()
    reachable = asyncio.Event()
    written: list[str] = []

    def writer(name: str) -> Callable[[], Awaitable[str]]:
        async def write() -> str:
            await reachable.wait()  # a database that hangs: the write waits until it answers
            written.append(name)
            return name

        return write

    spool.unreachable_now()
    answered = await asyncio.wait_for(spool.write("the end of flight 1", writer("flight end")), 1.0)
    assert answered is None  # kept, answered at once (not after the write's 5 s limit)
    assert spool.waiting and written == []

    reachable.set()  # the database answers again: the kept write reaches it, later ones go straight in
    await eventually(lambda: _is(not spool.waiting), "the kept write written", within_s=10)
    assert await spool.write("an audit row", writer("audit")) == "audit"
    assert written == ["flight end", "audit"]
    await spool.close()


async def _is(value: bool) -> bool:
    return value
