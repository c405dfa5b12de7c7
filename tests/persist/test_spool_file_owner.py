"""A spool file belongs to one database and one running spool: a file kept for another database is left
as it is (never written into this one), and a file another running spool holds is not shared (two
gateways started in one directory with one node id); either way this spool keeps its writes in memory.
A file of an older version, which does not name its database, is moved aside with none of its writes
made."""

from __future__ import annotations

import functools
import json
import logging
from pathlib import Path
from typing import Any

import pytest

from gateway.registry.spool import Spool


class Database:
    """A database as the spool sees it: refuses (unreachable) while down, else records what it takes."""

    def __init__(self) -> None:
        self.down = True
        self.written: list[tuple[str, dict[str, Any]]] = []

    async def apply(self, kind: str, data: dict[str, Any]) -> None:
        if self.down:
            raise ConnectionRefusedError("database down")
        self.written.append((kind, data))


async def keep(spool: Spool, db: Database, count: int) -> None:
    for i in range(count):
        data = {"i": i}
        write = functools.partial(db.apply, "row", data)
        assert await spool.write(f"row {i}", write, record=("row", data)) is None


def listing(folder: Path) -> list[Path]:
    return sorted(folder.iterdir())


def kept_lines(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text().splitlines()]


async def test_a_file_kept_for_another_database_is_left_alone(tmp_path: Path) -> None:
    path = tmp_path / "spool.jsonl"
    a, b = Database(), Database()
    first = Spool(apply=a.apply, owner="db-a")
    assert await first.attach(path) == 0
    await keep(first, a, 3)
    await first.close()
    before = path.read_text()
    assert kept_lines(path)[0] == {"database": "db-a"}

    b.down = False
    other = Spool(apply=b.apply, owner="db-b")
    assert await other.attach(path) == 0  # not its writes
    await keep(other, b, 1)  # written at once: its database answers
    assert b.written == [("row", {"i": 0})] and other.path is None
    await other.close()
    assert path.read_text() == before  # left as it was

    a.down = False
    again = Spool(apply=a.apply, owner="db-a")
    assert await again.attach(path) == 3
    assert await again.flush(10.0)
    assert a.written == [("row", {"i": i}) for i in range(3)]
    await again.close()
    assert not path.exists()


async def test_a_file_in_use_by_a_running_spool_is_not_shared(tmp_path: Path) -> None:
    path = tmp_path / "spool.jsonl"
    db = Database()
    running = Spool(apply=db.apply, owner="db")
    assert await running.attach(path) == 0
    await keep(running, db, 2)  # its file is open (and locked) while its writes wait

    second = Spool(apply=db.apply, owner="db")
    assert await second.attach(path) == 0 and second.path is None  # not read, not emptied
    await keep(second, db, 1)  # kept in memory only
    assert [x.get("n") for x in kept_lines(path)] == [None, 0, 1]  # the header, then the first's two

    db.down = False
    assert await running.flush(10.0) and await second.flush(10.0)
    assert sorted(d["i"] for _k, d in db.written) == [0, 0, 1]  # each write once
    await running.close()
    await second.close()
    assert not path.exists()


async def test_a_file_a_spool_opens_for_its_first_kept_write_is_locked_too(tmp_path: Path) -> None:
    """A spool whose file did not exist at its start takes it (and its lock) at its first kept write; a
    spool attached meanwhile to the same path keeps its own writes in memory."""
    path = tmp_path / "spool.jsonl"
    db = Database()
    first, second = Spool(apply=db.apply, owner="db"), Spool(apply=db.apply, owner="db")
    assert await first.attach(path) == 0 and await second.attach(path) == 0
    await keep(first, db, 1)
    await keep(second, db, 1)
    assert first.path == path and second.path is None
    assert [x.get("n") for x in kept_lines(path)] == [None, 0]
    await first.close()
    await second.close()


async def test_a_file_that_does_not_name_its_database_is_set_aside_unwritten(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    """A file of an older version (kept writes, no first line naming their database): none of its writes
    is made, the file is moved aside whole, and this spool keeps its own writes at the path."""
    path = tmp_path / "spool.jsonl"
    old = [{"n": 0, "what": "row 0", "kind": "row", "data": {"i": 100}},
           {"n": 1, "what": "row 1", "kind": "row", "data": {"i": 101}}, {"done": 0}]  # fmt: skip
    path.write_text("".join(json.dumps(x) + "\n" for x in old))
    before = path.read_text()
    db = Database()
    db.down = False
    spool = Spool(apply=db.apply, owner="db")
    with caplog.at_level(logging.ERROR, logger="gateway.spool"):
        assert await spool.attach(path) == 0
    assert db.written == []
    aside = [p for p in listing(tmp_path) if p.name.startswith("spool.jsonl.no-database-")]
    assert len(aside) == 1 and aside[0].read_text() == before
    assert not path.exists()
    lines = [r.getMessage() for r in caplog.records if r.name == "gateway.spool"]
    assert len(lines) == 1 and "does not name their database" in lines[0] and str(aside[0]) in lines[0]

    db.down = True
    await keep(spool, db, 1)  # its own write, in a file of its own at the path, named for its database
    assert spool.path == path and kept_lines(path) == [
        {"database": "db"},
        {"n": 0, "what": "row 0", "kind": "row", "data": {"i": 0}},
    ]
    db.down = False
    assert await spool.flush(10.0)
    assert db.written == [("row", {"i": 0})]
    await spool.close()
    assert not path.exists() and aside[0].read_text() == before


async def test_an_older_file_with_nothing_left_to_write_is_removed(tmp_path: Path) -> None:
    path = tmp_path / "spool.jsonl"
    path.write_text(json.dumps({"n": 0, "what": "row 0", "kind": "row", "data": {}}) + "\n" + '{"done": 0}\n')
    spool = Spool(apply=Database().apply, owner="db")
    assert await spool.attach(path) == 0
    assert listing(tmp_path) == []
    await spool.close()
