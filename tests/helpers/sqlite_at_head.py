"""A test's fresh SQLite database at the schema's head, copied from one made once per test process: the
store's upgrade of a fresh file took 0.4-1.2 s at a load of 20 on 2 cores (Alembic runs every
migration), the copy and the open after it 0.01-0.09 s, and a run opens a fresh database some 150 times
(the ``store`` fixture, every gateway stack). The tests of the upgrades themselves (tests/persist,
tests/api/test_cli.py) open empty files of their own."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from sqlalchemy.engine import make_url

from gateway.registry.store import Store

_made: list[Path] = []


async def at_head(url: str) -> str:
    """``url``, whose SQLite file, when it does not exist yet, is first made a copy of a database at the
    schema's head (the same tables and revision as the store's own upgrade makes, no rows but Alembic's
    one). Any other URL (PostgreSQL, in memory, a file that exists) is left as it is."""
    target = _missing_file(url)
    if target is None:
        return url
    if not _made:
        made = Path(tempfile.mkdtemp(prefix="fleet-tests-sqlite-")) / "head.db"
        store = await Store.open(f"sqlite+aiosqlite:///{made}")
        await store.close()  # the last connection's close folds the write-ahead log into the file
        _made.append(made)
    shutil.copyfile(_made[0], target)
    return url


def _missing_file(url: str) -> Path | None:
    """The SQLite file ``url`` names when it does not exist yet, else None."""
    parsed = make_url(url)
    if not parsed.drivername.startswith("sqlite") or parsed.database in (None, "", ":memory:"):
        return None
    target = Path(parsed.database)
    return None if target.exists() else target
