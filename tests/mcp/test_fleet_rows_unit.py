"""A drone's row in list_drones, read from its telemetry cache (over the real runtime and a fake drone)."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

from gateway.link.telemetry import BatteryValue
from gateway.mcp.tools.fleet import _row
from tests.fakes import FakeVehicle, fake, fake_gateway, unit_settings


async def test_a_battery_of_unknown_level_is_listed_without_a_percentage(tmp_path: Path) -> None:
    async with fake_gateway(unit_settings(tmp_path), [FakeVehicle("d1")]) as gateway:
        vehicle = fake(gateway, "d1")
        call = SimpleNamespace(commander=gateway.commander, settings=gateway.settings)
        vehicle.telemetry.put("battery", BatteryValue(remaining_pct=None, voltage_v=11.1))
        assert _row(call, vehicle)["battery_pct"] is None
        vehicle.telemetry.put("battery", BatteryValue(remaining_pct=76.04, voltage_v=11.1))
        assert _row(call, vehicle)["battery_pct"] == 76.0
