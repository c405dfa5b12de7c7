"""Arming a drone that is still initialising (issue 17): the wait for it to become able to arm and the
arming itself share one deadline, the MCP wait cap, with progress notices saying what is awaited; when
the time runs out the refusal is one line in the autopilot's own words plus what to do, never a bare
"Failed". MCP over Streamable HTTP against a real gateway and two simulated drones whose EKF position
estimate the simulator holds back (GPS fix and home kept, as on a real ArduCopter still converging)."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from tests.helpers.timing import eventually, scaled
from tests.mcp.conftest import Stack, error_text, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

DRONES = 2
ESTIMATE = "waiting for the position estimate"


async def _initialising(c: Any, drone_id: str) -> bool:
    rows = structured(await c.call_tool("list_drones", {}))["drones"]
    waiting = next(r["initialising"] for r in rows if r["drone_id"] == drone_id)
    return waiting is not None and ESTIMATE in waiting


async def _ready(c: Any, drone_id: str) -> bool:
    rows = structured(await c.call_tool("list_drones", {}))["drones"]
    return next(r["state"] for r in rows if r["drone_id"] == drone_id) == "ready"


async def test_arming_a_drone_that_never_becomes_ready_within_the_cap_is_refused_in_the_autopilots_words(
    stack: Stack,
) -> None:
    notices: list[str] = []

    async def on_progress(progress: float, total: float | None, message: str | None) -> None:
        notices.append(message or "")

    await stack.sim.control.hold_estimate(0)
    stack.settings.mcp_wait_cap_s = scaled(3.0)  # short: the estimate stays held back past it
    try:
        async with stack.client("auto", name="arm-too-early") as c:
            await eventually(
                lambda: _initialising(c, "d1"), "d1 initialising: waiting for the position estimate"
            )
            r = await c.call_tool("arm_drone", {"drone_id": "d1"}, progress_callback=on_progress)
            text = error_text(r)
            assert text.count("\n") == 0, text  # one line
            assert "drone 'd1' cannot arm yet: autopilot says 'Arm: Need Position Estimate'" in text, text
            assert "call again in a few seconds or check fleet_status" in text, text
            assert ESTIMATE in text and "GPS" in text, text  # what the gateway waits for, and the GPS
            assert "(FAILED)" not in text, text
            assert any(n.startswith("d1: " + ESTIMATE) for n in notices), notices  # said while it waited
            assert (await stack.true_state("d1"))["armed"] is False
    finally:
        stack.settings.mcp_wait_cap_s = 45.0
        await stack.sim.control.hold_estimate(0, held=False)


async def test_fleet_takeoff_says_it_waits_for_a_drone_still_initialising_and_then_takes_off(
    stack: Stack,
) -> None:
    notices: list[str] = []
    release: list[asyncio.Task[Any]] = []

    async def on_progress(progress: float, total: float | None, message: str | None) -> None:
        notices.append(message or "")
        if (message or "").startswith("d2: " + ESTIMATE) and not release:
            # heard while the call waits: now let the EKF converge, well within the cap
            release.append(asyncio.create_task(stack.sim.control.hold_estimate(1, held=False)))

    async with stack.client("auto", name="fleet-waits") as c:
        await eventually(lambda: _ready(c, "d1"), "d1 ready again")
        await stack.sim.control.hold_estimate(1)
        await eventually(lambda: _initialising(c, "d2"), "d2 initialising: waiting for the position estimate")
        r = structured(
            await c.call_tool(
                "fleet_takeoff", {"drone_ids": ["d1", "d2"], "alt_m": 6}, progress_callback=on_progress
            )
        )
        while r["status"] == "running":
            r = structured(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
        assert release, notices  # the notice came while fleet_takeoff waited for d2
        await release[0]
        assert r["status"] == "succeeded", (r["message"], r["drones"])
        down = structured(await c.call_tool("fleet_land", {"drone_ids": ["d1", "d2"]}))
        while down["status"] == "running":
            down = structured(await c.call_tool("monitor_fleet", {"operation_id": down["operation_id"]}))
    for drone_id in ("d1", "d2"):
        await wait_until_true(stack, drone_id, lambda s: not s["armed"], f"{drone_id} landed and disarmed")
