"""An operator's land for a drone that is already on the ground and disarmed is a conflict with the
drone's state, not bad input: REST answers 409 (code state_conflict) with the drone's state in the
message, and nothing is sent. On a simulated ArduCopter behind a real sidecar."""

from __future__ import annotations

import asyncio
from pathlib import Path

import httpx

from gateway.app import create_app
from tests.helpers import sim_process
from tests.helpers.timing import scaled

from .live import live_settings
from .server import serve_in_thread


async def test_land_on_the_ground_is_409(tmp_path: Path) -> None:
    async with sim_process(count=1, speedup=10) as sim:
        app = create_app(live_settings(tmp_path / "gateway.db"))
        with serve_in_thread(app) as base:
            async with httpx.AsyncClient(base_url=base, timeout=scaled(60)) as http:
                created = await http.post("/api/v1/vehicles", json={"id": "alpha", "url": sim.urls[0]})
                assert created.status_code == 201, created.text
                loop = asyncio.get_running_loop()
                deadline = loop.time() + scaled(60)
                while (await http.get("/api/v1/vehicles/alpha")).json().get("state") != "ready":
                    assert loop.time() < deadline, "the simulated drone never became ready"
                    await asyncio.sleep(0.2)
                answer = await http.post("/api/v1/vehicles/alpha/land")
                assert answer.status_code == 409, answer.text
                error = answer.json()["error"]
                assert error["code"] == "state_conflict"
                assert "alpha is already on the ground and disarmed" in error["message"]
                ops = (await http.get("/api/v1/operations", params={"vehicle_id": "alpha"})).json()["items"]
                assert [o for o in ops if o["kind"] == "land"] == []  # nothing was sent
