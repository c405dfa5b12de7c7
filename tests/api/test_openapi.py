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


_TYPED = {"type", "$ref", "anyOf", "oneOf", "allOf", "enum", "const", "not"}


def _untyped(node: Any, where: str = "") -> list[str]:
    """Every schema in the document that says nothing of its type, and every body without a schema."""
    found: list[str] = []
    if isinstance(node, list):
        for k, item in enumerate(node):
            found += _untyped(item, f"{where}/{k}")
        return found
    if not isinstance(node, dict):
        return found
    for key, value in node.items():
        at = f"{where}/{key}"
        if key in ("properties", "schemas"):
            for name, schema in value.items():
                if isinstance(schema, dict) and not _TYPED & set(schema):
                    found.append(f"{at}/{name}")
                found += _untyped(schema, f"{at}/{name}")
        elif key in ("items", "additionalProperties", "schema") and isinstance(value, dict):
            if not _TYPED & set(value):
                found.append(at)
            found += _untyped(value, at)
        elif key == "content":
            for media, body in value.items():
                if "schema" not in body:
                    found.append(f"{at}/{media}")
            found += _untyped(value, at)
        else:
            found += _untyped(value, at)
    return found


async def test_every_field_and_body_of_the_document_is_typed(authed: httpx.AsyncClient) -> None:
    doc = (await authed.get("/openapi.json")).json()
    assert _untyped(doc) == []


def _body_schema(doc: dict[str, Any], method: str, path: str, media: str = "application/json") -> Any:
    schema = doc["paths"][path][method]["requestBody"]["content"][media]["schema"]
    return {**schema, "components": doc["components"]}


@pytest.mark.parametrize(
    ("method", "path", "body"),
    [
        ("put", "/api/v1/vehicles/{vehicle_id}/mission", {}),
        ("put", "/api/v1/vehicles/{vehicle_id}/mission", {"fileType": "Plan", "mission": {"items": []}}),
        ("put", "/api/v1/fleet/geofences", {"type": "FeatureCollection", "features": [{"type": "Feature"}]}),
        (
            "put",
            "/api/v1/vehicles/{vehicle_id}/geofences",
            {
                "type": "FeatureCollection",
                "features": [{"type": "Feature", "properties": {"kind": "keep_in"}, "geometry": {}}],
            },
        ),
        ("patch", "/api/v1/vehicles/{vehicle_id}", {}),
        ("patch", "/api/v1/vehicles/{vehicle_id}", {"url": None}),
        ("post", "/api/v1/vehicles", {"id": "a", "url": ""}),
    ],
)
async def test_the_schema_refuses_what_the_validation_refuses(
    authed: httpx.AsyncClient, method: str, path: str, body: Any
) -> None:
    """A body the gateway answers 422 to is one its OpenAPI document already forbids."""
    doc = (await authed.get("/openapi.json")).json()
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(body, _body_schema(doc, method, path))
    concrete = path.replace("{vehicle_id}", "alpha")
    headers = {"Authorization": f"Bearer {OPERATOR}"}
    await authed.post("/api/v1/vehicles", json=ALPHA, headers=headers)
    answer = await authed.request(method.upper(), concrete, json=body, headers=headers)
    # a mission file is read once the drone is ready (the stand-in registry's drone never is): 409 first
    refused = (409, 422) if path.endswith("/mission") else (422,)
    assert answer.status_code in refused, answer.text


async def test_a_valid_plan_and_zone_pass_the_schema(authed: httpx.AsyncClient) -> None:
    doc = (await authed.get("/openapi.json")).json()
    plan = {
        "fileType": "Plan",
        "mission": {
            "items": [
                {"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0, None, 47.4, 8.5, 20]}
            ],
            "plannedHomePosition": [47.4, 8.5, 400],
        },
        "geoFence": {"circles": [], "polygons": [], "version": 2},
        "rallyPoints": {"points": [], "version": 2},
    }
    jsonschema.validate(plan, _body_schema(doc, "put", "/api/v1/vehicles/{vehicle_id}/mission"))
    ring = [[8.5, 47.4], [8.51, 47.4], [8.51, 47.41], [8.5, 47.4]]
    zone = {
        "type": "Feature",
        "properties": {"kind": "keep_in"},
        "geometry": {"type": "Polygon", "coordinates": [ring]},
    }
    jsonschema.validate(
        {"type": "FeatureCollection", "features": [zone]}, _body_schema(doc, "put", "/api/v1/fleet/geofences")
    )


@pytest.mark.parametrize(
    ("method", "path", "allowed"),
    [
        ("DELETE", "/api/v1/vehicles", "GET, POST"),
        ("OPTIONS", "/api/v1/vehicles/alpha", "DELETE, GET, PATCH"),
        ("POST", "/api/v1/vehicles/alpha/params/WPNAV_SPEED", "GET, PUT"),
        ("GET", "/api/v1/fleet/lock", "DELETE, POST"),
    ],
)
async def test_405_names_every_method_the_path_serves(
    authed: httpx.AsyncClient, method: str, path: str, allowed: str
) -> None:
    answer = await authed.request(method, path, headers={"Authorization": f"Bearer {OPERATOR}"})
    assert answer.status_code == 405
    assert answer.headers["allow"] == allowed
    assert answer.json()["error"]["message"] == f"{method} is not served here; this path accepts {allowed}"
