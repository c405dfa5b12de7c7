"""A refused or invalid tool call carries its code, rule and details as structured content beside the text
(the same fields REST returns), for every MCP client. In-process client, the real gateway, fake drones."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path

import pytest
from mcp import Client

from gateway.errors import SafetyRefusal, UnknownVehicle
from gateway.mcp.refusals import gateway_error_result
from gateway.mcp.server import build_mcp
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake, fake_gateway, unit_settings


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    settings = unit_settings(tmp_path, mcp_wait_cap_s=5.0, max_altitude_m=120.0)
    async with fake_gateway(settings, [FakeVehicle("d1"), FakeVehicle("d2")]) as gw:
        yield gw


async def test_refusals_and_invalid_arguments_are_data(gateway: Gateway) -> None:
    async with Client(build_mcp(gateway)) as c:
        r = await c.call_tool("takeoff", {"drone_id": "d1", "alt_m": 500})
        assert r.is_error
        data = r.structured_content
        assert data is not None and data["code"] == "safety_refusal" and data["rule"] == "max_altitude", data
        assert data["details"] == {"vehicle_id": "d1", "alt_rel_m": 500.0, "limit_m": 120.0}
        assert r.content[0].text == f"Refused: {data['message']}"

        r = await c.call_tool("takeoff", {"drone_id": "d1", "alt_m": "high"})
        assert r.is_error
        data = r.structured_content
        assert data is not None and data["code"] == "invalid_argument", data
        assert data["details"] == {"arguments": ["alt_m"]} and data["rule"] is None
        assert r.content[0].text == data["message"] and "alt_m" in data["message"]

        r = await c.call_tool("takeoff", {"drone_id": "d1", "altitude": 5})
        assert r.is_error and r.structured_content["details"] == {"arguments": ["altitude"]}

        r = await c.call_tool("set_parameter", {"drone_id": "d1", "name": "FENCE_ENABLE", "value": 0})
        assert r.is_error
        data = r.structured_content
        assert data["code"] == "safety_refusal" and data["rule"] == "param_deny", data
        assert r.content[0].text == f"Refused: {data['message']}"

        r = await c.call_tool("get_battery", {"drone_id": "d9"})
        assert r.is_error and r.structured_content["code"] == "unknown_vehicle"
        assert r.structured_content["details"]["known"] == ["d1", "d2"]
    assert fake(gateway, "d1").sent == []  # nothing refused reached the drone


def test_a_refusal_keeps_its_rule_out_of_the_details() -> None:
    out = gateway_error_result(SafetyRefusal("max_altitude", "too high", limit_m=120.0, seen={1}))
    assert out.is_error and out.content[0].text == "Refused: too high"
    assert out.structured_content == {
        "code": "safety_refusal",
        "message": "too high",
        "rule": "max_altitude",
        "details": {"limit_m": 120.0, "seen": [1]},
    }
    unknown = gateway_error_result(UnknownVehicle("d9", ["d1"]))
    assert unknown.structured_content is not None and unknown.structured_content["rule"] is None
