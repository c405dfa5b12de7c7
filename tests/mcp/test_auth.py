"""With GATEWAY_AGENT_TOKENS set, /mcp needs a bearer token; the session and audit carry the agent's
principal (derived from the token, never the token itself). In-process ASGI, no sockets."""

from __future__ import annotations

from typing import Any

import httpx2
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation

from gateway.config import Settings
from gateway.mcp.auth import principal_of
from gateway.mcp.server import build_mcp, mcp_http_app, mcp_lifespan
from tests.mcp.fakes import FakeGateway

URL = "http://127.0.0.1:8765/mcp"


class RecordingStore:
    def __init__(self) -> None:
        self.sessions: list[dict[str, Any]] = []
        self.audit: list[Any] = []

    async def touch_session(self, key: str, kind: str, **kw: Any) -> None:
        self.sessions.append({"key": key, "kind": kind, **kw})

    async def add_audit(self, entry: Any) -> None:
        self.audit.append(entry)

    async def save_operation(self, record: Any) -> None:
        return None

    async def list_operations(self, *args: Any, **kw: Any) -> list[Any]:
        return []


async def test_agent_token_required_and_recorded_as_principal() -> None:
    store = RecordingStore()
    settings = Settings(_env_file=None, agent_tokens="s3cret-token,other-token")
    server = build_mcp(FakeGateway(settings, store=store))
    app = mcp_http_app(server, settings)
    body = {"jsonrpc": "2.0", "id": 1, "method": "tools/list", "params": {}}
    headers = {"accept": "application/json, text/event-stream", "mcp-protocol-version": "2026-07-28"}
    async with mcp_lifespan(server):
        transport = httpx2.ASGITransport(app=app)
        async with httpx2.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as anon:
            assert (await anon.post("/mcp", json=body, headers=headers)).status_code == 401
            bad = {**headers, "authorization": "Bearer wrong"}
            assert (await anon.post("/mcp", json=body, headers=bad)).status_code == 401
        http = httpx2.AsyncClient(
            transport=transport,
            base_url="http://127.0.0.1:8765",
            headers={"authorization": "Bearer s3cret-token"},
        )
        async with (
            http,
            Client(
                streamable_http_client(URL, http_client=http),
                client_info=Implementation(name="a", version="1"),
            ) as c,
        ):
            r = await c.call_tool("get_battery", {"drone_id": "d1"})
            assert r.structured_content["remaining_pct"] == 87.0
    principal = principal_of("s3cret-token")
    assert (
        store.sessions
        and store.sessions[-1]["key"] == f"{principal}|a/1"
        and store.sessions[-1]["kind"] == "mcp-2026"
    )
    assert [(a.principal, a.action, a.outcome) for a in store.audit] == [(principal, "get_battery", "ok")]
    assert "s3cret" not in repr(store.sessions) + repr(store.audit)
