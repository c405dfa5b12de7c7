"""When the audit row of a call of a tool that commands a drone is written: before the tool runs, once the
SDK has taken the arguments. A call refused for its arguments sent nothing: no row is written on its way
(no database write per refusal), and its row is queued when it ends, with the same outcome and words.
In-process client, the real gateway (SQLite store), fake drones."""

from __future__ import annotations

from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest
from mcp import Client

from gateway.mcp.server import build_mcp
from gateway.registry.records import AuditEntry
from gateway.registry.store_audit import AuditCall
from gateway.runtime import Gateway
from tests.fakes import FakeVehicle, fake, fake_gateway, unit_settings


@pytest.fixture
async def gateway(tmp_path: Path) -> AsyncIterator[Gateway]:
    settings = unit_settings(tmp_path, mcp_wait_cap_s=5.0, max_altitude_m=120.0)
    async with fake_gateway(settings, [FakeVehicle("d1")]) as gw:
        yield gw


def rows_begun(gateway: Gateway, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The actions whose row the store was asked to write before the call ran (`Store.audit_call`)."""
    store = gateway.store
    assert store is not None
    begun: list[str] = []
    audit_call = store.audit_call

    def counted(entry: AuditEntry, *args: Any) -> AuditCall:  # Any: the store's own further arguments
        begun.append(entry.action)
        return audit_call(entry, *args)

    monkeypatch.setattr(store, "audit_call", counted)
    return begun


async def test_a_call_refused_for_its_arguments_writes_no_row_before_it_and_is_audited_when_it_ends(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    begun = rows_begun(gateway, monkeypatch)
    goto = {"drone_id": "d1", "lat_deg": 500.0, "lon_deg": 0.0, "alt_m": 10.0}
    async with Client(build_mcp(gateway)) as c:
        r = await c.call_tool("go_to_location", goto)
        assert r.is_error and r.structured_content is not None
        assert r.structured_content["code"] == "invalid_argument", r.structured_content
        assert begun == []  # the SDK refused the arguments: the tool never ran, no row before it
        assert fake(gateway, "d1").sent == []

        r = await c.call_tool("go_to_location", {**goto, "lat_deg": "north"})  # refused by the strict check
        assert r.is_error and begun == []

        r = await c.call_tool("set_max_speed", {"drone_id": "d1", "speed_mps": 5.0})
        assert not r.is_error, r.content
        assert begun == ["set_max_speed"]  # arguments taken: its row written before the tool ran

    store = gateway.store
    assert store is not None
    await store.flush_audit()
    rows = {(row.action, str(row.arguments.get("lat_deg"))): row for row in await store.list_audit()}
    refused = rows[("go_to_location", "500.0")]
    assert (refused.outcome, refused.vehicle_id) == ("error", "d1")
    assert refused.error is not None and "lat_deg" in refused.error and "500" in refused.error
    assert rows[("go_to_location", "north")].outcome == "error"
    assert rows[("set_max_speed", "None")].outcome == "ok"
    assert await store.count_audit() == 3  # one row per call
