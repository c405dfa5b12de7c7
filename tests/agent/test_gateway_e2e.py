"""End to end: scripted model -> agent host -> the gateway's /mcp -> mavsdk_server -> simulated drones."""

from __future__ import annotations

import json
from collections.abc import AsyncIterator, Callable

import pytest

from bench.agent_harness.scripted import ScriptedModelServer, ScriptedReply, call, say
from bench.agent_harness.stack import LocalStack
from gateway.agent.host import AgentHost
from gateway.agent.mcp_link import McpLink, McpLinkError
from gateway.agent.turns import AgentEvent, ModelConfig, TurnResult
from gateway.fleet.geo import horizontal_distance_m, offset_position
from tests.helpers.timing import scaled

pytestmark = pytest.mark.timeout(scaled(240))


@pytest.fixture
async def stack() -> AsyncIterator[LocalStack]:
    async with LocalStack(["alpha", "bravo"], speedup=10) as s:
        yield s


async def _turn_with(
    stack: LocalStack,
    scripted: Callable[..., ScriptedModelServer],
    request: str,
    replies: list[ScriptedReply],
) -> tuple[TurnResult, list[AgentEvent], ScriptedModelServer]:
    """One turn of the host on the stack's gateway, the model replaying ``replies``."""
    model = scripted(replies)
    events: list[AgentEvent] = []
    async with McpLink(stack.mcp_url, stack.token) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0),
            link,
            await link.list_tools(),
            on_event=events.append,
        )
        return await host.run_turn(request), events, model


def _ran(result: TurnResult) -> list[tuple[str, str]]:
    return [(c.name, c.status) for c in result.tool_calls]


async def test_model_flies_takeoff_goto_land_on_the_sim(stack: LocalStack, scripted) -> None:
    truth = stack.truth()
    home_lat, home_lon, _ = (await truth.homes(["alpha"]))["alpha"]
    target = offset_position(home_lat, home_lon, 40.0, 0.0)
    replies = [
        call("takeoff", drone_id="alpha", alt_m=12),
        # A small model's text-form call (qwen style), with the arguments as a JSON string.
        ScriptedReply(
            content='<tool_call>{"name": "go_to_location", "arguments": "{\\"drone_id\\": \\"alpha\\", '
            f'\\"lat_deg\\": {target[0]}, \\"lon_deg\\": {target[1]}, '
            '\\"alt_m\\": 12}"}</tool_call>'
        ),
        call("land", drone_id="alpha"),
        say("alpha flew 40 m north and landed"),
    ]
    request = "take alpha up to 12 m, 40 m north, and land"
    result, events, model = await _turn_with(stack, scripted, request, replies)

    assert result.outcome == "answered", result
    assert [(c.name, c.status) for c in result.tool_calls] == [
        ("takeoff", "ok"),
        ("go_to_location", "ok"),
        ("land", "ok"),
    ], result.tool_calls
    assert result.tool_calls[1].parsed_from_text
    # The drone really went there: the simulator's true state.
    final = (await truth.snapshot(["alpha"]))["alpha"]
    assert horizontal_distance_m(final.lat, final.lon, *target) < 4.0, final
    assert final.landed and not final.armed, final
    # Progress notifications came while takeoff was running, and each result reached the model.
    kinds = [(e.kind, e.data.get("name")) for e in events]
    assert ("progress", "takeoff") in kinds
    assert kinds.index(("progress", "takeoff")) < kinds.index(("tool_result", "takeoff"))
    # The model was told the fleet as the gateway's list_drones reports it, and only its ids are accepted.
    first_user = [m["content"] for m in model.requests[0]["messages"] if m["role"] == "user"][-1]
    assert first_user.startswith("Fleet now: alpha on the ground, battery 100%; bravo on the ground"), (
        first_user
    )
    takeoff = next(t for t in model.requests[0]["tools"] if t["function"]["name"] == "takeoff")
    assert takeoff["function"]["parameters"]["properties"]["drone_id"]["enum"] == ["alpha", "bravo"]
    tool_msgs = [m["content"] for m in model.requests[3]["messages"] if m["role"] == "tool"]
    assert "takeoff on alpha succeeded" in tool_msgs[0]
    assert "go_to_location on alpha succeeded" in tool_msgs[1]
    assert "land on alpha succeeded" in tool_msgs[2]


async def test_small_profile_on_the_gateways_own_tools(stack: LocalStack) -> None:
    from gateway.agent.checks import unknown_arguments
    from gateway.agent.profiles import ADVANCED_ARGUMENTS, SMALL_MODEL_TOOLS, apply_profile
    from gateway.agent.toolbox import tool_list_tokens

    async with McpLink(stack.mcp_url, stack.token) as link:
        every = await link.list_tools()
    small = apply_profile(every, "small")
    assert [t.name for t in small] == list(SMALL_MODEL_TOOLS)  # the gateway offers every one of them
    for tool in small:
        assert not ADVANCED_ARGUMENTS & set(tool.input_schema.get("properties", {})), tool.name
    small_tokens, _ = tool_list_tokens(small)
    every_tokens, _ = tool_list_tokens(every)
    assert small_tokens < every_tokens / 3, (small_tokens, every_tokens)
    # what the small model is not shown it may still write: the host sends it, the gateway takes it
    # (measured on the corpus's dev half, multi-west-and-land: west_m=40 was refused as unknown)
    move = next(t for t in small if t.name == "move_to_relative")
    assert {"south_m", "west_m"} <= move.hidden
    assert unknown_arguments(small, move, {"drone_id": "alpha", "west_m": 40, "alt_m": 15}) is None
    assert unknown_arguments(small, move, {"drone_id": "alpha", "lat_deg": 47.0}) is not None


async def test_refusals_reach_the_model_and_bad_calls_never_fly(stack: LocalStack, scripted) -> None:
    truth = stack.truth()
    model = scripted(
        [
            # beyond the policy's altitude limit the schema advertises: sent, and the gateway refuses it
            call("takeoff", drone_id="bravo", alt_m=500),
            call("takeoff", drone_id="bravo", alt_m="very high"),  # the host refuses (schema)
            # the gateway refuses
            ScriptedReply(
                tool_calls=[("set_parameter", {"drone_id": "bravo", "name": "FENCE_ENABLE", "value": 0})]
            ),
            # then it keeps asking: the second identical read is answered "already done" without being
            # sent, and the step limit stops it
            call("get_position", drone_id="bravo"),
        ],
        repeat_last=True,
    )
    async with McpLink(stack.mcp_url, stack.token) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0), link, await link.list_tools(), max_steps=5
        )
        result = await host.run_turn("climb bravo to 500 m")

    assert result.outcome == "step_limit" and len(model.requests) == 5
    assert [c.status for c in result.tool_calls] == ["error", "invalid", "error", "ok", "repeat"]
    limit_msg = [m for m in model.requests[1]["messages"] if m["role"] == "tool"][-1]["content"]
    assert "Refused: max_altitude: takeoff altitude 500 m exceeds the limit of 120 m" in limit_msg, limit_msg
    schema_msg = [m for m in model.requests[2]["messages"] if m["role"] == "tool"][-1]["content"]
    assert "'very high' is not of type 'number'" in schema_msg
    refusal = [m for m in model.requests[3]["messages"] if m["role"] == "tool"][-1]["content"]
    assert "Refused: param_deny" in refusal and "FENCE_ENABLE" in refusal
    # Bravo never left the ground.
    bravo = (await truth.snapshot(["bravo"]))["bravo"]
    assert bravo.landed and not bravo.armed
    # And the gateway's /mcp wants the agent token: without it the host gets a clear error.
    with pytest.raises(McpLinkError, match="cannot open an MCP session"):
        async with McpLink(stack.mcp_url, "not-the-token"):
            pass


async def test_request_shaped_tools_take_one_or_two_model_calls(stack: LocalStack, scripted) -> None:
    """With the small profile, as a small model sees it, from the ground: a relative move at an altitude
    then a landing is two calls; a leg beyond the distance limit is one call, refused before anything
    flies, and the turn still ends with an answer saying so (here the host's, the model giving none); a
    formation where the drones are is one call."""
    from gateway.agent.answer import ANSWER_TOOL
    from gateway.agent.profiles import SMALL_MODEL_SYSTEM_PROMPT, apply_profile, host_options_for

    truth = stack.truth()
    homes = await truth.homes(["alpha", "bravo"])

    async def turn(request: str, replies: list[ScriptedReply]) -> tuple[TurnResult, ScriptedModelServer]:
        model = scripted(replies)
        async with McpLink(stack.mcp_url, stack.token) as link:
            host = AgentHost(
                ModelConfig(model.base_url, "scripted", max_retries=0),
                link,
                apply_profile(await link.list_tools(), "small"),
                system_prompt=SMALL_MODEL_SYSTEM_PROMPT,
                # the tools' shape alone: the plan step asks once more, without tools (test_planning.py)
                **{**host_options_for("small"), "plan_first": False},
            )
            return await host.run_turn(request), model

    moved, model = await turn(
        "bravo: 30 m east at 15 m, then put it down",
        [
            call("move_to_relative", drone_id="bravo", east_m=30, alt_m=15),
            call("land", drone_id="bravo"),
            call(ANSWER_TOOL, text="bravo flew 30 m east at 15 m and landed."),
        ],
    )
    assert moved.outcome == "answered" and _ran(moved) == [("move_to_relative", "ok"), ("land", "ok")], moved
    assert len(model.requests) == 3  # two calls and the answer
    bravo = (await truth.snapshot(["bravo"]))["bravo"]
    want = offset_position(homes["bravo"][0], homes["bravo"][1], 0.0, 30.0)
    assert bravo.landed and horizontal_distance_m(bravo.lat, bravo.lon, *want) < 6.0, bravo

    far, model = await turn(
        "send bravo 5 km north at 20 m",
        [call("move_to_relative", drone_id="bravo", north_m=5000, alt_m=20)]
        + [ScriptedReply(content="")] * 3,
    )
    assert _ran(far) == [("move_to_relative", "error")], far
    assert far.outcome == "answered" and far.answered_by == "host", far
    assert "max_distance" in (far.final_text or "") and "beyond the limit of 1000 m" in (far.final_text or "")
    told = [m["content"] for m in model.requests[1]["messages"] if m["role"] == "tool"][-1]
    assert "nothing was sent" in told and "Host note" not in told, told  # no "take off first" for a refusal
    bravo_now = (await truth.snapshot(["bravo"]))["bravo"]
    assert (
        bravo_now.landed
        and not bravo_now.armed
        and horizontal_distance_m(bravo_now.lat, bravo_now.lon, bravo.lat, bravo.lon) < 2.0
    ), bravo_now  # nothing flew

    before = await truth.snapshot(["alpha", "bravo"])
    centre = (sum(d.lat for d in before.values()) / 2, sum(d.lon for d in before.values()) / 2)
    # the shape the 1.5B model wrote on the corpus's dev half (form-line-here): a centre of 0, 0 for "here"
    formed, model = await turn(
        "alpha and bravo side by side, 12 m apart, at 20 m, right where they are",
        [
            call(
                "formation_goto",
                drone_ids=["alpha", "bravo"],
                formation="line",
                alt_m=20,
                center_lat_deg=0,
                center_lon_deg=0,
                north_m=0,
                east_m=0,
                spacing_m=12,
            ),
            call(ANSWER_TOOL, text="alpha and bravo fly in a line 12 m apart at 20 m."),
        ],
    )
    assert formed.outcome == "answered" and _ran(formed) == [("formation_goto", "ok")], formed
    assert len(model.requests) == 2
    now = await truth.snapshot(["alpha", "bravo"])
    a, b = now["alpha"], now["bravo"]
    assert abs(a.alt_rel_m - 20) < 2 and abs(b.alt_rel_m - 20) < 2, now
    assert abs(horizontal_distance_m(a.lat, a.lon, b.lat, b.lon) - 12.0) < 3.0, now
    mid = ((a.lat + b.lat) / 2, (a.lon + b.lon) / 2)
    assert horizontal_distance_m(*mid, *centre) < 4.0, (mid, centre)


def _text_plan(*calls: tuple[str, dict]) -> ScriptedReply:
    """A whole plan in one reply, written as text the way the 1.5B model writes it (doubled braces)."""
    return ScriptedReply(
        content="\n".join("{" + json.dumps({"name": n, "arguments": a}) + "}" for n, a in calls)
    )


async def test_a_small_models_plan_with_zero_zero_for_up_flies_as_meant(stack: LocalStack, scripted) -> None:
    """The measured first reply to "go up to 15 m, fly 60 m north, land": go_to_location(0, 0, 15) is read as
    the takeoff, and the rest of the plan runs in the same reply."""
    truth = stack.truth()
    home = (await truth.homes(["alpha"]))["alpha"]
    plan = _text_plan(
        ("go_to_location", {"drone_id": "alpha", "lat_deg": 0, "lon_deg": 0, "alt_m": 12}),
        ("move_to_relative", {"drone_id": "alpha", "north_m": 30, "east_m": 0, "up_m": 0}),
        ("land", {"drone_id": "alpha"}),
    )
    request = "Alpha: go up to 12 m, fly 30 metres north, and land there."
    result, events, model = await _turn_with(stack, scripted, request, [plan, say("alpha flew 30 m north")])
    assert result.outcome == "answered", result
    assert _ran(result) == [("takeoff", "ok"), ("move_to_relative", "ok"), ("land", "ok")], result
    corrected = [e.data["notes"] for e in events if e.kind == "arguments_corrected"]
    assert corrected == [
        ["go_to_location(0, 0, 12 m) read as takeoff to 12 m: alpha is on the ground and the request names "
         "no point 0, 0"]
    ]  # fmt: skip
    told = [m["content"] for m in model.requests[1]["messages"] if m["role"] == "tool"]
    assert (
        told[0].startswith("takeoff on alpha succeeded")
        and "(Host note: go_to_location(0, 0, 12 m)" in told[0]
    )
    final = (await truth.snapshot(["alpha"]))["alpha"]
    north = horizontal_distance_m(final.lat, final.lon, *offset_position(home[0], home[1], 30.0, 0.0))
    assert north < 6.0 and final.landed and not final.armed, (north, final)


async def test_a_zero_zero_formation_before_each_drones_own_move_is_left_out(
    stack: LocalStack, scripted
) -> None:
    """The measured plan for "take off alpha and bravo, fly them in a line 100 m north, then land"."""
    truth = stack.truth()
    homes = await truth.homes(["alpha", "bravo"])
    formation = {
        "drone_ids": ["alpha", "bravo"],
        "formation": "line",
        "center_lat_deg": 0,
        "center_lon_deg": 0,
        "alt_m": 10,
        "spacing_m": 20,
    }
    plan = _text_plan(
        ("takeoff", {"drone_id": "alpha", "alt_m": 10}),
        ("takeoff", {"drone_id": "bravo", "alt_m": 10}),
        ("formation_goto", formation),
        ("move_to_relative", {"drone_id": "alpha", "north_m": 20, "east_m": 0, "up_m": 0}),
        ("move_to_relative", {"drone_id": "bravo", "north_m": 20, "east_m": 0, "up_m": 0}),
    )
    request = "Take off alpha and bravo to 10 m, fly them in a line 20 m north."
    result, _, model = await _turn_with(stack, scripted, request, [plan, say("both are 20 m north")])
    assert result.outcome == "answered", result
    assert _ran(result) == [
        ("takeoff", "ok"),
        ("takeoff", "ok"),
        ("formation_goto", "left_out"),
        ("move_to_relative", "ok"),
        ("move_to_relative", "ok"),
    ], result.tool_calls
    told = [m["content"] for m in model.requests[1]["messages"] if m["role"] == "tool"]
    assert told[2].startswith("Left out: formation_goto centred on 0, 0 left out") and "goes on" in told[2]
    final = await truth.snapshot(["alpha", "bravo"])
    for d in ("alpha", "bravo"):
        want = offset_position(homes[d][0], homes[d][1], 20.0, 0.0)
        assert horizontal_distance_m(final[d].lat, final[d].lon, *want) < 6.0, (d, final[d])


async def test_coordinates_written_as_metres_go_to_that_point_and_the_refusal_is_the_answer(
    stack: LocalStack, scripted
) -> None:
    """A far point given as move_to_relative metres is read as go_to_location there; the gateway refuses the
    distance, and the model's answer copying that refusal ends the turn (after a re-prompt that quoted it)."""
    truth = stack.truth()
    home = (await truth.homes(["bravo"]))["bravo"]
    far = offset_position(home[0], home[1], 5000.0, 0.0)
    request = f"Send bravo at 10 m to {far[0]:.6f}, {far[1]:.6f}, that's the farm 5 km north."
    refusal = "Refused: max_distance: target is 5000 m from home, beyond the limit of 1000 m"
    metres = {"drone_id": "bravo", "north_m": 0, "east_m": round(far[0], 6), "up_m": round(far[1], 6)}
    plan = _text_plan(
        ("takeoff", {"drone_id": "bravo", "alt_m": 10}),
        ("move_to_relative", metres),
        ("land", {"drone_id": "bravo"}),
    )
    replies = [plan, ScriptedReply(content=""), say(refusal)]
    result, _, model = await _turn_with(stack, scripted, request, replies)
    assert result.outcome == "answered" and result.final_text == refusal, result
    assert _ran(result) == [("takeoff", "ok"), ("go_to_location", "error"), ("land", "skipped")], result
    went = result.tool_calls[1].arguments or {}
    assert (went["lat_deg"], went["lon_deg"]) == (round(far[0], 6), round(far[1], 6))
    told = [m["content"] for m in model.requests[1]["messages"] if m["role"] == "tool"][1]
    assert told.startswith(f"Error: {refusal}") and "not metres" in told
    assert "is on the ground" not in told  # the takeoff earlier in the same reply is known (fresh roster)
    reprompt = [m["content"] for m in model.requests[2]["messages"] if m["role"] == "user"][-1]
    assert f"Refused (cannot be done, do not retry): go_to_location: {refusal}" in reprompt
    assert "If every part of the request is done or refused" in reprompt
    bravo = (await truth.snapshot(["bravo"]))["bravo"]
    assert horizontal_distance_m(bravo.lat, bravo.lon, home[0], home[1]) < 10.0, bravo


async def test_stack_moves_on_when_its_port_is_taken(monkeypatch) -> None:
    """A port picked free can be taken before the gateway binds it: the stack must not talk to the
    squatter, it must notice its own gateway failed to bind and use another port."""
    import socket

    from gateway import localstack as stack_module

    squatter = socket.socket()
    squatter.bind(("127.0.0.1", 0))
    squatter.listen()
    taken = squatter.getsockname()[1]
    real = stack_module.free_tcp_port
    ports = iter([taken])
    monkeypatch.setattr(stack_module, "free_tcp_port", lambda: next(ports, None) or real())
    try:
        async with LocalStack(["alpha"], speedup=10) as s:
            assert s.api_url != f"http://127.0.0.1:{taken}"
            async with McpLink(s.mcp_url, s.token) as link:
                assert "takeoff" in {t.name for t in await link.list_tools()}
    finally:
        squatter.close()
