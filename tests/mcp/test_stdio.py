"""`fleet-gateway mcp-stdio`: the same server over stdio, for clients that launch it (both eras)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from mcp import Client
from mcp.client.stdio import StdioServerParameters
from mcp.types import Implementation

from gateway.registry.store import Store

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("mode", ["auto", "legacy"])
async def test_stdio_server_lists_tools_answers_and_records_the_session(tmp_path: Path, mode: str) -> None:
    url = f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}"
    env = {**os.environ, "GATEWAY_DATABASE_URL": url, "GATEWAY_MCP_TOOLSETS": "flight,telemetry"}
    params = StdioServerParameters(
        command=sys.executable, args=["-m", "gateway.cli", "mcp-stdio"], env=env, cwd=ROOT
    )
    async with Client(params, mode=mode, client_info=Implementation(name="stdio-host", version="2.0")) as c:
        names = {t.name for t in (await c.list_tools()).tools}
        assert "takeoff" in names and "get_battery" in names and "go_to_location" not in names  # toolsets
        r = await c.call_tool("get_battery", {"drone_id": "d1"})
        assert r.is_error and "none registered" in r.content[0].text
    store = await Store.open(url)
    try:
        sessions = await store.list_sessions()
        audit = await store.list_audit()
    finally:
        await store.close()
    kind = "mcp-2026" if mode == "auto" else "mcp-2025"
    assert [(s.kind, s.client_name, s.principal) for s in sessions] == [(kind, "stdio-host", "local")]
    assert [(a.action, a.outcome, a.vehicle_id) for a in audit] == [("get_battery", "error", "d1")]


async def test_stdio_server_creates_a_missing_database_directory(tmp_path: Path) -> None:
    """As `serve` does: the SQLite file's directory is created, and the client gets its tools."""
    database = tmp_path / "not" / "yet" / "gateway.db"
    env = {**os.environ, "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{database}"}
    params = StdioServerParameters(
        command=sys.executable, args=["-m", "gateway.cli", "mcp-stdio"], env=env, cwd=ROOT
    )
    async with Client(params, client_info=Implementation(name="stdio-host", version="2.0")) as c:
        assert "takeoff" in {t.name for t in (await c.list_tools()).tools}
    assert database.is_file()


def test_stdio_server_with_an_unwritable_database_place_says_so_in_one_line(tmp_path: Path) -> None:
    import subprocess

    blocker = tmp_path / "a-file"
    blocker.write_text("")
    env = {**os.environ, "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{blocker / 'sub' / 'gateway.db'}"}
    done = subprocess.run(
        [sys.executable, "-m", "gateway.cli", "mcp-stdio"],
        env=env,
        cwd=ROOT,
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2 and done.stdout == ""
    assert (
        done.stderr.startswith("error: cannot create the database directory")
        and "Traceback" not in done.stderr
    )
