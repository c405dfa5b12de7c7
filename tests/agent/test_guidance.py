"""What keeps a small model on track, over real HTTP (scripted endpoint, toy MCP server): the roster, drone
ids as an enum, empty replies asked again, repeated calls not sent twice, the closest tool suggested."""

from __future__ import annotations

import argparse
import io
from typing import Any

from rich.console import Console

from bench.agent_harness.scripted import ScriptedModelServer, ScriptedReply, call, say
from gateway.agent import cli
from gateway.agent.host import AgentHost
from gateway.agent.mcp_link import McpLink
from gateway.agent.turns import AgentEvent, ModelConfig, TurnResult
from tests.agent.toy_mcp import TOKEN, ToyServer

EMPTY = ScriptedReply(content="")


def _tool_texts(request: dict[str, Any]) -> list[str]:
    return [m["content"] for m in request["messages"] if m["role"] == "tool"]


def _user_texts(request: dict[str, Any]) -> list[str]:
    return [m["content"] for m in request["messages"] if m["role"] == "user"]


async def _turn(
    toy: ToyServer, model: ScriptedModelServer, prompt: str, events: list[AgentEvent] | None = None
) -> TurnResult:
    async with McpLink(toy.url, TOKEN) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0),
            link,
            await link.list_tools(),
            on_event=events.append if events is not None else None,
        )
        return await host.run_turn(prompt)


# --- roster ----------------------------------------------------------------------------------------


async def test_the_model_is_told_the_fleet_before_the_request_and_after_each_step(toy, scripted) -> None:
    model = scripted([call("takeoff", drone_id="alpha", alt_m=15), say("alpha is up")])
    result = await _turn(toy, model, "take alpha up to 15 m")
    assert result.outcome == "answered"
    first_user = _user_texts(model.requests[0])[-1]
    assert first_user == (
        "Fleet now: alpha on the ground, battery 90%; bravo on the ground, battery 90%.\n\n"
        "take alpha up to 15 m"
    )
    after_takeoff = _tool_texts(model.requests[1])[-1]
    assert after_takeoff.endswith(
        "Fleet now: alpha flying at 15 m, battery 90%; bravo on the ground, battery 90%."
    )
    # The system prompt and the tool list are the same in every request (a server's prompt cache holds).
    assert model.requests[0]["messages"][0] == model.requests[1]["messages"][0]
    assert model.requests[0]["tools"] == model.requests[1]["tools"]


async def test_a_server_without_list_drones_gets_no_roster(toy, scripted) -> None:
    model = scripted([call("land", drone_id="alpha"), say("landed")])
    events: list[AgentEvent] = []
    async with McpLink(toy.url, TOKEN) as link:
        tools = [t for t in await link.list_tools() if t.name != "list_drones"]
        toy.mcp.remove_tool("list_drones")
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0), link, tools, on_event=events.append
        )
        result = await host.run_turn("land alpha")
    assert result.outcome == "answered"
    assert _user_texts(model.requests[0])[-1] == "land alpha"
    assert "enum" not in str(model.requests[0]["tools"])
    assert [e.data["available"] for e in events if e.kind == "roster"] == [False]  # asked once only


# --- drone ids ---------------------------------------------------------------------------------------


async def test_drone_ids_are_an_enum_and_an_invented_id_is_refused_before_any_call(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="drone1", alt_m=10),
            call("takeoff", drone_id="Alpha", alt_m=10),  # right id, wrong case: corrected
            say("alpha is up"),
        ]
    )
    events: list[AgentEvent] = []
    result = await _turn(toy, model, "take off the first drone to 10 m", events)
    takeoff = next(t for t in model.requests[0]["tools"] if t["function"]["name"] == "takeoff")
    assert takeoff["function"]["parameters"]["properties"]["drone_id"]["enum"] == ["alpha", "bravo"]
    assert [c.status for c in result.tool_calls] == ["invalid", "ok"]
    refused = _tool_texts(model.requests[1])[-1]
    assert "'drone1' is not one of ['alpha', 'bravo']" in refused and "Nothing was executed" in refused
    assert toy.world.calls == [("takeoff", {"drone_id": "alpha", "alt_m": 10.0})]
    corrected = [e.data["notes"] for e in events if e.kind == "arguments_corrected"]
    assert corrected == [["drone id 'Alpha' read as 'alpha'"]]


async def test_an_argument_the_tool_does_not_have_is_refused(toy, scripted) -> None:
    model = scripted([call("takeoff", drone_id="alpha", alt_m=10, lat_deg=-35.36), say("no")])
    result = await _turn(toy, model, "take off alpha")
    assert [c.status for c in result.tool_calls] == ["invalid"] and toy.world.calls == []
    assert _tool_texts(model.requests[1])[-1].startswith(
        "Error: takeoff has no argument lat_deg; it takes takeoff(drone_id: string, alt_m: number)."
    )


def test_down_m_is_named_as_the_up_m_the_tool_has() -> None:
    """down_m is retired (gateway/mcp/naming.py): "10 m lower" as down_m=10 is told it is up_m=-10."""
    from gateway.agent.checks import unknown_arguments
    from gateway.agent.toolbox import ToolInfo

    props = {n: {"type": "number"} for n in ("north_m", "east_m", "up_m", "south_m", "west_m")}
    move = ToolInfo("move_to_relative", "m", {"type": "object", "properties": {"drone_id": {}, **props}})
    assert unknown_arguments([move], move, {"drone_id": "alpha", "west_m": 40, "south_m": 5}) is None
    text = unknown_arguments([move], move, {"drone_id": "alpha", "down_m": 10})
    assert text is not None
    assert text.startswith("move_to_relative has no argument down_m (down_m=10 is up_m=-10);")


# --- empty replies -----------------------------------------------------------------------------------


async def test_an_empty_reply_is_asked_again_with_the_request_and_what_was_done(toy, scripted) -> None:
    model = scripted([call("takeoff", drone_id="alpha", alt_m=15), EMPTY, call("land", drone_id="alpha"),
                      say("alpha went up to 15 m and landed")])  # fmt: skip
    result = await _turn(toy, model, "hop alpha to 15 m, then land it")
    assert result.outcome == "answered" and result.empty_replies == 1
    assert [name for name, _ in toy.world.calls] == ["takeoff", "land"]
    nudge = _user_texts(model.requests[2])[-1]
    assert nudge.startswith("Your reply was empty.")
    assert "The request: hop alpha to 15 m, then land it" in nudge
    assert "Already done (do not repeat): takeoff: status=reached." in nudge  # in words, no call to echo
    assert "Fleet now: alpha flying at 15 m" in nudge
    # The empty reply itself is not kept in the conversation.
    assert not any(
        m["role"] == "assistant" and not m.get("tool_calls") for m in model.requests[2]["messages"]
    )


async def test_three_empty_replies_end_the_turn_as_empty_answer(toy, scripted) -> None:
    model = scripted([EMPTY, ScriptedReply(content="  \n"), ScriptedReply(content="<think>hmm</think>")])
    events: list[AgentEvent] = []
    result = await _turn(toy, model, "land bravo", events)
    assert result.outcome == "empty_answer" and result.answered_by == "host"
    assert (result.final_text or "").startswith("(Answer from the host"), result.final_text
    assert "Nothing was done" in result.final_text
    assert len(model.requests) == 3 and result.empty_replies == 3
    assert "Already done (do not repeat): nothing yet." in _user_texts(model.requests[1])[-1]
    assert [e.kind for e in events if e.kind != "roster"][-3:] == ["empty_answer", "final", "turn_end"]
    assert events[-2].data["via"] == "host"


async def test_the_count_of_empty_replies_starts_again_once_the_model_acts(toy, scripted) -> None:
    # Measured: the 1.5B model answers a re-prompt with the next step and then falls silent again after
    # its result; the step limit, not an old count, bounds a model that keeps making progress.
    takeoff, land = call("takeoff", drone_id="alpha", alt_m=15), call("land", drone_id="alpha")
    model = scripted([takeoff, EMPTY, EMPTY, land, EMPTY, EMPTY, say("alpha went up to 15 m and landed")])
    events: list[AgentEvent] = []
    result = await _turn(toy, model, "hop alpha to 15 m, then land it", events)
    assert result.outcome == "answered" and result.empty_replies == 4
    assert [e.data["attempt"] for e in events if e.kind == "empty_reply"] == [1, 2, 1, 2]


async def test_a_refusal_is_named_in_the_re_prompt_and_copying_it_is_an_answer(toy, scripted) -> None:
    refusal = "refused by rule max_altitude: target altitude 500 m exceeds the limit of 120 m above home"
    model = scripted([call("takeoff", drone_id="alpha", alt_m=500), EMPTY, say(refusal)])
    result = await _turn(toy, model, "climb alpha to 500 m", [])
    assert result.outcome == "answered" and result.final_text == refusal
    nudge = _user_texts(model.requests[2])[-1]
    said = f"Refused (cannot be done, do not retry): takeoff: Error executing tool takeoff: {refusal}."
    assert said in nudge
    assert "If every part of the request is done or refused, reply with one sentence for the user saying " \
        "what was done and what was refused." in nudge  # fmt: skip


async def test_an_error_the_model_can_correct_is_not_named_a_refusal_in_the_re_prompt(toy, scripted) -> None:
    model = scripted(
        [call("move_north", drone_id="alpha", distance_m=20), EMPTY, say("alpha is on the ground")]
    )
    await _turn(toy, model, "fly alpha 20 m north", [])
    nudge = _user_texts(model.requests[2])[-1]
    assert "Refused" not in nudge and "If every part of the request is done, reply" in nudge


async def test_the_command_exits_non_zero_on_an_empty_answer(toy, scripted) -> None:
    model = scripted([EMPTY], repeat_last=True)
    parser = argparse.ArgumentParser()
    cli.register(parser.add_subparsers(dest="command"))
    args = parser.parse_args(["agent", "--mcp-url", toy.url, "--token", TOKEN, "--endpoint",
                              model.base_url, "--model", "m", "land alpha"])  # fmt: skip
    buf = io.StringIO()
    console = Console(file=buf, force_terminal=False, width=200, color_system=None)
    assert await cli.run_async(args, console=console) == cli.EXIT_EMPTY_ANSWER
    assert "no answer" in buf.getvalue() and len(model.requests) == 3


# --- repeated calls ----------------------------------------------------------------------------------


async def test_a_call_identical_to_one_that_just_succeeded_is_not_sent_again(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=15),
            call("get_position", drone_id="alpha"),  # reading in between does not make it new
            call("takeoff", drone_id="alpha", alt_m=15),
            call("land", drone_id="alpha"),
            say("done"),
        ]
    )
    result = await _turn(toy, model, "take off alpha to 15 m and land")
    assert [c.status for c in result.tool_calls] == ["ok", "ok", "repeat", "ok"]
    assert [name for name, _ in toy.world.calls] == ["takeoff", "land"]
    told = _tool_texts(model.requests[3])[-1]
    assert told.startswith("Not sent again: this takeoff call already succeeded in this request")
    assert "The request: take off alpha to 15 m and land" in told and "next step" in told


async def test_a_plan_with_the_same_action_twice_stops_at_the_second(toy, scripted) -> None:
    """Measured on the corpus's dev half (compound-two-climbs): "up to 10 m, then another 10 m higher, then
    land" was planned as takeoff(10), takeoff(10), land; the landing flew and the climb never did."""
    takeoff = ("takeoff", {"drone_id": "alpha", "alt_m": 10})
    model = scripted(
        [
            ScriptedReply(tool_calls=[takeoff, takeoff, ("land", {"drone_id": "alpha"})]),
            call("move_north", drone_id="alpha", distance_m=10),
            call("land", drone_id="alpha"),
            say("alpha went up to 10 m, 10 m north, and landed"),
        ]
    )
    result = await _turn(toy, model, "take alpha up to 10 m, then 10 m north, then land it")
    assert [(c.name, c.status) for c in result.tool_calls][:3] == [
        ("takeoff", "ok"),
        ("takeoff", "repeat"),
        ("land", "skipped"),
    ]
    assert _tool_texts(model.requests[1])[-1].startswith(
        "Not executed: the earlier call takeoff in the same reply repeats a step it already did"
    )
    assert [name for name, _ in toy.world.calls] == ["takeoff", "move_north", "land"]
    assert result.outcome == "answered"


async def test_the_third_time_a_done_call_comes_back_the_model_is_told_to_stop(toy, scripted) -> None:
    """Measured on the dev half (compound-two-climbs): the same finished move sent eight times in a row."""
    model = scripted([call("takeoff", drone_id="alpha", alt_m=10)] * 4 + [say("alpha is at 10 m")])
    result = await _turn(toy, model, "take alpha up to 10 m")
    assert [c.status for c in result.tool_calls] == ["ok", "repeat", "repeat", "repeat"]
    texts = [_tool_texts(model.requests[i])[-1] for i in (2, 3, 4)]
    assert ["third time this same call came back" in t for t in texts] == [False, False, True]
    assert [name for name, _ in toy.world.calls] == ["takeoff"]


async def test_the_same_call_after_another_action_on_that_drone_is_sent(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call("land", drone_id="alpha"),
            call("takeoff", drone_id="alpha", alt_m=10),  # a second hop: wanted
            call("takeoff", drone_id="bravo", alt_m=10),
            call("takeoff", drone_id="alpha", alt_m=10),  # bravo's takeoff changed nothing for alpha
            say("done"),
        ]
    )
    result = await _turn(toy, model, "hop alpha twice, then bravo up")
    assert [c.status for c in result.tool_calls] == ["ok", "ok", "ok", "ok", "repeat"]
    assert [(n, a["drone_id"]) for n, a in toy.world.calls] == [
        ("takeoff", "alpha"), ("land", "alpha"), ("takeoff", "alpha"), ("takeoff", "bravo")]  # fmt: skip


async def test_a_call_that_failed_may_be_tried_again(toy, scripted) -> None:
    model = scripted(
        [call("move_north", drone_id="alpha", distance_m=20)] * 2 + [say("alpha is on the ground")]
    )
    result = await _turn(toy, model, "move alpha 20 m north")
    assert [c.status for c in result.tool_calls] == ["error", "error"]
    assert len(toy.world.calls) == 2


# --- unknown tools -----------------------------------------------------------------------------------


async def test_an_unknown_tool_gets_the_closest_one_and_firmer_when_repeated(toy, scripted) -> None:
    model = scripted(
        [
            call("get_location", drone_id="alpha"),
            call("get_location", drone_id="alpha"),
            call("fly_north", drone_id="alpha", distance_m=5),
            say("stuck"),
        ]
    )
    result = await _turn(toy, model, "where is alpha, then fly it north")
    assert [c.status for c in result.tool_calls] == ["unknown_tool"] * 3
    first, second, third = (_tool_texts(model.requests[i])[-1] for i in (1, 2, 3))
    assert "unknown tool 'get_location'. The closest tool is get_position(drone_id: string)" in first
    assert "'get_location' does not exist; you called it again. Use get_position(drone_id: string)" in second
    assert "The closest tool is move_north(drone_id: string, distance_m: number)" in third
    assert toy.world.calls == []


# --- several calls in one reply ------------------------------------------------------------------------


async def test_after_a_failed_call_the_rest_of_the_reply_is_not_sent(toy, scripted) -> None:
    plan = ScriptedReply(
        tool_calls=[
            ("move_north", {"drone_id": "alpha", "distance_m": 60}),  # on the ground: refused
            ("land", {"drone_id": "alpha"}),
        ]
    )
    model = scripted([plan, say("alpha must take off first")])
    result = await _turn(toy, model, "fly alpha 60 m north and land")
    assert [c.status for c in result.tool_calls] == ["error", "skipped"]
    assert [name for name, _ in toy.world.calls] == ["move_north"]
    skipped = _tool_texts(model.requests[1])[-1]
    assert skipped.startswith("Not executed: the earlier call move_north in the same reply failed.")


async def test_the_third_identical_refused_call_is_told_to_stop(toy, scripted) -> None:
    model = scripted([call("land")] * 3 + [say("land needs a drone id; nothing was done")])
    result = await _turn(toy, model, "land")
    assert [c.status for c in result.tool_calls] == ["invalid"] * 3
    texts = [_tool_texts(model.requests[i])[-1] for i in (1, 2, 3)]
    assert ["third time" in t for t in texts] == [False, False, True]
    assert "Stop calling it: answer in words, saying what was done and what was refused." in texts[2]


async def test_the_third_refusal_for_the_same_reason_is_told_to_stop(toy, scripted) -> None:
    """Measured on the dev half (refuse-all-150m): 150 m asked five times, for three drones, after the
    first refusal; the calls differ, the gateway's reason does not."""
    model = scripted(
        [call("takeoff", drone_id=d, alt_m=150) for d in ("alpha", "bravo", "alpha")]
        + [say("The gateway refused 150 m: the limit is 120 m.")]
    )
    result = await _turn(toy, model, "send both up to 150 m")
    assert [c.status for c in result.tool_calls] == ["error"] * 3
    texts = [_tool_texts(model.requests[i])[-1] for i in (1, 2, 3)]
    assert ["the gateway refused this, for the same reason" in t for t in texts] == [False, False, True]
    assert "Stop asking: answer in words" in texts[2]


async def test_a_refused_move_of_a_grounded_drone_names_the_takeoff_with_its_altitude() -> None:
    from gateway.agent.roster import DroneEntry, Roster

    host = AgentHost(ModelConfig("http://127.0.0.1:9/v1", "m"), caller=None, tools=[])  # type: ignore[arg-type]
    host.fleet.enabled = False  # the roster below is the fleet (reading it again is tested on the gateway)
    host.fleet.roster = Roster(
        (DroneEntry("bravo", False, 0.0, 100.0), DroneEntry("alpha", True, 10.0, 90.0))
    )
    note = await host.sender.takeoff_first("go_to_location", {"drone_id": "bravo", "alt_m": 30})
    assert note == (
        ' (Host note: bravo is on the ground. Call takeoff with drone_id "bravo" and alt_m 30 first, '
        "then this call again.)"
    )
    flying = await host.sender.takeoff_first("go_to_location", {"drone_id": "alpha", "alt_m": 30})
    assert flying == ""  # alpha flies
    assert await host.sender.takeoff_first("takeoff", {"drone_id": "bravo", "alt_m": 500}) == ""


async def test_calls_skipped_after_a_failure_are_shown_as_still_to_do_until_they_run(toy, scripted) -> None:
    plan = ScriptedReply(
        tool_calls=[("move_north", {"drone_id": "alpha", "distance_m": 60}), ("land", {"drone_id": "alpha"})]
    )
    model = scripted(
        [
            plan,
            call("takeoff", drone_id="alpha", alt_m=10),
            call("move_north", drone_id="alpha", distance_m=60),
            call("land", drone_id="alpha"),
            say("done"),
        ]
    )
    result = await _turn(toy, model, "fly alpha 60 m north and land")
    assert [c.status for c in result.tool_calls] == ["error", "skipped", "ok", "ok", "ok"]
    after_failure, after_takeoff, after_move, after_land = (
        _tool_texts(model.requests[i])[-1] for i in (1, 2, 3, 4)
    )
    assert "Not sent yet" not in after_failure  # the failure itself is the news
    # The failed call is not repeated for the model (it may be the mistake); the skipped ones wait.
    pending = "Not sent yet from your earlier reply (their turn comes after the call that failed):\n"
    assert pending + '{"name": "land", "arguments": {"drone_id": "alpha"}}' in after_takeoff
    assert "move_north" not in after_takeoff.split("Not sent yet")[1]
    assert pending in after_move
    assert "Not sent yet" not in after_land


async def test_a_reply_that_repeats_the_request_is_not_an_answer(toy, scripted) -> None:
    prompt = "hop alpha to 15 m, then land it"
    model = scripted([call("takeoff", drone_id="alpha", alt_m=15), say(prompt),
                      call("land", drone_id="alpha"), say("alpha went up to 15 m and landed")])  # fmt: skip
    events: list[AgentEvent] = []
    result = await _turn(toy, model, prompt, events)
    assert result.outcome == "answered" and result.final_text == "alpha went up to 15 m and landed"
    assert result.empty_replies == 1
    assert [e.data["text"] for e in events if e.kind == "echo_reply"] == [prompt]
    nudge = _user_texts(model.requests[2])[-1]
    assert nudge.startswith("Your reply only repeated the request or my note; that is not an answer.")
    assert [name for name, _ in toy.world.calls] == ["takeoff", "land"]


async def test_the_nudge_names_a_drone_of_the_request_nothing_was_done_with(toy, scripted) -> None:
    model = scripted([call("takeoff", drone_id="alpha", alt_m=10), EMPTY,
                      call("takeoff", drone_id="bravo", alt_m=10), say("both are up")])  # fmt: skip
    result = await _turn(toy, model, "take off alpha and bravo to 10 m", [])
    assert result.outcome == "answered"
    nudge = _user_texts(model.requests[2])[-1]
    assert "The request names bravo, and nothing has been done with it yet." in nudge
    assert [args["drone_id"] for _, args in toy.world.calls] == ["alpha", "bravo"]


# --- every turn ends with an answer; finished steps are not flown again -------------------------------


async def test_a_model_that_stops_after_acting_is_answered_for_by_the_host(toy, scripted) -> None:
    """Flown right, then no answer (empty replies): the host answers from the gateway's results, marked
    as its own, and the turn counts as answered (exit status 0)."""
    model = scripted([call("takeoff", drone_id="alpha", alt_m=12), EMPTY, EMPTY, EMPTY])
    events: list[AgentEvent] = []
    result = await _turn(toy, model, "alpha up to 12 m please", events)
    assert result.outcome == "answered" and result.answered_by == "host", result
    text = result.final_text or ""
    assert text.startswith("(Answer from the host, from the gateway's results"), text
    assert "Done: takeoff (" in text and "alpha flying at 12 m" in text, text
    final = next(e for e in events if e.kind == "final")
    assert final.data["via"] == "host"


async def test_a_short_echo_of_the_hosts_note_is_no_answer(toy, scripted) -> None:
    """Measured: "Nothing yet." (the re-prompt's "Already done: nothing yet") ended a turn as its answer."""
    model = scripted([EMPTY, say("Nothing yet."), call("land", drone_id="bravo"), say("bravo landed.")])
    result = await _turn(toy, model, "land bravo", None)
    assert result.outcome == "answered" and result.final_text == "bravo landed.", result
    assert result.answered_by == "model" and result.empty_replies == 2


async def test_the_roster_line_given_back_is_no_answer(toy, scripted) -> None:
    """Measured on the dev half (cond-above-forty-hop): the host's "Fleet now: ..." line as the answer."""
    roster = "Fleet now: alpha on the ground, battery 90%; bravo on the ground, battery 90%."
    model = scripted([call("get_position", drone_id="alpha"), say(roster), say("alpha is on the ground.")])
    result = await _turn(toy, model, "where is alpha?", None)
    assert result.outcome == "answered" and result.final_text == "alpha is on the ground.", result
    assert result.empty_replies == 1


async def test_a_finished_step_is_not_flown_again_unless_the_request_asks(toy, scripted) -> None:
    """Out, back and landed, then the model starts over: the same takeoff is not sent again; with "again"
    in the request it is."""
    plan = [
        call("takeoff", drone_id="alpha", alt_m=10),
        call("move_north", drone_id="alpha", distance_m=30),
        call("move_north", drone_id="alpha", distance_m=-30),
        call("land", drone_id="alpha"),
        call("takeoff", drone_id="alpha", alt_m=10),
        say("alpha is back on the ground where it took off."),
    ]
    result = await _turn(
        toy, scripted(plan), "alpha: 30 m north at 10 m, then back and land where it started"
    )
    assert [c.status for c in result.tool_calls] == ["ok", "ok", "ok", "ok", "repeat"], result.tool_calls
    assert "already ran earlier in this request" in result.tool_calls[-1].text
    assert toy.world.calls[-1][0] == "land"
    again = await _turn(toy, scripted(plan), "alpha: 30 m north at 10 m, back, land, then do it all again")
    assert [c.status for c in again.tool_calls][-1] == "ok", again.tool_calls


async def test_a_drone_landed_as_the_request_ends_is_not_taken_up_again(toy, scripted) -> None:
    """The landing was the request's last step: another takeoff (other arguments) is held back once; the
    same call sent again goes through (the model may know better)."""
    plan = [
        call("takeoff", drone_id="alpha", alt_m=10),
        call("move_north", drone_id="alpha", distance_m=20),
        call("land", drone_id="alpha"),
        call("takeoff", drone_id="alpha", alt_m=12),
        call("takeoff", drone_id="alpha", alt_m=12),
        say("alpha flew 20 m north and landed."),
    ]
    result = await _turn(toy, scripted(plan), "alpha: up to 10 m, 20 m north, then set it down there")
    assert [c.status for c in result.tool_calls] == ["ok", "ok", "ok", "repeat", "ok"], result.tool_calls
    assert "alpha already came down as the request's last step asks" in result.tool_calls[3].text
    ongoing = await _turn(
        toy, scripted(plan[:5]), "alpha: up to 10 m, 20 m north, land, then take off to 12 m"
    )
    assert [c.status for c in ongoing.tool_calls][:4] == ["ok", "ok", "ok", "ok"], ongoing.tool_calls


def test_the_hosts_answer_tells_a_refusal_from_a_call_that_failed() -> None:
    """Measured on the dev half (multi-two-heights): "alpha is on the ground; say how high to fly" was
    reported as something the gateway refused."""
    from gateway.agent.turns import ToolCallRecord
    from gateway.agent.wording import answer_from_results

    mistake = "Error: alpha is on the ground; say how high to fly"
    rule = "Error: Refused: max_altitude: 150 m exceeds the limit of 120 m"
    failed = ToolCallRecord("1", "move_to_relative", {"drone_id": "alpha"}, "error", "s", text=mistake)
    refused = ToolCallRecord("2", "takeoff", {"drone_id": "bravo"}, "error", "s", text=rule)
    result = TurnResult(outcome="empty_answer", final_text=None, steps=3, tool_calls=[failed, refused])
    text = answer_from_results(result, "alpha to 10 m, bravo to 150 m", None)
    assert "Not done, the gateway refused: takeoff: Refused: max_altitude: 150 m exceeds" in text
    assert "Not done, the call failed: move_to_relative: alpha is on the ground; say how high" in text
