"""A ``fleet-gateway serve`` process on SQLite for the fault tests, killed or stopped by them, and the
waits and calls they share."""

from __future__ import annotations

import asyncio
import contextlib
import os
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
from tests.helpers.procs import stop_popen_group, tail
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
def gateway_process(
    db: Path, log: Path, extra_env: dict[str, str] | None = None
) -> Iterator[tuple[subprocess.Popen[bytes], str]]:
    port = free_tcp_port()
    with log.open("ab") as out:
        proc = subprocess.Popen(
            [sys.executable, "-m", "gateway.cli", "serve", "--host", "127.0.0.1", "--port", str(port)],
            env={**gateway_env(db), **(extra_env or {})},
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
    try:
        yield proc, f"http://127.0.0.1:{port}"
    finally:
        stop_popen_group(proc, 20)


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


async def get_ok(base: str, path: str) -> bool:
    async with httpx.AsyncClient(base_url=base, timeout=scaled(5)) as http:
        return (await http.get(path)).status_code == 200


async def is_state(base: str, state: str) -> bool:
    return await vehicle_state(base) == state


async def fly_d1_toward(base: str, url: str, home: dict[str, Any], north_m: float, log: Path) -> None:
    """Register the simulator's drone as d1, take it off to 10 m and send it north_m north without waiting."""
    async with httpx.AsyncClient(base_url=base, timeout=scaled(10)) as http:
        added = await http.post("/api/v1/vehicles", json={"id": "d1", "url": url, "expected_sysid": 1})
        assert added.status_code == 201, added.text
    await until("d1 ready", lambda: is_state(base, "ready"), log)
    far = geo.offset_position(home["lat"], home["lon"], north_m, 0)
    async with mcp_client(base) as c:

        async def took_off() -> Any:  # pre-arm checks pass once the simulated EKF has settled
            r = await c.call_tool("takeoff", {"drone_id": "d1", "alt_m": 10})
            return not r.is_error and r.structured_content["status"] == "succeeded"

        await until("takeoff", took_off, log)
        goto = {"drone_id": "d1", "lat_deg": far[0], "lon_deg": far[1], "alt_m": 10, "wait": False}
        sent = await c.call_tool("go_to_location", goto)
        assert not sent.is_error, sent.content
