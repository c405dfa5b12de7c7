"""The gateway process killed with SIGKILL mid-flight, then restarted on the same database.

Expected: its sidecars die with it (no orphan holding the drone's link), the drone flies its last command
on its own, the restarted gateway restores the vehicle, closes the flight the dead process left open at its
last committed track sample (none of those samples lost) and records the rest of the flight as a new
one; the SQLite file passes ``PRAGMA integrity_check``.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import sqlite3
import subprocess
import sys
from collections.abc import AsyncIterator, Iterator
from pathlib import Path
from typing import Any

import httpx
from mcp import Client
from mcp.types import Implementation

from gateway.fleet import geo
from gateway.util.ports import free_tcp_port
from tests.helpers import sim_process
from tests.helpers.procs import tail
from tests.helpers.timing import scaled

WAIT_S = scaled(90.0)  # generous: waiting is never an assertion


def gateway_env(db: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("GATEWAY_")}
    env.update(
        GATEWAY_DATABASE_URL=f"sqlite+aiosqlite:///{db}",
        GATEWAY_TRACK_FLUSH_S="0.5",
        GATEWAY_SIDECAR_BACKOFF_INITIAL_S="0.2",
        GATEWAY_SIDECAR_BACKOFF_MAX_S="1.0",
        PYTHONUNBUFFERED="1",
    )
    return env


@contextlib.contextmanager
def gateway_process(db: Path, log: Path) -> Iterator[tuple[subprocess.Popen, str]]:
    port = free_tcp_port()
    with log.open("ab") as out:
        proc = subprocess.Popen(
            [sys.executable, "-m", "gateway.cli", "serve", "--host", "127.0.0.1", "--port", str(port)],
            env=gateway_env(db),
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
    try:
        yield proc, f"http://127.0.0.1:{port}"
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGTERM)
            try:
                proc.wait(timeout=scaled(20))
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait(timeout=scaled(5))


async def until(what: str, check: Any, log: Path) -> Any:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + WAIT_S
    while True:
        try:
            result = await check()
        except (httpx.HTTPError, OSError):
            result = None
        if result:
            return result
        if loop.time() > deadline:
            raise AssertionError(f"{what} not reached\n{tail(str(log), 40)}")
        await asyncio.sleep(0.2)


async def vehicle_state(base: str) -> str | None:
    async with httpx.AsyncClient(base_url=base, timeout=scaled(5)) as http:
        r = await http.get("/api/v1/vehicles/d1")
        return r.json().get("state") if r.status_code == 200 else None


@contextlib.asynccontextmanager
async def mcp_client(base: str) -> AsyncIterator[Client]:
    async with Client(f"{base}/mcp", client_info=Implementation(name="sigkill", version="1")) as c:
        yield c


def query(db: Path, sql: str, *args: Any) -> list[tuple]:
    with contextlib.closing(sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=scaled(10))) as conn:
        return conn.execute(sql, args).fetchall()


def sidecars_for(url: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                cmd = (entry / "cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            if cmd and b"mavsdk_server" in cmd[0] and url.encode() in cmd:
                found.append(int(entry.name))
    return found


async def test_gateway_sigkill_mid_flight_then_restart(tmp_path: Path) -> None:
    db, log = tmp_path / "gateway.db", tmp_path / "gateway.log"
    async with sim_process(count=1, speedup=8.0) as sim:
        url = sim.urls[0]
        with gateway_process(db, log) as (proc, base):
            await until("gateway up", lambda: _get_ok(base, "/healthz"), log)
            async with httpx.AsyncClient(base_url=base, timeout=scaled(10)) as http:
                r = await http.post("/api/v1/vehicles", json={"id": "d1", "url": url, "expected_sysid": 1})
                assert r.status_code == 201, r.text
            await until("d1 ready", lambda: _is(base, "ready"), log)
            home = await sim.control.state(0)
            far = geo.offset_position(home["lat"], home["lon"], 60, 0)
            async with mcp_client(base) as c:

                async def took_off() -> Any:  # pre-arm checks pass once the simulated EKF has settled
                    r = await c.call_tool("takeoff", {"drone_id": "d1", "alt_m": 10})
                    return not r.is_error and r.structured_content["status"] == "succeeded"

                await until("takeoff", took_off, log)
                r = await c.call_tool(
                    "go_to_location",
                    {"drone_id": "d1", "lat_deg": far[0], "lon_deg": far[1], "alt_m": 10,
                     "wait": False},
                )  # fmt: skip
                assert not r.is_error, r.content

            async def some_samples() -> bool:
                rows = query(db, "SELECT count(*) FROM track_samples")
                return rows[0][0] >= 3

            await until("track samples committed", some_samples, log)
            committed = query(db, "SELECT flight_id, t, lat, lon FROM track_samples ORDER BY id")
            (flight_id,) = {row[0] for row in committed}
            proc.send_signal(signal.SIGKILL)
            proc.wait(timeout=scaled(10))

            async def no_sidecar() -> bool:
                return not sidecars_for(url)

            await until("the dead gateway's sidecar gone", no_sidecar, log)
        # the drone keeps flying its last command on its own
        s = await sim.control.state(0)
        assert s["armed"] and s["mode"] == "GUIDED", s

        with gateway_process(db, log) as (proc, base):
            await until("d1 restored and ready", lambda: _is(base, "ready"), log)
            flights = {
                row[0]: row
                for row in query(db, "SELECT id, ended_at, duration_s FROM flights WHERE vehicle_id = 'd1'")
            }
            assert flights[flight_id][1] is not None, f"flight {flight_id} left open: {flights}"
            sql = "SELECT flight_id, t, lat, lon FROM track_samples WHERE flight_id = ?"
            kept = query(db, sql, flight_id)
            assert set(committed) <= set(kept), "a committed track sample was lost"

            async def resumed() -> list[tuple]:
                return query(db, "SELECT id FROM flights WHERE vehicle_id = 'd1' AND ended_at IS NULL")

            (new_flight,) = (await until("the rest of the flight recorded", resumed, log))[0]
            assert new_flight != flight_id
            async with mcp_client(base) as c:
                r = await c.call_tool("land", {"drone_id": "d1"})
                assert not r.is_error and r.structured_content["status"] == "succeeded", r.content

            async def closed() -> bool:
                rows = query(db, "SELECT ended_at FROM flights WHERE id = ?", new_flight)
                return rows[0][0] is not None

            await until("the resumed flight closed after landing", closed, log)
        assert query(db, "PRAGMA integrity_check") == [("ok",)]
        assert not sidecars_for(url)


async def _get_ok(base: str, path: str) -> bool:
    async with httpx.AsyncClient(base_url=base, timeout=scaled(5)) as http:
        return (await http.get(path)).status_code == 200


async def _is(base: str, state: str) -> bool:
    return await vehicle_state(base) == state
