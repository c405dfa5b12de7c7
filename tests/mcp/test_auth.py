"""With GATEWAY_AGENT_TOKENS set, /mcp needs a bearer token; the session and audit carry the agent's
principal (derived from the token, never the token itself). In-process ASGI, no sockets."""

from __future__ import annotations

from pathlib import Path

import httpx2
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation

from gateway.mcp.auth import principal_of
from gateway.mcp.server import build_mcp, mcp_http_app
from tests.fakes import FakeVehicle, fake_gateway, unit_settings

URL = "http://127.0.0.1:8765/mcp"


async def test_agent_token_required_and_recorded_as_principal(tmp_path: Path) -> None:
    settings = unit_settings(tmp_path, agent_tokens="s3cret-token,other-token")
    async with fake_gateway(settings, [FakeVehicle("d1")]) as gateway:
        server = build_mcp(gateway)
        app = mcp_http_app(server, settings)
        body = {"jsonrpc": "2.0", "id": 1, "method": "tools/list", "params": {}}
        headers = {"accept": "application/json, text/event-stream", "mcp-protocol-version": "2026-07-28"}
        async with server.session_manager.run():
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
        store = gateway.require_store()
        sessions = await store.list_sessions()
        audit = await store.list_audit()
    principal = principal_of("s3cret-token")
    assert [(s.key, s.kind) for s in sessions] == [(f"{principal}|a/1", "mcp-2026")]
    assert [(a.principal, a.action, a.outcome) for a in audit] == [(principal, "get_battery", "ok")]
    assert "s3cret" not in repr(sessions) + repr(audit)
