"""Helpers of the live REST tests: the gateway app served by uvicorn in the test's own event loop.

Serving in the same loop lets a test reach the running gateway's Vehicle objects directly (e.g. to fly
a simulated drone) while every REST call still goes over real HTTP on loopback.
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from pathlib import Path
from typing import Any

import httpx
import uvicorn
from fastapi import FastAPI

from gateway.app import create_app
from gateway.config import Settings
from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

WAIT_S = scaled(90.0)  # generous: waiting is not asserting a duration


def live_settings(db_path: Path, **overrides: Any) -> Settings:
    base: dict[str, Any] = {
        "database_url": f"sqlite+aiosqlite:///{db_path}",
        "sidecar_backoff_initial_s": 0.2,
        "sidecar_backoff_max_s": 1.0,
        "link_lost_after_s": 3.0,
        "track_sample_hz": 5.0,
        "track_flush_s": 0.5,
    }
    base.update(overrides)
    return Settings(**base)


@contextlib.asynccontextmanager
async def served(settings: Settings) -> AsyncIterator[tuple[FastAPI, httpx.AsyncClient]]:
    """Serve a new gateway app on 127.0.0.1:<free port>; yield it and an HTTP client bound to it."""
    app = create_app(settings)
    port = free_tcp_port()
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning"))
    server.capture_signals = contextlib.nullcontext  # type: ignore[method-assign]  # pytest owns signals
    task = asyncio.create_task(server.serve(), name=f"gateway-{port}")
    try:
        deadline = time.monotonic() + WAIT_S
        while not server.started:
            if task.done():
                task.result()  # raises the startup error
                raise RuntimeError("the gateway server exited during startup")
            if time.monotonic() > deadline:
                raise TimeoutError("the gateway server did not start")
            await asyncio.sleep(0.05)
        async with httpx.AsyncClient(base_url=f"http://127.0.0.1:{port}", timeout=scaled(30.0)) as client:
            yield app, client
    finally:
        server.should_exit = True
        with contextlib.suppress(Exception):
            await asyncio.wait_for(task, WAIT_S)


@contextlib.asynccontextmanager
async def lifespan_running(app: FastAPI) -> AsyncIterator[FastAPI]:
    """Run the app's lifespan in a task of its own (its task groups must enter and exit in one task)."""
    started, stop = asyncio.Event(), asyncio.Event()

    async def run() -> None:
        async with app.router.lifespan_context(app):
            started.set()
            await stop.wait()

    task = asyncio.create_task(run(), name="app-lifespan")
    waiter = asyncio.create_task(started.wait())
    try:
        await asyncio.wait({task, waiter}, return_when=asyncio.FIRST_COMPLETED)
        if task.done():
            task.result()  # startup failed: raise its error
        yield app
    finally:
        waiter.cancel()
        stop.set()
        await task


async def wait_until(
    check: Callable[[], Awaitable[bool]], what: str, within_s: float = WAIT_S, every_s: float = 0.25
) -> None:
    deadline = time.monotonic() + within_s
    while not await check():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what}")
        await asyncio.sleep(every_s)


async def states(client: httpx.AsyncClient) -> dict[str, str]:
    response = await client.get("/api/v1/vehicles")
    response.raise_for_status()
    return {v["id"]: v["state"] for v in response.json()["items"]}


async def wait_all_ready(client: httpx.AsyncClient, ids: list[str]) -> None:
    async def all_ready() -> bool:
        current = await states(client)
        return all(current.get(i) == "ready" for i in ids)

    await wait_until(all_ready, f"{ids} to be ready")
