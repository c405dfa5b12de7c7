"""The one pass (`gateway.fleet.commands.command_pass`): a command resolves its drone once and is judged on
one
context, counted on the real Gateway over fake drones; fleet steps take the same pass."""

from __future__ import annotations

from typing import Any

import pytest

from gateway.errors import SafetyRefusal
from gateway.fleet import geo
from gateway.fleet.commands.command_pass import AUDIT_SENT
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.runtime import Gateway
from tests.fakes import HOME, fake
from tests.fleet._util import AGENT, OPERATOR


class Counts:
    """How often the drone is looked up and a `VehicleContext` is built while it is armed."""

    def __init__(self, gateway: Gateway, monkeypatch: pytest.MonkeyPatch) -> None:
        self.resolved: list[str] = []
        self.contexts = 0
        registry = gateway.commander.registry
        lookup = registry.get

        def get(vehicle_id: str) -> Any:
            self.resolved.append(vehicle_id)
            return lookup(vehicle_id)

        build = VehicleContext.__init__

        def init(ctx: VehicleContext, *args: Any, **kwargs: Any) -> None:
            self.contexts += 1
            build(ctx, *args, **kwargs)

        monkeypatch.setattr(registry, "get", get)
        monkeypatch.setattr(VehicleContext, "__init__", init)

    def reset(self) -> None:
        self.resolved.clear()
        self.contexts = 0


async def test_goto_resolves_the_drone_once_and_builds_one_context(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    commander = gateway.commander
    climb = await commander.takeoff(AGENT, "d1", 10.0)
    assert (await commander.wait(climb.operation_id, 10.0)).status == "succeeded"
    counts = Counts(gateway, monkeypatch)
    lat, lon = geo.offset_position(HOME[0], HOME[1], 20.0, 0.0)
    op = await commander.goto(AGENT, "d1", lat, lon, 12.0)  # what the go_to_location tool calls
    assert op.kind == "goto"
    assert counts.resolved == ["d1"], counts.resolved
    assert counts.contexts == 1, counts.contexts
    # by name (REST, a forwarding cluster node): the same single pass
    counts.reset()
    again = await commander.call("goto", AGENT, drone_id="d1", lat_deg=lat, lon_deg=lon, alt_m=14)
    assert again["kind"] == "goto" and counts.resolved == ["d1"] and counts.contexts == 1
    assert fake(gateway, "d1").sent[-2:] == [("goto", lat, lon, 12.0), ("goto", lat, lon, 14.0)]


async def test_a_refused_command_sends_nothing_and_is_judged_once(
    gateway: Gateway, monkeypatch: pytest.MonkeyPatch
) -> None:
    commander = gateway.commander
    await commander.lock(OPERATOR, "d2", "battery swap")
    counts = Counts(gateway, monkeypatch)
    with pytest.raises(SafetyRefusal, match="operator_lock"):
        await commander.takeoff(AGENT, "d2", 10.0)
    assert counts.resolved == ["d2"] and counts.contexts == 1
    assert fake(gateway, "d2").sent == []


async def test_the_pass_tells_the_door_the_operation_once_it_is_sent(gateway: Gateway) -> None:
    """The door's audit row is written when the operation is sent (`AUDIT_SENT`), not when the call
    ends; a fleet operation's steps are not the call and tell nothing."""
    commander = gateway.commander
    told: list[str] = []
    fake(gateway, "d1").speed = 0.5  # a slow climb: it surely still runs when the call returns
    token = AUDIT_SENT.set(told.append)
    try:
        climb = await commander.takeoff(AGENT, "d1", 10.0)
        assert told == [climb.operation_id]
        assert commander.operation(climb.operation_id).status == "running"  # told while it still flies
        fleet = await commander.fleet_takeoff(OPERATOR, ["d2"], 10.0)
        done = await commander.wait_fleet(fleet.operation_id, 10.0)
        assert done.status == "succeeded", done
        assert told == [climb.operation_id]
    finally:
        AUDIT_SENT.reset(token)
