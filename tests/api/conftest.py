"""Fixtures of the REST tests: an app on a real SQLite file, driven in-process through its lifespan."""

from __future__ import annotations

from collections.abc import AsyncIterator, Iterator
from pathlib import Path

import httpx
import pytest
from fastapi import FastAPI

from gateway.app import create_app
from gateway.config import Settings
from tests.fakes import FakeRegistry
from tests.helpers.sqlite_at_head import at_head

from .live import lifespan_running


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return Settings(
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}", max_request_body_bytes=4096
    )


@pytest.fixture
async def app(settings: Settings) -> AsyncIterator[FastAPI]:
    await at_head(settings.database_url)  # its store opens a copy at head, not Alembic's upgrade of it
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as app:
        yield app


@pytest.fixture
async def client(app: FastAPI) -> AsyncIterator[httpx.AsyncClient]:
    transport = httpx.ASGITransport(app=app)
    async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as client:
        yield client


@pytest.fixture(scope="session")
def pg_server_url() -> Iterator[str]:
    from tests.persist.pg import find_pg_bin, postgres_server

    if not (find_pg_bin("initdb") and find_pg_bin("postgres")):
        pytest.skip("PostgreSQL server binaries are not installed (apt-get install postgresql)")
    with postgres_server() as url:
        yield url


@pytest.fixture
async def pg_database_url(pg_server_url: str) -> str:
    from tests.persist.pg import create_database

    return await create_database(pg_server_url)
