"""Faults in flight against simulated drones with real sidecars: a sidecar killed with SIGKILL during a
goto, and the MAVLink link lost during a mission (the autopilot's own GCS failsafe acts).

One gateway + simulator for the module; d1 takes the sidecar kill, d2 the link loss.
"""

from __future__ import annotations

import asyncio
import os
import signal
from typing import Any

import httpx
import pytest
from mcp.types import CallToolResult

from tests.helpers.timing import scaled
from tests.mcp.conftest import (
    WAIT_S,
    Stack,
    distance_m,
    error_text,
    point_from,
    structured,
    wait_until_true,
)

pytestmark = pytest.mark.asyncio(loop_scope="module")
DRONES = 2


async def ok(c: Any, tool: str, args: dict[str, Any]) -> dict[str, Any]:
    return structured(await c.call_tool(tool, args))


async def vehicle(stack: Stack, drone_id: str) -> dict[str, Any]:
    """The vehicle's status as the gateway sees it (state, sidecar pid / restarts, last error)."""
    return stack.app.state.gateway.registry.get(drone_id).status()


async def wait_state(stack: Stack, drone_id: str, wanted: str) -> dict[str, Any]:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + WAIT_S
    while (body := await vehicle(stack, drone_id))["state"] != wanted:
        assert loop.time() < deadline, f"{drone_id} stayed {body['state']}, never {wanted}: {body}"
        await asyncio.sleep(0.1)
    return body


def text_of(r: CallToolResult) -> str:
    return " ".join(getattr(part, "text", "") for part in r.content)


async def test_sidecar_killed_during_goto_restarts_and_drone_is_commandable(stack: Stack) -> None:
    d = {"drone_id": "d1"}
    home = await stack.true_state("d1")
    far = point_from(home, 70, 0)
    async with stack.client("auto", name="sidecar-kill") as c:
        assert (await ok(c, "takeoff", {**d, "alt_m": 10}))["status"] == "succeeded"
        r = await ok(
            c, "go_to_location", {**d, "lat_deg": far[0], "lon_deg": far[1], "alt_m": 10,
                                  "wait": False},
        )  # fmt: skip
        assert r["status"] == "running"
        await wait_until_true(
            stack, "d1", lambda s: distance_m(s, home["lat"], home["lon"]) > 15, "on its way"
        )
        before = await vehicle(stack, "d1")
        pid = before["sidecar"]["pid"]
        progress: list[str] = []

        async def on_progress(done: float, total: float | None, message: str | None) -> None:
            progress.append(message or "")

        # The agent keeps waiting on the goto (monitor_flight, with progress) while the sidecar dies.
        monitor = asyncio.create_task(c.call_tool("monitor_flight", d, progress_callback=on_progress))
        await asyncio.sleep(0.5)
        os.kill(pid, signal.SIGKILL)

        # While the sidecar is down: the state says so and commands name it.
        down = await wait_state(stack, "d1", "connecting")
        refused = await c.call_tool("hold_position", d)
        assert "connecting" in error_text(refused), text_of(refused)
        mon = await monitor
        interrupted = [m for m in progress if m.startswith("connection interrupted")]
        assert interrupted, progress
        assert "keeps flying its last command" in interrupted[0], interrupted
        assert "code -9" in interrupted[0] or "connecting" in interrupted[0], (interrupted, down)
        # the goto itself is followed again once the vehicle is back, to its real outcome
        assert not mon.is_error, text_of(mon)

        # The drone flies its last command on its own meanwhile.
        s = await wait_until_true(stack, "d1", lambda s: distance_m(s, far[0], far[1]) < 5, "arrived alone")
        assert s["armed"] and s["mode"] == "GUIDED"

        # A new sidecar: ready again, and the drone obeys new commands.
        after = await wait_state(stack, "d1", "ready")
        assert after["sidecar"]["pid"] not in (None, pid) and after["sidecar"]["restarts"] >= 1, after
        back = point_from(home, 20, 20)
        r = await ok(
            c,
            "go_to_location",
            {**d, "lat_deg": back[0], "lon_deg": back[1], "alt_m": 12},
        )
        assert r["status"] == "succeeded", r
        s = await stack.true_state("d1")
        assert distance_m(s, back[0], back[1]) < 4 and abs(s["rel_alt_m"] - 12) < 2, s
        assert (await ok(c, "land", d))["status"] == "succeeded"
    await wait_until_true(stack, "d1", lambda s: not s["armed"], "landed and disarmed")


async def test_link_loss_during_mission_failsafe_then_recovery(stack: Stack) -> None:
    index = stack.index("d2")
    d = {"drone_id": "d2"}
    # The operator configured the autopilot's GCS failsafe (RTL) for the gateway's system id.
    await stack.sim.control.set_param(index, "MAV_GCS_SYSID", stack.settings.gcs_sysid)
    # The simulator runs 8x faster than real time while the GCS heartbeat stays 1 Hz (8 s of simulated
    # time apart): a timeout above that keeps the failsafe quiet until the link really goes.
    await stack.sim.control.set_param(index, "FS_GCS_TIMEOUT", 16)
    await stack.sim.control.set_param(index, "FS_GCS_ENABLE", 1)
    home = await stack.true_state("d2")
    a, b = point_from(home, 40, 0), point_from(home, 40, 40)
    wps = [
        {"lat_deg": home["lat"], "lon_deg": home["lon"], "alt_m": 10, "kind": "takeoff"},
        {"lat_deg": a[0], "lon_deg": a[1], "alt_m": 10},
        {"lat_deg": b[0], "lon_deg": b[1], "alt_m": 10},
        {"lat_deg": home["lat"], "lon_deg": home["lon"], "alt_m": 10},
    ]
    async with stack.client("auto", name="link-loss-mission") as c:
        r = await ok(c, "initiate_mission", {**d, "waypoints": wps, "wait": False})
        assert r["status"] == "running"
        await wait_until_true(
            stack, "d2", lambda s: s["mission_current"] >= 2 and s["mode"] == "AUTO", "on leg 2"
        )
        await stack.sim.control.link_down(index)
        try:
            await wait_state(stack, "d2", "link_lost")
            refused = await c.call_tool("go_to_location", {**d, "lat_deg": a[0], "lon_deg": a[1],
                                                           "alt_m": 10})  # fmt: skip
            assert "link_lost" in error_text(refused)
            # reads answer from the cache, flagged stale once older than link_lost_after_s (the state
            # can turn link_lost a moment before the last position sample is that old)
            deadline = asyncio.get_running_loop().time() + WAIT_S
            while not (pos := await ok(c, "get_position", d))["stale"]:
                assert asyncio.get_running_loop().time() < deadline, pos
                await asyncio.sleep(0.1)
            # the autopilot's own failsafe acts: GCS lost -> RTL
            s = await wait_until_true(stack, "d2", lambda s: s["failsafe_gcs"] and s["mode"] == "RTL", "RTL")
            assert s["armed"]
        finally:
            await stack.sim.control.link_up(index)
        await wait_state(stack, "d2", "ready")
        # the mission's progress as the autopilot has it (MISSION_CURRENT comes at 1 Hz once the rates are
        # asked for again after the link's return)
        deadline = asyncio.get_running_loop().time() + 15
        while True:
            truth = await stack.true_state("d2")
            prog = await ok(c, "print_mission_progress", d)
            if prog["total"] == len(wps) and prog["current"] == truth["mission_current"]:
                break
            assert asyncio.get_running_loop().time() < deadline, (prog, truth)
            await asyncio.sleep(0.2)
        mode = await ok(c, "get_flight_mode", d)
        assert mode["value"] == "RTL", mode
        # the mission operation tells the truth: the autopilot took over, the mission is not flown
        ops = stack.app.state.gateway.operations
        loop = asyncio.get_running_loop()
        deadline = loop.time() + WAIT_S
        while (op := ops.latest("d2")).status == "running":
            assert loop.time() < deadline, op.message
            await asyncio.sleep(0.2)
        assert op.status == "interrupted" and "switched from AUTO to RTL" in op.message, (
            op.status,
            op.message,
        )
        mon = await ok(c, "monitor_flight", d)
        assert mon["status"] == "interrupted" and "RTL" in mon["message"], mon
        # a takeover like a pilot's (docs/safety.md): agents are refused until an operator releases it
        assert "taken_over" in error_text(await c.call_tool("hold_position", d))
        assert stack.app.state.gateway.commander.locks.takeover_for("d2") is not None
    await wait_until_true(stack, "d2", lambda s: not s["armed"], "home after the failsafe RTL")


async def test_operator_kills_a_flying_drone_over_rest(stack: Stack) -> None:
    """Kill in the air is an operator decision: REST does it at once, and the audit records who."""
    async with stack.client("auto", name="before-kill") as c:
        assert (await ok(c, "takeoff", {"drone_id": "d1", "alt_m": 6}))["status"] == "succeeded"
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        r = await http.post("/api/v1/vehicles/d1/kill")
        assert r.status_code == 200 and r.json()["outcome"] == "sent", r.text
        await wait_until_true(stack, "d1", lambda s: not s["armed"], "motors stopped")
        audit = (await http.get("/api/v1/audit", params={"vehicle_id": "d1", "limit": 5})).json()["items"]
        assert any(a["action"] == "rest.kill_vehicle" and a["outcome"] == "ok" for a in audit), audit
