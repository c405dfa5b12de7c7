"""With GATEWAY_AGENT_TOKENS set, /mcp needs a bearer token; the session and audit carry the agent's
principal (derived from the token, never the token itself). In-process ASGI, no sockets."""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import httpx2
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation
from pydantic import ValidationError

from gateway.config import Settings
from gateway.mcp.auth import principal_of
from gateway.mcp.server import build_mcp, mcp_http_app
from tests.fakes import FakeVehicle, fake, fake_gateway, unit_settings

URL = "http://127.0.0.1:8765/mcp"


@contextlib.asynccontextmanager
async def agent_client(app: Any, token: str) -> AsyncIterator[Client]:
    """An MCP client presenting ``token`` to the in-process app."""
    http = httpx2.AsyncClient(
        transport=httpx2.ASGITransport(app=app),
        base_url="http://127.0.0.1:8765",
        headers={"authorization": f"Bearer {token}"},
    )
    client = Client(
        streamable_http_client(URL, http_client=http), client_info=Implementation(name="a", version="1")
    )
    async with http, client as c:
        yield c


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
            async with agent_client(app, "s3cret-token") as c:
                r = await c.call_tool("get_battery", {"drone_id": "d1"})
                assert r.structured_content["remaining_pct"] == 87.0
        store = gateway.require_store()
        sessions = await store.list_sessions()
        audit = await store.list_audit()
    principal = principal_of("s3cret-token")
    assert [(s.key, s.kind) for s in sessions] == [(f"{principal}|a/1", "mcp-2026")]
    assert [(a.principal, a.action, a.outcome) for a in audit] == [(principal, "get_battery", "ok")]
    assert "s3cret" not in repr(sessions) + repr(audit)


async def test_a_scope_keyed_by_a_token_that_looks_like_a_principal_confines_that_token(
    tmp_path: Path,
) -> None:
    token = "agent-alpha-only-7f3c"  # starts with "agent-": once read as a principal name, it confined nobody
    settings = unit_settings(tmp_path, agent_tokens=f"{token},other-token", agent_scopes={token: ["d1"]})
    async with fake_gateway(settings, [FakeVehicle("d1"), FakeVehicle("d2")]) as gateway:
        server = build_mcp(gateway)
        app = mcp_http_app(server, settings)
        async with server.session_manager.run():
            async with agent_client(app, token) as c:
                listed = await c.call_tool("list_drones", {})
                assert [d["drone_id"] for d in listed.structured_content["drones"]] == ["d1"]
                calls = {"get_battery": {}, "takeoff": {"alt_m": 10}, "land": {}, "disarm_drone": {}}
                for tool, args in calls.items():
                    r = await c.call_tool(tool, {"drone_id": "d2", **args})
                    assert r.is_error and "unknown drone" in r.content[0].text.lower(), (tool, r.content)
                refused = await c.call_tool(
                    "set_parameter", {"drone_id": "d2", "name": "WPNAV_ACCEL", "value": 1}
                )
                assert refused.is_error and "unknown drone" in refused.content[0].text.lower()
        assert fake(gateway, "d2").sent == []  # nothing reached the drone outside the scope


def test_a_scope_key_that_matches_no_agent_stops_the_settings_with_one_line() -> None:
    with pytest.raises(ValidationError) as info:
        Settings(_env_file=None, agent_tokens="alpha-token", agent_scopes={"agent-00000000": ["d1"]})
    text = str(info.value)
    assert "GATEWAY_AGENT_SCOPES key agent-00000000 is neither one of GATEWAY_AGENT_TOKENS" in text
    with pytest.raises(ValidationError, match=r"key beta\.\.\. \(10 characters\)"):
        Settings(_env_file=None, agent_tokens="alpha-token", agent_scopes={"beta-token": ["d1"]})
    by_principal = Settings(
        _env_file=None, agent_tokens="alpha-token", agent_scopes={principal_of("alpha-token"): ["d1"]}
    )
    assert list(by_principal.agent_scopes) == [principal_of("alpha-token")]
