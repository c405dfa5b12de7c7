"""A call that returns while its operation still runs (wait:false, or a capped wait) is audited as
"running"; when the operation ends, however it ends, its row says so. MCP over Streamable HTTP against a
real gateway and three simulated drones: d1 and d2 fly as a fleet, d3 alone."""

from __future__ import annotations

from typing import Any

import pytest

from tests.helpers.timing import eventually
from tests.mcp.conftest import Stack, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

DRONES = 3


async def _row(stack: Stack, session_key: str, action: str) -> dict[str, Any]:
    """The newest audit row of ``action`` in the session."""
    rows = (await stack.rest("/audit", session_key=session_key, limit=100))["items"]
    return next(a for a in rows if a["action"] == action)


async def _ended(stack: Stack, session_key: str, action: str, outcome: str) -> dict[str, Any] | None:
    row = await _row(stack, session_key, action)
    return row if row["outcome"] == outcome else None


async def _finish(c: Any, r: dict[str, Any]) -> dict[str, Any]:
    """Keep waiting (monitor_fleet, capped waits) until the fleet operation has ended."""
    while r["status"] == "running":
        r = structured(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
    return r


async def test_a_fleet_takeoff_and_landing_sent_with_wait_false_end_in_the_audit_as_ok(stack: Stack) -> None:
    session = "anonymous|fleet-no-wait/1.0"
    async with stack.client("auto", name="fleet-no-wait") as c:
        up = structured(
            await c.call_tool("fleet_takeoff", {"drone_ids": ["d1", "d2"], "alt_m": 8, "wait": False})
        )
        assert up["status"] == "running", up
        row = await _row(stack, session, "fleet_takeoff")
        assert row["operation_id"] == up["operation_id"], row  # written as running, naming the fleet op
        assert (await _finish(c, up))["status"] == "succeeded"
        await eventually(
            lambda: _ended(stack, session, "fleet_takeoff", "ok"),
            "the wait:false fleet_takeoff's audit row ends ok",
        )
        down = structured(await c.call_tool("fleet_land", {"drone_ids": ["d1", "d2"], "wait": False}))
        assert down["status"] == "running", down
        assert (await _finish(c, down))["status"] == "succeeded"
        row = await eventually(
            lambda: _ended(stack, session, "fleet_land", "ok"),
            "the wait:false fleet_land's audit row ends ok",
        )
        assert row["error"] is None, row


async def test_a_goto_sent_with_wait_false_and_stopped_by_a_hold_ends_in_the_audit_as_superseded(
    stack: Stack,
) -> None:
    session = "anonymous|goto-superseded/1.0"
    home = await stack.true_state("d3")
    lat, lon = point_from(home, 300.0, 0.0)  # far enough to be still flying when the hold comes
    async with stack.client("auto", name="goto-superseded") as c:
        assert (
            structured(await c.call_tool("takeoff", {"drone_id": "d3", "alt_m": 10}))["status"] == "succeeded"
        )
        goto = {"drone_id": "d3", "lat_deg": lat, "lon_deg": lon, "alt_m": 10, "wait": False}
        sent = structured(await c.call_tool("go_to_location", goto))
        assert sent["status"] == "running", sent
        held = structured(await c.call_tool("hold_position", {"drone_id": "d3"}))
        assert held["superseded_operation"] == sent["operation_id"], held
        row = await eventually(
            lambda: _ended(stack, session, "go_to_location", "superseded"),
            "the wait:false goto's audit row ends superseded",
        )
        assert "superseded by hold_position" in row["error"], row
        structured(await c.call_tool("land", {"drone_id": "d3"}))
    await wait_until_true(stack, "d3", lambda s: not s["armed"], "d3 landed and disarmed")
