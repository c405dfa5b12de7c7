"""Geofences set over REST, per fleet and per drone: the policy refuses targets in them at once, bad input
changes nothing, viewers cannot set them, and with GATEWAY_GEOFENCE_FILE they survive a restart."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import httpx
import pytest

from gateway.app import create_app
from gateway.config import Settings
from gateway.errors import SafetyRefusal
from gateway.fleet.policy.safety_inputs import Target, VehicleContext
from tests.fakes import FakeRegistry

from .live import lifespan_running

HOME = (47.3970, 8.5460, 488.0)


def square(lat: float, lon: float, half_deg: float = 0.0005) -> dict[str, Any]:
    h = half_deg
    ring = [
        [lon - h, lat - h],
        [lon + h, lat - h],
        [lon + h, lat + h],
        [lon - h, lat + h],
        [lon - h, lat - h],
    ]
    return {"type": "Polygon", "coordinates": [ring]}


def collection(*features: tuple[str, str, dict[str, Any]]) -> dict[str, Any]:
    return {
        "type": "FeatureCollection",
        "features": [
            {"type": "Feature", "properties": {"kind": kind, "name": name}, "geometry": geometry}
            for name, kind, geometry in features
        ],
    }


def ctx(vehicle_id: str) -> VehicleContext:
    return VehicleContext(vehicle_id, True, True, True, 90.0, HOME, (HOME[0], HOME[1], 10.0))


def refused(app: Any, vehicle_id: str, lat: float, lon: float) -> str | None:
    try:
        app.state.gateway.safety.check_motion(ctx(vehicle_id), Target(lat, lon, 10.0))
    except SafetyRefusal as exc:
        return exc.rule
    return None


@pytest.mark.parametrize("with_file", [False, True])
async def test_geofences_over_rest(tmp_path: Path, with_file: bool) -> None:
    fence_file = tmp_path / "fences.geojson"
    settings = Settings(
        _env_file=None,
        database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        operator_tokens="op-token",
        viewer_tokens="view-token",
        geofence_file=str(fence_file) if with_file else None,
    )
    if with_file:
        fence_file.write_text('{"type": "FeatureCollection", "features": []}')
    op = {"authorization": "Bearer op-token"}
    school = (HOME[0] + 0.002, HOME[1])
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as app:
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as http:
            for vid in ("alpha", "bravo"):
                r = await http.post(
                    "/api/v1/vehicles", json={"id": vid, "url": "udpin://127.0.0.1:14550"}, headers=op
                )
                assert r.status_code == 201, r.text
            assert refused(app, "alpha", *school) is None

            fleet = collection(("school", "keep_out", square(*school)))
            r = await http.put("/api/v1/fleet/geofences", json=fleet, headers=op)
            assert r.status_code == 200, r.text
            assert r.json()["persisted"] is with_file
            assert refused(app, "alpha", *school) == "geofence_keep_out"
            assert refused(app, "bravo", *school) == "geofence_keep_out"

            field = collection(("alpha-field", "keep_in", square(HOME[0], HOME[1], 0.001)))
            r = await http.put("/api/v1/vehicles/alpha/geofences", json=field, headers=op)
            assert r.status_code == 200, r.text
            far = (HOME[0] - 0.003, HOME[1])
            assert refused(app, "alpha", *far) == "geofence_keep_in"
            assert refused(app, "bravo", *far) is None
            listed = (
                await http.get("/api/v1/geofences", headers={"authorization": "Bearer view-token"})
            ).json()
            assert [
                (f["properties"]["name"], f["properties"].get("vehicle_id")) for f in listed["features"]
            ] == [
                ("school", None),
                ("alpha-field", "alpha"),
            ]

            # bad input is refused with the reason and changes nothing
            bad = [
                collection(("hole", "keep_out", {"type": "Point", "coordinates": [8.5, 47.3]})),
                collection(("x", "keep_sideways", square(*school))),
                collection(("school", "keep_out", square(*far))),  # the fleet already has a "school"
                {
                    "type": "FeatureCollection",
                    "features": [{"type": "Feature", "properties": [], "geometry": {}}],
                },
                collection(("upside", "keep_in", square(95.0, 8.5))),
            ]
            for body in bad:
                r = await http.put("/api/v1/vehicles/alpha/geofences", json=body, headers=op)
                assert r.status_code == 422, (body, r.text)
                assert r.json()["error"]["message"], r.text
            r = await http.put("/api/v1/vehicles/ghost/geofences", json=field, headers=op)
            assert r.status_code == 404 and "alpha" in r.text
            r = await http.put(
                "/api/v1/fleet/geofences", json=field, headers={"authorization": "Bearer view-token"}
            )
            assert r.status_code == 403
            assert (await http.get("/api/v1/geofences", headers=op)).json()["features"] == listed["features"]
            assert refused(app, "alpha", *far) == "geofence_keep_in"

    # a restart: with the file the zones come back, without it they are gone
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as app:
        assert (refused(app, "alpha", *far) == "geofence_keep_in") is with_file
        assert (refused(app, "bravo", *school) == "geofence_keep_out") is with_file
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as http:
            if with_file:
                r = await http.delete("/api/v1/vehicles/alpha/geofences", headers=op)
                assert r.status_code == 200 and [f["properties"]["name"] for f in r.json()["features"]] == [
                    "school"
                ]
                assert refused(app, "alpha", *far) is None
