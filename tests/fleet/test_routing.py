"""The Commander's routing seam (unit): a verb for a drone this node does not own goes to the router as
JSON and comes back as the same model; callbacks travel as progress messages; the owner's side runs the
same verb (with the agent's scope applied again) and never forwards a forwarded call again.

The router here is a loopback: its "owner" is the same Commander, reached through the owner's real
handler (`gateway.cluster.forwarding.answer`), with every message passed through JSON."""

from __future__ import annotations

import json
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import pytest

from gateway.cluster.forwarding import answer
from gateway.errors import NoOwner, UnknownVehicle
from gateway.fleet.commands.commander import Commander
from gateway.fleet.commands.scopes import ScopedDirectory, VehicleScope
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.operations.routing import ACTING, FORWARDED, RoutedCall
from gateway.fleet.operations.views import ActionResult, OperationView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety_inputs import RunningOperation
from gateway.runtime import Gateway
from tests.fakes import HOME, fake, fake_gateway, spread, unit_settings

AGENT = Caller(via="mcp", principal="agent-1", session="s1")
SCOPED = Caller(via="mcp", principal="agent-scoped", session="s2")


class Loopback:
    """Owns no drone, except while answering a forwarded call (then the owner is "this" node)."""

    def __init__(self) -> None:
        self.commander: Commander | None = None
        self.calls: list[tuple[str, str, dict[str, Any], dict[str, Any]]] = []
        self.owner_lost = False

    def owns(self, drone_id: str) -> bool:
        return FORWARDED.get() and not self.owner_lost

    def running(self, drone_id: str) -> RunningOperation | None:
        return None

    def published(self, drone_id: str) -> dict[str, Any] | None:
        return None

    async def call(self, routed: RoutedCall) -> Any:
        assert self.commander is not None
        sent = json.loads(json.dumps(routed.arguments))  # what crosses NATS is JSON
        self.calls.append((routed.drone_id, routed.verb, sent, routed.caller.to_dict()))

        async def progress(body: dict[str, Any]) -> None:
            if routed.on_message is not None:
                await routed.on_message(json.loads(json.dumps(body)))

        result = await answer(self.commander, routed.verb, sent, routed.caller.to_dict(), progress)
        return json.loads(json.dumps(result))

    async def announce(self, kind: str, body: dict[str, Any]) -> None:
        pass


@pytest.fixture
async def routed(tmp_path: Path) -> AsyncIterator[tuple[Gateway, Commander, Loopback]]:
    async with fake_gateway(unit_settings(tmp_path, mcp_wait_cap_s=10.0), spread(2)) as gw:
        base = gw.commander
        loop = Loopback()
        scopes = {"agent-scoped": VehicleScope.parse(["d1"])}
        assert isinstance(base.registry, ScopedDirectory)
        commander = Commander(
            gw.settings,
            ScopedDirectory(base.registry.directory, scopes),
            gw.store,
            base.operations,
            base.fleet,
            base.safety,
            base.locks,
            router=loop,
        )
        loop.commander = commander
        yield gw, commander, loop


async def test_a_verb_goes_to_the_owner_as_json_and_comes_back_as_the_same_model(
    routed: tuple[Gateway, Commander, Loopback],
) -> None:
    gw, commander, loop = routed
    notices: list[str] = []

    async def notify(text: str) -> None:
        notices.append(text)

    fake(gw, "d1").initialising = lambda: "waiting for a position estimate"  # type: ignore[method-assign]
    started = await commander.takeoff(AGENT, "d1", 10.0, notify=notify)
    assert isinstance(started, OperationView) and started.kind == "takeoff"
    assert loop.calls[0][:3] == ("d1", "takeoff", {"drone_id": "d1", "alt_m": 10.0})
    assert loop.calls[0][3] == AGENT.to_dict()  # the door's caller, not the forwarding node
    assert notices == ["d1: waiting for a position estimate"]  # the owner's notice, relayed
    assert fake(gw, "d1").sent[0] == ("takeoff", 10.0)
    await commander.monitor(AGENT, "d1", cap_s=10.0)  # an agent's upload waits for the takeoff to end
    items = [MissionItem(lat=HOME[0], lon=HOME[1], alt_rel_m=10.0, kind="waypoint")]
    uploaded = await commander.upload_mission(AGENT, "d1", items)
    assert isinstance(uploaded, ActionResult) and uploaded.facts == {"items": 1}
    assert loop.calls[-1][2]["items"][0]["lat"] == HOME[0]  # models cross as JSON


async def test_progress_of_a_forwarded_monitor_arrives_as_operation_views(
    routed: tuple[Gateway, Commander, Loopback],
) -> None:
    _gw, commander, loop = routed
    await commander.takeoff(AGENT, "d2", 10.0)
    views: list[OperationView] = []

    async def on_progress(view: OperationView) -> None:
        views.append(view)

    done = await commander.monitor(AGENT, "d2", cap_s=10.0, on_progress=on_progress)
    assert done.status == "succeeded" and views and all(v.drone_id == "d2" for v in views)
    assert loop.calls[-1][1] == "monitor" and loop.calls[-1][2]["cap_s"] == 10.0


async def test_the_scope_holds_here_and_again_on_the_owner(
    routed: tuple[Gateway, Commander, Loopback],
) -> None:
    _gw, commander, loop = routed
    token = ACTING.set(SCOPED)
    try:
        with pytest.raises(UnknownVehicle, match="known ids: d1"):
            await commander.takeoff(SCOPED, "d2", 10.0)  # named here: nothing forwarded
        assert loop.calls == []
    finally:
        ACTING.reset(token)
    # forwarded by a node that did not apply the scope: the owner applies it (ACTING = forwarded caller)
    with pytest.raises(UnknownVehicle, match="known ids: d1"):
        await loop.call(RoutedCall("d2", "takeoff", SCOPED, {"drone_id": "d2", "alt_m": 10.0}))


async def test_a_forwarded_call_is_never_forwarded_again(routed: tuple[Gateway, Commander, Loopback]) -> None:
    gw, commander, loop = routed
    loop.owner_lost = True  # the drone changed owner while the call was on its way
    with pytest.raises(NoOwner, match="does not own drone 'd1'"):
        await commander.hold(AGENT, "d1")
    assert [c[1] for c in loop.calls] == ["hold"] and fake(gw, "d1").sent == []
