"""2025-era MCP sessions (Mcp-Session-Id) are capped per caller: a client that opens sessions and never
closes them keeps at most GATEWAY_MCP_SESSIONS_PER_CALLER; the one idle the longest makes room. Real HTTP,
the real app, fake drones."""

from __future__ import annotations

from pathlib import Path

import httpx

from gateway.app import create_app
from gateway.config import Settings
from tests.api.server import serve_in_thread
from tests.fakes import FakeRegistry
from tests.helpers.timing import scaled

OPENING = {
    "jsonrpc": "2.0",
    "id": 1,
    "method": "initialize",
    "params": {
        "protocolVersion": "2025-06-18",
        "capabilities": {},
        "clientInfo": {"name": "leaky", "version": "1"},
    },
}
HEADERS = {"accept": "application/json, text/event-stream"}
PING = {"jsonrpc": "2.0", "id": 2, "method": "ping"}


def test_one_caller_keeps_at_most_its_cap_of_sessions(tmp_path: Path) -> None:
    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        mcp_sessions_per_caller=3,
    )
    app = create_app(settings, registry_factory=FakeRegistry)
    with serve_in_thread(app) as url, httpx.Client(base_url=url, timeout=scaled(30)) as http:
        opened = []
        for _ in range(5):  # opened and never closed
            r = http.post("/mcp", json=OPENING, headers=HEADERS)
            assert r.status_code == 200, r.text
            opened.append(r.headers["mcp-session-id"])
        manager = app.state.mcp.session_manager
        assert len(manager._server_instances) == 3
        answers = [
            http.post(
                "/mcp",
                json=PING,
                headers={**HEADERS, "mcp-session-id": sid, "mcp-protocol-version": "2025-06-18"},
            ).status_code
            for sid in opened
        ]
        assert answers == [404, 404, 200, 200, 200], answers  # the two idle the longest made room


def test_the_settings_bound_the_cap_and_the_idle_time() -> None:
    import pytest
    from pydantic import ValidationError

    for bad in ({"mcp_sessions_per_caller": 0}, {"mcp_session_idle_s": 0}):
        with pytest.raises(ValidationError):
            Settings(_env_file=None, **bad)


def test_a_session_idle_past_its_time_is_closed(tmp_path: Path) -> None:
    """GATEWAY_MCP_SESSION_IDLE_S: a session nobody sends a request on is closed after it (a client that
    opens one session and goes away does not hold it until the cap makes room)."""
    import time

    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        mcp_session_idle_s=1.0,
    )
    app = create_app(settings, registry_factory=FakeRegistry)
    with serve_in_thread(app) as url, httpx.Client(base_url=url, timeout=scaled(30)) as http:
        r = http.post("/mcp", json=OPENING, headers=HEADERS)
        assert r.status_code == 200, r.text
        session = {
            **HEADERS,
            "mcp-session-id": r.headers["mcp-session-id"],
            "mcp-protocol-version": "2025-06-18",
        }
        manager = app.state.mcp.session_manager
        deadline = time.monotonic() + scaled(30)
        while manager._server_instances:  # closed by the manager once idle for a second
            assert time.monotonic() < deadline, "the idle session was never closed"
            time.sleep(0.1)
        assert http.post("/mcp", json=PING, headers=session).status_code == 404
