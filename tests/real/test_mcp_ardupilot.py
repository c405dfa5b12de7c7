"""The paper's failures on a real autopilot: an MCP client over Streamable HTTP, the gateway served by
uvicorn with its SQLite store, one mavsdk_server, and real ArduCopter SITL (speed-up 5)."""

from __future__ import annotations

from pathlib import Path

import httpx
import pytest
from mcp import Client
from mcp.types import Implementation

from gateway.app import create_app
from gateway.fleet import geo
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.api.server import serve_in_thread
from tests.helpers.timing import eventually
from tests.mcp.conftest import error_text, integration_settings, structured

pytestmark = pytest.mark.real


async def test_takeoff_then_goto_at_once_is_refused_and_limits_hold_on_real_arducopter(
    arducopter, tmp_path: Path
) -> None:
    settings = integration_settings(tmp_path)
    store = await Store.open(settings.database_url)
    try:
        await store.add_vehicle(VehicleSpec(id="ap1", url=arducopter.url))
    finally:
        await store.close()
    app = create_app(settings)
    with serve_in_thread(app) as base_url:
        client = Client(f"{base_url}/mcp", client_info=Implementation(name="real-paper", version="1.0"))
        async with client as c:
            seen: list[tuple[str, str | None, str, str | None]] = []  # list_drones and REST, while waiting

            async def ready() -> bool:
                listed = await c.call_tool("list_drones", {})
                row = structured(listed)["drones"][0]
                async with httpx.AsyncClient(base_url=base_url) as http:
                    rest = (await http.get("/api/v1/vehicles/ap1")).json()
                rest_waits = rest["status"]["initialising"]
                seen.append((row["state"], row["initialising"], rest["state"], rest_waits))
                if row["initialising"]:
                    assert f"ap1 connected ({row['initialising']})" in listed.content[0].text
                return row["state"] == "ready"

            await eventually(ready, "ap1 ready", within_s=120)
            # GPS and home long before the EKF uses GPS: "connected (waiting for the position estimate)"
            estimate = "waiting for the position estimate (the EKF is not using GPS yet)"
            assert ("connected", estimate, "connected", estimate) in seen, seen
            assert seen[-1] == ("ready", None, "ready", None), seen
            home = structured(await c.call_tool("get_position", {"drone_id": "ap1"}))
            lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], 40.0, 0.0)
            goto = {"drone_id": "ap1", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}

            # the paper's crash: takeoff and goto back to back. The goto is refused, nothing sent.
            r = structured(await c.call_tool("takeoff", {"drone_id": "ap1", "alt_m": 10, "wait": False}))
            assert r["status"] == "running", r
            text = error_text(await c.call_tool("go_to_location", goto))
            assert "takeoff_in_progress" in text and "monitor_flight" in text, text
            while (r := structured(await c.call_tool("monitor_flight", {"drone_id": "ap1"})))[
                "status"
            ] == "running":
                pass
            assert r["status"] == "succeeded" and r["kind"] == "takeoff", r

            # the policy's limits hold on a real vehicle, in words the model can act on
            high = {**goto, "alt_m": settings.max_altitude_m + 30}
            assert "Refused: max_altitude" in error_text(await c.call_tool("go_to_location", high))
            far_lat, far_lon = geo.offset_position(
                home["lat_deg"], home["lon_deg"], settings.max_distance_m + 500, 0
            )
            far = {**goto, "lat_deg": far_lat, "lon_deg": far_lon}
            assert "Refused: max_distance" in error_text(await c.call_tool("go_to_location", far))

            r = structured(await c.call_tool("go_to_location", goto))
            assert r["status"] == "succeeded", r
            r = structured(await c.call_tool("return_to_launch", {"drone_id": "ap1"}))
            assert r["status"] == "succeeded", r
