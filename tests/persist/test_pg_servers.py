"""The throwaway PostgreSQL servers of the tests (tests/persist/pg.py): each a copy of one initdb made
once, and each its own server (a database made on one is not on another, the template never runs)."""

from __future__ import annotations

import asyncpg
import pytest

from tests.persist.pg import create_database, find_pg_bin, initdb_template, restartable_postgres

pytestmark = pytest.mark.skipif(
    not (find_pg_bin("initdb") and find_pg_bin("postgres")),
    reason="PostgreSQL server binaries are not installed (apt-get install postgresql)",
)


async def test_servers_copied_from_one_initdb_are_each_their_own() -> None:
    initdb = find_pg_bin("initdb")
    assert initdb is not None
    template = initdb_template(initdb)
    with restartable_postgres() as one, restartable_postgres() as other:
        assert one.data != other.data and one.port != other.port
        made = await create_database(one.url)
        name = made.rsplit("/", 1)[1]
        conn = await asyncpg.connect(f"postgresql://gw@127.0.0.1:{one.port}/{name}")
        await conn.close()
        with pytest.raises(asyncpg.InvalidCatalogNameError):
            await asyncpg.connect(f"postgresql://gw@127.0.0.1:{other.port}/{name}")
    assert initdb_template(initdb) == template
    assert (template / "PG_VERSION").is_file() and not (template / "postmaster.pid").exists()
