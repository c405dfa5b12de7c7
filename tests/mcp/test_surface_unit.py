"""Unit tests of the MCP surface over an in-process client, the real gateway and fake drones (both
protocol eras)."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from pathlib import Path

import pytest
from mcp import Client

from gateway.config import ALL_TOOLSETS
from gateway.mcp.server import build_mcp, tool_names
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake, fake_gateway, unit_settings


@pytest.fixture(params=["auto", "legacy"])
def mode(request: pytest.FixtureRequest) -> str:
    return request.param


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    settings = unit_settings(tmp_path, mcp_wait_cap_s=5.0)
    async with fake_gateway(settings, [FakeVehicle("d1"), FakeVehicle("d2")]) as gw:
        yield gw


async def test_takeoff_goto_land_and_refusals(gateway: Gateway, mode: str) -> None:
    server = build_mcp(gateway)
    async with Client(server, mode=mode) as c:
        listed = (await c.list_tools()).tools
        # every toolset's tools (the default enables all), derived from the declarations: a new command
        # changes no number here
        assert [t.name for t in listed] == tool_names(ALL_TOOLSETS)
        # every tool names its toolset in _meta, so clients can offer a model only some toolsets
        toolset_of = {t.name: (t.meta or {}).get("fleet-gateway/toolset") for t in listed}
        assert toolset_of["takeoff"] == "flight" and toolset_of["go_to_location"] == "navigation"
        assert toolset_of["formation_goto"] == "fleet" and toolset_of["get_battery"] == "telemetry"
        assert set(toolset_of.values()) == {"flight", "navigation", "mission", "telemetry", "params", "fleet"}
        drone = fake(gateway, "d1")
        climb = drone.speed
        drone.speed = 0.0  # the climb waits for the goto below: the takeoff runs however loaded the host
        r = await c.call_tool("takeoff", {"drone_id": "d1", "alt_m": 10, "wait": False})
        assert not r.is_error, r.content
        assert r.structured_content["status"] == "running"
        r = await c.call_tool(
            "go_to_location",
            {"drone_id": "d1", "lat_deg": 47.398, "lon_deg": 8.5456, "alt_m": 10},
        )
        assert r.is_error and "monitor_flight" in r.content[0].text
        drone.speed = climb
        r = await c.call_tool("monitor_flight", {"drone_id": "d1"})
        assert r.structured_content["status"] == "succeeded", r.structured_content
        r = await c.call_tool(
            "go_to_location",
            {"drone_id": "d1", "lat_deg": 47.398, "lon_deg": 8.5456, "alt_m": 10},
        )
        assert r.structured_content["status"] == "succeeded", r.content
        r = await c.call_tool("check_arrival", {"drone_id": "d1"})
        assert r.structured_content["arrived"] is True
        r = await c.call_tool("land", {"drone_id": "d1"})
        assert r.structured_content["status"] == "succeeded", r.content
        r = await c.call_tool("get_battery", {"drone_id": "d9"})
        assert r.is_error and "d1, d2" in r.content[0].text
        r = await c.call_tool("list_parameters", {"drone_id": "d1", "prefix": "sr0", "limit": 100})
        assert r.structured_content["total"] == 300 and r.structured_content["next_offset"] == 100


async def test_parallel_takeoff_and_goto_the_goto_is_refused(gateway: Gateway) -> None:
    """LLM hosts may issue tool calls in parallel: a goto racing a takeoff (still arming) is refused."""
    server = build_mcp(gateway)
    vehicle = fake(gateway, "d1")
    vehicle.arm_delay_s = 0.5
    goto = {"drone_id": "d1", "lat_deg": 47.398, "lon_deg": 8.5456, "alt_m": 10}
    async with Client(server) as c:

        async def late_goto() -> object:
            await asyncio.sleep(0.1)  # sent while the takeoff command is still being sent
            # armed and lifting off: the takeoff guard, not the on-the-ground check, must refuse
            vehicle.set(in_air=True, armed=True)
            return await c.call_tool("go_to_location", goto)

        takeoff, refused = await asyncio.gather(
            c.call_tool("takeoff", {"drone_id": "d1", "alt_m": 10, "wait": False}), late_goto()
        )
    assert takeoff.structured_content["status"] == "running"
    assert refused.is_error and "takeoff_in_progress" in refused.content[0].text
    assert [s[0] for s in vehicle.sent] == ["takeoff"]
