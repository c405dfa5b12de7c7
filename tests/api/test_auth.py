"""Bearer tokens on the REST API: open without tokens; with them, operators change, viewers read."""

from __future__ import annotations

import hashlib
from collections.abc import AsyncIterator
from pathlib import Path

import httpx
import pytest
from fastapi import FastAPI

from gateway.app import create_app
from gateway.config import Settings
from gateway.server_cli import main
from tests.fakes import FakeRegistry

from .live import lifespan_running
from .server import serve_in_thread

OPERATOR, VIEWER, AGENT = "op-secret-1", "view-secret-1", "agent-secret-1"
ALPHA = {"id": "alpha", "url": "tcpout://127.0.0.1:5760"}


def token_settings(tmp_path: Path) -> Settings:
    return Settings(
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'auth.db'}",
        operator_tokens=f"other-op, {OPERATOR}",
        viewer_tokens=VIEWER,
        agent_tokens=AGENT,
    )


@pytest.fixture
async def secured(tmp_path: Path) -> AsyncIterator[tuple[FastAPI, httpx.AsyncClient]]:
    async with lifespan_running(create_app(token_settings(tmp_path), registry_factory=FakeRegistry)) as app:
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as client:
            yield app, client


def bearer(token: str) -> dict[str, str]:
    return {"Authorization": f"Bearer {token}"}


async def test_tokens_are_required_and_roles_enforced(secured: tuple[FastAPI, httpx.AsyncClient]) -> None:
    app, client = secured
    store = app.state.gateway.store

    for headers in ({}, bearer("wrong"), bearer(AGENT), {"Authorization": f"Basic {OPERATOR}"}):
        response = await client.get("/api/v1/vehicles", headers=headers)
        assert response.status_code == 401 and response.json()["error"]["code"] == "unauthorized"
        assert response.headers["www-authenticate"].startswith("Bearer")
    denied = await client.post("/api/v1/vehicles", json=ALPHA)
    assert denied.status_code == 401 and await store.list_vehicles() == []

    viewer_post = await client.post("/api/v1/vehicles", json=ALPHA, headers=bearer(VIEWER))
    assert viewer_post.status_code == 403 and viewer_post.json()["error"]["code"] == "forbidden"
    assert "operator token" in viewer_post.json()["error"]["message"]
    assert await store.list_vehicles() == []

    created = await client.post("/api/v1/vehicles", json=ALPHA, headers=bearer(OPERATOR))
    assert created.status_code == 201
    assert (await client.get("/api/v1/vehicles", headers=bearer(VIEWER))).json()["total"] == 1
    assert (await client.delete("/api/v1/vehicles/alpha", headers=bearer(VIEWER))).status_code == 403
    assert [v.id for v in await store.list_vehicles()] == ["alpha"]

    locked = await client.post("/api/v1/fleet/lock", json={"reason": "checks"}, headers=bearer(OPERATOR))
    name = "operator-" + hashlib.sha256(OPERATOR.encode()).hexdigest()[:8]
    assert locked.json()["by"] == name and OPERATOR not in locked.text

    audit = (await client.get("/api/v1/audit", headers=bearer(VIEWER))).json()["items"]
    viewer = "viewer-" + hashlib.sha256(VIEWER.encode()).hexdigest()[:8]
    registrations = [(e["outcome"], e["principal"]) for e in audit if e["action"] == "rest.register_vehicle"]
    # oldest last: unidentified (401), the viewer's refused attempt (403), the operator's registration
    assert registrations == [("ok", name), ("error", viewer), ("error", None)]
    assert all(OPERATOR not in str(e) and VIEWER not in str(e) for e in audit)
    sessions = (await client.get("/api/v1/sessions", headers=bearer(VIEWER))).json()["items"]
    assert sorted(s["key"] for s in sessions) == sorted([f"rest:{name}", f"rest:{viewer}"])

    # health and readiness stay open for probes; metrics need a token like every other read
    for path in ("/healthz", "/readyz"):
        assert (await client.get(path)).status_code == 200
    assert (await client.get("/metrics")).status_code == 401
    assert "gateway_vehicles" in (await client.get("/metrics", headers=bearer(VIEWER))).text


def test_cli_sends_the_operator_token(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch
) -> None:
    monkeypatch.delenv("GATEWAY_API_TOKEN", raising=False)
    monkeypatch.delenv("GATEWAY_OPERATOR_TOKENS", raising=False)
    app = create_app(token_settings(tmp_path), registry_factory=FakeRegistry)
    with serve_in_thread(app) as base:
        assert main(["drones", "list", "--api", base]) == 1
        assert "(unauthorized)" in capsys.readouterr().err
        assert main(["drones", "add", "alpha", ALPHA["url"], "--api", base, "--token", VIEWER]) == 1
        assert "(forbidden)" in capsys.readouterr().err
        assert main(["drones", "add", "alpha", ALPHA["url"], "--api", base, "--token", OPERATOR]) == 0
        monkeypatch.setenv("GATEWAY_API_TOKEN", VIEWER)
        assert main(["drones", "list", "--api", base]) == 0
        assert capsys.readouterr().out.splitlines()[-1].startswith("alpha")
        monkeypatch.delenv("GATEWAY_API_TOKEN")
        monkeypatch.setenv("GATEWAY_OPERATOR_TOKENS", OPERATOR)
        assert main(["drones", "remove", "alpha", "--api", base]) == 0


def test_serve_allows_a_public_bind_only_with_operator_tokens(monkeypatch, capsys) -> None:
    monkeypatch.setenv("GATEWAY_OPERATOR_TOKENS", "")
    assert main(["serve", "--host", "0.0.0.0", "--port", "1"]) == 2
    assert "loopback only" in capsys.readouterr().err
