"""A tool call's arguments are validated once (by the SDK's run), and a bad one is still answered in
one line naming the argument, what was given and what is accepted. In-process client, the real gateway
and fake drones."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest
from mcp import Client
from mcp.server.mcpserver.utilities.func_metadata import FuncMetadata

from gateway.mcp.server import build_mcp
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake, fake_gateway, unit_settings


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=5.0), [FakeVehicle("d1")]) as gw:
        yield gw


async def test_arguments_are_validated_once_and_refused_in_one_line(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    validated: list[dict[str, Any]] = []
    validate = FuncMetadata.validate_arguments

    def counting(self: FuncMetadata, arguments: dict[str, Any]) -> dict[str, Any]:
        validated.append(arguments)
        return validate(self, arguments)

    monkeypatch.setattr(FuncMetadata, "validate_arguments", counting)
    async with Client(build_mcp(gateway)) as c:
        r = await c.call_tool("set_max_speed", {"drone_id": "d1", "speed_mps": 5})
        assert not r.is_error, r.content
        assert len(validated) == 1, validated
        validated.clear()
        r = await c.call_tool("set_max_speed", {"drone_id": "d1", "speed_mps": 500})
        assert r.is_error and len(validated) == 1
        text = r.content[0].text
        assert text == (
            "invalid arguments for set_max_speed: speed_mps must be a number (m/s), "
            "0 < speed_mps <= 100 (got 500)"
        ), text
        r = await c.call_tool("set_max_speed", {"drone_id": "d1", "speed": 5})
        assert r.is_error and '"speed" is not an argument of set_max_speed' in r.content[0].text
    assert fake(gateway, "d1").sent == [("speed", 5.0)]  # only the valid call reached the drone


async def test_a_refusal_from_a_tool_is_its_own_words(gateway: Gateway) -> None:
    """A ToolError the gateway raises on purpose (here the kill's policy check) reaches the model as
    written, without the SDK's "Error executing tool kill_motors:" in front."""
    drone = fake(gateway, "d1")
    drone.set(armed=True, in_air=True)
    async with Client(build_mcp(gateway)) as c:
        r = await c.call_tool("kill_motors", {"drone_id": "d1"})
    assert r.is_error
    text = r.content[0].text
    assert text.startswith("Refused: ") and "kill_in_air" in text, text


async def test_a_stored_mission_with_items_at_latitude_and_longitude_0_downloads(gateway: Gateway) -> None:
    """A mission another planner stored (ArduPilot reads lat/lon 0 as where the drone is) is reported as
    the drone holds it, not refused as if it were new input."""
    from gateway.fleet.missions.mission import MissionItem

    fake(gateway, "d1").mission = [
        MissionItem.model_construct(
            lat=0.0, lon=0.0, alt_rel_m=10.0, kind="loiter_time", hold_s=5.0, speed_mps=None, command=None
        )
    ]
    async with Client(build_mcp(gateway)) as c:
        r = await c.call_tool("download_mission", {"drone_id": "d1"})
    assert not r.is_error, r.content[0].text
    assert r.structured_content is not None
    [item] = r.structured_content["items"]
    assert (item["kind"], item["lat_deg"], item["lon_deg"], item["hold_s"]) == ("loiter_time", 0.0, 0.0, 5.0)
