"""MCP over Streamable HTTP against a real gateway and simulated drones: long operations and their waits.

Each test flies its own drone of the shared stack (d1..d4), and checks that the audit table holds every
call it made on that drone.
"""

from __future__ import annotations

import asyncio
import time

import pytest
from mcp.shared.exceptions import MCPError

from tests.helpers.timing import eventually, settled
from tests.mcp.conftest import (
    Stack,
    distance_m,
    error_text,
    point_from,
    structured,
    wait_audited,
    wait_until_true,
)

pytestmark = pytest.mark.asyncio(loop_scope="module")


async def _paper_prompt(stack: Stack) -> None:
    """takeoff 10 m, goto, land back to back with defaults: each call waits, the drone lands at the target."""
    home = await stack.true_state("d1")
    lat, lon = point_from(home, 60.0, 30.0)
    progress: list[tuple[float, str | None]] = []

    async def on_progress(p: float, total: float | None, message: str | None) -> None:
        progress.append((p, message))

    async with stack.client("legacy", name="paper-prompt") as c:
        r = structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 10}))
        assert r["status"] == "succeeded" and r["alt_m"] > 9.0, r
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
        started = time.perf_counter()
        r = structured(await stack.call(c, "go_to_location", goto, progress_callback=on_progress))
        stack.figures["goto_67m_tool_latency_s"] = round(time.perf_counter() - started, 2)
        assert r["status"] == "succeeded", r
        assert distance_m(await stack.true_state("d1"), lat, lon) <= stack.settings.arrival_tolerance_m + 0.5
        # progress notifications arrived during the goto, and only ever grew
        assert len(progress) >= 2 and any("m to go" in (m or "") for _, m in progress), progress
        assert [p for p, _ in progress] == sorted(p for p, _ in progress)
        r = structured(await stack.call(c, "land", {"drone_id": "d1"}))
        assert r["status"] == "succeeded", r
    state = await stack.true_state("d1")
    assert not state["armed"] and distance_m(state, lat, lon) < 5.0, state


async def _premature_goto(stack: Stack) -> None:
    """With wait=false the goto sent during the takeoff is refused (nothing sent); a later goto flies."""
    home = await stack.true_state("d2")
    lat, lon = point_from(home, -40.0, 20.0)
    goto = {"drone_id": "d2", "lat_deg": lat, "lon_deg": lon, "alt_m": 12}
    async with stack.client("auto", name="premature-goto") as c:
        r = structured(await stack.call(c, "takeoff", {"drone_id": "d2", "alt_m": 12, "wait": False}))
        assert r["status"] == "running" and r["kind"] == "takeoff"
        text = error_text(await stack.call(c, "go_to_location", goto))
        assert "takeoff_in_progress" in text and "monitor_flight" in text, text
        # the refused goto moved nothing: the drone is climbing above home
        assert distance_m(await stack.true_state("d2"), home["lat"], home["lon"]) < 2.0
        while (r := structured(await stack.call(c, "monitor_flight", {"drone_id": "d2"})))[
            "status"
        ] == "running":
            pass
        assert r["status"] == "succeeded" and r["kind"] == "takeoff", r

        async def takeoff_audited_ok() -> bool:  # the wait:false call's row ends with the real outcome
            rows = (await stack.rest("/audit", vehicle_id="d2", limit=100))["items"]
            return next(a for a in rows if a["action"] == "takeoff")["outcome"] == "ok"

        await eventually(takeoff_audited_ok, "the audit row of the wait:false takeoff says ok")
        r = structured(await stack.call(c, "go_to_location", goto))
        assert r["status"] == "succeeded", r
        assert distance_m(await stack.true_state("d2"), lat, lon) <= stack.settings.arrival_tolerance_m + 0.5
        r = structured(await stack.call(c, "return_to_launch", {"drone_id": "d2"}))
        assert r["status"] == "succeeded", r
    state = await stack.true_state("d2")
    assert not state["armed"] and distance_m(state, home["lat"], home["lon"]) < 5.0, state


async def test_two_sessions_at_once_paper_prompt_and_premature_goto(stack: Stack) -> None:
    """A 2025-era session flies d1 while a 2026-07-28 client flies d2, at the same time."""
    await asyncio.gather(_paper_prompt(stack), _premature_goto(stack))
    await wait_audited(stack, "d1")
    await wait_audited(stack, "d2")
    sessions = (await stack.rest("/sessions"))["items"]
    legacy = [s for s in sessions if s["client_name"] == "paper-prompt"]
    modern = [s for s in sessions if s["client_name"] == "premature-goto"]
    assert legacy and legacy[0]["kind"] == "mcp-2025" and legacy[0]["client_version"] == "1.0"
    assert modern and modern[0]["kind"] == "mcp-2026" and modern[0]["key"] == "anonymous|premature-goto/1.0"
    assert modern[0]["last_seen"] > modern[0]["first_seen"]
    audit = (await stack.rest("/audit", session_key="anonymous|premature-goto/1.0", limit=100))["items"]
    outcomes = {(a["action"], a["outcome"]) for a in audit}
    # the wait:false takeoff was "running" when its call returned; its row now says how it ended
    assert ("go_to_location", "refused") in outcomes and ("takeoff", "ok") in outcomes, outcomes
    assert all(a["duration_ms"] is not None and a["principal"] == "anonymous" for a in audit)


async def test_goto_beyond_wait_cap_returns_running_and_monitor_flight_lands(stack: Stack) -> None:
    stack.settings.mcp_wait_cap_s = 1.0
    try:
        home = await stack.true_state("d3")
        lat, lon = point_from(home, 400.0, 0.0)  # several wait caps long even at the sim's speed-up
        async with stack.client("auto", name="cap") as c:
            r = structured(await stack.call(c, "takeoff", {"drone_id": "d3", "alt_m": 10}))
            while r["status"] == "running":
                r = structured(await stack.call(c, "monitor_flight", {"drone_id": "d3"}))
            assert r["status"] == "succeeded", r
            goto = {"drone_id": "d3", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
            r = structured(await stack.call(c, "go_to_location", goto))
            assert r["status"] == "running" and r["kind"] == "goto", r
            assert r["eta_s"] is not None and r["eta_s"] > 0 and 0 <= r["progress"] < 1
            op_id = r["operation_id"]
            arrival = structured(await stack.call(c, "check_arrival", {"drone_id": "d3"}))
            assert (
                arrival["arrived"] is False
                and arrival["operation_id"] == op_id
                and arrival["distance_m"] > 10
            )
            kinds = []
            while r["status"] == "running" or r["kind"] == "goto":
                r = structured(
                    await stack.call(c, "monitor_flight", {"drone_id": "d3", "land_on_arrival": True})
                )
                kinds.append((r["kind"], r["status"]))
            assert r["kind"] == "land" and r["status"] == "succeeded", kinds
            assert ("goto", "running") in kinds or ("land", "running") in kinds, kinds
            arrival = structured(await stack.call(c, "check_arrival", {"drone_id": "d3"}))
            assert arrival["arrived"] is False and arrival["operation_id"] != op_id  # latest is the landing
    finally:
        stack.settings.mcp_wait_cap_s = 45.0
    state = await stack.true_state("d3")
    assert not state["armed"] and distance_m(state, lat, lon) < 5.0, state
    ops = (await stack.rest("/operations", vehicle_id="d3"))["items"]
    by_id = {o["id"]: o for o in ops}
    assert by_id[op_id]["status"] == "succeeded" and by_id[op_id]["kind"] == "goto"
    assert any(o["kind"] == "land" and o["status"] == "succeeded" for o in ops)
    await wait_audited(stack, "d3")


def _still(a: dict, b: dict) -> bool:
    """Two true states of a drone less than 1 m apart (horizontally and in height)."""
    return distance_m(b, a["lat"], a["lon"]) < 1.0 and abs(b["rel_alt_m"] - a["rel_alt_m"]) < 1.0


@pytest.mark.parametrize("mode", ["legacy", "auto"])
async def test_cancelled_wait_leaves_flight_going_and_hold_stops_it(stack: Stack, mode: str) -> None:
    """The client gives up waiting (read timeout: the request is cancelled / its stream closed): the wait
    ends, the drone keeps flying its goto; hold_position then stops it where it is. Both eras, on d4."""
    await wait_until_true(stack, "d4", lambda s: not s["armed"], "d4 on the ground")
    home = await stack.true_state("d4")
    lat, lon = point_from(home, 0.0, 250.0)
    async with stack.client(mode, name=f"cancel-{mode}") as c:
        structured(await stack.call(c, "takeoff", {"drone_id": "d4", "alt_m": 10}))
        goto = {"drone_id": "d4", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
        with pytest.raises(MCPError):
            await stack.call(c, "go_to_location", goto, read_timeout_seconds=1.0)
        before = distance_m(await stack.true_state("d4"), lat, lon)

        async def closer() -> bool:  # the drone keeps flying its goto
            return distance_m(await stack.true_state("d4"), lat, lon) < before - 3.0

        await eventually(closer, "d4 keeps flying towards its goto target after the wait was cancelled")
        running = (await stack.rest("/operations", vehicle_id="d4", status="running"))["items"]
        assert [o["kind"] for o in running] == ["goto"]
        r = structured(await stack.call(c, "hold_position", {"drone_id": "d4"}))
        assert r["superseded_operation"] == running[0]["id"], r
        s2 = await settled(lambda: stack.true_state("d4"), _still, "d4 brakes and holds")
        assert distance_m(s2, lat, lon) > 50.0  # stopped where it was, far from the target
        arrival = structured(await stack.call(c, "check_arrival", {"drone_id": "d4"}))
        assert arrival["status"] == "superseded" and arrival["arrived"] is False
        structured(await stack.call(c, "land", {"drone_id": "d4"}))
    await wait_until_true(stack, "d4", lambda s: not s["armed"], "disarmed after landing")
    await wait_audited(stack, "d4")
    audit = (await stack.rest("/audit", vehicle_id="d4", limit=100))["items"]
    # the goto's row was written when the goto was sent; the cancelled wait changed nothing on the
    # drone, so the row ends as the goto did: stopped by the hold
    cancelled = next(a for a in audit if a["action"] == "go_to_location")  # newest first
    assert cancelled["operation_id"] == running[0]["id"], cancelled
    assert cancelled["outcome"] == "superseded" and "hold_position" in cancelled["error"], cancelled
