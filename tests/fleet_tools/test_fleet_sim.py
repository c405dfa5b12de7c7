"""The fleet tools over MCP (Streamable HTTP) against a real gateway and four simulated drones on loopback:
refusals naming each drone with its rule and numbers (nothing sent), concurrent dispatch, a formation
flown to its slots, and recovery actions that skip the drones that cannot take them."""

from __future__ import annotations

import asyncio
import json
import time
from typing import Any

import pytest

from gateway.fleet import geo
from gateway.fleet.policy.operator_locks import LockBook
from tests.helpers.timing import settled
from tests.mcp.conftest import WAIT_S, Stack, distance_m, error_text, structured

pytestmark = pytest.mark.asyncio(loop_scope="module")

DRONES = 4
IDS = [f"d{i + 1}" for i in range(DRONES)]


async def _states(stack: Stack) -> dict[str, dict[str, Any]]:
    return {d: await stack.true_state(d) for d in IDS}


async def _until(what: str, check: Any) -> Any:
    deadline = time.monotonic() + WAIT_S
    while not (result := await check()):
        if time.monotonic() > deadline:
            raise AssertionError(f"{what} not reached")
        await asyncio.sleep(0.2)
    return result


async def _battery_seen(stack: Stack, c: Any, drone_id: str, low: bool) -> bool:
    rows = structured(await c.call_tool("list_drones", {}))["drones"]
    pct = next(r["battery_pct"] for r in rows if r["drone_id"] == drone_id)
    return pct is not None and ((pct < 30) if low else (pct > 90))


async def _finish(c: Any, r: dict[str, Any]) -> dict[str, Any]:
    while r["status"] == "running":
        r = structured(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
    return r


async def test_fleet_flight_partial_failures_and_concurrent_dispatch(
    fleet_stack: tuple[Stack, LockBook],
) -> None:
    stack, locks = fleet_stack
    homes = await _states(stack)
    async with stack.client("auto", name="fleet-pilot") as c:
        # --- refused as a whole, every drone that cannot take part named with its rule and numbers
        locks.lock("d2", "propeller check", "alice")
        listed = (await c.call_tool("list_drones", {})).content[0].text
        assert "LOCKED" in listed and "propeller check" in listed, listed  # the lock is said in text too
        await stack.sim.control.set_battery(
            3, 28.0
        )  # below the 30 % takeoff minimum, above the sim's low-voltage failsafe
        await _until("low battery seen", lambda: _battery_seen(stack, c, "d4", low=True))
        text = error_text(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 8}))
        assert "nothing was sent" in text and "2 of 4" in text, text
        assert "d2: operator_lock: drone d2 is locked by alice: propeller check" in text, text
        assert "d4: min_battery_takeoff: battery 28 % is below the 30 % needed to take off" in text, text
        text = error_text(await c.call_tool("fleet_takeoff", {"drone_ids": ["d1", "ghost"], "alt_m": 8}))
        assert "ghost" in text and "d1, d2, d3, d4" in text, text
        await asyncio.sleep(1.0)
        assert all(not s["armed"] for s in (await _states(stack)).values()), "a refused takeoff armed a drone"

        # --- all four at once: every command out before the first is accepted
        locks.unlock("d2")
        await stack.sim.control.set_battery(3, 100.0)
        await _until("battery restored", lambda: _battery_seen(stack, c, "d4", low=False))
        first = await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 8})
        told = first.content[0].text  # the text says what each drone was told: staggered altitudes
        altitudes = {d["drone_id"]: d["target_alt_m"] for d in structured(first)["drones"]}
        assert sorted(altitudes.values()) == [8.0, 15.0, 22.0, 29.0], altitudes  # default stagger 7 m
        assert all(f"(to {altitudes[d]:g} m)" in told for d in IDS), told
        r = await _finish(c, structured(first))
        assert r["status"] == "succeeded", (r["message"], r["drones"])
        sent = [d["sent_after_s"] for d in r["drones"]]
        accepted = [d["accepted_after_s"] for d in r["drones"]]
        assert max(sent) <= min(accepted), (sent, accepted)
        stack.figures["takeoff_dispatch_4_drones_s"] = r["dispatch_s"][0]
        stack.figures["takeoff_accepted_after_s"] = accepted
        now = await _states(stack)
        for k, d in enumerate(IDS):  # staggered: 8, 15, 22, 29 m (stagger = 5 m separation + 2 m)
            assert abs(now[d]["rel_alt_m"] - (8 + 7 * k)) < 1.0, (d, now[d])

        # --- a line 40 m north of the fleet, at one altitude
        lat, lon = geo.offset_position(homes["d2"]["lat"], homes["d2"]["lon"], 40.0, 2.5)
        args = {"drone_ids": IDS, "formation": "line", "center_lat_deg": lat, "center_lon_deg": lon,
                "alt_m": 15, "spacing_m": 8, "heading_deg": 0}  # fmt: skip
        r = await _finish(c, structured(await c.call_tool("formation_goto", args)))
        assert r["status"] == "succeeded", (r["message"], r["drones"])
        assert r["plan"]["formation"] == "line" and r["plan"]["min_clearance_m"] >= 5.0
        now = await _states(stack)
        for slot in r["drones"]:
            state = now[slot["drone_id"]]
            assert distance_m(state, slot["target_lat_deg"], slot["target_lon_deg"]) <= 2.5, (slot, state)
            assert abs(state["rel_alt_m"] - 15) <= 1.5, (slot, state)

        # --- land: a locked drone is skipped and named, the others land
        locks.lock("d3", "operator flying it", "bob")
        r = await _finish(c, structured(await c.call_tool("fleet_land", {"drone_ids": IDS})))
        assert r["status"] == "succeeded" and sorted(d["drone_id"] for d in r["drones"]) == ["d1", "d2", "d4"]
        assert [(u["drone_id"], u["code"]) for u in r["not_sent"]] == [("d3", "operator_lock")], r
        now = await _states(stack)
        assert [d for d in IDS if now[d]["armed"]] == ["d3"], now
        # a fleet hold of the landed drones and the locked one has nothing it may do: refused, with reasons
        text = error_text(await c.call_tool("fleet_hold", {"drone_ids": ["d1", "d3"]}))
        assert "d1:" in text and "on the ground" in text and "locked by bob" in text, text

        # --- the operator unlocks; the last drone returns home
        locks.unlock("d3")
        r = await _finish(c, structured(await c.call_tool("fleet_return_to_launch", {"drone_ids": ["d3"]})))
        assert r["status"] == "succeeded", (r["message"], r["drones"])
    state = await stack.true_state("d3")
    assert not state["armed"] and distance_m(state, homes["d3"]["lat"], homes["d3"]["lon"]) < 3.0, state
    ops = (await stack.rest("/operations", vehicle_id="d1"))["items"]
    assert {o["kind"] for o in ops} >= {"takeoff", "formation", "land"}, ops


async def test_formation_stops_and_holds_when_one_drone_is_taken_over(
    fleet_stack: tuple[Stack, LockBook],
) -> None:
    """A drone of a running formation gets another command: the formation is aborted, the drones still
    flying their legs are held where they are (short of their slots), and no later phase starts."""
    stack, _locks = fleet_stack
    async with stack.client("auto", name="fleet-abort") as c:
        r = await _finish(c, structured(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 10})))
        assert r["status"] == "succeeded", (r["message"], r["drones"])
        start = await _states(stack)
        lat, lon = geo.offset_position(start["d1"]["lat"], start["d1"]["lon"], 0.0, 150.0)
        args = {"drone_ids": IDS, "formation": "column", "center_lat_deg": lat, "center_lon_deg": lon,
                "alt_m": 12, "spacing_m": 10, "wait": False}  # fmt: skip
        r = structured(await c.call_tool("formation_goto", args))
        assert r["status"] == "running"
        fleet_id = r["operation_id"]
        await _until(
            "the formation's flying phase",
            lambda: _phase_is(c, fleet_id, 2),
        )
        await asyncio.sleep(1.0)
        structured(await c.call_tool("hold_position", {"drone_id": "d2"}))
        r = await _finish(c, structured(await c.call_tool("monitor_fleet", {"operation_id": fleet_id})))
        assert r["status"] == "aborted", (r["message"], r["drones"])
        drones = {d["drone_id"]: d for d in r["drones"]}
        assert drones["d2"]["status"] == "superseded" and "d2" in r["message"], r["message"]
        held = [d for d in IDS if drones[d]["status"] == "held"]
        assert held, r["drones"]
        s2 = await settled(
            lambda: _states(stack),
            lambda a, b: all(distance_m(b[d], a[d]["lat"], a[d]["lon"]) < 1.0 for d in held),
            "held drones brake and stay put",
        )
        for d in held:
            assert distance_m(s2[d], drones[d]["target_lat_deg"], drones[d]["target_lon_deg"]) > 20.0, (
                d,
                s2[d],
            )
        r = await _finish(c, structured(await c.call_tool("fleet_return_to_launch", {})))
        assert r["status"] == "succeeded", (r["message"], r["drones"])


async def _phase_is(c: Any, operation_id: str, phase: int) -> bool:
    res = await c.read_resource("fleet://formation")
    body = json.loads(res.contents[0].text)
    return body.get("operation_id") == operation_id and body["phase"] >= phase
