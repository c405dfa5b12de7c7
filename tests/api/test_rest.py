"""REST API on a real SQLite file with a stand-in registry: results, error bodies, audit, metrics.

Live vehicles (real sidecars and simulated drones) are covered by test_integration.py.
"""

from __future__ import annotations

import asyncio
import json
import re
from collections.abc import AsyncIterator
from datetime import UTC, datetime, timedelta
from pathlib import Path

import httpx
import pytest
from fastapi import FastAPI

from gateway.app import create_app
from gateway.config import Settings
from gateway.fleet.vehicles.vehicle import ConnectionState
from gateway.registry.store import AuditEntry, StatusTextIn, Store, TrackSample
from tests.fakes import FakeRegistry
from tests.helpers.timing import scaled

from .live import lifespan_running

T0 = datetime(2026, 5, 1, 12, 0, tzinfo=UTC)
ALPHA = {"id": "alpha", "url": "tcpout://127.0.0.1:5760", "name": "Alpha", "tags": ["survey"]}


def store_of(app: FastAPI) -> Store:
    return app.state.gateway.store


def assert_error(response: httpx.Response, status: int, code: str) -> dict:
    assert response.status_code == status, response.text
    assert response.headers["content-type"].startswith("application/json")
    error = response.json()["error"]
    assert error["code"] == code and error["message"]
    return error


# --- health, docs ------------------------------------------------------------------------------


async def test_health_ready_and_docs(client: httpx.AsyncClient) -> None:
    assert (await client.get("/healthz")).json() == {"status": "ok"}
    ready = await client.get("/readyz")
    assert ready.status_code == 200 and ready.json()["checks"] == {"database": True, "registry": True}
    paths = (await client.get("/openapi.json")).json()["paths"]
    for path in (
        "/api/v1/vehicles",
        "/api/v1/vehicles/{vehicle_id}",
        "/api/v1/vehicles/{vehicle_id}/connect",
        "/api/v1/vehicles/{vehicle_id}/disconnect",
        "/api/v1/vehicles/{vehicle_id}/statustexts",
        "/api/v1/flights",
        "/api/v1/flights/{flight_id}",
        "/api/v1/flights/{flight_id}/track.geojson",
        "/api/v1/sessions",
        "/api/v1/audit",
    ):
        assert path in paths
    docs = await client.get("/docs")
    assert docs.status_code == 200 and "swagger" in docs.text.lower()


async def test_not_running_gateway_answers_503(settings: Settings) -> None:
    app = create_app(settings, registry_factory=FakeRegistry)  # lifespan never started
    transport = httpx.ASGITransport(app=app)
    async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as client:
        ready = await client.get("/readyz")
        assert ready.status_code == 503 and ready.json()["status"] == "not_ready"
        assert_error(await client.get("/api/v1/vehicles"), 503, "not_ready")
        assert (await client.get("/healthz")).status_code == 200


# --- vehicles ----------------------------------------------------------------------------------


async def test_vehicle_lifecycle(client: httpx.AsyncClient, app: FastAPI) -> None:
    created = await client.post("/api/v1/vehicles", json=ALPHA)
    assert created.status_code == 201, created.text
    body = created.json()
    assert body["id"] == "alpha" and body["state"] == "connecting" and body["auto_connect"] is True
    await client.post(
        "/api/v1/vehicles", json={"id": "bravo", "url": "udpin://0.0.0.0:14541", "connect": False}
    )

    listing = (await client.get("/api/v1/vehicles")).json()
    assert listing["total"] == 2
    assert {v["id"]: v["state"] for v in listing["items"]} == {"alpha": "connecting", "bravo": "registered"}
    assert listing["items"][1]["auto_connect"] is False

    one = (await client.get("/api/v1/vehicles/alpha")).json()
    assert one["telemetry"]["battery"]["remaining_pct"] == 87.0 and one["status"]["sidecar"]["restarts"] == 0

    patched = await client.patch("/api/v1/vehicles/alpha", json={"name": "A1", "expected_sysid": 3})
    assert patched.status_code == 200 and (patched.json()["name"], patched.json()["expected_sysid"]) == (
        "A1",
        3,
    )
    assert (await store_of(app).get_vehicle("alpha")).name == "A1"

    assert (await client.post("/api/v1/vehicles/bravo/connect")).json()["state"] == "connecting"
    assert (await client.post("/api/v1/vehicles/bravo/disconnect")).json()["state"] == "registered"

    deleted = await client.delete("/api/v1/vehicles/bravo")
    assert deleted.status_code == 204 and deleted.content == b""
    assert [v.id for v in await store_of(app).list_vehicles()] == ["alpha"]


@pytest.mark.parametrize(
    ("body", "fields"),
    [
        ({"id": "Bad_ID!", "url": "tcpout://127.0.0.1:5760"}, {"id"}),
        ({"id": "x" * 33, "url": "tcpout://127.0.0.1:5760"}, {"id"}),
        ({"id": "alpha", "url": "http://127.0.0.1:5760"}, {"url"}),
        ({"id": "alpha", "url": "tcpout://127.0.0.1"}, {"url"}),
        ({"id": "alpha"}, {"url"}),
        ({"id": 7, "url": "tcpout://127.0.0.1:5760"}, {"id"}),
        ({"id": "alpha", "url": "tcpout://127.0.0.1:5760", "tags": "survey"}, {"tags"}),
        ({"id": "alpha", "url": "tcpout://127.0.0.1:5760", "expected_sysid": "one"}, {"expected_sysid"}),
        ({"id": "alpha", "url": "tcpout://127.0.0.1:5760", "expected_sysid": 300}, {"expected_sysid"}),
        ({"id": "alpha", "url": "tcpout://127.0.0.1:5760", "connect": "maybe"}, {"connect"}),
        ({"id": "alpha", "url": "tcpout://127.0.0.1:5760", "colour": "red"}, {"colour"}),
        (["alpha"], {"body"}),
    ],
)
async def test_invalid_registration_is_refused_and_changes_nothing(
    client: httpx.AsyncClient, app: FastAPI, body: object, fields: set[str]
) -> None:
    error = assert_error(await client.post("/api/v1/vehicles", json=body), 422, "validation_error")
    assert {e["field"] for e in error["details"]["errors"]} == fields
    for field in fields:
        assert field in error["message"]
    assert await store_of(app).list_vehicles() == []


async def test_malformed_json_is_a_clear_400(client: httpx.AsyncClient, app: FastAPI) -> None:
    response = await client.post(
        "/api/v1/vehicles", content=b'{"id": "alpha", "url": ', headers={"content-type": "application/json"}
    )
    error = assert_error(response, 400, "malformed_json")
    assert "not valid JSON" in error["message"] and error["details"]["position"] == 23
    assert await store_of(app).list_vehicles() == []


async def test_duplicate_registration_is_a_409(client: httpx.AsyncClient, app: FastAPI) -> None:
    assert (await client.post("/api/v1/vehicles", json=ALPHA)).status_code == 201
    again = await client.post("/api/v1/vehicles", json={**ALPHA, "url": "udpin://0.0.0.0:14550", "name": "X"})
    error = assert_error(again, 409, "duplicate_vehicle")
    assert "alpha" in error["message"]
    [record] = await store_of(app).list_vehicles()
    assert (record.url, record.name) == (ALPHA["url"], "Alpha")


async def test_oversized_bodies_are_refused(client: httpx.AsyncClient, app: FastAPI) -> None:
    big = {**ALPHA, "name": "n" * 5000}
    error = assert_error(await client.post("/api/v1/vehicles", json=big), 413, "body_too_large")
    assert "4096" in error["message"]

    async def chunks():
        for _ in range(10):
            yield b" " * 1000

    streamed = await client.post(
        "/api/v1/vehicles", content=chunks(), headers={"content-type": "application/json"}
    )
    assert_error(streamed, 413, "body_too_large")
    assert await store_of(app).list_vehicles() == []


@pytest.mark.parametrize(
    ("method", "path"),
    [
        ("GET", "/api/v1/vehicles/ghost"),
        ("PATCH", "/api/v1/vehicles/ghost"),
        ("DELETE", "/api/v1/vehicles/ghost"),
        ("POST", "/api/v1/vehicles/ghost/connect"),
        ("POST", "/api/v1/vehicles/ghost/disconnect"),
        ("GET", "/api/v1/vehicles/ghost/statustexts"),
    ],
)
async def test_unknown_vehicle_names_the_known_ones(
    client: httpx.AsyncClient, method: str, path: str
) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    kwargs = {"json": {"name": "x"}} if method == "PATCH" else {}
    error = assert_error(await client.request(method, path, **kwargs), 404, "unknown_vehicle")
    assert "'ghost'" in error["message"] and "alpha" in error["message"]
    assert error["details"]["known"] == ["alpha"]


@pytest.mark.parametrize(
    ("patch", "code", "field"),
    [
        ({"url": "ftp://x:1"}, "validation_error", "url"),
        ({"url": None}, "validation_error", "url"),
        ({"tags": None}, "validation_error", "tags"),
        ({"expected_sysid": 0}, "validation_error", "expected_sysid"),
        ({"id": "other"}, "validation_error", "id"),
        ({}, "invalid_argument", None),
    ],
)
async def test_invalid_update_changes_nothing(
    client: httpx.AsyncClient, app: FastAPI, patch: dict, code: str, field: str | None
) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    before = await store_of(app).get_vehicle("alpha")
    error = assert_error(await client.patch("/api/v1/vehicles/alpha", json=patch), 422, code)
    if field:
        assert field in error["message"]
    assert await store_of(app).get_vehicle("alpha") == before


async def test_patch_clears_optional_fields(client: httpx.AsyncClient) -> None:
    await client.post("/api/v1/vehicles", json={**ALPHA, "expected_sysid": 4})
    cleared = (
        await client.patch("/api/v1/vehicles/alpha", json={"name": None, "expected_sysid": None})
    ).json()
    assert cleared["name"] is None and cleared["expected_sysid"] is None and cleared["tags"] == ["survey"]


async def test_unexpected_failure_is_a_json_500(client: httpx.AsyncClient, app: FastAPI) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)

    async def broken(vehicle_id: str) -> None:
        raise RuntimeError("sidecar exploded")

    app.state.gateway.registry.connect = broken
    transport = httpx.ASGITransport(app=app, raise_app_exceptions=False)
    async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as quiet:
        error = assert_error(await quiet.post("/api/v1/vehicles/alpha/connect"), 500, "internal_error")
    assert "RuntimeError" in error["message"]
    [entry] = await store_of(app).list_audit(limit=1)
    assert entry.action == "rest.connect_vehicle" and entry.outcome == "error"


async def test_routing_errors_use_the_error_shape(client: httpx.AsyncClient) -> None:
    assert_error(await client.get("/api/v1/nothing-here"), 404, "not_found")
    assert_error(await client.delete("/api/v1/flights"), 405, "method_not_allowed")
    error = assert_error(await client.get("/api/v1/flights/abc"), 422, "validation_error")
    assert error["details"]["errors"][0]["field"] == "flight_id"


# --- flights, status texts ---------------------------------------------------------------------


async def seed_flights(store: Store) -> list[int]:
    ids = []
    for i, vid in enumerate(["alpha", "bravo", "alpha"]):
        start = T0 + timedelta(hours=i)
        fid = await store.open_flight(vid, start, 47.0, 8.0, 400.0)
        await store.add_track_samples(
            [
                TrackSample(
                    flight_id=fid,
                    t=start + timedelta(seconds=s),
                    lat=47.0 + s * 1e-5,
                    lon=8.0,
                    alt_rel_m=float(s),
                    heading_deg=0.0,
                    ground_speed_mps=1.0,
                    battery_pct=100.0 - s,
                )
                for s in range(5)
            ]
        )
        await store.close_flight(fid, start + timedelta(seconds=5), 5.0, 4.4, 4.0, 4.0)
        ids.append(fid)
    return ids


async def test_flights_list_filter_and_page(client: httpx.AsyncClient, app: FastAPI) -> None:
    ids = await seed_flights(store_of(app))
    page = (await client.get("/api/v1/flights")).json()
    assert page["total"] == 3 and [f["id"] for f in page["items"]] == ids[::-1]
    assert page["items"][0]["distance_m"] == 4.4

    alpha = (await client.get("/api/v1/flights", params={"vehicle_id": "alpha"})).json()
    assert alpha["total"] == 2 and {f["vehicle_id"] for f in alpha["items"]} == {"alpha"}

    paged = (await client.get("/api/v1/flights", params={"limit": 1, "offset": 1})).json()
    assert (paged["total"], paged["limit"], paged["offset"]) == (3, 1, 1)
    assert [f["id"] for f in paged["items"]] == [ids[1]]

    window = {"since": (T0 + timedelta(minutes=30)).isoformat(), "until": "2026-05-01T13:30:00"}
    windowed = (await client.get("/api/v1/flights", params=window)).json()
    assert [f["id"] for f in windowed["items"]] == [ids[1]]

    backwards = {"since": "2026-05-02T00:00:00Z", "until": "2026-05-01T00:00:00Z"}
    error = assert_error(await client.get("/api/v1/flights", params=backwards), 422, "invalid_argument")
    assert "since" in error["message"]
    error = assert_error(
        await client.get("/api/v1/flights", params={"since": "yesterday"}), 422, "validation_error"
    )
    assert error["details"]["errors"][0]["field"] == "since"
    assert_error(await client.get("/api/v1/flights", params={"limit": 501}), 422, "validation_error")


async def test_flight_and_track_geojson(client: httpx.AsyncClient, app: FastAPI) -> None:
    ids = await seed_flights(store_of(app))
    flight = (await client.get(f"/api/v1/flights/{ids[0]}")).json()
    assert flight["vehicle_id"] == "alpha" and flight["home_alt_amsl"] == 400.0

    response = await client.get(f"/api/v1/flights/{ids[0]}/track.geojson")
    assert response.status_code == 200 and response.headers["content-type"].startswith("application/geo+json")
    feature = response.json()
    assert feature["type"] == "Feature" and feature["geometry"]["type"] == "LineString"
    coords = feature["geometry"]["coordinates"]
    # lon, lat, altitude above mean sea level (home 400 m AMSL + 1 m above home)
    assert len(coords) == 5 and coords[1] == [8.0, pytest.approx(47.00001), 401.0]
    props = feature["properties"]
    assert props["flight_id"] == ids[0] and props["sample_count"] == 5
    assert props["alt_rel_m"] == [0.0, 1.0, 2.0, 3.0, 4.0] and "mean sea level" in props["altitude_reference"]
    assert props["battery_pct"] == [100.0, 99.0, 98.0, 97.0, 96.0]
    assert len(props["times"]) == 5 and props["times"][0].startswith("2026-05-01T12:00:00")

    assert_error(await client.get("/api/v1/flights/999"), 404, "not_found")
    assert_error(await client.get("/api/v1/flights/999/track.geojson"), 404, "not_found")


async def test_flight_as_kml_and_tlog(client: httpx.AsyncClient, app: FastAPI, tmp_path: Path) -> None:
    """KML with altitudes above sea level; a .tlog that pymavlink reads back to the whole track."""
    import xml.etree.ElementTree as ET

    from pymavlink import mavutil

    await client.post("/api/v1/vehicles", json={**ALPHA, "expected_sysid": 7})
    ids = await seed_flights(store_of(app))
    await store_of(app).add_status_texts(
        [
            StatusTextIn(
                vehicle_id="alpha",
                flight_id=ids[0],
                t=T0 + timedelta(seconds=2),
                severity=4,
                text="PreArm: test",
            )
        ]
    )
    kml = await client.get(f"/api/v1/flights/{ids[0]}/track.kml")
    assert kml.status_code == 200 and kml.headers["content-type"].startswith(
        "application/vnd.google-earth.kml+xml"
    )
    ns = {"k": "http://www.opengis.net/kml/2.2", "gx": "http://www.google.com/kml/ext/2.2"}
    root = ET.fromstring(kml.content)
    line = root.find(".//k:LineString", ns)
    assert line is not None and line.findtext("k:altitudeMode", namespaces=ns) == "absolute"
    points = [p.split(",") for p in (line.findtext("k:coordinates", namespaces=ns) or "").split()]
    assert len(points) == 5 and [float(p[2]) for p in points] == [400.0, 401.0, 402.0, 403.0, 404.0]
    assert len(root.findall(".//gx:Track/k:when", ns)) == 5

    tlog = await client.get(f"/api/v1/flights/{ids[0]}/tlog")
    assert tlog.status_code == 200 and 'filename="alpha-flight-' in tlog.headers["content-disposition"]
    assert tlog.headers["x-tlog-source"] == "reconstructed"  # no raw log of a seeded flight
    path = tmp_path / "flight.tlog"
    path.write_bytes(tlog.content)
    log = mavutil.mavlink_connection(str(path), dialect="common")
    positions, texts, stamps = [], [], []
    while (msg := log.recv_match()) is not None:
        if msg.get_type() == "GLOBAL_POSITION_INT":
            assert msg.get_srcSystem() == 7
            positions.append((msg.lat / 1e7, msg.lon / 1e7, msg.alt / 1000, msg.relative_alt / 1000))
            stamps.append(msg._timestamp)
        elif msg.get_type() == "STATUSTEXT":
            texts.append((msg.severity, msg.text))
    assert [p[3] for p in positions] == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert positions[1] == (pytest.approx(47.00001), 8.0, 401.0, 1.0)
    assert stamps[0] == pytest.approx(T0.timestamp()) and stamps[4] - stamps[0] == pytest.approx(4.0)
    assert texts == [(4, "PreArm: test")]
    assert_error(await client.get("/api/v1/flights/999/tlog"), 404, "not_found")
    assert_error(await client.get("/api/v1/flights/999/track.kml"), 404, "not_found")


async def test_empty_track_has_no_geometry(client: httpx.AsyncClient, app: FastAPI) -> None:
    fid = await store_of(app).open_flight("alpha", T0)
    feature = (await client.get(f"/api/v1/flights/{fid}/track.geojson")).json()
    assert feature["geometry"] is None and feature["properties"]["sample_count"] == 0


async def test_status_texts_endpoint(client: httpx.AsyncClient, app: FastAPI) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    await store_of(app).add_status_texts(
        [
            StatusTextIn(vehicle_id="alpha", t=T0 + timedelta(seconds=i), severity=6, text=f"t{i}")
            for i in range(5)
        ]
    )
    body = (await client.get("/api/v1/vehicles/alpha/statustexts", params={"limit": 2})).json()
    assert body["vehicle_id"] == "alpha" and [t["text"] for t in body["items"]] == ["t3", "t4"]
    assert body["items"][0]["severity"] == "INFO"
    since = (
        await client.get("/api/v1/vehicles/alpha/statustexts", params={"since": "2026-05-01T12:00:04Z"})
    ).json()
    assert [t["text"] for t in since["items"]] == ["t4"]


# --- audit and sessions ------------------------------------------------------------------------


async def test_rest_calls_are_audited(client: httpx.AsyncClient, app: FastAPI) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    await client.post("/api/v1/vehicles", json=ALPHA)  # duplicate
    await client.post("/api/v1/vehicles", json={"id": "BAD"})  # invalid
    await client.get("/api/v1/vehicles")  # reads are not audited
    await client.delete("/api/v1/vehicles/alpha")

    audit = (await client.get("/api/v1/audit")).json()
    assert audit["total"] == 4
    rows = [(e["action"], e["outcome"], e["vehicle_id"]) for e in audit["items"]]
    assert rows == [
        ("rest.remove_vehicle", "ok", "alpha"),
        ("rest.register_vehicle", "error", "BAD"),
        ("rest.register_vehicle", "error", "alpha"),
        ("rest.register_vehicle", "ok", "alpha"),
    ]
    first = audit["items"][-1]
    assert first["source"] == "rest" and first["principal"] == "anonymous"
    assert first["arguments"]["body"]["url"] == ALPHA["url"] and first["duration_ms"] >= 0
    assert audit["items"][2]["error"].startswith("duplicate_vehicle")

    by_vehicle = (await client.get("/api/v1/audit", params={"vehicle_id": "alpha", "limit": 2})).json()
    assert by_vehicle["total"] == 3 and len(by_vehicle["items"]) == 2

    sessions = (await client.get("/api/v1/sessions")).json()["items"]
    assert [(s["key"], s["kind"], s["request_count"]) for s in sessions] == [("rest:anonymous", "rest", 4)]
    assert (await client.get("/api/v1/sessions", params={"kind": "mcp-2025"})).json()["items"] == []
    assert_error(await client.get("/api/v1/sessions", params={"kind": "smtp"}), 422, "validation_error")


async def test_audit_lists_mcp_entries_too(client: httpx.AsyncClient, app: FastAPI) -> None:
    await store_of(app).add_audit(
        AuditEntry(session_key="s-1", source="mcp", vehicle_id="alpha", action="takeoff", outcome="refused")
    )
    items = (await client.get("/api/v1/audit", params={"session_key": "s-1"})).json()["items"]
    assert [(e["source"], e["action"], e["outcome"]) for e in items] == [("mcp", "takeoff", "refused")]


# --- metrics -----------------------------------------------------------------------------------


async def test_metrics_per_app(client: httpx.AsyncClient, app: FastAPI, settings: Settings, tmp_path) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    text = (await client.get("/metrics")).text
    assert 'fleet_gateway_vehicles{state="connecting"} 1.0' in text
    assert 'fleet_gateway_vehicles{state="ready"} 0.0' in text
    assert 'fleet_gateway_sidecar_restarts_total{vehicle="alpha"} 0.0' in text
    counted = app.state.gateway.registry.get("alpha").telemetry.message_counts["position"]
    pattern = r'fleet_gateway_telemetry_messages_total\{stream="position",vehicle="alpha"\} (\d+)'
    found = re.search(pattern, text)
    assert found is not None and int(found.group(1)) >= 1 and counted >= 1, text
    assert (
        'fleet_gateway_http_requests_total{method="POST",route="/api/v1/vehicles",status="201"} 1.0' in text
    )
    assert "fleet_gateway_ready 1.0" in text
    assert 'fleet_gateway_calls_total{action="rest.register_vehicle",outcome="ok",source="rest"} 1.0' in text
    # a refusal counts by its rule
    app.state.gateway.registry.get("alpha").state = ConnectionState.READY
    refused = await client.post("/api/v1/vehicles/alpha/takeoff", json={"alt_rel_m": 5000})
    assert refused.status_code == 403 and refused.json()["error"]["message"].startswith("max_altitude")
    counted = 'fleet_gateway_refusals_total{rule="max_altitude"} 1.0'
    deadline = asyncio.get_running_loop().time() + scaled(10)
    while counted not in (text := (await client.get("/metrics")).text):  # audited after the answer
        assert asyncio.get_running_loop().time() < deadline, text
        await asyncio.sleep(0.05)
    call = 'fleet_gateway_calls_total{action="rest.takeoff_vehicle",outcome="refused",source="rest"} 1.0'
    assert call in text

    other = create_app(settings.model_copy(update={"database_url": f"sqlite+aiosqlite:///{tmp_path}/b.db"}))
    assert other.state.metrics_registry is not app.state.metrics_registry


async def test_mcp_is_served_beside_the_api(client: httpx.AsyncClient) -> None:
    """/mcp reaches the MCP app (one ASGI app); its neighbours keep the API's JSON errors."""
    initialize = {
        "jsonrpc": "2.0",
        "id": 1,
        "method": "initialize",
        "params": {
            "protocolVersion": "2025-11-25",
            "capabilities": {},
            "clientInfo": {"name": "rest-test", "version": "1"},
        },
    }
    response = await client.post(
        "/mcp", json=initialize, headers={"accept": "application/json, text/event-stream"}
    )
    assert response.status_code == 200, response.text
    assert "fleet" in response.text.lower() or "serverInfo" in response.text
    assert_error(await client.get("/mcp-nothing"), 404, "not_found")
    big = {**initialize, "params": {**initialize["params"], "pad": "x" * 5000}}
    too_big = await client.post("/mcp", json=big)  # a JSON-RPC error, which MCP clients show
    assert too_big.status_code == 413
    error = too_big.json()["error"]
    assert error["code"] == -32600 and "larger than the gateway's limit of" in error["message"], error

    async def chunks() -> AsyncIterator[bytes]:  # no Content-Length: found too big while read
        body = json.dumps(big).encode()
        for i in range(0, len(body), 1000):
            yield body[i : i + 1000]

    streamed = await client.post(
        "/mcp", content=chunks(), headers={"content-type": "application/json", "accept": "application/json"}
    )
    assert streamed.status_code == 413, streamed.text
    error = streamed.json()["error"]
    assert error["code"] == -32600 and "request is larger than the gateway's limit of" in error["message"], (
        error
    )


# --- operator control --------------------------------------------------------------------------


async def test_locks_set_shown_persisted_and_restored(
    client: httpx.AsyncClient, app: FastAPI, settings
) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    locked = await client.post("/api/v1/vehicles/alpha/lock", json={"reason": "battery swap"})
    assert locked.status_code == 200 and locked.json()["by"] == "anonymous"
    assert (await client.post("/api/v1/fleet/lock", json={"reason": "storm"})).json()["scope"] == "*"
    assert [lk["scope"] for lk in (await client.get("/api/v1/locks")).json()["items"]] == ["*", "alpha"]
    view = (await client.get("/api/v1/vehicles/alpha")).json()
    assert "battery swap" in view["locked"] and "storm" in view["locked"]
    # the safety policy (what MCP checks) sees the locks through its read-only view
    assert "battery swap" in app.state.gateway.safety.locks.reason_for("alpha")

    assert_error(
        await client.post("/api/v1/vehicles/ghost/lock", json={"reason": "x"}), 404, "unknown_vehicle"
    )
    # a command route takes the id in any case; the lock is keyed by the registered id
    assert (await client.delete("/api/v1/vehicles/ALPHA/lock")).json()["was_locked"] is True
    relocked = await client.post("/api/v1/vehicles/Alpha/lock", json={"reason": "battery swap"})
    assert relocked.json()["scope"] == "alpha"
    error = assert_error(await client.post("/api/v1/fleet/lock", json={}), 422, "validation_error")
    assert "reason" in error["message"]
    too_long = await client.post("/api/v1/fleet/lock", json={"reason": "r" * 501})
    assert_error(too_long, 422, "validation_error")
    assert (await client.get("/api/v1/locks")).json()["items"][0]["reason"] == "storm"

    unlocked = (await client.delete("/api/v1/fleet/lock")).json()
    assert unlocked == {"scope": "*", "was_locked": True}
    assert (await client.delete("/api/v1/fleet/lock")).json()["was_locked"] is False

    # a new gateway on the same database still has the drone's lock
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as again:
        assert (
            again.state.gateway.locks.reason_for("alpha")
            == "drone alpha is locked by anonymous: battery swap"
        )
        assert again.state.gateway.locks.get("*") is None


async def test_operator_actions_and_fleet_stop(client: httpx.AsyncClient, app: FastAPI) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    await client.post("/api/v1/vehicles", json={"id": "bravo", "url": "udpin://0.0.0.0:14541"})
    registry = app.state.gateway.registry
    alpha, bravo = registry.get("alpha"), registry.get("bravo")

    # an operator's hold/land/RTL goes to a drone that has a link, ready or not (e.g. no GPS)
    alpha.state = ConnectionState.CONNECTED
    alpha.set(in_air=True, armed=True)
    for action in ("hold", "land"):
        sent = (await client.post(f"/api/v1/vehicles/alpha/{action}")).json()
        assert (sent["vehicle_id"], sent["action"], sent["outcome"]) == ("alpha", action, "sent")
    assert [c[0] for c in alpha.sent] == ["hold", "land"]
    assert sent["operation_id"], "an operator's landing is a tracked operation"
    error = assert_error(await client.post("/api/v1/vehicles/bravo/rtl"), 409, "vehicle_not_ready")
    assert "connecting" in error["message"]
    assert_error(await client.post("/api/v1/vehicles/ghost/hold"), 404, "unknown_vehicle")

    alpha.set(in_air=True, armed=True)  # flying again
    bravo.set(in_air=False)
    stop = await client.post("/api/v1/fleet/stop", json={"action": "land", "lock_reason": "take-over"})
    body = stop.json()
    assert stop.status_code == 200 and body["fleet_lock"]["reason"] == "take-over"
    assert {r["vehicle_id"]: r["outcome"] for r in body["results"]} == {"alpha": "sent", "bravo": "skipped"}
    assert alpha.sent[-1] == ("land",) and bravo.sent == []
    assert app.state.gateway.locks.get("*") is not None
    await client.post("/api/v1/vehicles/bravo/disconnect")
    alpha.set(in_air=True, armed=True)
    after = (await client.post("/api/v1/fleet/stop", json={"action": "hold"})).json()["results"]
    assert {r["vehicle_id"]: (r["outcome"], r["message"]) for r in after} == {
        "alpha": ("sent", None),
        "bravo": ("skipped", "not connected (registered)"),
    }
    assert_error(await client.post("/api/v1/fleet/stop", json={"action": "kill"}), 422, "validation_error")
    default = (await client.post("/api/v1/fleet/stop")).json()
    assert default["action"] == "hold" and default["fleet_lock"]["reason"] == "emergency stop"
    unlocked = (await client.post("/api/v1/fleet/stop", json={"action": "rtl", "lock": False})).json()
    assert unlocked["action"] == "rtl" and unlocked["fleet_lock"] is None

    actions = [e["action"] for e in (await client.get("/api/v1/audit")).json()["items"]]
    assert "rest.fleet_stop" in actions and "rest.land_vehicle" in actions


# --- the same API on PostgreSQL ----------------------------------------------------------------


async def test_rest_on_postgresql(pg_database_url: str) -> None:
    settings = Settings(database_url=pg_database_url, max_request_body_bytes=4096)
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as app:
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as client:
            assert (await client.post("/api/v1/vehicles", json=ALPHA)).status_code == 201
            assert_error(await client.post("/api/v1/vehicles", json=ALPHA), 409, "duplicate_vehicle")
            ids = await seed_flights(store_of(app))
            page = (await client.get("/api/v1/flights", params={"vehicle_id": "alpha", "limit": 1})).json()
            assert page["total"] == 2 and page["items"][0]["id"] == ids[2]
            feature = (await client.get(f"/api/v1/flights/{ids[0]}/track.geojson")).json()
            assert len(feature["geometry"]["coordinates"]) == 5
            await client.post("/api/v1/vehicles/alpha/lock", json={"reason": "pg"})
            audit = (await client.get("/api/v1/audit")).json()
            assert [e["action"] for e in audit["items"]][:2] == ["rest.lock_vehicle", "rest.register_vehicle"]
    # restored from PostgreSQL by a new app
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as again:
        assert again.state.gateway.locks.reason_for("alpha").endswith(": pg")
        assert [v.id for v in await store_of(again).list_vehicles()] == ["alpha"]


@pytest.mark.parametrize(
    ("path", "body", "field"),
    [
        ("takeoff", {"alt_rel_m": 0}, "alt_rel_m"),
        ("takeoff", {"alt_rel_m": "high"}, "alt_rel_m"),
        ("takeoff", {}, "alt_rel_m"),
        ("goto", {"lat": 91, "lon": 8, "alt_rel_m": 10}, "lat"),
        ("goto", {"lat": 47, "lon": 8, "alt_rel_m": -1}, "alt_rel_m"),
        ("goto", {"lat": 47, "lon": 8, "alt_rel_m": 10, "speed": 3}, "speed"),
    ],
)
async def test_operator_flight_commands_validate_first(
    client: httpx.AsyncClient, app: FastAPI, path: str, body: dict, field: str
) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    error = assert_error(
        await client.post(f"/api/v1/vehicles/alpha/{path}", json=body), 422, "validation_error"
    )
    assert field in error["message"]
    assert app.state.gateway.registry.get("alpha").sent == []


async def test_operator_goto_rejects_nan(client: httpx.AsyncClient) -> None:
    await client.post("/api/v1/vehicles", json=ALPHA)
    raw = b'{"lat": NaN, "lon": 8, "alt_rel_m": 10}'
    response = await client.post(
        "/api/v1/vehicles/alpha/goto", content=raw, headers={"content-type": "application/json"}
    )
    assert response.status_code in (400, 422) and "lat" in response.text
