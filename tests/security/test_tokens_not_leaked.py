"""Bearer tokens never reach the logs or the database (audit, sessions), whether accepted or refused."""

from __future__ import annotations

import logging
from pathlib import Path

import httpx
import pytest

from gateway.app import create_app
from gateway.config import Settings
from tests.api.server import serve_in_thread
from tests.fakes import FakeRegistry
from tests.helpers.timing import scaled

OPERATOR, VIEWER, AGENT = "op-Zq8w-secret", "view-Zq8w-secret", "agent-Zq8w-secret"
WRONG = "wrong-Zq8w-secret"
MCP_HEADERS = {
    "accept": "application/json, text/event-stream",
    "mcp-protocol-version": "2026-07-28",
    "mcp-method": "tools/list",
}
MCP_BODY = {
    "jsonrpc": "2.0",
    "id": 1,
    "method": "tools/list",
    "params": {
        "_meta": {
            "io.modelcontextprotocol/clientInfo": {"name": "leak-check", "version": "1"},
            "io.modelcontextprotocol/protocolVersion": "2026-07-28",
            "io.modelcontextprotocol/clientCapabilities": {},
        }
    },
}


def test_tokens_stay_out_of_logs_and_database(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    db = tmp_path / "gateway.db"
    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{db}",
        operator_tokens=OPERATOR,
        viewer_tokens=VIEWER,
        agent_tokens=AGENT,
        log_level="DEBUG",
    )
    caplog.set_level(logging.DEBUG)
    with serve_in_thread(create_app(settings, registry_factory=FakeRegistry)) as base:
        with httpx.Client(base_url=base, timeout=scaled(30)) as http:

            def auth(token: str) -> dict[str, str]:
                return {"authorization": f"Bearer {token}"}

            vehicle = {"id": "alpha", "url": "udpin://127.0.0.1:14550"}
            assert http.post("/api/v1/vehicles", json=vehicle, headers=auth(OPERATOR)).status_code == 201
            assert http.get("/api/v1/vehicles", headers=auth(VIEWER)).status_code == 200
            assert (
                http.post("/api/v1/fleet/lock", json={"reason": "x"}, headers=auth(VIEWER)).status_code == 403
            )
            assert http.get("/api/v1/vehicles", headers=auth(WRONG)).status_code == 401
            assert http.get("/api/v1/vehicles", headers=auth(AGENT)).status_code == 401
            assert http.post("/mcp", json=MCP_BODY, headers={**MCP_HEADERS, **auth(AGENT)}).status_code == 200
            assert http.post("/mcp", json=MCP_BODY, headers={**MCP_HEADERS, **auth(WRONG)}).status_code == 401
            assert (
                http.post("/mcp", json=MCP_BODY, headers={**MCP_HEADERS, **auth(OPERATOR)}).status_code == 401
            )
            audit = http.get("/api/v1/audit", headers=auth(OPERATOR)).json()
            assert audit["total"] >= 2  # calls were recorded, under principals
    stored = b"".join(p.read_bytes() for p in tmp_path.glob("gateway.db*"))
    logged = caplog.text
    assert caplog.records  # the check below looked at real log output
    for token in (OPERATOR, VIEWER, AGENT, WRONG):
        assert token not in logged, f"a token was logged: {token}"
        assert token.encode() not in stored, f"a token was stored in the database: {token}"
        assert "Zq8w" not in str(audit)
