"""The schema check at open: a current database opens without Alembic, any other is still upgraded."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from sqlalchemy import text

from gateway.registry.database import (
    create_engine_for,
    current_revision,
    head_revision,
    migrations_dir,
    upgrade_schema,
)
from gateway.registry.schema_check import head_from_files, schema_is_current
from gateway.registry.store import Store


def test_head_read_from_the_files_is_alembics_head() -> None:
    assert head_from_files(migrations_dir() / "versions") == head_revision()


def test_no_single_head_is_no_answer(tmp_path: Path) -> None:
    (tmp_path / "a.py").write_text("revision = 'a'\ndown_revision = None\n")
    (tmp_path / "b.py").write_text("revision = 'b'\ndown_revision = 'a'\n")
    assert head_from_files(tmp_path) == "b"
    branch = tmp_path / "branch"
    branch.mkdir()
    for name, down in (("a", None), ("b", "a"), ("c", "a")):
        (branch / f"{name}.py").write_text(f"revision: str = {name!r}\ndown_revision = {down!r}\n")
    assert head_from_files(branch) is None


async def test_only_a_database_at_head_is_current(db_url: str) -> None:
    engine = create_engine_for(db_url)
    try:
        assert not await schema_is_current(engine, migrations_dir())  # new: no alembic_version table
        await upgrade_schema(engine, db_url, "0001")
        assert not await schema_is_current(engine, migrations_dir())
        await upgrade_schema(engine, db_url)
        assert await schema_is_current(engine, migrations_dir())
        async with engine.begin() as conn:  # a revision this gateway does not know (a newer one)
            await conn.execute(text("UPDATE alembic_version SET version_num = '9999'"))
        assert not await schema_is_current(engine, migrations_dir())
    finally:
        await engine.dispose()


async def test_an_outdated_database_is_still_upgraded_on_open(db_url: str) -> None:
    engine = create_engine_for(db_url)
    try:
        await upgrade_schema(engine, db_url, "0003")
    finally:
        await engine.dispose()
    store = await Store.open(db_url)
    try:
        assert await current_revision(store.engine) == head_revision()
    finally:
        await store.close()


OPEN_AND_CLOSE = """
import asyncio, sys
from gateway.registry.store import Store

async def main(url):
    store = await Store.open(url)
    await store.close()
    print("alembic" in sys.modules)

asyncio.run(main(sys.argv[1]))
"""


def test_a_current_database_opens_without_importing_alembic(tmp_path: Path) -> None:
    url = f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}"

    def open_in_a_new_process() -> str:
        done = subprocess.run(
            [sys.executable, "-c", OPEN_AND_CLOSE, url],
            capture_output=True,
            text=True,
            timeout=120,
            check=True,
        )
        return done.stdout.strip()

    assert open_in_a_new_process() == "True"  # a new database: Alembic creates the schema
    assert open_in_a_new_process() == "False"  # current: checked without it
