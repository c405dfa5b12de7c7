"""The fleet as the compiler reads it over MCP: a drone's home is where it stood on the ground when the
turn began (it arms there), not a home its autopilot kept from an earlier flight."""

from __future__ import annotations

from typing import Any

import pytest

from fleet_agent.compiler import CompileError
from fleet_agent.records import Arguments, ToolOutcome
from fleet_agent.sensors import McpSensors

PAD = (47.3977, 8.5456)
EARLIER_HOME = (47.3979, 8.5456)  # about 22 m north: where the drone armed for its last flight


class Gateway:
    """``list_drones`` and ``get_home_position`` as the gateway answers them, the fleet changeable."""

    def __init__(self, flying: bool) -> None:
        self.rows: list[dict[str, Any]] = [_row("alpha", *PAD, flying)]
        self.calls: list[str] = []

    async def read(self, tool: str, args: Arguments) -> ToolOutcome:
        self.calls.append(tool)
        if tool == "list_drones":
            return ToolOutcome("", structured={"drones": self.rows})
        lat, lon = EARLIER_HOME
        return ToolOutcome("", structured={"drone_id": args["drone_id"], "lat_deg": lat, "lon_deg": lon})


def _row(drone: str, lat: float, lon: float, in_air: bool) -> dict[str, Any]:
    return {"drone_id": drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 10.0 if in_air else 0.0,
            "in_air": in_air, "battery_pct": 80.0}  # fmt: skip


async def test_a_drone_on_the_ground_as_the_turn_begins_has_its_home_where_it_stands() -> None:
    gateway = Gateway(flying=False)
    sensors = McpSensors(gateway.read)
    assert await sensors.home("alpha") == PAD and "get_home_position" not in gateway.calls
    # it flies off and lands 40 m away within the turn: its home is still the pad it left
    gateway.rows = [_row("alpha", PAD[0] + 0.00036, PAD[1], False)]
    sensors.invalidate()
    assert await sensors.home("alpha") == PAD


async def test_a_drone_flying_as_the_turn_begins_has_its_autopilots_home() -> None:
    gateway = Gateway(flying=True)
    sensors = McpSensors(gateway.read)
    assert await sensors.home("alpha") == EARLIER_HOME and "get_home_position" in gateway.calls


async def test_a_drone_with_no_position_as_the_turn_begins_has_its_autopilots_home_or_none() -> None:
    gateway = Gateway(flying=False)
    gateway.rows = [{**gateway.rows[0], "lat_deg": None, "lon_deg": None}]
    assert await McpSensors(gateway.read).home("alpha") == EARLIER_HOME

    async def no_home(tool: str, args: Arguments) -> ToolOutcome:
        if tool == "list_drones":
            return await gateway.read(tool, args)
        return ToolOutcome("no home position from alpha yet", is_error=True)

    with pytest.raises(CompileError, match="alpha's home is unknown"):
        await McpSensors(no_home).home("alpha")
