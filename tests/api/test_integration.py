"""The gateway over real HTTP with simulated drones behind real mavsdk_server sidecars."""

from __future__ import annotations

import asyncio
import os
import signal
import sys
from pathlib import Path

import httpx
import pytest
from mcp import Client
from mcp.types import Implementation

from gateway.registry.store import Store
from gateway.util.ports import free_tcp_port
from tests.helpers import sim_process
from tests.helpers.procs import stop_process, tail
from tests.helpers.timing import scaled
from tests.registry.procs import alive, mavsdk_servers_of

from .live import WAIT_S, live_settings, served, states, wait_all_ready, wait_until

IDS = ["alpha", "bravo", "charlie"]


async def vehicles_in_db(db_path: Path) -> list[tuple[str, str]]:
    store = await Store.open(f"sqlite+aiosqlite:///{db_path}")
    try:
        return [(v.id, v.url) for v in await store.list_vehicles()]
    finally:
        await store.close()


async def test_register_three_drones_restart_and_restore(tmp_path: Path) -> None:
    db = tmp_path / "gateway.db"
    settings = live_settings(db)
    async with sim_process(count=3, speedup=10) as sim:
        async with served(settings) as (_app, client):
            for vid, url in zip(IDS, sim.urls, strict=True):
                created = await client.post("/api/v1/vehicles", json={"id": vid, "url": url, "tags": ["sim"]})
                assert created.status_code == 201, created.text
            await wait_all_ready(client, IDS)

            one = (await client.get("/api/v1/vehicles/alpha")).json()
            assert one["status"]["is_simulator"] is True and one["status"]["sidecar"]["pid"]
            assert one["telemetry"]["position"]["lat_deg"] == pytest.approx(
                one["telemetry"]["home"]["lat_deg"], abs=1e-3
            )
            metrics = (await client.get("/metrics")).text
            assert 'fleet_gateway_vehicles{state="ready"} 3.0' in metrics
            assert 'fleet_gateway_telemetry_age_seconds{stream="position",vehicle="alpha"}' in metrics
            assert 'fleet_gateway_heartbeat_age_seconds{vehicle="charlie"}' in metrics
            assert 'fleet_gateway_telemetry_messages_total{stream="position",vehicle="bravo"}' in metrics

            before = await vehicles_in_db(db)
            bad = [
                ({"id": "Not Valid", "url": sim.urls[0]}, 422, "validation_error"),
                ({"id": "delta", "url": "http://127.0.0.1:5760"}, 422, "validation_error"),
                ({"id": "alpha", "url": sim.urls[1]}, 409, "duplicate_vehicle"),
                ({"id": "delta", "url": sim.urls[0], "expected_sysid": "x"}, 422, "validation_error"),
                ({"id": ["delta"], "url": 5760}, 422, "validation_error"),
            ]
            for body, status, code in bad:
                response = await client.post("/api/v1/vehicles", json=body)
                assert response.status_code == status and response.json()["error"]["code"] == code, body
            malformed = await client.post(
                "/api/v1/vehicles", content=b"{'id': 'delta'}", headers={"content-type": "application/json"}
            )
            assert malformed.status_code == 400 and malformed.json()["error"]["code"] == "malformed_json"
            assert await vehicles_in_db(db) == before
            assert sorted(await states(client)) == IDS

        # the app (and its lifespan) stopped: every sidecar is gone
        assert mavsdk_servers_of() == []

        # a new gateway on the same database restores the three and connects them again
        async with served(settings) as (_app, client):
            assert sorted(await states(client)) == IDS
            await wait_all_ready(client, IDS)
            audit = (await client.get("/api/v1/audit", params={"limit": 1000})).json()
            actions = [(e["action"], e["outcome"]) for e in audit["items"]]
            assert actions.count(("rest.register_vehicle", "ok")) == 3
            assert actions.count(("rest.register_vehicle", "error")) == len(bad) + 1

            # remove one through REST: its sidecar stops, the others stay ready
            pid = (await client.get("/api/v1/vehicles/charlie")).json()["status"]["sidecar"]["pid"]
            assert (await client.delete("/api/v1/vehicles/charlie")).status_code == 204
            assert not alive(pid)
            assert await states(client) == {"alpha": "ready", "bravo": "ready"}
        assert mavsdk_servers_of() == []


async def test_flown_flight_is_listed_with_its_track(tmp_path: Path) -> None:
    settings = live_settings(tmp_path / "gateway.db")
    async with sim_process(count=1, speedup=10) as sim:
        async with served(settings) as (app, client):
            created = await client.post("/api/v1/vehicles", json={"id": "alpha", "url": sim.urls[0]})
            assert created.status_code == 201, created.text
            await wait_all_ready(client, ["alpha"])

            vehicle = app.state.gateway.registry.get("alpha")
            home = vehicle.telemetry.home.value
            # the operator flies it over REST; the safety limits apply to operators too
            too_high = await client.post("/api/v1/vehicles/alpha/takeoff", json={"alt_rel_m": 500})
            assert too_high.status_code == 403, too_high.text
            assert too_high.json()["error"]["code"] == "safety_refusal" and "120" in too_high.text
            took_off = await client.post("/api/v1/vehicles/alpha/takeoff", json={"alt_rel_m": 5})
            assert took_off.status_code == 200 and took_off.json()["outcome"] == "sent", took_off.text
            await wait_until(lambda: _at(vehicle, lambda p: p.rel_alt_m > 4.0), "takeoff to 5 m", every_s=0.1)
            target_lat = home.lat_deg + 30.0 / 111_320.0  # ~30 m north
            far = {"lat": home.lat_deg + 0.1, "lon": home.lon_deg, "alt_rel_m": 5}  # ~11 km
            refused = await client.post("/api/v1/vehicles/alpha/goto", json=far)
            assert refused.status_code == 403 and refused.json()["error"]["details"]["rule"] == "max_distance"
            goto = {"lat": target_lat, "lon": home.lon_deg, "alt_rel_m": 5.0}
            assert (await client.post("/api/v1/vehicles/alpha/goto", json=goto)).status_code == 200
            await wait_until(
                lambda: _at(vehicle, lambda p: abs(p.lat_deg - target_lat) < 3e-5), "arrival", every_s=0.1
            )
            # the operator's emergency stop lands it (and locks the fleet against agents)
            stop = await client.post(
                "/api/v1/fleet/stop", json={"action": "land", "lock_reason": "test over"}
            )
            assert stop.status_code == 200, stop.text
            assert [(r["vehicle_id"], r["outcome"]) for r in stop.json()["results"]] == [("alpha", "sent")]
            assert "test over" in (await client.get("/api/v1/vehicles/alpha")).json()["locked"]
            # an agent (MCP on the same app) is refused while the operator's lock holds, reads still work
            base = str(client.base_url).rstrip("/")
            async with Client(
                f"{base}/mcp", client_info=Implementation(name="rest-test", version="1")
            ) as agent:
                goto = {"drone_id": "alpha", "lat_deg": home.lat_deg, "lon_deg": home.lon_deg}
                refused = await agent.call_tool("go_to_location", {**goto, "alt_m": 5, "wait": False})
                assert refused.is_error and "test over" in refused.content[0].text
                status = await agent.call_tool("get_armed", {"drone_id": "alpha"})
                assert not status.is_error

            async def flight_closed() -> bool:
                page = (await client.get("/api/v1/flights", params={"vehicle_id": "alpha"})).json()
                return page["total"] == 1 and page["items"][0]["ended_at"] is not None

            await wait_until(flight_closed, "the flight to be closed after landing")
            [flight] = (await client.get("/api/v1/flights", params={"vehicle_id": "alpha"})).json()["items"]
            assert flight["distance_m"] > 20 and 4.0 < flight["max_alt_rel_m"] < 7.0
            assert flight["home_lat"] == pytest.approx(home.lat_deg)
            assert (await client.get(f"/api/v1/flights/{flight['id']}")).json() == flight
            others = (await client.get("/api/v1/flights", params={"vehicle_id": "bravo"})).json()
            assert others["total"] == 0

            geojson = await client.get(f"/api/v1/flights/{flight['id']}/track.geojson")
            assert geojson.headers["content-type"].startswith("application/geo+json")
            feature = geojson.json()
            coords = feature["geometry"]["coordinates"]
            assert feature["geometry"]["type"] == "LineString" and len(coords) >= 5
            assert max(c[1] for c in coords) == pytest.approx(target_lat, abs=5e-5)
            assert max(c[2] for c in coords) > 4.0
            assert len(feature["properties"]["times"]) == len(coords)

            audit = (await client.get("/api/v1/audit", params={"vehicle_id": "alpha"})).json()["items"]
            outcomes = [(e["action"], e["outcome"]) for e in audit]
            assert ("rest.takeoff_vehicle", "refused") in outcomes and (
                "rest.goto_vehicle",
                "refused",
            ) in outcomes
            # the takeoff's row ends as its operation did: reached, or replaced by the goto sent at 4 m
            took = {o for a, o in outcomes if a == "rest.takeoff_vehicle" and o != "refused"}
            assert len(took) == 1 and took <= {"ok", "superseded"}, outcomes
            assert ("go_to_location", "refused") in outcomes  # the agent's refused call, same table

            texts = (await client.get("/api/v1/vehicles/alpha/statustexts")).json()["items"]
            assert texts and all(t["severity"] for t in texts)
        assert mavsdk_servers_of() == []


async def _at(vehicle, predicate) -> bool:
    position = vehicle.telemetry.fresh("position")
    return position is not None and predicate(position)


@pytest.mark.parametrize("stop_signal", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
async def test_serve_command_stops_cleanly_on_signals(tmp_path: Path, stop_signal: signal.Signals) -> None:
    """`fleet-gateway serve` in its own process: SIGTERM or Ctrl-C stops the app and every sidecar."""
    port = free_tcp_port()
    db_url = f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}"
    log_path = tmp_path / "serve.log"
    async with sim_process(count=1, speedup=10) as sim:
        with log_path.open("wb") as log:
            proc = await asyncio.create_subprocess_exec(
                *[
                    sys.executable,
                    "-m",
                    "gateway.cli",
                    "serve",
                    "--port",
                    str(port),
                    "--database-url",
                    db_url,
                ],
                env={**os.environ, "GATEWAY_LINK_LOST_AFTER_S": "3"},
                stdin=asyncio.subprocess.DEVNULL,
                stdout=log,
                stderr=log,
                start_new_session=True,
            )
        try:
            async with httpx.AsyncClient(base_url=f"http://127.0.0.1:{port}", timeout=scaled(30.0)) as client:

                async def up() -> bool:
                    try:
                        return (await client.get("/readyz")).status_code == 200
                    except httpx.TransportError:
                        assert proc.returncode is None, tail(str(log_path))
                        return False

                await wait_until(up, "the gateway to be ready")
                created = await client.post("/api/v1/vehicles", json={"id": "alpha", "url": sim.urls[0]})
                assert created.status_code == 201, created.text
                await wait_all_ready(client, ["alpha"])
                sidecars = mavsdk_servers_of(proc.pid)
                assert len(sidecars) == 1

            proc.send_signal(stop_signal)
            returncode = await asyncio.wait_for(proc.wait(), WAIT_S)
        finally:
            await stop_process(proc)
        output = log_path.read_text(errors="replace")
        assert returncode == 0, output[-2000:]
        assert "gateway stopped" in output and "Application shutdown complete" in output
        assert not alive(sidecars[0])
