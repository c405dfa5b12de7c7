"""Unit tests of the fleet toolset over an in-process MCP client and fake drones (no sidecars): concurrent
dispatch, phase barriers, all-or-nothing joins with each drone's reason, aborts, recovery actions."""

from __future__ import annotations

import asyncio
import json
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest
from mcp import Client

from gateway.fleet import geo
from gateway.fleet.operations.fleet_steps import rtl_order
from gateway.fleet.vehicles.vehicle import ConnectionState
from gateway.link.telemetry import BatteryValue
from gateway.mcp.server import build_mcp
from gateway.runtime import Gateway
from tests.fakes import HOME, FakeVehicle, fake, fake_gateway, spread, unit_settings

IDS = ["d1", "d2", "d3", "d4", "d5"]


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=20.0), spread(5)) as gw:
        yield gw


def vehicles(gateway: Gateway) -> list[FakeVehicle]:
    return [fake(gateway, d) for d in IDS]


def ok(r: Any) -> dict[str, Any]:
    assert not r.is_error, r.content[0].text
    return r.structured_content


def err(r: Any) -> str:
    assert r.is_error, r.structured_content
    return r.content[0].text


def ahead(north_m: float, east_m: float = 20.0) -> tuple[float, float]:
    return geo.offset_position(HOME[0], HOME[1], north_m, east_m)


async def take_off(c: Client, alt: float = 10.0) -> dict[str, Any]:
    return ok(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": alt}))


def sent_names(v: FakeVehicle) -> list[str]:
    return [name for _t, name, _a in v.log]


async def test_fleet_takeoff_dispatch_is_concurrent(gateway: Gateway) -> None:
    """Every drone's takeoff waits at a barrier that opens only once all five have been sent: a
    dispatcher that sent one drone after another would never get past the first (the barrier times
    out and the drone's command fails)."""
    barrier = asyncio.Barrier(len(IDS))
    for v in vehicles(gateway):
        v.barrier = barrier
    async with Client(build_mcp(gateway)) as c:
        r = await take_off(c)
    assert r["status"] == "succeeded", r
    drones = {d["drone_id"]: d for d in r["drones"]}
    assert set(drones) == set(IDS)
    # staggered altitudes in the order given, at the default stagger (the minimum separation + 2 m)
    assert [fake(gateway, d).sent[-1] for d in IDS] == [("takeoff", 10.0 + 7 * k) for k in range(5)]
    # every command went out before the first one was accepted
    assert max(d["sent_after_s"] for d in drones.values()) <= min(
        d["accepted_after_s"] for d in drones.values()
    )


async def test_formation_refused_before_anything_moves_names_every_drone(gateway: Gateway) -> None:
    async with Client(build_mcp(gateway)) as c:
        await take_off(c)
        for v in vehicles(gateway):
            v.log.clear()
        gateway.locks.lock("d2", "battery swap", "alice")
        fake(gateway, "d4").set(battery=BatteryValue(remaining_pct=12.0, voltage_v=10.1))
        lat, lon = ahead(150.0)
        args = {
            "formation": "wedge",
            "center_lat_deg": lat,
            "center_lon_deg": lon,
            "alt_m": 20,
            "spacing_m": 12,
        }
        # a lock and an unknown id are found before planning
        text = err(await c.call_tool("formation_goto", {"drone_ids": [*IDS, "d9"], **args}))
        assert text.startswith("Refused: formation_goto refused, nothing was sent") and "2 of 6" in text, text
        assert "d2: operator_lock: drone d2 is locked by alice: battery swap" in text, text
        assert "d9: unknown" in text.lower() or "d9:" in text, text
        gateway.locks.unlock("d2")
        # the battery minimum of a new leg, with the numbers, found by the policy over the plan
        text = err(await c.call_tool("formation_goto", {"drone_ids": IDS, **args}))
        assert "1 of 5" in text and "d4: min_battery_leg:" in text, text
        assert "battery 12 % is below the 25 % needed to start a new leg" in text, text
        # a spacing below the minimum separation is the planner's refusal, with the numbers
        text = err(await c.call_tool("formation_goto", {"drone_ids": IDS, **{**args, "spacing_m": 3}}))
        assert "min_separation" in text and "3 m" in text and "5 m" in text, text
        # a formation altitude above the limit: the policy's max_altitude rule with the numbers
        text = err(await c.call_tool("formation_goto", {"drone_ids": ["d1", "d2"], **{**args, "alt_m": 150}}))
        assert "150" in text and "120" in text, text
    assert all(sent_names(v) == [] for v in vehicles(gateway)), [v.log for v in vehicles(gateway)]


async def test_formation_phases_are_barriers(gateway: Gateway) -> None:
    """Drones lined up eastwards fly to a line centred on the first one: the direct paths cross, so some
    drones transit at other altitudes, and no drone starts a phase before every drone finished the
    previous one."""
    slow = fake(gateway, "d3")
    slow.speed = 40.0  # one slow drone: the others must wait for it at each barrier
    async with Client(build_mcp(gateway)) as c:
        ok(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 20, "stagger_m": 0}))
        for v in vehicles(gateway):
            v.log.clear()
        result = await c.call_tool(
            "formation_goto",
            {"drone_ids": IDS, "formation": "line", "center_lat_deg": HOME[0], "center_lon_deg": HOME[1],
             "alt_m": 20, "spacing_m": 10, "heading_deg": 0},
        )  # fmt: skip
    r = ok(result)
    assert r["status"] == "succeeded", r
    layered = [d for d in r["drones"] if d["transit_alt_m"] is not None]
    assert len(layered) == 4, "the test needs crossing paths"
    told = result.content[0].text  # the text names each layered drone's transit altitude, not only the data
    for d in layered:
        assert f"{d['drone_id']} succeeded (transit at {d['transit_alt_m']:g} m, to 20 m)" in told, told
    plan = gateway.fleet_operations.latest("formation_goto").plan
    legs_by_phase = [set(p) for p in plan["phases"]]
    # every drone's gotos are in phase order; a phase's first command comes after the previous
    # phase's last arrival (the arrival is when its operation finished)
    ops = gateway.operations
    for k in (1, 2):
        if not legs_by_phase[k] or not legs_by_phase[k - 1]:
            continue
        finished = [
            ops._ops[oid].finished_at
            for oid in (
                op.id
                for op in ops._ops.values()
                if op.kind == "formation"
                and op.params.get("phase") == k
                and op.vehicle_id in legs_by_phase[k - 1]
            )
        ]
        started = [
            op.created_at
            for op in ops._ops.values()
            if op.kind == "formation" and op.params.get("phase") == k + 1
        ]
        assert finished and started and max(finished) <= min(started), (k, finished, started)


async def test_failure_in_a_phase_holds_the_others_and_stops(gateway: Gateway) -> None:
    async with Client(build_mcp(gateway)) as c:
        await take_off(c)
        fake(gateway, "d3").fail["goto"] = "DENIED"
        for v in vehicles(gateway):
            v.speed = 10.0
            v.log.clear()
        lat, lon = ahead(150.0)
        r = ok(
            await c.call_tool(
                "formation_goto",
                {"drone_ids": IDS, "formation": "line", "center_lat_deg": lat, "center_lon_deg": lon,
                 "alt_m": 20, "spacing_m": 12, "heading_deg": 0},
            )
        )  # fmt: skip
    assert r["status"] == "aborted", r
    drones = {d["drone_id"]: d for d in r["drones"]}
    assert drones["d3"]["status"] == "failed" and "DENIED" in drones["d3"]["message"]
    assert "d3" in r["message"] and "held" in r["message"]
    for d in ("d1", "d2", "d4", "d5"):
        v = fake(gateway, d)
        if "goto" in sent_names(v):  # it was flying its leg: it must have been held, and sent no more
            assert drones[d]["status"] in ("held", "succeeded"), drones[d]
            gotos = [a for _t, n, a in v.log if n == "goto"]
            assert len(gotos) == 1, v.log


async def test_recovery_actions_go_to_every_drone_that_can(gateway: Gateway) -> None:
    async with Client(build_mcp(gateway)) as c:
        await take_off(c)
        gateway.locks.lock("d5", "operator flying it", "bob")
        r = ok(await c.call_tool("fleet_hold", {"drone_ids": [*IDS, "nope"]}))
        assert sorted(r["held"]) == ["d1", "d2", "d3", "d4"]
        assert {u["drone_id"]: u["code"] for u in r["not_sent"]} == {
            "d5": "operator_lock",
            "nope": "unknown_vehicle",
        }
        r = ok(await c.call_tool("fleet_land", {"drone_ids": ["d1", "d2", "d5"]}))
        assert r["status"] == "succeeded" and [d["drone_id"] for d in r["drones"]] == ["d1", "d2"]
        assert r["not_sent"][0]["drone_id"] == "d5" and "locked by bob" in r["not_sent"][0]["message"]
        # nothing left that can land: refused, with the reasons
        text = err(await c.call_tool("fleet_land", {"drone_ids": ["d1", "d5"]}))
        assert "already on the ground" in text and "locked by bob" in text, text
    assert "land" not in sent_names(fake(gateway, "d5"))


async def test_return_to_launch_staggers_and_orders_altitudes(gateway: Gateway) -> None:
    async with Client(build_mcp(gateway)) as c:
        await take_off(c)  # 10..38 m
        lat, lon = ahead(120.0, 20.0)
        ok(
            await c.call_tool(
                "formation_goto",
                {"drone_ids": IDS, "formation": "circle", "center_lat_deg": lat, "center_lon_deg": lon,
                 "alt_m": 25, "spacing_m": 12},
            )
        )  # fmt: skip
        for v in vehicles(gateway):
            v.log.clear()
        text = err(await c.call_tool("fleet_return_to_launch", {"stagger_m": 2}))
        assert "min_separation" in text and "2 m" in text, text
        r = ok(await c.call_tool("fleet_return_to_launch", {}))
    assert r["status"] == "succeeded", r
    alts = {d["drone_id"]: d["rtl_alt_m"] for d in r["drones"]}
    # above every drone's altitude (25 m) so each climbs to its own layer, 7 m apart
    assert sorted(alts.values()) == [26.0 + 7 * k for k in range(5)], alts
    climbed = 0
    for d, alt in alts.items():
        v = fake(gateway, d)
        names = sent_names(v)
        assert names.index("param") < names.index("rtl"), names
        if alt > 25.0 + 1.0:  # more than the tolerance above its altitude: it climbed there first
            assert names.index("goto") < names.index("param"), names
            climbed += 1
        assert ("param", "RTL_ALT", round(alt * 100)) in v.sent
    assert climbed == 4
    # the climbs all finished before any drone was sent home
    climbs = [t for v in vehicles(gateway) for t, n, _a in v.log if n == "goto"]
    homes = [t for v in vehicles(gateway) for t, n, _a in v.log if n == "param"]
    assert max(climbs) < min(homes)


def test_rtl_order_puts_the_drone_passing_over_a_home_above_its_owner() -> None:
    h1 = (HOME[0], HOME[1])
    h2 = geo.offset_position(HOME[0], HOME[1], 0.0, 10.0)
    # d1 is north of d2's home and returns to its own home, passing right over d2's home: d1 above d2
    p1 = (*geo.offset_position(HOME[0], HOME[1], 100.0, 20.0), 20.0)
    p2 = (*geo.offset_position(HOME[0], HOME[1], 100.0, 40.0), 20.0)
    order, notes = rtl_order({"d1": p1, "d2": p2}, {"d1": h1, "d2": h2}, 5.0)
    assert notes == []

    # d1's path from (100 N, 20 E) to (0, 0) passes ~2 m from d2's home (0, 10)? it passes at x=...
    # whichever crosses, the one passing over the other's home is later (higher) in the order
    def passes(a: str, b: str) -> bool:
        from gateway.fleet.operations.fleet_steps import _passes_near

        pos = {"d1": p1, "d2": p2}[a]
        return _passes_near(pos[0], pos[1], {"d1": h1, "d2": h2}[a], {"d1": h1, "d2": h2}[b], 5.0)

    for a, b in (("d1", "d2"), ("d2", "d1")):
        if passes(a, b):
            assert order.index(a) > order.index(b), order
    # a cycle is named, not hidden
    q1 = (*h2, 20.0)  # d1 sits over d2's home and must pass... its own home is h1
    q2 = (*h1, 20.0)
    order, notes = rtl_order({"d1": q1, "d2": q2}, {"d1": h1, "d2": h2}, 5.0)
    assert len(order) == 2 and notes and "d1" in notes[0] and "d2" in notes[0]


async def test_formation_resource_and_monitor(gateway: Gateway) -> None:
    for v in vehicles(gateway):
        v.speed = 25.0
    gateway.settings.mcp_wait_cap_s = 0.3
    async with Client(build_mcp(gateway)) as c:
        res = await c.read_resource("fleet://formation")
        assert json.loads(res.contents[0].text)["formation"] is None
        r = ok(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 10, "wait": False}))
        assert r["status"] == "running"
        while (r := ok(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]})))[
            "status"
        ] == "running":
            pass
        assert r["status"] == "succeeded"
        lat, lon = ahead(60.0)
        r = ok(
            await c.call_tool(
                "formation_goto",
                {
                    "drone_ids": IDS,
                    "formation": "grid",
                    "center_lat_deg": lat,
                    "center_lon_deg": lon,
                    "alt_m": 15,
                },
            )
        )
        assert r["status"] == "running" and r["plan"]["formation"] == "grid"
        # another move on a drone of a running formation is refused, naming the way out
        text = err(
            await c.call_tool(
                "formation_goto",
                {
                    "drone_ids": ["d1", "d2"],
                    "formation": "line",
                    "center_lat_deg": lat,
                    "center_lon_deg": lon,
                    "alt_m": 15,
                },
            )
        )
        assert "drone_busy" in text and "fleet_hold" in text, text
        res = json.loads((await c.read_resource("fleet://formation")).contents[0].text)
        assert res["operation_id"] == r["operation_id"] and res["status"] == "running"
        assert len(res["plan"]["slots"]) == 5
        while (r := ok(await c.call_tool("monitor_fleet", {})))["status"] == "running":
            pass
        assert r["status"] == "succeeded"
        res = json.loads((await c.read_resource("fleet://formation")).contents[0].text)
        assert res["status"] == "succeeded" and res["progress"] == 1.0


async def test_list_drones_filters_and_fleet_status_is_compact(gateway: Gateway) -> None:
    fake(gateway, "d2").spec.tags = ["survey"]
    fake(gateway, "d5").state = ConnectionState.LINK_LOST
    async with Client(build_mcp(gateway)) as c:
        r = ok(await c.call_tool("list_drones", {"tag": "survey"}))
        assert [d["drone_id"] for d in r["drones"]] == ["d2"]
        r = ok(await c.call_tool("list_drones", {"state": "link_lost"}))
        assert [d["drone_id"] for d in r["drones"]] == ["d5"]
        assert err(await c.call_tool("list_drones", {"state": "sleeping"}))
        r = await c.call_tool("fleet_status", {})
        lines = r.content[0].text.splitlines()
        assert len(lines) == 6 and lines[0].startswith("id state")
        assert lines[5].startswith("d5 link_lost")
        # d5 is not ready: a fleet takeoff including it is refused as a whole
        text = err(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 10}))
        assert "d5:" in text and "link_lost" in text, text
        assert not text.startswith("Refused"), "no safety rule refused it: the drone is unavailable"
        text = err(await c.call_tool("fleet_takeoff", {"drone_ids": ["d1", "d1"], "alt_m": 10}))
        assert "more than once" in text


async def test_fleet_tools_follow_the_surface_rules(gateway: Gateway) -> None:
    """Like the other toolsets: one short description line, annotations set, structured output."""
    async with Client(build_mcp(gateway)) as c:
        tools = {t.name: t for t in (await c.list_tools()).tools}
    fleet = ["list_drones", "fleet_status", "monitor_fleet", "formation_goto", "fleet_takeoff", "fleet_land",
             "fleet_return_to_launch", "fleet_hold"]  # fmt: skip
    for name in fleet:
        tool = tools[name]
        assert tool.description and "\n" not in tool.description and len(tool.description) <= 110, name
        assert '"title"' not in json.dumps(tool.input_schema), name
        assert tool.output_schema is not None and tool.annotations is not None, name
    assert all(tools[n].annotations.read_only_hint for n in ("list_drones", "fleet_status", "monitor_fleet"))
    assert not tools["formation_goto"].annotations.read_only_hint


async def test_return_altitudes_fall_back_to_the_separation_when_the_margin_does_not_fit(
    tmp_path: Path,
) -> None:
    settings = unit_settings(tmp_path, mcp_wait_cap_s=20.0, max_altitude_m=45.0)
    async with fake_gateway(settings, spread(5)) as gateway, Client(build_mcp(gateway)) as c:
        drones = vehicles(gateway)
        ok(await c.call_tool("fleet_takeoff", {"drone_ids": IDS, "alt_m": 10, "stagger_m": 5}))  # 10..30 m
        # from 31 m, 7 m apart reaches 59 m, above 45; 5 m apart reaches 51: still above, refused with numbers
        text = err(await c.call_tool("fleet_return_to_launch", {}))
        assert "max_altitude" in text and "45" in text, text
        r = ok(await c.call_tool("fleet_return_to_launch", {"rtl_alt_m": 20}))  # 20..40 at 5 m apart
    alts = {d["drone_id"]: d["rtl_alt_m"] for d in r["drones"]}
    assert sorted(alts.values()) == [20.0, 25.0, 30.0, 35.0, 40.0]
    assert any("did not fit" in n for n in r["notes"]), r["notes"]
    # each drone first moved in place to its own layer, up or down (else a drone above its RTL
    # altitude would return at its current one, breaking the layers)
    for v in drones:
        gotos = [a for _t, n, a in v.log if n == "goto"]
        start = 10.0 + 5 * IDS.index(v.id)
        if abs(start - alts[v.id]) > 1.0:
            assert gotos and gotos[-1][2] == alts[v.id], (v.id, gotos)


async def test_a_formation_placed_where_the_drones_are_takes_off_grounded_ones_first(
    gateway: Gateway,
) -> None:
    """No centre given: the drones' own centre, moved north_m; the drones on the ground take off first
    (staggered, a phase of the same fleet operation), then fly into the formation."""
    three = ["d1", "d2", "d3"]
    positions = [geo.offset_position(HOME[0], HOME[1], 0.0, 10.0 * k) for k in range(3)]
    lat0 = sum(p[0] for p in positions) / 3
    lon0 = sum(p[1] for p in positions) / 3
    async with Client(build_mcp(gateway)) as c:
        far = {"drone_ids": three, "formation": "line", "alt_m": 15, "north_m": 5000}
        text = err(await c.call_tool("formation_goto", far))
        assert "max_distance" in text and "beyond the limit of 1000 m" in text, text
        assert all(sent_names(fake(gateway, d)) == [] for d in three)
        result = ok(
            await c.call_tool(
                "formation_goto", {"drone_ids": three, "formation": "line", "alt_m": 15, "north_m": 30}
            )
        )
    assert result["status"] == "succeeded", result
    assert result["phases"][0] == "take off the drones on the ground" and len(result["phases"]) == 4, result
    for d in three:
        names = sent_names(fake(gateway, d))
        assert names[0] == "takeoff" and "goto" in names[1:], (d, names)
    slots = [(s["target_lat_deg"], s["target_lon_deg"]) for s in result["drones"]]
    centre = (sum(s[0] for s in slots) / 3, sum(s[1] for s in slots) / 3)
    north, east = geo.ned_offset(lat0, lon0, *centre)
    assert abs(north - 30.0) < 0.5 and abs(east) < 0.5, (north, east)
    assert all(d["target_alt_m"] == 15 for d in result["drones"]), result
