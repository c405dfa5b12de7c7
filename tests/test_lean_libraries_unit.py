"""Libraries whose start-up imports the gateway leaves out, still whole when used: uvicorn without its
command line (gateway/util/lean_uvicorn.py), FastAPI's pydantic v1 checks without ``pydantic.v1``
(gateway/api/fastapi_v1.py) and SQLAlchemy's async engine without the ORM
(gateway/registry/sql_async.py). Each check runs in a fresh interpreter, since what is in
``sys.modules`` is the point."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[1]

UVICORN = r"""
import sys
from gateway.util.lean_uvicorn import Config, Server
import sse_starlette.sse as sse
import uvicorn.server

assert "uvicorn.main" not in sys.modules and "click" not in sys.modules, "uvicorn's command line loaded"
assert Server is uvicorn.server.Server
assert Server.handle_exit is sse.AppStatus.handle_exit, "sse_starlette did not wrap the server's exit"
from uvicorn.lifespan.on import LifespanOn  # imports Config from the package
assert "uvicorn.main" not in sys.modules

import uvicorn
assert callable(uvicorn.run), "the package's own names"  # runs its __init__: the command line loads
assert sys.modules["uvicorn.main"].Server is Server and "click" in sys.modules
print("ok")
"""

FASTAPI_V1 = r"""
import sys
import gateway.api  # its routes are built
from fastapi import APIRouter
from fastapi.encoders import jsonable_encoder
from pydantic import BaseModel

assert "pydantic.v1" not in sys.modules, "pydantic.v1 loaded by building the routes"

class Answer(BaseModel):
    x: int

router = APIRouter()

@router.get("/a", response_model=Answer)
def answer() -> Answer:
    return Answer(x=1)

assert jsonable_encoder(Answer(x=1)) == {"x": 1}
assert "pydantic.v1" not in sys.modules

from fastapi.exceptions import PydanticV1NotSupportedError
from pydantic import v1

class Old(v1.BaseModel):
    x: int

try:
    jsonable_encoder(Old(x=1))
except PydanticV1NotSupportedError:
    pass
else:
    raise AssertionError("a v1 model was encoded")
try:
    @router.get("/old", response_model=Old)
    def old() -> None: ...
except PydanticV1NotSupportedError:
    pass
else:
    raise AssertionError("a v1 response model was taken")
print("ok")
"""

SQL_ASYNC = r"""
import asyncio, sys
from gateway.registry.sql_async import create_async_engine
from gateway.registry.models import metadata, vehicles
from sqlalchemy import insert, select

async def main():
    engine = create_async_engine("sqlite+aiosqlite://")
    async with engine.begin() as conn:
        await conn.run_sync(metadata.create_all)
        await conn.execute(insert(vehicles).values(id="a", url="udpin://0.0.0.0:14540", created_at=now,
                                                   updated_at=now))
    async with engine.connect() as conn:
        row = (await conn.execute(select(vehicles))).mappings().one()
    await engine.dispose()
    return row

from datetime import UTC, datetime
now = datetime.now(UTC)
row = asyncio.run(main())
assert row["id"] == "a" and row["tags"] == [] and row["auto_connect"] is True and row["created_at"] == now
assert not [m for m in sys.modules if m.startswith("sqlalchemy.orm")], "the ORM was loaded"

from sqlalchemy.ext.asyncio import AsyncSession, async_sessionmaker  # the package's own names: whole
assert "sqlalchemy.orm" in sys.modules and AsyncSession.__module__ == "sqlalchemy.ext.asyncio.session"
print("ok")
"""


def run_child(code: str) -> None:
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=scaled(120)
    )
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr[-3000:]


def test_uvicorn_serves_without_its_command_line_and_is_whole_when_asked() -> None:
    run_child(UVICORN)


def test_fastapi_refuses_pydantic_v1_models_without_the_gateway_importing_pydantic_v1() -> None:
    run_child(FASTAPI_V1)


def test_the_store_runs_on_the_async_engine_without_the_orm_which_loads_when_asked() -> None:
    run_child(SQL_ASYNC)
