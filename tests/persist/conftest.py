"""Fixtures of the persistence tests: each store test runs on a real SQLite file and on PostgreSQL."""

from __future__ import annotations

import os
from collections.abc import AsyncIterator, Iterator
from pathlib import Path

import pytest
from sqlalchemy.engine import URL, make_url

from gateway.registry.store import Store

from .pg import create_database, find_pg_bin, postgres_server


@pytest.fixture(scope="session")
def pg_base_url() -> Iterator[str]:
    """A PostgreSQL server URL without a database name: GATEWAY_TEST_DATABASE_URL when set (a role that
    may CREATE DATABASE; each test gets its own), else a throwaway local server."""
    given = os.environ.get("GATEWAY_TEST_DATABASE_URL", "").strip()
    if given:
        url = make_url(given)
        if not url.drivername.startswith("postgresql"):
            raise pytest.UsageError(f"GATEWAY_TEST_DATABASE_URL must be postgresql; got {url.drivername}")
        server = URL.create("postgresql+asyncpg", url.username, url.password, url.host, url.port)
        yield server.render_as_string(hide_password=False)
        return
    if not (find_pg_bin("initdb") and find_pg_bin("postgres")):
        pytest.skip("PostgreSQL server binaries are not installed (apt-get install postgresql)")
    with postgres_server() as url:
        yield url


@pytest.fixture(params=["sqlite", "postgresql"])
async def db_url(request: pytest.FixtureRequest, tmp_path: Path) -> str:
    if request.param == "sqlite":
        return f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}"
    return await create_database(request.getfixturevalue("pg_base_url"))


@pytest.fixture
def sqlite_url(tmp_path: Path) -> str:
    return f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}"


@pytest.fixture
async def sqlite_store(sqlite_url: str) -> AsyncIterator[Store]:
    store = await Store.open(sqlite_url)
    try:
        yield store
    finally:
        await store.close()
