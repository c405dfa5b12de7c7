"""A stop this node took over (`gateway.cluster.stop_takeover`): once its own sidecar holds the drone,
the stop goes through this node's command path with the arguments the verb takes, as soon as the drone
is heard (connected), not only once it is ready to fly."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import pytest

import gateway.cluster.stop_takeover as stop_takeover
import gateway.fleet.commands.commander  # noqa: F401  (fills ROUTED with every verb)
from gateway.cluster.stop_takeover import StopTakeover
from gateway.fleet.commands.command_core import ROUTED
from gateway.fleet.policy.caller import Caller

OPERATOR = Caller(via="rest", principal="operator")


class Registry:
    def __init__(self, state: str) -> None:
        self.view = SimpleNamespace(state=state)

    def find(self, _drone_id: str) -> Any:
        return self.view

    def is_local(self, _drone_id: str) -> bool:
        return True


def taken_over(state: str, sent: list[tuple[str, dict[str, Any]]], monkeypatch: pytest.MonkeyPatch) -> Any:
    async def answer(_commander: Any, name: str, arguments: dict[str, Any], *_rest: Any) -> object:
        sent.append((name, ROUTED[name].parse(arguments)))  # the verb's own parsing: refuses what it lacks
        return {}

    monkeypatch.setattr(stop_takeover, "answer", answer)
    gateway = SimpleNamespace(commander=None)
    node = SimpleNamespace(node_id="node-b", registry=Registry(state), gateway=gateway, leases=None)
    return StopTakeover(node)  # type: ignore[arg-type]


@pytest.mark.parametrize("verb", ["land", "return_to_launch", "hold"])
@pytest.mark.parametrize("state", ["connected", "ready"])
async def test_a_drone_taken_over_gets_the_stop_through_this_nodes_sidecar_once_heard(
    verb: str, state: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    sent: list[tuple[str, dict[str, Any]]] = []
    takeover = taken_over(state, sent, monkeypatch)
    how = await takeover._round("d1", verb, OPERATOR, 3, "node-a")
    assert how == "through node node-b's own sidecar, which took the drone over"
    assert [(name, parsed["drone_id"]) for name, parsed in sent] == [(verb, "d1")]


@pytest.mark.parametrize("state", ["registered", "connecting", "link_lost", "failed"])
async def test_a_drone_taken_over_but_not_heard_yet_waits_for_its_link(
    state: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    sent: list[tuple[str, dict[str, Any]]] = []
    takeover = taken_over(state, sent, monkeypatch)
    assert await takeover._round("d1", "land", OPERATOR, 3, "node-a") is None
    assert sent == []
