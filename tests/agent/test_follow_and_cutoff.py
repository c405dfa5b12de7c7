"""The host waits for actions still running after the gateway's capped wait, and notices a reply cut
off at the length limit (a scripted model endpoint; the MCP side is a fake caller)."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any

from bench.agent_harness.scripted import ScriptedReply, call, say
from gateway.agent.host import AgentHost
from gateway.agent.toolbox import ToolInfo, ToolOutcome
from gateway.agent.turns import AgentEvent, ModelConfig

Progress = Callable[[float, float | None, str | None], Awaitable[None]] | None

TOOLS = [
    ToolInfo("move_to_relative", "move", {"type": "object", "properties": {
        "drone_id": {"type": "string"}, "north_m": {"type": "number"}, "wait": {"type": "boolean"}},
        "required": ["drone_id", "north_m"]}),
    ToolInfo("fleet_land", "land all", {"type": "object", "properties": {}}),
    ToolInfo("land", "land", {"type": "object", "properties": {"drone_id": {"type": "string"}},
                              "required": ["drone_id"]}),
]  # fmt: skip


def _running(drone: str) -> ToolOutcome:
    data = {"status": "running", "drone_id": drone, "operation_id": "op1", "kind": "goto"}
    return ToolOutcome(f"goto on {drone} running: 40 m to go", False, data)


class FakeGateway:
    """Answers a move with 'running' and then ``running_waits`` more 'running' monitor answers."""

    def __init__(self, running_waits: int = 1) -> None:
        self.calls: list[tuple[str, dict[str, Any]]] = []
        self.running_waits = running_waits

    async def call_tool(self, name: str, arguments: dict[str, Any], progress: Progress = None) -> ToolOutcome:
        self.calls.append((name, arguments))
        if name == "list_drones":
            return ToolOutcome("", True)  # no roster: the host goes without it
        if name == "move_to_relative":
            return _running(arguments["drone_id"])
        if name == "monitor_flight":
            if self.running_waits > 0:
                self.running_waits -= 1
                return _running(arguments["drone_id"])
            data = {"status": "succeeded", "drone_id": arguments["drone_id"], "operation_id": "op1"}
            return ToolOutcome(f"goto on {arguments['drone_id']} succeeded: arrived", False, data)
        if name == "fleet_land":
            data = {"status": "running", "operation_id": "fleet-1", "drones": [{"drone_id": "alpha"}]}
            return ToolOutcome("fleet land running", False, data)
        if name == "monitor_fleet":
            data = {"status": "succeeded", "operation_id": "fleet-1", "drones": [{"drone_id": "alpha"}]}
            return ToolOutcome("fleet land succeeded: all 1 drones landed", False, data)
        return ToolOutcome(f"{name} done", False, {"status": "succeeded"})


async def _turn(model_url: str, gateway: FakeGateway, prompt: str, *, follow: bool = True,
                events: list[AgentEvent] | None = None) -> Any:  # fmt: skip
    host = AgentHost(ModelConfig(model_url, "scripted", max_retries=0), gateway, TOOLS, follow_running=follow,
                     on_event=events.append if events is not None else None)  # fmt: skip
    return await host.run_turn(prompt)


def _tool_texts(request: dict[str, Any]) -> list[str]:
    return [m["content"] for m in request["messages"] if m["role"] == "tool"]


async def test_an_action_still_running_after_the_capped_wait_is_waited_for_by_the_host(scripted) -> None:
    model = scripted([call("move_to_relative", drone_id="alpha", north_m=300), say("alpha arrived")])
    gateway = FakeGateway(running_waits=2)
    events: list[AgentEvent] = []
    result = await _turn(model.base_url, gateway, "alpha 300 m north", events=events)

    assert [name for name, _ in gateway.calls if name != "list_drones"] == [
        "move_to_relative", "monitor_flight", "monitor_flight", "monitor_flight"]  # fmt: skip
    assert _tool_texts(model.requests[1]) == ["goto on alpha succeeded: arrived"]
    assert result.tool_calls[0].status == "ok" and not result.tool_calls[0].running
    assert [e.data["tool"] for e in events if e.kind == "following"] == ["monitor_flight"] * 3


async def test_a_fleet_operation_still_running_is_followed_with_monitor_fleet(scripted) -> None:
    model = scripted([call("fleet_land"), say("all landed")])
    gateway = FakeGateway()
    await _turn(model.base_url, gateway, "land everything")
    assert ("monitor_fleet", {"operation_id": "fleet-1"}) in gateway.calls
    assert _tool_texts(model.requests[1]) == ["fleet land succeeded: all 1 drones landed"]


async def test_a_call_sent_with_wait_false_or_without_following_is_left_running(scripted) -> None:
    model = scripted([call("move_to_relative", drone_id="alpha", north_m=300, wait=False), say("sent")])
    gateway = FakeGateway()
    await _turn(model.base_url, gateway, "alpha 300 m north, don't wait")
    assert "monitor_flight" not in [name for name, _ in gateway.calls]

    model = scripted([call("move_to_relative", drone_id="alpha", north_m=300), say("running")])
    gateway = FakeGateway()
    await _turn(model.base_url, gateway, "alpha 300 m north", follow=False)
    assert "monitor_flight" not in [name for name, _ in gateway.calls]
    assert _tool_texts(model.requests[1]) == ["goto on alpha running: 40 m to go"]


async def test_a_reply_cut_off_at_the_length_limit_says_the_rest_was_not_read(scripted) -> None:
    cut = ScriptedReply(
        content='{"name": "land", "arguments": {"drone_id": "alpha"}}\n{"name": "land", "argu',
        finish_reason="length",
    )
    model = scripted([cut, say("alpha landed")])
    gateway = FakeGateway()
    await _turn(model.base_url, gateway, "land alpha and bravo")
    told = _tool_texts(model.requests[1])[-1]
    assert told.startswith("land done")
    assert "cut off at the length limit after this call" in told


async def test_a_reply_cut_off_before_any_complete_call_is_not_taken_as_the_answer(scripted) -> None:
    cut = ScriptedReply(content='{"name": "land", "argu', finish_reason="length")
    model = scripted([cut, call("land", drone_id="alpha"), say("alpha landed")])
    result = await _turn(model.base_url, FakeGateway(), "land alpha")
    assert result.outcome == "answered" and result.final_text == "alpha landed"
    asked = [m["content"] for m in model.requests[1]["messages"] if m["role"] == "user"][-1]
    assert asked.startswith("Your reply was cut off at the length limit before a complete tool call.")
