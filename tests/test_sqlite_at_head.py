"""A test's fresh SQLite database, copied at the schema's head (tests/helpers/sqlite_at_head.py)."""

from __future__ import annotations

from pathlib import Path

from gateway.registry.database import create_engine_for, current_revision, head_revision
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.helpers.sqlite_at_head import at_head


async def revision(url: str) -> str | None:
    engine = create_engine_for(url)
    try:
        return await current_revision(engine)
    finally:
        await engine.dispose()


async def test_a_fresh_file_is_a_database_of_its_own_at_head(tmp_path: Path) -> None:
    one, other = (f"sqlite+aiosqlite:///{tmp_path / name}" for name in ("one.db", "other.db"))
    assert await at_head(one) == one and await at_head(other) == other
    assert await revision(one) == head_revision() and await revision(other) == head_revision()
    store = await Store.open(one)
    try:
        await store.add_vehicle(VehicleSpec(id="d1", url="udpin://127.0.0.1:14540"))
    finally:
        await store.close()
    store = await Store.open(other)
    try:
        assert await store.list_vehicles() == []
    finally:
        await store.close()


async def test_a_file_that_exists_and_other_databases_are_left_alone(tmp_path: Path) -> None:
    existing = tmp_path / "existing.db"
    existing.write_bytes(b"")
    url = f"sqlite+aiosqlite:///{existing}"
    assert await at_head(url) == url and existing.read_bytes() == b""
    for other in ("sqlite+aiosqlite:///:memory:", "postgresql+asyncpg://gw@127.0.0.1:1/gw_x"):
        assert await at_head(other) == other
