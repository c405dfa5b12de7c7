"""A plain start imports only what its configuration uses: `serve` and `mcp-stdio` with one SQLite
database, no cluster, no drone flying a mission, no ground-station relay, no agent. Each runs as its own
process; once it serves, it writes the names in its ``sys.modules`` and is stopped. Memory is what these
imports cost (docs/benchmarks.md, "Memory per drone"), so a module that slips back into the start shows
here rather than as a few MiB more in a benchmark nobody runs."""

from __future__ import annotations

import asyncio
import json
import os
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from gateway.registry.schema_check import head_from_files
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from gateway.util.ports import free_tcp_port, free_udp_port
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[1]

#: what a plain start must not import, each with the configuration or the moment that needs it
NOT_AT_START = {
    "alembic": "a database whose schema is older than the code (Store.open)",
    "mako": "Alembic's templates",
    "pymavlink": "a mission judged, a ground-station relay, a flight exported",
    "numpy": "a formation planned",
    "scipy": "a formation's slot assignment",
    "shapely": "a geofence",
    "fleet_agent": "`fleet-gateway agent`",
    "openai": "`fleet-gateway agent`",
    "nats": "a cluster",
    "asyncpg": "PostgreSQL or a cluster",
    "sqlalchemy.dialects.postgresql": "PostgreSQL",
    "gateway.cluster": "a cluster",
    "gateway.sim": "`fleet-gateway sim`",
    "gateway.demo": "`fleet-gateway demo`",
    "httpx": "the drones commands that call the API",
    "jwt": "nothing of the gateway",
    "rich": "nothing of a server (the MCP SDK's logging handler: gateway.mcp.sdk_private)",
    "cryptography": "a request state sealed (a 2026-07-28 elicited confirmation): gateway.mcp.sdk_crypto",
    "mcp.client": "nothing of a server (the MCP SDK's package __init__: gateway.mcp.sdk_package)",
    "httpx2": "a resource the MCP SDK fetches by URL (the gateway registers none)",
    "mavsdk_grpc.system": "nothing: gateway.link.mavsdk_system loads only the plugins the gateway uses",
    "mavsdk_grpc.camera": "nothing: a plugin the gateway does not use",
    "mavsdk_grpc.telemetry": "nothing: the link uses the *_pb2 messages, never the wrappers (grpcio)",
    "grpc": "nothing: the link to mavsdk_server speaks grpclib (gateway.link.mavsdk_rpc)",
    "pydantic.v1": "a pydantic v1 model (FastAPI's checks for one: gateway.api.fastapi_v1)",
    "uvicorn.main": "uvicorn's command line (the gateway's own: gateway.util.lean_uvicorn)",
    "click": "uvicorn's command line",
    "multiprocessing": "uvicorn's reloader and workers",
    "sqlalchemy.orm": "nothing: the store writes Core statements (gateway.registry.models, sql_async)",
    "sqlalchemy.ext.asyncio.session": "nothing: the store uses the async engine's connections only",
}

# The child: start the command in the main thread; a watcher thread waits until it serves, writes the
# loaded modules and stops it (SIGINT for serve, the end of stdin for mcp-stdio).
CHILD = r"""
import json, os, signal, sys, threading, time, urllib.error, urllib.request

command, out, port = sys.argv[1], sys.argv[2], sys.argv[3]

def serving():
    if command == "serve":
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/healthz", timeout=2)
        except urllib.error.HTTPError:
            pass  # it answers: it serves
        except OSError:
            return False
        return True
    # the stdio server has started its gateway (the runtime and a MAVSDK plugin are loaded by then)
    started = ("mcp.server.stdio", "gateway.mcp.server", "gateway.runtime", "mavsdk_grpc.telemetry_pb2")
    return all(name in sys.modules for name in started)

def ready():
    wanted = filter(None, os.environ.get("LEAN_START_LOADED", "").split(","))
    return serving() and all(name in sys.modules for name in wanted)

def watch():
    deadline = time.monotonic() + float(os.environ["LEAN_START_DEADLINE"])
    while time.monotonic() < deadline and not ready():
        time.sleep(0.1)
    with open(out + ".tmp", "w") as fh:
        json.dump({"serving": ready(), "modules": sorted(sys.modules)}, fh)
    os.replace(out + ".tmp", out)
    if command == "serve":
        os.kill(os.getpid(), signal.SIGINT)

threading.Thread(target=watch, daemon=True).start()
from gateway.cli import main
args = ["serve", "--port", port] if command == "serve" else ["mcp-stdio"]
sys.exit(main(args))
"""


def environment(database_url: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("GATEWAY_")}
    env.update(
        PYTHONPATH=str(ROOT),
        GATEWAY_DATABASE_URL=database_url,
        LEAN_START_DEADLINE=str(scaled(90)),
    )
    return env


def loaded_at_start(
    command: str, tmp_path: Path, upgraded_first: bool = True, drone_url: str | None = None
) -> list[str]:
    """The modules ``command`` has loaded once it serves; with ``drone_url``, a drone registered at that
    URL first, and once its link has started its relay too."""
    database_url = f"sqlite+aiosqlite:///{tmp_path / 'fleet.db'}"
    env = environment(database_url)
    if upgraded_first:  # a database at the current schema, as every start after the first finds it
        subprocess.run(
            [sys.executable, "-m", "gateway.cli", "db", "upgrade"],
            cwd=tmp_path, env=env, check=True, capture_output=True, timeout=scaled(120),
        )  # fmt: skip
    if drone_url is not None:
        asyncio.run(register_drone(database_url, drone_url))
        env["LEAN_START_LOADED"] = "gateway.link.relay"
    out = tmp_path / f"{command}.json"
    proc = subprocess.Popen(
        [sys.executable, "-c", CHILD, command, str(out), str(free_tcp_port())],
        cwd=tmp_path, env=env, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + scaled(120)
        while not out.exists() and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.1)
        assert out.exists(), f"{command} wrote no module list (exit {proc.poll()})"
    finally:
        if proc.stdin is not None:
            proc.stdin.close()  # mcp-stdio ends with its input
        try:
            proc.wait(timeout=scaled(30))
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        stderr = proc.stderr.read().decode(errors="replace") if proc.stderr is not None else ""
        if proc.stderr is not None:
            proc.stderr.close()
    report = json.loads(out.read_text())
    assert report["serving"], f"{command} did not start serving: {stderr[-2000:]}"
    modules: list[str] = report["modules"]
    return modules


async def register_drone(database_url: str, url: str) -> None:
    store = await Store.open(database_url)
    try:
        await store.add_vehicle(VehicleSpec(id="d1", url=url))
    finally:
        await store.close()


def unexpected(modules: list[str]) -> dict[str, str]:
    return {
        name: why
        for name, why in NOT_AT_START.items()
        if any(m == name or m.startswith(name + ".") for m in modules)
    }


@pytest.mark.parametrize("command", ["serve", "mcp-stdio"])
def test_a_plain_start_imports_only_what_its_configuration_uses(command: str, tmp_path: Path) -> None:
    modules = loaded_at_start(command, tmp_path)
    assert "gateway.runtime" in modules and "mavsdk_grpc.telemetry_pb2" in modules  # it did start a gateway
    assert unexpected(modules) == {}, f"{command} imported at start what only these need"


def test_a_drone_relayed_for_its_raw_flight_log_loads_no_pymavlink(tmp_path: Path) -> None:
    """Every drone's link runs through the gateway's relay while flights' raw MAVLink is recorded (the
    default): its frames are split, checked and routed by `gateway.link.mavlink_frames` with
    `gateway.link.mavlink_messages`, and pymavlink (its dialect module, about 6 MiB, and its CRC with
    the fastcrc extension) waits for a ground station's frame or a mission."""
    modules = loaded_at_start("serve", tmp_path, drone_url=f"udpin://127.0.0.1:{free_udp_port()}")
    assert "gateway.link.relay" in modules  # the drone's link did start its relay
    mavlink = [m for m in modules if m.startswith(("pymavlink", "fastcrc", "gateway.link.ground_commands"))]
    assert mavlink == [], "a drone relayed only for its raw flight log loaded pymavlink"


def test_a_first_start_upgrades_the_new_database_without_keeping_alembic(tmp_path: Path) -> None:
    """``serve`` on a database that does not exist yet: the schema upgrade runs in a child process,
    which takes Alembic and Mako with it, and the database is at the newest revision afterwards."""
    modules = loaded_at_start("serve", tmp_path, upgraded_first=False)
    assert "gateway.runtime" in modules
    assert unexpected(modules) == {}, "serve kept the schema upgrade's modules"
    versions = ROOT / "migrations" / "versions"
    with sqlite3.connect(tmp_path / "fleet.db") as db:
        rows = db.execute("SELECT version_num FROM alembic_version").fetchall()
    assert rows == [(head_from_files(versions),)]


def test_no_gateway_module_imports_mavsdk_grpc_but_the_one_that_loads_it_lean() -> None:
    """Importing ``mavsdk_grpc`` (or one of its modules) first anywhere else would run the package's
    ``__init__``, which imports all 40 plugins: the gateway reaches it through gateway.link.mavsdk_system."""
    offenders = []
    for path in sorted((ROOT / "gateway").rglob("*.py")):
        if path.name == "mavsdk_system.py":
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            words = line.split()
            if words[:2] in (["import", "mavsdk_grpc"], ["from", "mavsdk_grpc"]) or (
                len(words) >= 2 and words[0] in ("import", "from") and words[1].startswith("mavsdk_grpc.")
            ):
                offenders.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()}")
    assert offenders == []
