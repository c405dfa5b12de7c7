"""Serve the gateway on a free loopback port for tests (real HTTP): an app in a background thread, or a
``fleet-gateway serve`` process."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import httpx
import uvicorn
from fastapi import FastAPI

from gateway.config import Settings
from gateway.util.ports import free_tcp_port
from tests.helpers.procs import stop_popen_group, tail
from tests.helpers.timing import scaled
from tests.registry.procs import mavsdk_servers_of


@contextmanager
def serve_in_thread(app: FastAPI, startup_timeout_s: float = 60.0, port: int | None = None) -> Iterator[str]:
    """Yield the base URL of ``app`` served on 127.0.0.1 (a free port unless ``port``); the server (and its
    lifespan) stop on exit."""
    port = port or free_tcp_port()
    server = uvicorn.Server(
        uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning", lifespan="on")
    )
    thread = threading.Thread(target=server.run, name=f"uvicorn-{port}", daemon=True)
    thread.start()
    try:
        deadline = time.monotonic() + scaled(startup_timeout_s)
        while not server.started:
            if not thread.is_alive():
                raise RuntimeError("the test server exited during startup")
            if time.monotonic() > deadline:
                raise TimeoutError(f"the test server did not start within {startup_timeout_s} s")
            time.sleep(0.05)
        yield f"http://127.0.0.1:{port}"
    finally:
        server.should_exit = True
        thread.join(timeout=scaled(60))


@contextmanager
def serve_in_process(settings: Settings, log: Path, startup_timeout_s: float = 60.0) -> Iterator[str]:
    """Yield the base URL of a ``fleet-gateway serve`` process on 127.0.0.1 (a free port) with the
    settings ``settings`` was made with (as GATEWAY_* variables), its output in ``log``. Its own process,
    as in production: clients in the test's process do not take the gateway's interpreter lock. Stopped
    with SIGTERM on exit; the sidecars it started must be gone with it."""
    port = free_tcp_port()
    env = {k: v for k, v in os.environ.items() if not k.startswith("GATEWAY_")}
    for name in settings.model_fields_set:
        value = getattr(settings, name)
        env[f"GATEWAY_{name.upper()}"] = value if isinstance(value, str) else json.dumps(value)
    env["PYTHONUNBUFFERED"] = "1"
    with log.open("ab") as out:
        proc = subprocess.Popen(
            [sys.executable, "-m", "gateway.cli", "serve", "--host", "127.0.0.1", "--port", str(port)],
            env=env,
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
    base_url = f"http://127.0.0.1:{port}"
    sidecars: list[int] = []
    try:
        deadline = time.monotonic() + scaled(startup_timeout_s)
        while not _answers(f"{base_url}/readyz"):
            if proc.poll() is not None:
                raise RuntimeError(
                    f"the gateway exited during startup ({proc.returncode}):\n{tail(str(log))}"
                )
            if time.monotonic() > deadline:
                raise TimeoutError(
                    f"the gateway was not ready within {startup_timeout_s} s:\n{tail(str(log))}"
                )
            time.sleep(0.1)
        yield base_url
        sidecars = mavsdk_servers_of(proc.pid)
    finally:
        stop_popen_group(proc, 30)
    survivors = [pid for pid in sidecars if Path(f"/proc/{pid}").exists()]
    assert not survivors, f"mavsdk_server {survivors} survived the gateway"


def _answers(url: str) -> bool:
    try:
        return httpx.get(url, timeout=2.0).status_code == 200
    except httpx.HTTPError:
        return False
