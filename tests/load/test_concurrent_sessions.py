"""20 MCP sessions read telemetry and resources as fast as they can while one session flies a formation:
no read fails, the formation succeeds, and every drone ends where its plan put it (none left without its
commands), checked against the simulator's true state."""

from __future__ import annotations

import asyncio
from collections import Counter
from typing import Any

import pytest

from gateway.fleet import geo
from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack, distance_m, structured

pytestmark = pytest.mark.asyncio(loop_scope="module")
DRONES = 4
READERS = 20


async def finish(c: Any, r: dict[str, Any]) -> dict[str, Any]:
    while r["status"] == "running":
        r = structured(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
    return r


async def reader(
    stack: Stack, n: int, flying: asyncio.Event, counts: Counter[str], errors: list[str]
) -> None:
    drone = stack.drone_ids[n % len(stack.drone_ids)]
    async with stack.client("auto", name=f"reader-{n}") as c:
        counts["sessions"] += 1
        while not flying.is_set():
            for tool, args in (
                ("get_telemetry", {"drone_id": drone}),
                ("get_position", {"drone_id": drone}),
                ("fleet_status", {}),
            ):
                r = await c.call_tool(tool, args)
                counts["calls"] += 1
                if r.is_error:
                    errors.append(f"{tool}: {r.content[0].text if r.content else r}")
            for uri in ("fleet://drones", f"drone://{drone}/state"):
                res = await c.read_resource(uri)
                counts["resources"] += 1
                if not res.contents:
                    errors.append(f"{uri}: empty")
            await asyncio.sleep(0)


async def test_twenty_sessions_read_while_a_formation_flies(stack: Stack) -> None:
    ids = stack.drone_ids
    homes = {d: await stack.true_state(d) for d in ids}
    counts: Counter[str] = Counter()
    errors: list[str] = []
    done = asyncio.Event()
    async with stack.client("auto", name="pilot") as pilot:
        r = await finish(
            pilot, structured(await pilot.call_tool("fleet_takeoff", {"drone_ids": ids, "alt_m": 8}))
        )
        assert r["status"] == "succeeded", (r["message"], r["drones"])
        readers = [asyncio.create_task(reader(stack, n, done, counts, errors)) for n in range(READERS)]
        try:
            loop = asyncio.get_running_loop()
            deadline = loop.time() + scaled(60)
            while counts["sessions"] < READERS:  # every session open and reading before the formation
                assert loop.time() < deadline and not any(t.done() for t in readers), counts
                await asyncio.sleep(0.1)
            lat, lon = geo.offset_position(homes[ids[0]]["lat"], homes[ids[0]]["lon"], 60.0, 5.0)
            args = {"drone_ids": ids, "formation": "wedge", "center_lat_deg": lat, "center_lon_deg": lon,
                    "alt_m": 12, "spacing_m": 8, "wait": False}  # fmt: skip
            r = await finish(pilot, structured(await pilot.call_tool("formation_goto", args)))
        finally:
            done.set()
            results = await asyncio.gather(*readers, return_exceptions=True)
        crashed = [repr(x) for x in results if isinstance(x, BaseException)]
        assert not crashed, crashed
        assert not errors, errors[:5]
        if r["status"] != "succeeded":  # what the simulator says happened, beside what the gateway saw
            truths = {d: await stack.true_state(d) for d in ids}
            sim_log = stack.sim.log_tail()
            raise AssertionError(f"{r['message']}: {r['drones']}; true states {truths}\n{sim_log}")
        for slot in r["drones"]:
            state = await stack.true_state(slot["drone_id"])
            assert distance_m(state, slot["target_lat_deg"], slot["target_lon_deg"]) <= 2.5, (slot, state)
            assert abs(state["rel_alt_m"] - 12) <= 1.5, (slot, state)
        r = await finish(pilot, structured(await pilot.call_tool("fleet_land", {"drone_ids": ids})))
        assert r["status"] == "succeeded", (r["message"], r["drones"])
    assert counts["sessions"] == READERS
    assert counts["calls"] >= READERS * 3 and counts["resources"] >= READERS * 2, counts
    print(f"\nload: {READERS} reader sessions, {dict(counts)} during the formation, 0 errors")
