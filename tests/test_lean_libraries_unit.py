"""Libraries whose start-up imports the gateway leaves out, still whole when used: uvicorn without its
command line (gateway/util/lean_uvicorn.py), FastAPI's pydantic v1 checks without ``pydantic.v1``
(gateway/api/fastapi_v1.py), SQLAlchemy's async engine without the ORM
(gateway/registry/sql_async.py), and the MCP SDK's wire types and FastAPI's OpenAPI models with their
validators built at first use (gateway/util/deferred_models.py). Each check runs in a fresh interpreter,
since what is in ``sys.modules`` (or built) is the point."""

from __future__ import annotations

import json
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

# argv[1]: "deferred" imports the gateway first (as a start does), "eager" the two libraries before it.
# Both then validate the same requests of each protocol era, dump a result and build the OpenAPI
# document; the outputs must be the same.
DEFERRED_MODELS = r"""
import json, sys
if sys.argv[1] == "eager":
    import fastapi.openapi.models, mcp_types.methods
import gateway.app
from gateway.config import Settings
from gateway.util.deferred_models import deferral_available
import fastapi.openapi.models as openapi_models
import mcp_types, mcp_types.methods as methods
import mcp_types._v2025_11_25 as v2025, mcp_types._v2026_07_28 as v2026
from pydantic import BaseModel, ValidationError

def built(module):
    classes = [c for c in vars(module).values()
               if isinstance(c, type) and issubclass(c, BaseModel) and c.__module__ == module.__name__]
    return sum(c.__pydantic_complete__ for c in classes) / len(classes)

shares = [built(m) for m in (v2025, v2026, mcp_types._types, openapi_models)]
if sys.argv[1] == "deferred":
    assert deferral_available(), "pydantic changed: gateway/util/deferred_models.py defers nothing"
    assert max(shares) < 0.25 and not mcp_types.client_request_adapter.pydantic_complete, shares
else:
    assert min(shares) > 0.9, shares

out = {}
call = {"name": "get_position", "arguments": {"drone_id": "d1"}}
meta = {"io.modelcontextprotocol/protocolVersion": "2026-07-28",
        "io.modelcontextprotocol/clientInfo": {"name": "c", "version": "1"},
        "io.modelcontextprotocol/clientCapabilities": {}}
for version in ("2025-11-25", "2026-07-28"):
    for i, params in enumerate([call, {"arguments": {}}, {**call, "_meta": meta}]):
        try:
            request = methods.parse_client_request("tools/call", version, params)
            out[f"{version} {i}"] = request.model_dump(mode="json")
        except ValidationError as exc:
            out[f"{version} {i}"] = exc.errors(include_url=False)
message = '{"jsonrpc": "2.0", "id": 1, "method": "tools/list"}'
out["message"] = mcp_types.jsonrpc_message_adapter.validate_json(message).model_dump(mode="json")
out["ping"] = mcp_types.client_request_adapter.validate_python({"method": "ping"}).model_dump(mode="json")
text = mcp_types.TextContent(type="text", text="hi")
result = mcp_types.CallToolResult(content=[text], structured_content={})
out["result"] = result.model_dump(mode="json", by_alias=True, exclude_none=True)
app = gateway.app.create_app(Settings(_env_file=None, database_url="sqlite+aiosqlite:///:memory:"))
out["openapi"] = app.openapi()
if sys.argv[1] == "deferred":
    assert openapi_models.OpenAPI.__pydantic_complete__, "the OpenAPI document was not validated"
print(json.dumps(out, sort_keys=True, default=str))
"""


def run_child(code: str, *args: str) -> str:
    done = subprocess.run(
        [sys.executable, "-c", code, *args], cwd=ROOT, capture_output=True, text=True, timeout=scaled(120)
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.strip()


def test_uvicorn_serves_without_its_command_line_and_is_whole_when_asked() -> None:
    assert run_child(UVICORN) == "ok"


def test_fastapi_refuses_pydantic_v1_models_without_the_gateway_importing_pydantic_v1() -> None:
    assert run_child(FASTAPI_V1) == "ok"


def test_the_store_runs_on_the_async_engine_without_the_orm_which_loads_when_asked() -> None:
    assert run_child(SQL_ASYNC) == "ok"


def test_sdk_wire_types_and_openapi_models_built_when_used_answer_as_built_at_import() -> None:
    """The gateway imports both libraries' models unbuilt; validating, dumping and the OpenAPI document
    answer the same as with every model built at import (a validation error included)."""
    deferred = json.loads(run_child(DEFERRED_MODELS, "deferred"))
    eager = json.loads(run_child(DEFERRED_MODELS, "eager"))
    assert deferred == eager
    assert deferred["2025-11-25 0"]["params"]["name"] == "get_position"
    assert deferred["2025-11-25 1"][0]["loc"] == ["params", "name"]  # a call without a name
    assert "/api/v1/fleet/stop" in deferred["openapi"]["paths"]
