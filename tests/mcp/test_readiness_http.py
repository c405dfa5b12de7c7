"""A drone that is connected but still initialising says so in list_drones and REST, and arm_drone at
once after "ready" arms: an MCP client over Streamable HTTP, the gateway served by uvicorn, one simulated
ArduCopter booting from zero (the same on real ArduCopter is checked while tests/real/tour.py boots)."""

from __future__ import annotations

from pathlib import Path

import httpx
from mcp import Client
from mcp.types import Implementation

from gateway.app import create_app
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.api.server import serve_in_thread
from tests.helpers import sim_process
from tests.helpers.timing import eventually
from tests.mcp.conftest import integration_settings, structured


async def _state(http: httpx.AsyncClient, state: str) -> bool:
    return bool((await http.get("/api/v1/vehicles/d1")).json()["state"] == state)


ESTIMATE = "waiting for the position estimate (the EKF is not using GPS yet)"


async def test_list_drones_and_rest_say_initialising_until_the_drone_can_arm(tmp_path: Path) -> None:
    async with sim_process(1, speedup=8.0) as sim:
        settings = integration_settings(tmp_path)
        store = await Store.open(settings.database_url)
        try:
            await store.add_vehicle(VehicleSpec(id="d1", url=sim.urls[0]))
        finally:
            await store.close()
        with serve_in_thread(create_app(settings)) as base_url:
            client = Client(f"{base_url}/mcp", client_info=Implementation(name="readiness", version="1.0"))
            async with client as c, httpx.AsyncClient(base_url=base_url) as http:
                seen: list[tuple[str, str | None, str, str | None]] = []
                positions: list[dict[str, object]] = []

                async def ready() -> bool:
                    listed = await c.call_tool("list_drones", {})
                    row = structured(listed)["drones"][0]
                    rest = (await http.get("/api/v1/vehicles/d1")).json()
                    rest_waits = (rest.get("status") or {}).get("initialising")  # None until loaded
                    seen.append((row["state"], row["initialising"], rest["state"], rest_waits))
                    # while booting the autopilot streams 0, 0: never reported as a position
                    pos = await c.call_tool("get_position", {"drone_id": "d1"})
                    if pos.is_error:
                        assert "no position position from d1 yet" not in pos.content[0].text
                        assert "has no global position fix" in pos.content[0].text, pos.content
                    else:
                        where = structured(pos)
                        assert (where["lat_deg"], where["lon_deg"]) != (0.0, 0.0), where
                        positions.append(where)
                    if row["initialising"]:
                        assert f"d1 connected ({row['initialising']})" in listed.content[0].text
                    return row["state"] == "ready" and rest["state"] == "ready"

                async def ready_or_estimating() -> bool:
                    await ready()
                    return seen[-1] == ("connected", ESTIMATE, "connected", ESTIMATE)

                await eventually(ready, "d1 ready", within_s=60, explain=lambda: seen[-1:])
                # the simulator booted while the gateway started: boot it again from zero, watched; the
                # estimate is held back until the gateway has seen the boot (under load the sidecar's
                # reconnect can otherwise take longer than the simulator's sped-up boot)
                await sim.control.hold_estimate(0, True)
                await sim.control.reboot(0)
                await eventually(lambda: _state(http, "connected"), "d1 rebooting", within_s=60)
                seen.clear()
                await eventually(ready_or_estimating, "d1 waiting for its estimate", within_s=60)
                await sim.control.hold_estimate(0, False)
                await eventually(ready, "d1 ready after the reboot", within_s=60, explain=lambda: seen[-1:])
                assert ("connected", ESTIMATE, "connected", ESTIMATE) in seen, seen
                assert seen[-1] == ("ready", None, "ready", None), seen
                assert len(positions) >= 2, positions  # read through the reboot, never at 0, 0

                armed = structured(await c.call_tool("arm_drone", {"drone_id": "d1"}))  # at once
                assert armed["action"] == "arm" and armed["message"] == "armed", armed
                assert (await sim.control.state(0))["armed"] is True
