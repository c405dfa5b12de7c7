"""A 2026-07-28 request without a progress token is answered as plain JSON, past the SDK's streaming
machinery; a request with one, a 2025-era session's and a subscription stream go the SDK's usual
way (gateway/mcp/json_answers.py). In-process ASGI, no sockets; the streamed answers with progress
over real HTTP are in tests/mcp/test_flight_http.py and test_arming_wait_http.py."""

from __future__ import annotations

import inspect
from pathlib import Path
from typing import Any

import httpx2
import pytest
from mcp.server._streamable_http_modern import handle_modern_request
from mcp.server.lowlevel import Server
from mcp.server.streamable_http_manager import StreamableHTTPSessionManager

from gateway.mcp import sdk_private
from gateway.mcp.json_answers import wants_no_stream
from gateway.mcp.server import build_mcp, mcp_http_app
from tests.fakes import FakeVehicle, fake_gateway, unit_settings

VERSION = "2026-07-28"
META = {"io.modelcontextprotocol/protocolVersion": VERSION, "io.modelcontextprotocol/clientCapabilities": {}}
SDK_ENTRY = ["app", "security_settings", "json_response", "lifespan_state", "scope", "receive", "send"]
MANAGER_PARTS = (
    "asgi_app",
    "_handle_request",
    "_lifespan_state",
    "max_request_body_size",
    "security_settings",
)


def _headers(tool: str) -> dict[str, str]:
    return {
        "accept": "application/json, text/event-stream",
        "mcp-protocol-version": VERSION,
        "mcp-method": "tools/call",
        "mcp-name": tool,
    }


def _call(tool: str, arguments: dict[str, Any], **meta: Any) -> dict[str, Any]:
    params = {"name": tool, "arguments": arguments, "_meta": {**META, **meta}}
    return {"jsonrpc": "2.0", "id": 7, "method": "tools/call", "params": params}


def test_only_a_whole_body_without_a_progress_token_or_a_listen_is_answered_as_json() -> None:
    body = b'{"method": "tools/call", "params": {"name": "get_battery"}}'
    assert wants_no_stream({"type": "http.request", "body": body})
    assert not wants_no_stream({"type": "http.request", "body": body, "more_body": True})
    assert not wants_no_stream({"type": "http.request", "body": b'{"_meta": {"progressToken": 3}}'})
    assert not wants_no_stream({"type": "http.request", "body": b'{"method": "subscriptions/listen"}'})
    assert not wants_no_stream({"type": "http.disconnect"})


def test_the_sdk_pieces_the_json_answer_uses_are_still_there() -> None:
    """An SDK upgrade that renames them fails here, not in a client."""
    assert list(inspect.signature(handle_modern_request).parameters) == SDK_ENTRY
    manager = StreamableHTTPSessionManager(app=Server("stub"))
    for name in MANAGER_PARTS:
        assert hasattr(manager, name), name


async def test_a_call_without_a_progress_token_gets_json_and_one_with_a_token_the_sdks_way(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    routes: list[str] = []
    as_json, usual = sdk_private.answer_single_exchange_as_json, sdk_private.handle_request

    async def spy_json(*args: Any) -> None:
        routes.append("json")
        await as_json(*args)

    async def spy_usual(*args: Any) -> None:
        routes.append("usual")
        await usual(*args)

    monkeypatch.setattr(sdk_private, "answer_single_exchange_as_json", spy_json)
    monkeypatch.setattr(sdk_private, "handle_request", spy_usual)
    settings = unit_settings(tmp_path)
    async with fake_gateway(settings, [FakeVehicle("d1")]) as gateway:
        server = build_mcp(gateway)
        app = mcp_http_app(server, settings)
        async with server.session_manager.run():
            transport = httpx2.ASGITransport(app=app)
            async with httpx2.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as http:
                battery = _call("get_battery", {"drone_id": "d1"})
                plain = await http.post("/mcp", json=battery, headers=_headers("get_battery"))
                assert plain.status_code == 200, plain.text
                assert plain.headers["content-type"].startswith("application/json"), plain.headers
                assert plain.json()["result"]["structuredContent"]["remaining_pct"] == 87.0, plain.text
                assert routes == ["json"]

                refused = await http.post(
                    "/mcp",
                    json=_call("go_to_location", {"drone_id": "d1"}),
                    headers=_headers("go_to_location"),
                )
                result = refused.json()["result"]
                assert result["isError"] is True and "lat_deg" in result["content"][0]["text"], refused.text
                assert routes == ["json", "json"]

                token = _call("get_battery", {"drone_id": "d1"}, progressToken="p1")
                streamed = await http.post("/mcp", json=token, headers=_headers("get_battery"))
                assert streamed.status_code == 200, streamed.text
                assert "87" in streamed.text, streamed.text
                assert routes == ["json", "json", "usual"]

                client = {"name": "t", "version": "1"}
                hello = {"protocolVersion": "2025-11-25", "capabilities": {}, "clientInfo": client}
                legacy = {"jsonrpc": "2.0", "id": 1, "method": "initialize", "params": hello}
                accept = {"accept": "application/json, text/event-stream"}
                assert (await http.post("/mcp", json=legacy, headers=accept)).status_code == 200
                assert routes == ["json", "json", "usual", "usual"]
        audit = [(a.action, a.outcome) for a in await gateway.require_store().list_audit()]
    # the JSON answers are audited like any call
    assert sorted(audit) == [("get_battery", "ok"), ("get_battery", "ok"), ("go_to_location", "error")], audit
