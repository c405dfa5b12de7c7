"""An operator starts, pauses and resumes a drone's mission and reads and writes its parameters over REST:
the same verbs the MCP tools call, each write audited. The simulator, the real gateway, real HTTP."""

from __future__ import annotations

import asyncio
from typing import Any

import httpx
import pytest

from tests.helpers.timing import eventually, scaled
from tests.mcp.conftest import Stack, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")
DRONES = 1


async def _post(http: httpx.AsyncClient, path: str, **kw: Any) -> dict[str, Any]:
    r = await http.request(kw.pop("method", "POST"), f"/api/v1{path}", **kw)
    assert r.status_code == 200, (path, r.text)
    return dict(r.json())


async def _operation_ends(stack: Stack, operation_id: str) -> dict[str, Any]:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(90)
    while True:
        ops = (await stack.rest("/operations", vehicle_id="d1"))["items"]
        op = next((o for o in ops if o["id"] == operation_id), None)
        if op is not None and op["status"] != "running":
            return dict(op)
        assert loop.time() < deadline, op
        await asyncio.sleep(0.3)


async def test_an_unknown_parameter_is_refused_from_the_list_fetched_at_connect(stack: Stack) -> None:
    """The gateway fetches the autopilot's parameter list as the drone connects (before any read, as a
    ground station does), so the first read of a name the autopilot does not have is refused from that
    list without asking the autopilot (older ArduPilot does not answer one: ~3 s for nothing)."""
    vehicle = stack.app.state.gateway.registry.get("d1").flown_here()

    async def list_held() -> bool:
        return vehicle.params_fetched_age_s is not None

    await eventually(list_held, "d1's parameter list fetched at connect, with no read asked for")
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        unknown = await http.get("/api/v1/vehicles/d1/params/NO_SUCH_PARAM")
    assert unknown.status_code == 404, unknown.text
    assert "unknown parameter 'NO_SUCH_PARAM' on drone 'd1': not among the" in unknown.text, unknown.text


async def test_an_operator_flies_the_stored_mission_and_sets_a_parameter(stack: Stack) -> None:
    home = await stack.true_state("d1")
    waypoints = [
        {"lat_deg": p[0], "lon_deg": p[1], "alt_m": 12}
        for p in (point_from(home, 200.0, 0.0), point_from(home, 200.0, 60.0))
    ]
    async with stack.client("auto", name="planner") as c:
        assert not (
            await stack.call(c, "upload_mission", {"drone_id": "d1", "waypoints": waypoints})
        ).is_error
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        took_off = await _post(http, "/vehicles/d1/takeoff", json={"alt_rel_m": 12})
        assert (await _operation_ends(stack, took_off["operation_id"]))["status"] == "succeeded"

        started = await _post(http, "/vehicles/d1/mission/start")
        assert started["action"] == "start_mission" and started["operation_id"], started
        await wait_until_true(stack, "d1", lambda s: s["mode"] == "AUTO", "flying the mission")
        paused = await _post(http, "/vehicles/d1/mission/pause")
        assert paused["outcome"] == "sent", paused
        await wait_until_true(stack, "d1", lambda s: s["mode"] == "GUIDED", "holding (paused)")
        resumed = await _post(http, "/vehicles/d1/mission/resume")
        assert resumed["action"] == "resume_mission" and resumed["operation_id"], resumed
        await wait_until_true(stack, "d1", lambda s: s["mode"] == "AUTO", "on its mission again")

        read = await _post(http, "/vehicles/d1/params/wpnav_speed", method="GET")
        assert read["name"] == "WPNAV_SPEED" and read["type"] == "float", read
        written = await _post(http, "/vehicles/d1/params/WPNAV_SPEED", method="PUT", json={"value": 600})
        assert written["value"] == 600 and written["vehicle_id"] == "d1", written
        again = await _post(http, "/vehicles/d1/params/WPNAV_SPEED", method="GET")
        assert again["value"] == 600, again
        unknown = await http.get("/api/v1/vehicles/d1/params/NO_SUCH_PARAM")
        # a name the autopilot does not list is a missing resource, in the autopilot's words
        assert unknown.status_code == 404 and "unknown parameter 'NO_SUCH_PARAM'" in unknown.text, (
            unknown.text
        )
        bad = await http.put("/api/v1/vehicles/d1/params/WPNAV_SPEED", json={"value": "fast"})
        assert bad.status_code == 422, bad.text
        await _post(http, "/vehicles/d1/rtl")

    audit = (await stack.rest("/audit", vehicle_id="d1"))["items"]
    actions = {a["action"] for a in audit if a["source"] == "rest"}
    wanted = {"rest.start_mission", "rest.pause_mission", "rest.resume_mission", "rest.write_param"}
    assert wanted <= actions, actions
    assert "rest.read_param" not in actions  # reads are not audited
    async with stack.client("auto", name="check") as c:
        r = structured(await stack.call(c, "get_parameter", {"drone_id": "d1", "name": "WPNAV_SPEED"}))
        assert r["value"] == 600, r
