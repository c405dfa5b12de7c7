"""One command path, whichever door: an operator's takeoff over REST is a tracked operation the agent's
MCP tools respect. The source paper's crash (a goto sent mid-climb) stays impossible when the climb was
started by an operator. Real simulator, real mavsdk_server, real HTTP for both REST and MCP."""

from __future__ import annotations

from collections.abc import AsyncIterator

import httpx
import pytest
import pytest_asyncio

from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack, error_text, gateway_stack, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

CLIMB_TO_M = 80.0  # high and slow (speed-up 2): the agent's call surely lands inside the climb


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def slow_stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    async with gateway_stack(tmp_path_factory.mktemp("one-path"), count=1, speedup=2.0) as stack:
        yield stack


async def test_operator_takeoff_over_rest_then_agent_goto_mid_climb_is_refused(slow_stack: Stack) -> None:
    stack = slow_stack
    home = await stack.true_state("d1")
    lat, lon = point_from(home, 50.0, 0.0)
    goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 20, "wait": False}
    async with (
        stack.client("auto", name="agent") as agent,
        httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http,
    ):
        r = await http.post("/api/v1/vehicles/d1/takeoff", json={"alt_rel_m": CLIMB_TO_M})
        assert r.status_code == 200, r.text
        sent = r.json()
        assert sent["outcome"] == "sent" and sent["operation_id"], sent
        climbing = await wait_until_true(stack, "d1", lambda s: s["rel_alt_m"] > 2.0, "climbing")
        assert climbing["rel_alt_m"] < CLIMB_TO_M - 10.0, "the climb ended before the agent's call"

        refused = await stack.call(agent, "go_to_location", goto)
        text = error_text(refused)
        assert text.startswith("Refused: takeoff_in_progress:") and "monitor_flight" in text, text

        # nothing was sent: the operator's takeoff is still the drone's operation, and it keeps climbing
        ops = (await http.get("/api/v1/operations", params={"vehicle_id": "d1", "limit": 1})).json()["items"]
        latest = (ops[0]["id"], ops[0]["kind"], ops[0]["status"])
        assert latest == (sent["operation_id"], "takeoff", "running"), ops
        state = await stack.true_state("d1")
        assert abs(state["lat"] - home["lat"]) < 2e-5, "the drone moved sideways: a goto got through"
        telemetry = structured(await stack.call(agent, "get_telemetry", {"drone_id": "d1"}))
        assert telemetry["operation"]["operation_id"] == sent["operation_id"], telemetry["operation"]

        # the operator keeps the last word: its hold ends the takeoff at once
        held = await http.post("/api/v1/vehicles/d1/hold")
        assert held.status_code == 200 and held.json()["superseded_operation"] == sent["operation_id"]
        audit = (await http.get("/api/v1/audit", params={"vehicle_id": "d1"})).json()["items"]
    rows = {(a["source"], a["action"], a["outcome"]) for a in audit}
    assert {("rest", "rest.takeoff_vehicle", "ok"), ("mcp", "go_to_location", "refused")} <= rows, rows
