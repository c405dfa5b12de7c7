"""The OpenAPI document says what the REST API really answers: operation ids, bearer scheme, error
responses of the one error shape, typed vehicle status and telemetry."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import httpx
import jsonschema
import pytest

from gateway.api.openapi import ERROR_SCHEMA
from gateway.app import create_app
from gateway.config import Settings
from tests.fakes import FakeRegistry

from .live import lifespan_running

ALPHA = {"id": "alpha", "url": "tcpout://127.0.0.1:5760"}
OPERATOR, VIEWER = "op-token-1", "view-token-1"


@pytest.fixture
async def authed(tmp_path: Path) -> Any:
    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        operator_tokens=OPERATOR,
        viewer_tokens=VIEWER,
    )
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as app:
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as client:
            yield client


def _documented(doc: dict[str, Any], method: str, path: str, status: int) -> dict[str, Any]:
    responses = doc["paths"][path][method]["responses"]
    assert str(status) in responses, (
        f"{method.upper()} {path} answers {status}, undocumented: {list(responses)}"
    )
    return responses[str(status)]


async def test_operation_ids_are_the_route_names_and_unique(authed: httpx.AsyncClient) -> None:
    doc = (await authed.get("/openapi.json")).json()
    ids = [op["operationId"] for item in doc["paths"].values() for op in item.values()]
    assert len(ids) == len(set(ids))
    assert doc["paths"]["/api/v1/vehicles"]["get"]["operationId"] == "list_vehicles"
    assert doc["paths"]["/api/v1/vehicles/{vehicle_id}/goto"]["post"]["operationId"] == "goto_vehicle"
    assert all("_api_v1_" not in i for i in ids)


async def test_bearer_scheme_on_every_api_route(authed: httpx.AsyncClient) -> None:
    doc = (await authed.get("/openapi.json")).json()
    scheme = doc["components"]["securitySchemes"]["bearer"]
    assert scheme["type"] == "http" and scheme["scheme"] == "bearer"
    for path, item in doc["paths"].items():
        for op in item.values():
            assert ("security" in op) == (path.startswith("/api/v1") or path == "/metrics"), path
    track = doc["paths"]["/api/v1/flights/{flight_id}/track.geojson"]["get"]["responses"]["200"]
    assert "application/geo+json" in track["content"]


async def test_the_errors_the_api_returns_are_documented_in_its_error_shape(
    authed: httpx.AsyncClient,
) -> None:
    doc = (await authed.get("/openapi.json")).json()
    op, view = {"Authorization": f"Bearer {OPERATOR}"}, {"Authorization": f"Bearer {VIEWER}"}
    cases = [
        ("get", "/api/v1/vehicles", "/api/v1/vehicles", None, None, 401),
        ("post", "/api/v1/vehicles", "/api/v1/vehicles", view, ALPHA, 403),
        ("post", "/api/v1/vehicles", "/api/v1/vehicles", op, ALPHA, 201),
        ("post", "/api/v1/vehicles", "/api/v1/vehicles", op, ALPHA, 409),
        ("get", "/api/v1/vehicles/{vehicle_id}", "/api/v1/vehicles/nope", op, None, 404),
        ("get", "/api/v1/flights/{flight_id}", "/api/v1/flights/99", op, None, 404),
        ("post", "/api/v1/vehicles/{vehicle_id}/takeoff", "/api/v1/vehicles/alpha/takeoff", op, {}, 422),
    ]
    for method, template, url, headers, body, status in cases:
        response = await authed.request(method, url, headers=headers, json=body)
        assert response.status_code == status, (url, response.text)
        documented = _documented(doc, method, template, status)
        if status >= 400:
            assert documented["content"]["application/json"]["schema"] == {
                "$ref": "#/components/schemas/Error"
            }
            jsonschema.validate(response.json(), ERROR_SCHEMA)
    assert doc["components"]["schemas"]["Error"] == ERROR_SCHEMA
    assert "HTTPValidationError" not in str(doc)


async def test_vehicle_status_and_telemetry_are_typed(authed: httpx.AsyncClient) -> None:
    doc = (await authed.get("/openapi.json")).json()
    schemas = doc["components"]["schemas"]
    vehicle = schemas["VehicleOut"]["properties"]
    assert "VehicleStatus" in str(vehicle["status"]) and "TelemetrySnapshot" in str(vehicle["telemetry"])
    position = schemas["PositionPart"]["properties"]
    assert {"lat_deg", "lon_deg", "abs_alt_m", "rel_alt_m", "age_s", "stale"} <= set(position)
    assert {"position", "battery", "flight_mode", "mission_progress", "status_texts"} <= set(
        schemas["TelemetrySnapshot"]["properties"]
    )
    op = {"Authorization": f"Bearer {OPERATOR}"}
    assert (await authed.post("/api/v1/vehicles", headers=op, json=ALPHA)).status_code == 201
    got = (await authed.get("/api/v1/vehicles/alpha", headers=op)).json()
    assert got["status"]["id"] == "alpha" and got["telemetry"]["position"]["lat_deg"] is not None
