"""Run an app with uvicorn on a free loopback port in a background thread (real HTTP for tests)."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

import uvicorn
from fastapi import FastAPI

from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled


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
