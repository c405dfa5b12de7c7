"""One command path, whichever door: an operator's takeoff over REST is a tracked operation the agent's
MCP tools respect. The source paper's crash (a goto sent mid-climb) stays impossible when the climb was
started by an operator; and the operator's fleet stop ends a fleet operation an agent started. Real
simulator, real mavsdk_server, real HTTP for both REST and MCP."""

from __future__ import annotations

from collections.abc import AsyncIterator
from typing import Any

import httpx
import pytest
import pytest_asyncio

from tests.helpers.timing import eventually, scaled
from tests.mcp.conftest import Stack, error_text, gateway_stack, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

CLIMB_TO_M = 80.0  # high and slow (speed-up 2): the agent's call surely lands inside the climb


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def slow_stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    async with gateway_stack(tmp_path_factory.mktemp("one-path"), count=3, speedup=2.0) as stack:
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

        # the operator's takeoff row names its operation and ends as it did: superseded by the hold
        async def audited() -> set[tuple[str, str, str]] | None:
            audit = (await http.get("/api/v1/audit", params={"vehicle_id": "d1"})).json()["items"]
            rows = {(a["source"], a["action"], a["outcome"]) for a in audit}
            takeoff = ("rest", "rest.takeoff_vehicle", "superseded")
            return rows if {takeoff, ("mcp", "go_to_location", "refused")} <= rows else None

        await eventually(audited, "the takeoff's row superseded and the agent's goto refused")


async def test_an_operator_fleet_stop_over_rest_supersedes_an_agents_fleet_takeoff_and_lands_its_drones(
    slow_stack: Stack,
) -> None:
    stack = slow_stack
    fleet = ["d2", "d3"]
    async with (
        stack.client("auto", name="agent") as agent,
        httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http,
    ):
        started = structured(
            await stack.call(agent, "fleet_takeoff", {"drone_ids": fleet, "alt_m": CLIMB_TO_M, "wait": False})
        )
        assert started["status"] == "running" and started["kind"] == "fleet_takeoff", started
        for d in fleet:
            await wait_until_true(stack, d, lambda s: s["rel_alt_m"] > 2.0, "climbing")
        takeoffs = {}
        for d in fleet:
            ops = (await http.get("/api/v1/operations", params={"vehicle_id": d, "limit": 1})).json()["items"]
            assert (ops[0]["kind"], ops[0]["status"]) == ("takeoff", "running"), ops
            takeoffs[d] = ops[0]["id"]

        r = await http.post("/api/v1/fleet/stop", json={"action": "land", "lock_reason": "one-path stop"})
        assert r.status_code == 200, r.text
        stop = r.json()
        assert stop["superseded_fleet_operations"] == [started["operation_id"]], stop
        results = {x["vehicle_id"]: x for x in stop["results"]}
        for d in fleet:
            got = results[d]
            assert (got["action"], got["outcome"]) == ("land", "sent"), got
            assert got["superseded_operation"] == takeoffs[d] and got["operation_id"], got

        # the agent sees its fleet operation ended by the operator, not still climbing
        after = structured(
            await stack.call(agent, "monitor_fleet", {"operation_id": started["operation_id"]})
        )
        assert after["status"] == "superseded" and "operator stop (land)" in after["message"], after

        for d in fleet:  # both drones come down and disarm instead of finishing the climb
            landed = await wait_until_true(stack, d, lambda s: not s["armed"], "landed and disarmed")
            assert landed["rel_alt_m"] < 1.0, landed

            async def landing_ended(d: str = d) -> list[dict[str, Any]] | None:
                r = await http.get("/api/v1/operations", params={"vehicle_id": d, "limit": 2})
                items = list(r.json()["items"])
                return items if items[0]["status"] != "running" else None

            ops = await eventually(landing_ended, f"{d}'s landing ended")
            assert [(o["kind"], o["status"]) for o in ops] == [
                ("land", "succeeded"),
                ("takeoff", "superseded"),
            ]
            assert ops[1]["id"] == takeoffs[d], ops
        assert (await http.delete("/api/v1/fleet/lock")).json()["was_locked"] is True
