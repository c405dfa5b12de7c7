"""Registrations, origins and geofence zones are verbs: callable by name with JSON like every command,
operators only (an agent is refused with rule operator_lock and nothing changes). The real Gateway
(store, policy, Commander) over fake drones."""

from __future__ import annotations

from typing import Any

import pytest

from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet.policy.geofence import FLEET
from gateway.runtime import Gateway
from tests.fakes import HOME
from tests.fleet._util import AGENT, OPERATOR


def square(lat: float, lon: float, half_deg: float = 0.0005) -> dict[str, Any]:
    h = half_deg
    ring = [
        [lon - h, lat - h],
        [lon + h, lat - h],
        [lon + h, lat + h],
        [lon - h, lat + h],
        [lon - h, lat - h],
    ]
    return {"type": "Polygon", "coordinates": [ring]}


def zone(name: str, kind: str = "keep_out") -> dict[str, Any]:
    return {"type": "Feature", "properties": {"kind": kind, "name": name}, "geometry": square(*HOME[:2])}


AGENT_CALLS: list[tuple[str, dict[str, Any]]] = [
    ("register_drone", {"spec": {"id": "x1", "url": "udpin://127.0.0.1:14599"}, "connect": False}),
    ("update_drone", {"drone_id": "d1", "changes": {"name": "renamed"}}),
    ("remove_drone", {"drone_id": "d1"}),
    ("connect_drone", {"drone_id": "d1"}),
    ("disconnect_drone", {"drone_id": "d1"}),
    ("move_origin", {"drone_id": "d1", "lat": HOME[0], "lon": HOME[1], "alt_amsl_m": HOME[2]}),
    ("set_geofences", {"scope": FLEET, "features": [zone("school")]}),
    ("upload_plan", {"drone_id": "d1", "content": "QGC WPL 110\n"}),
]


@pytest.mark.parametrize(("verb", "arguments"), AGENT_CALLS, ids=[v for v, _ in AGENT_CALLS])
async def test_an_agent_is_refused_and_nothing_changes(
    gateway: Gateway, verb: str, arguments: dict[str, Any]
) -> None:
    store = gateway.require_store()
    before = [r.model_dump() for r in await store.list_vehicles()]
    with pytest.raises(SafetyRefusal) as refused:
        await gateway.commander.call(verb, AGENT, **arguments)
    assert refused.value.rule == "operator_lock" and "only an operator may" in refused.value.message
    assert [r.model_dump() for r in await store.list_vehicles()] == before
    assert [v.id for v in gateway.require_registry().all()] == ["d1", "d2"]
    assert list(gateway.require_safety().geofences) == []


async def test_an_operator_registers_changes_and_removes_by_name(gateway: Gateway) -> None:
    commander = gateway.commander
    added = await commander.call(
        "register_drone", OPERATOR, spec={"id": "x1", "url": "udpin://127.0.0.1:14599"}, connect=False
    )
    assert added["id"] == "x1" and added["auto_connect"] is False
    changed = await commander.call("update_drone", OPERATOR, drone_id="x1", changes={"name": "Spare"})
    assert changed["name"] == "Spare"
    with pytest.raises(InvalidArgument, match="changes: colour cannot be changed; changeable: url, name"):
        await commander.call("update_drone", OPERATOR, drone_id="x1", changes={"colour": "red"})
    with pytest.raises(InvalidArgument, match="nothing to update"):
        await commander.call("update_drone", OPERATOR, drone_id="x1", changes={})
    removed = await commander.call("remove_drone", OPERATOR, drone_id="x1")
    assert removed["id"] == "x1"
    assert await gateway.require_store().get_vehicle("x1") is None


async def test_an_operator_swaps_zones_whole_or_not_at_all(gateway: Gateway) -> None:
    commander = gateway.commander
    view = await commander.call("set_geofences", OPERATOR, scope="d1", features=[zone("field", "keep_in")])
    assert [f["properties"] for f in view["features"]] == [
        {"kind": "keep_in", "name": "field", "vehicle_id": "d1"}
    ]
    bad = {"type": "Feature", "properties": {"kind": "keep_sideways"}, "geometry": square(*HOME[:2])}
    with pytest.raises(InvalidArgument, match="keep_sideways"):
        await commander.call("set_geofences", OPERATOR, scope="d1", features=[zone("other"), bad])
    assert [(z.name, z.scope) for z in gateway.require_safety().geofences] == [("field", "d1")]
    cleared = await commander.call("set_geofences", OPERATOR, scope="d1", features=[])
    assert cleared["features"] == [] and list(gateway.require_safety().geofences) == []
