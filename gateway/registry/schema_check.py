"""Is a database's schema at the newest migration? Answered without importing Alembic.

`Store.open` asks this first and runs Alembic's upgrade (`gateway.registry.store.upgrade_schema`) only
when the answer is no: Alembic and what it pulls in (Mako, its DDL modules, about 10 MiB) stay out of a
gateway whose database is already current, which is every start but the first after an upgrade.

The head revision is read from the migration files themselves (their ``revision = ...`` and
``down_revision = ...`` lines: the one revision no other names as its parent); the database's from
Alembic's own ``alembic_version`` table. Anything unexpected (no single head, no such table, several
rows, a database that cannot be read) answers no, and Alembic decides as it always did.
"""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

from sqlalchemy import text
from sqlalchemy.exc import DBAPIError

from gateway.registry.sql_async import AsyncEngine

__all__ = ["head_from_files", "schema_is_current"]

_ASSIGNMENT = re.compile(r"^(revision|down_revision)\b[^=]*=\s*(.+?)\s*$", re.MULTILINE)


@functools.cache
def head_from_files(versions: Path) -> str | None:
    """The one revision among the migration files in ``versions`` that no other revision follows;
    None when there is not exactly one (a branch, a file that cannot be read this way)."""
    revisions: set[str] = set()
    parents: set[str] = set()
    for path in sorted(versions.glob("*.py")):
        source = path.read_text(encoding="utf-8")
        found: dict[str, str] = {m.group(1): m.group(2) for m in _ASSIGNMENT.finditer(source)}
        try:
            revision = ast.literal_eval(found["revision"])
            down = ast.literal_eval(found.get("down_revision", "None"))
        except (KeyError, ValueError, SyntaxError):
            return None
        if not isinstance(revision, str):
            return None
        revisions.add(revision)
        if isinstance(down, str):
            parents.add(down)
        elif isinstance(down, tuple | list):
            parents.update(str(d) for d in down)
    heads = revisions - parents
    return heads.pop() if len(heads) == 1 else None


async def schema_is_current(engine: AsyncEngine, migrations: Path) -> bool:
    """True when the database's ``alembic_version`` holds exactly the head of ``migrations``/versions."""
    head = head_from_files(migrations / "versions")
    if head is None:
        return False
    try:
        async with engine.connect() as conn:
            rows = (await conn.execute(text("SELECT version_num FROM alembic_version"))).scalars().all()
    except DBAPIError:  # no such table yet (a new database), or it cannot be read: Alembic will tell
        return False
    return list(rows) == [head]
