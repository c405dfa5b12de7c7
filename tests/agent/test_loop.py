"""The agent loop over real HTTP: a scripted model endpoint and a real (toy) MCP server."""

from __future__ import annotations

import json
from typing import Any

import pytest

from bench.agent_harness.scripted import ScriptedModelServer, ScriptedReply, call, say
from gateway.agent.host import AgentHost
from gateway.agent.mcp_link import McpLink, McpLinkError
from gateway.agent.turns import AgentEvent, ModelConfig
from tests.agent.toy_mcp import TOKEN, ToyServer


def _tool_messages(request: dict[str, Any]) -> list[dict[str, Any]]:
    return [m for m in request["messages"] if m["role"] == "tool"]


async def run_on_toy(
    toy: ToyServer,
    model: ScriptedModelServer,
    prompt: str,
    *,
    max_steps: int = 12,
    events: list[AgentEvent] | None = None,
    answer_tool: bool = False,
    plan_first: bool = False,
) -> tuple[AgentHost, Any]:
    """One turn of a host over the toy server's tools (``answer_tool``: with the host's answer_user;
    ``plan_first``: the request split into steps first)."""
    async with McpLink(toy.url, TOKEN) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0),
            link,
            await link.list_tools(),
            max_steps=max_steps,
            on_event=(events.append if events is not None else None),
            answer_tool=answer_tool,
            plan_first=plan_first,
        )
        result = await host.run_turn(prompt)
    return host, result


async def test_structured_calls_run_and_results_reach_the_model(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=15),
            call("move_north", drone_id="alpha", distance_m=100),
            call("land", drone_id="alpha"),
            say("alpha flew 100 m north and landed"),
        ]
    )
    events: list[AgentEvent] = []
    _, result = await run_on_toy(toy, model, "take off alpha to 15 m, fly 100 m north, land", events=events)

    assert result.outcome == "answered"
    assert result.final_text == "alpha flew 100 m north and landed"
    assert [c.name for c in result.tool_calls] == ["takeoff", "move_north", "land"]
    assert [c.status for c in result.tool_calls] == ["ok", "ok", "ok"]
    # The toy world really changed.
    alpha = toy.world.drones["alpha"]
    assert (alpha.north_m, alpha.alt_m, alpha.armed) == (100.0, 0.0, False)
    # The model was sent the tools and, each time, the previous results.
    first = model.requests[0]
    assert {t["function"]["name"] for t in first["tools"]} == {
        "takeoff",
        "move_north",
        "land",
        "get_position",
        "get_battery",
        "list_drones",
    }
    assert first["messages"][0]["role"] == "system" and first["messages"][-1]["content"].endswith(
        "take off alpha to 15 m, fly 100 m north, land"
    )
    assert '"reached"' in _tool_messages(model.requests[1])[-1]["content"]
    assert '"north_m": 100.0' in _tool_messages(model.requests[2])[-1]["content"]
    # Progress notifications arrived while the tool ran, before its result.
    kinds = [(e.kind, e.data.get("name")) for e in events]
    first_progress = kinds.index(("progress", "takeoff"))
    assert first_progress < kinds.index(("tool_result", "takeoff"))
    climbs = [e.data["message"] for e in events if e.kind == "progress" and e.data["name"] == "takeoff"]
    assert climbs == ["climbing 5.0/15 m", "climbing 10.0/15 m", "climbing 15.0/15 m"]


async def test_refusal_reaches_the_model_verbatim_and_it_can_correct(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="bravo", alt_m=500),
            call("takeoff", drone_id="bravo", alt_m=100),
            say("500 m is above the 120 m limit; bravo climbed to 100 m instead"),
        ]
    )
    _, result = await run_on_toy(toy, model, "climb bravo to 500 m")
    assert [c.status for c in result.tool_calls] == ["error", "ok"]
    refusal = _tool_messages(model.requests[1])[-1]["content"]
    assert (
        "refused by rule max_altitude: target altitude 500 m exceeds the limit of 120 m above home" in refusal
    )
    assert toy.world.drones["bravo"].alt_m == 100.0


async def test_invalid_arguments_are_not_executed(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m="fifteen"),  # wrong type
            # beyond a limit the schema advertises: the server's to refuse (a gateway names its rule)
            call("move_north", drone_id="alpha", distance_m=5000),
            call("land"),  # required drone_id missing
            ScriptedReply(tool_calls=[("land", '{"drone_id": "alpha"')]),  # undecodable arguments
            call("self_destruct", drone_id="alpha"),  # no such tool
            say("I could not do it"),
        ]
    )
    _, result = await run_on_toy(toy, model, "do bad things")
    assert [c.status for c in result.tool_calls] == [
        "invalid",
        "error",
        "invalid",
        "invalid",
        "unknown_tool",
    ]
    assert toy.world.calls == []  # nothing was executed by the server either
    msgs = [_tool_messages(model.requests[i])[-1]["content"] for i in range(1, 6)]
    assert "alt_m: 'fifteen' is not of type 'number'" in msgs[0]
    assert "1000" in msgs[1] and "distance_m" in msgs[1], msgs[1]
    assert "'drone_id' is a required property" in msgs[2]
    assert "not valid JSON" in msgs[3]
    assert "unknown tool 'self_destruct'" in msgs[4] and "takeoff" in msgs[4]
    assert all("Nothing was executed" in m for i, m in enumerate(msgs) if i != 1)


async def test_tool_call_written_as_text_is_parsed_and_flagged(toy, scripted) -> None:
    model = scripted(
        [
            ScriptedReply(
                content='Sure.\n<tool_call>\n{"name": "takeoff", "arguments": '
                '"{\\"drone_id\\": \\"alpha\\", \\"alt_m\\": 12,}"}\n</tool_call>'
            ),
            ScriptedReply(content='```json\n{{"name": "land", "arguments": {{"drone_id": "alpha"}}}}\n```'),
            say("done"),
        ]
    )
    events: list[AgentEvent] = []
    _, result = await run_on_toy(toy, model, "hop alpha", events=events)
    assert result.outcome == "answered" and result.parsed_from_text == 2
    assert toy.world.calls == [
        ("takeoff", {"drone_id": "alpha", "alt_m": 12.0}),
        ("land", {"drone_id": "alpha"}),
    ]
    assert sum(e.kind == "parsed_from_text" for e in events) == 2
    assert all(e.data["parsed_from_text"] for e in events if e.kind == "tool_call")
    # The recovered call went back to the model in the structured form, followed by its result.
    second = model.requests[1]["messages"]
    assistant = second[-2]
    assert assistant["role"] == "assistant" and assistant["tool_calls"][0]["function"]["name"] == "takeoff"
    assert second[-1]["role"] == "tool" and second[-1]["tool_call_id"] == assistant["tool_calls"][0]["id"]


async def test_parsed_call_with_invalid_arguments_is_not_executed(toy, scripted) -> None:
    model = scripted(
        [
            ScriptedReply(
                content='<tool_call>{"name": "takeoff", "arguments": {"drone_id": "alpha"}}</tool_call>'
            ),
            say("missing altitude"),
        ]
    )
    _, result = await run_on_toy(toy, model, "take off")
    assert result.tool_calls[0].status == "invalid" and result.tool_calls[0].parsed_from_text
    assert toy.world.calls == []
    assert "'alt_m' is a required property" in _tool_messages(model.requests[1])[-1]["content"]


async def test_step_limit_holds(toy, scripted) -> None:
    model = scripted([call("get_position", drone_id="alpha")], repeat_last=True)
    events: list[AgentEvent] = []
    _, result = await run_on_toy(toy, model, "keep looking", max_steps=3, events=events)
    assert result.outcome == "step_limit" and result.answered_by == "host"
    assert "Done: get_position" in (result.final_text or ""), result.final_text
    assert result.steps == 3 and len(model.requests) == 3 and len(result.tool_calls) == 3
    assert any(e.kind == "step_limit" for e in events)


async def test_token_accounting_per_turn_and_session(toy, scripted) -> None:
    model = scripted(
        [
            ScriptedReply(
                tool_calls=[("get_position", {"drone_id": "alpha"})],
                usage={"prompt_tokens": 100, "completion_tokens": 7, "total_tokens": 107},
            ),
            ScriptedReply(
                content="alpha is home",
                usage={"prompt_tokens": 130, "completion_tokens": 5, "total_tokens": 135},
            ),
            ScriptedReply(content="still home", usage={}),  # an endpoint that reports no usage
        ]
    )
    async with McpLink(toy.url, TOKEN) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0), link, await link.list_tools()
        )
        first = await host.run_turn("where is alpha?")
        second = await host.run_turn("and now?")
    assert (first.usage.prompt_tokens, first.usage.completion_tokens, first.usage.model_calls) == (230, 12, 2)
    assert second.usage.prompt_tokens is None and second.usage.calls_without_usage == 1
    assert (host.total_usage.prompt_tokens, host.total_usage.model_calls) == (230, 3)
    # The conversation is kept across turns.
    contents = [m.get("content") or "" for m in model.requests[2]["messages"]]
    assert any(c.endswith("where is alpha?") for c in contents) and "alpha is home" in contents
    assert contents[-1].endswith("and now?")


async def test_model_endpoint_failure_ends_the_turn_cleanly(toy, scripted) -> None:
    model = scripted([call("get_position", drone_id="alpha")])  # second request: script exhausted -> HTTP 500
    events: list[AgentEvent] = []
    _, result = await run_on_toy(toy, model, "where?", events=events)
    assert result.outcome == "model_error" and "exhausted" in (result.error or "")
    assert [e.kind for e in events if e.kind != "roster"][-3:] == ["model_error", "final", "turn_end"]
    # the host still answers from what the gateway did: the position read before the model failed
    assert result.answered_by == "host" and "Done: get_position" in (result.final_text or ""), result


async def test_bad_token_is_a_clear_error(toy) -> None:
    with pytest.raises(McpLinkError, match="cannot open an MCP session"):
        async with McpLink(toy.url, "wrong-token"):
            pass


async def test_tool_selection_by_toolset_uses_meta(toy) -> None:
    from gateway.agent.toolbox import select_tools

    async with McpLink(toy.url, TOKEN) as link:
        tools = await link.list_tools()
    assert {t.name: t.toolset for t in tools} == {
        "takeoff": "flight",
        "move_north": "navigation",
        "land": "flight",
        "get_position": "telemetry",
        "get_battery": "telemetry",
        "list_drones": "fleet",
    }
    assert {t.name for t in select_tools(tools, toolsets=["flight"])} == {"takeoff", "land"}
    assert {t.name for t in select_tools(tools, toolsets=["flight"], names=["get_position"])} == {
        "takeoff",
        "land",
        "get_position",
    }


def test_events_serialise_as_json() -> None:
    e = AgentEvent("tool_call", {"name": "land", "arguments": {"drone_id": "a"}})
    assert json.loads(json.dumps(e.to_json())) == {
        "event": "tool_call",
        "name": "land",
        "arguments": {"drone_id": "a"},
    }


async def test_interrupted_turn_keeps_the_conversation_valid(toy, scripted) -> None:
    """Ctrl-C while a tool runs: the open call gets an 'interrupted' result, and the next turn works."""
    import asyncio

    model = scripted([call("takeoff", drone_id="alpha", alt_m=15), say("alpha may still be climbing")])
    holder: list[asyncio.Task] = []
    events: list[AgentEvent] = []

    def on_event(e: AgentEvent) -> None:
        events.append(e)
        if e.kind == "progress" and holder:
            holder[0].cancel()  # as asyncio.run does on Ctrl-C

    async with McpLink(toy.url, TOKEN) as link:
        tools = await link.list_tools()
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0), link, tools, on_event=on_event
        )
        holder.append(asyncio.create_task(host.run_turn("take off alpha")))
        with pytest.raises(asyncio.CancelledError):
            await holder[0]
        holder.clear()
        assert host.messages[-1]["role"] == "tool"
        assert host.messages[-1]["tool_call_id"] == host.messages[-2]["tool_calls"][0]["id"]
        assert "Interrupted by the user" in host.messages[-1]["content"]
        assert events[-1].kind == "interrupted"
        result = await host.run_turn("what now?")
    assert result.outcome == "answered"
    assert "Interrupted by the user" in _tool_messages(model.requests[1])[-1]["content"]
