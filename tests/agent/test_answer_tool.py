"""The host's answer_user tool: how a small model ends a turn (a scripted model, a real toy MCP server)."""

from __future__ import annotations

from typing import Any

from bench.agent_harness.scripted import ScriptedModelServer, ScriptedReply, call, say
from gateway.agent.answer import ANSWER_TOOL, answer_text
from gateway.agent.host import AgentHost
from gateway.agent.turns import AgentEvent
from tests.agent.test_loop import run_on_toy
from tests.agent.toy_mcp import ToyServer


async def _run(
    toy: ToyServer, model: ScriptedModelServer, prompt: str, events: list[AgentEvent] | None = None
) -> tuple[AgentHost, Any]:
    return await run_on_toy(toy, model, prompt, events=events, answer_tool=True)


def _last_tool_text(request: dict[str, Any]) -> str:
    return [m for m in request["messages"] if m["role"] == "tool"][-1]["content"]


async def test_the_model_is_offered_answer_user_and_calling_it_ends_the_turn_with_its_text(
    toy, scripted
) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call("land", drone_id="alpha"),
            call(ANSWER_TOOL, text="Alpha went up to 10 m and landed."),
        ]
    )
    events: list[AgentEvent] = []
    _, result = await _run(toy, model, "take off alpha to 10 m, then land it", events)

    assert ANSWER_TOOL in {t["function"]["name"] for t in model.requests[0]["tools"]}
    assert result.outcome == "answered"
    assert result.final_text == "Alpha went up to 10 m and landed."
    # The answer is the host's, never a gateway call.
    assert [c.name for c in result.tool_calls] == ["takeoff", "land"]
    assert ANSWER_TOOL not in [c[0] for c in toy.world.calls]
    assert len(model.requests) == 3  # nothing asked after the answer
    assert [e.data.get("via") for e in events if e.kind == "final"] == [ANSWER_TOOL]


async def test_an_answer_written_as_text_in_the_same_reply_as_the_last_call_ends_the_turn(
    toy, scripted
) -> None:
    model = scripted(
        [
            say(
                '{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 5}}\n'
                '{"name": "answer_user", "arguments": {"text": "Alpha is hovering at 5 m."}}'
            )
        ]
    )
    _, result = await _run(toy, model, "take off alpha to 5 m")
    assert result.outcome == "answered" and result.final_text == "Alpha is hovering at 5 m."
    assert [(c.name, c.status) for c in result.tool_calls] == [("takeoff", "ok")]
    assert toy.world.drones["alpha"].alt_m == 5.0


async def test_an_answer_after_a_failed_call_of_the_same_reply_is_not_taken(toy, scripted) -> None:
    model = scripted(
        [
            ScriptedReply(
                tool_calls=[
                    ("takeoff", '{"drone_id": "alpha", "alt_m": 500}'),
                    (ANSWER_TOOL, '{"text": "Alpha is at 500 m."}'),
                ]
            ),
            call(ANSWER_TOOL, text="The gateway refused 500 m: the limit is 120 m above home."),
        ]
    )
    _, result = await _run(toy, model, "climb alpha to 500 m")
    assert [(c.name, c.status) for c in result.tool_calls] == [("takeoff", "error"), (ANSWER_TOOL, "skipped")]
    assert result.final_text == "The gateway refused 500 m: the limit is 120 m above home."


async def test_an_answer_written_before_a_refusal_is_not_believed_when_sent_again_unchanged(
    toy, scripted
) -> None:
    plan = ScriptedReply(
        tool_calls=[
            ("takeoff", '{"drone_id": "alpha", "alt_m": 500}'),
            (ANSWER_TOOL, '{"text": "Alpha is at 500 m."}'),
        ]
    )
    refused = "500 m was refused: the limit is 120 m."
    model = scripted([plan, call(ANSWER_TOOL, text="Alpha is at 500 m."), call(ANSWER_TOOL, text=refused)])
    _, result = await _run(toy, model, "climb alpha to 500 m")
    told = _last_tool_text(model.requests[2])
    assert told.startswith("Not an answer: you wrote it with your plan, before the results; it was not sent.")
    assert "refused: takeoff: Error executing tool takeoff: refused by rule max_altitude" in told
    assert result.outcome == "answered" and result.final_text == refused


async def test_an_answer_that_quotes_the_gateways_refusal_is_an_answer_even_inside_a_host_note(
    toy, scripted
) -> None:
    refusal = "refused by rule max_altitude: target altitude 500 m exceeds the limit of 120 m above home"
    # the re-prompt's own line, copied: a host note, and yet it tells the user what was refused
    quoting = f"Refused (cannot be done, do not retry): takeoff: Error executing tool takeoff: {refusal}."
    model = scripted([call("takeoff", drone_id="alpha", alt_m=500), ScriptedReply(content=""),
                      call(ANSWER_TOOL, text=quoting)])  # fmt: skip
    _, result = await _run(toy, model, "climb alpha to 500 m")
    assert result.outcome == "answered" and result.final_text == quoting


async def test_an_empty_or_echoed_answer_is_asked_again_and_three_end_as_empty_answer(toy, scripted) -> None:
    request = "take off alpha to 10 m"
    model = scripted(
        [call(ANSWER_TOOL, text=""), call(ANSWER_TOOL, text=request), call(ANSWER_TOOL, text="  ")]
    )
    _, result = await _run(toy, model, request)
    assert result.outcome == "empty_answer" and result.answered_by == "host"
    assert (result.final_text or "").startswith("(Answer from the host"), result.final_text
    assert "Nothing was done" in result.final_text
    assert result.empty_replies == 3
    assert "Not an answer: answer_user needs text" in _last_tool_text(model.requests[1])
    assert "Not an answer: that only repeats the request" in _last_tool_text(model.requests[2])


async def test_an_answer_that_forgets_a_named_drone_is_sent_back_once_then_taken(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call(ANSWER_TOOL, text="Alpha is up."),
            call("takeoff", drone_id="bravo", alt_m=10),
            call(ANSWER_TOOL, text="Alpha and bravo are at 10 m."),
        ]
    )
    _, result = await _run(toy, model, "take off alpha and bravo to 10 m")
    held = _last_tool_text(model.requests[2])
    assert held.startswith(
        "Not finished yet: The request names bravo, and nothing has been done with it yet."
    )
    assert result.final_text == "Alpha and bravo are at 10 m."
    assert toy.world.drones["bravo"].alt_m == 10.0


async def test_a_premature_answer_is_held_back_only_once(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call(ANSWER_TOOL, text="Only alpha flew."),
            call(ANSWER_TOOL, text="Only alpha flew; bravo stayed down."),
        ]
    )
    _, result = await _run(toy, model, "take off alpha and bravo to 10 m")
    assert result.outcome == "answered" and result.final_text == "Only alpha flew; bravo stayed down."


def test_answer_text_reads_text_or_the_one_string_a_model_put_under_another_name() -> None:
    assert answer_text({"text": " done "}) == "done"
    assert answer_text({"answer": "done"}) == "done"
    assert answer_text({"a": "x", "b": "y"}) == ""
    assert answer_text(None) == ""


async def test_an_answer_right_after_an_invalid_call_is_sent_back_to_fix_the_call(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m="ten"),
            call(ANSWER_TOOL, text="I could not take off."),
            call("takeoff", drone_id="alpha", alt_m=10),
            call(ANSWER_TOOL, text="Alpha is at 10 m."),
        ]
    )
    _, result = await _run(toy, model, "take off alpha to 10 m")
    assert _last_tool_text(model.requests[2]).startswith("Not finished yet: your takeoff call was not valid")
    assert result.final_text == "Alpha is at 10 m." and toy.world.drones["alpha"].alt_m == 10.0


async def test_an_answer_that_leaves_a_drone_flying_the_request_lands_is_sent_back(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call(ANSWER_TOOL, text="Alpha climbed to 10 m and landed."),
            call("land", drone_id="alpha"),
            call(ANSWER_TOOL, text="Alpha climbed to 10 m and landed."),
        ]
    )
    _, result = await _run(toy, model, "take off alpha to 10 m, then land it again")
    held = _last_tool_text(model.requests[2])
    # said to have landed while it flies: the claim is sent back first (what is left would be next)
    assert held.startswith(
        "Not sent to the user yet: your answer says alpha 'landed', but alpha is not there "
        "(now: alpha flying at 10 m"
    ), held
    assert result.outcome == "answered" and not toy.world.drones["alpha"].armed
    quiet = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call(ANSWER_TOOL, text="Alpha climbed to 10 m."),
            call("land", drone_id="alpha"),
            call(ANSWER_TOOL, text="Alpha climbed to 10 m and landed."),
        ]
    )
    _, result = await _run(toy, quiet, "take off alpha to 10 m, then land it again")
    assert _last_tool_text(quiet.requests[2]).startswith(
        "Not finished yet: The request asks to land or come home, and alpha is still flying. Call the tool "
        "for the next step; call answer_user when every part is done, or to say why it cannot be done."
    )
    assert result.outcome == "answered" and not toy.world.drones["alpha"].armed


async def test_an_answer_that_copies_the_hosts_refusal_is_an_echo_but_a_copied_gateway_text_is_an_answer(
    toy, scripted
) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m="high"),
            call("takeoff", drone_id="alpha", alt_m=10),
            call(
                ANSWER_TOOL,
                text="Error: invalid arguments for takeoff: 'high' is not of type 'number'.",
            ),
            call(ANSWER_TOOL, text="Alpha is at 10 m."),
        ]
    )
    _, result = await _run(toy, model, "take alpha up")
    assert result.empty_replies == 1 and result.final_text == "Alpha is at 10 m."

    # A gateway refusal or a reading, copied, tells the user what happened.
    model = scripted(
        [
            call("takeoff", drone_id="bravo", alt_m=500),
            call(ANSWER_TOOL, text="refused by rule max_altitude: target altitude 500 m exceeds the limit"),
        ]
    )
    _, result = await _run(toy, model, "climb bravo to 500 m")
    assert result.final_text == "refused by rule max_altitude: target altitude 500 m exceeds the limit"
    model = scripted(
        [
            call("get_position", drone_id="bravo"),
            call(ANSWER_TOOL, text="bravo: 0 m north, 0 m up, armed=False"),
        ]
    )
    _, result = await _run(toy, model, "where is bravo?")
    assert result.final_text == "bravo: 0 m north, 0 m up, armed=False"


async def test_an_answer_after_an_invalid_call_whose_plan_was_skipped_is_sent_back_too(toy, scripted) -> None:
    model = scripted(
        [
            ScriptedReply(
                tool_calls=[
                    ("takeoff", '{"drone_id": "alpha", "alt_m": "ten"}'),
                    ("land", '{"drone_id": "alpha"}'),
                ]
            ),
            call(ANSWER_TOOL, text="Nothing yet."),
            call("takeoff", drone_id="alpha", alt_m=10),
            call("land", drone_id="alpha"),
            call(ANSWER_TOOL, text="Alpha went up to 10 m and landed."),
        ]
    )
    _, result = await _run(toy, model, "take off alpha to 10 m, then land it")
    assert _last_tool_text(model.requests[2]).startswith("Not finished yet: your takeoff call was not valid")
    assert result.final_text == "Alpha went up to 10 m and landed."


async def test_an_answer_before_any_call_ran_is_sent_back_once(toy, scripted) -> None:
    """Measured on the corpus's dev half (cond-above-forty-hop, ask-anyone-flying): the 1.5B model answered
    at once, with no call, and the answer was a guess ("sending it up ..."; "all three are flying")."""
    model = scripted(
        [
            call(ANSWER_TOOL, text="Alpha is above 40 percent, sending it up to 12 m."),
            call("takeoff", drone_id="alpha", alt_m=12),
            call(ANSWER_TOOL, text="Alpha climbed to 12 m."),
        ]
    )
    _, result = await _run(toy, model, "only if alpha is above 40 percent, send it up to 12 m")
    assert result.outcome == "answered" and result.final_text == "Alpha climbed to 12 m."
    assert _last_tool_text(model.requests[1]).startswith("Not sent to the user yet: no tool has run")
    assert toy.world.drones["alpha"].alt_m == 12.0


async def test_the_same_answer_again_without_a_call_is_believed_in_prose_too(toy, scripted) -> None:
    model = scripted([say("Hello! I fly your drones."), say("Hello! I fly your drones.")])
    _, result = await _run(toy, model, "hi")
    assert result.outcome == "answered" and result.final_text == "Hello! I fly your drones."
    told = [m for m in model.requests[1]["messages"] if m["role"] == "user"][-1]["content"]
    assert told.startswith("Not sent to the user yet: no tool has run")
    assert len(model.requests) == 2 and toy.world.calls == []


async def test_an_answer_whose_arguments_are_a_bare_string_is_that_text(toy, scripted) -> None:
    """Measured on the dev half (cond-above-forty-hop): ``"arguments": "Charlie is above 40 percent ..."``."""
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=5),
            ScriptedReply(tool_calls=[(ANSWER_TOOL, '"Alpha hovers at 5 m."')]),
        ]
    )
    _, result = await _run(toy, model, "take off alpha to 5 m")
    assert result.outcome == "answered" and result.final_text == "Alpha hovers at 5 m."


async def test_an_answer_written_as_text_with_a_bare_string_is_that_text(toy, scripted) -> None:
    """The measured form (cond-above-forty-hop), written as text the way the 1.5B model writes it."""
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=5),
            say('{{"name": "answer_user", "arguments": "Alpha hovers at 5 m."}}'),
        ]
    )
    _, result = await _run(toy, model, "take off alpha to 5 m")
    assert result.outcome == "answered" and result.final_text == "Alpha hovers at 5 m."


def test_bare_answer_reads_a_string_and_nothing_else() -> None:
    from gateway.agent.answer import bare_answer

    assert bare_answer("Charlie is up.") == "Charlie is up."  # as read from text
    assert bare_answer('"Charlie is up."') == "Charlie is up."  # a JSON string from the API
    assert bare_answer('{"txt": 1') == "" and bare_answer(None) == "" and bare_answer(3) == ""


async def test_an_answer_after_a_correctable_gateway_error_is_sent_back_once(toy, scripted) -> None:
    """Measured on the dev half (multi-two-heights): the gateway's "alpha is on the ground; say how high
    to fly" came back as the answer; nothing had flown. A refusal by a rule is still taken at once (the
    test above)."""
    model = scripted(
        [
            call("move_north", drone_id="alpha", distance_m=10),
            call(ANSWER_TOOL, text="Error: alpha is on the ground: take off first"),
            call("takeoff", drone_id="alpha", alt_m=10),
            call("move_north", drone_id="alpha", distance_m=10),
            call(ANSWER_TOOL, text="Alpha flew 10 m north at 10 m."),
        ]
    )
    _, result = await _run(toy, model, "take alpha 10 m north at 10 m")
    assert _last_tool_text(model.requests[2]).startswith("Not finished yet: your move_north call failed")
    assert result.outcome == "answered" and result.final_text == "Alpha flew 10 m north at 10 m."
    assert toy.world.drones["alpha"].north_m == 10.0


async def test_an_answer_still_silent_about_a_refusal_gets_the_hosts_line_naming_it(toy, scripted) -> None:
    """Measured on the dev half (refuse-all-150m): sent back once, the same silent answer came again."""
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=150),
            call("takeoff", drone_id="alpha", alt_m=120),
            call(ANSWER_TOOL, text="Alpha is now flying at 120 m."),
            call(ANSWER_TOOL, text="Alpha is now flying at 120 m."),
        ]
    )
    events: list[AgentEvent] = []
    _, result = await _run(toy, model, "send alpha up to 150 m", events)
    assert result.outcome == "answered" and result.final_text.startswith(
        "Alpha is now flying at 120 m. (Host: the gateway refused takeoff: refused by rule max_altitude: "
        "target altitude 150 m exceeds"
    ), result.final_text
    assert [e.data["text"] for e in events if e.kind == "final"] == [result.final_text]  # what is shown


async def test_an_answer_silent_about_a_refusal_is_sent_back_once_quoting_it(toy, scripted) -> None:
    """Measured on the dev half (refuse-all-150m): refused 150 m, the model flew to the limit and answered
    "Alpha ... is now flying at 120 m", with no word of the refusal."""
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=150),
            call("takeoff", drone_id="alpha", alt_m=120),
            call(ANSWER_TOOL, text="Alpha is now flying at 120 m."),
            call(ANSWER_TOOL, text="150 m was refused (limit 120 m); alpha flies at 120 m."),
        ]
    )
    _, result = await _run(toy, model, "send alpha up to 150 m")
    told = _last_tool_text(model.requests[3])
    assert told.startswith(
        "Not sent to the user yet: the gateway refused part of the request (takeoff: refused by rule"
    )
    assert result.outcome == "answered" and result.final_text.startswith("150 m was refused")


async def test_an_answer_saying_a_drone_acted_when_no_call_acted_on_it_is_sent_back(toy, scripted) -> None:
    """Measured on the dev half (cond-above-forty-hop): the battery read, the plan said as the answer."""
    model = scripted(
        [
            call("get_position", drone_id="alpha"),
            call(ANSWER_TOOL, text="Alpha is above 40 percent, sending it up to 12 m."),
            call("takeoff", drone_id="alpha", alt_m=12),
            call(ANSWER_TOOL, text="Alpha climbed to 12 m."),
        ]
    )
    _, result = await _run(toy, model, "only if alpha is above 40 percent, send it up to 12 m")
    note = _last_tool_text(model.requests[2])
    assert note.startswith("Not sent to the user yet: your answer says alpha 'sending'"), note
    assert "alpha is on the ground: takeoff first" in note
    assert result.outcome == "answered" and result.final_text == "Alpha climbed to 12 m."
    assert toy.world.drones["alpha"].alt_m == 12.0


async def test_the_same_unbacked_answer_again_is_passed_on_with_what_the_gateway_did(toy, scripted) -> None:
    claim = "Alpha is above 40 percent, sending it up to 12 m."
    model = scripted([call("get_position", drone_id="alpha"), call(ANSWER_TOOL, text=claim),
                      call(ANSWER_TOOL, text=claim)])  # fmt: skip
    _, result = await _run(toy, model, "only if alpha is above 40 percent, send it up to 12 m")
    assert result.outcome == "answered"
    assert result.final_text.startswith(
        f"{claim} (Host: no call in this turn acted on alpha; now: alpha on the ground"
    )
    assert toy.world.drones["alpha"].alt_m == 0.0


async def test_an_answer_written_beside_the_reading_it_reports_is_sent_back_once_with_the_reading(
    toy, scripted
) -> None:
    """Measured on the dev half (cond-charlie-sixty): get_battery and, in the same reply, an answer that
    guessed the level; the reading never reached the user."""
    read_and_guess = say(
        '{"name": "get_position", "arguments": {"drone_id": "alpha"}}\n'
        '{"name": "answer_user", "arguments": {"text": "Alpha is high up."}}'
    )
    model = scripted([read_and_guess, call(ANSWER_TOOL, text="Alpha is on the ground, 0 m up.")])
    _, result = await _run(toy, model, "how high is alpha?")
    assert result.final_text == "Alpha is on the ground, 0 m up."
    assert [c.name for c in result.tool_calls] == ["get_position"]
    note = _last_tool_text(model.requests[1])
    assert note.startswith("Not sent to the user yet: you wrote the answer in the same reply as the reading")
    assert "alpha: 0 m north, 0 m up" in note
    # an answer that states a number of the reading was written from it (or guessed right): taken at once
    states = say(
        '{"name": "get_position", "arguments": {"drone_id": "alpha"}}\n'
        '{"name": "answer_user", "arguments": {"text": "Alpha is 0 m up."}}'
    )
    again = scripted([states])
    _, result = await _run(toy, again, "how high is alpha?")
    assert result.final_text == "Alpha is 0 m up." and len(again.requests) == 1


async def test_an_answer_that_picks_a_drone_the_readings_do_not_pick_is_sent_back(toy, scripted) -> None:
    """Measured on the dev half (ask-most-charge): 54, 69 and 91 % read, "which drone has the most battery
    left?" answered "alpha has the most battery left with 54%". Sent back once with the readings; the same
    answer again is believed, with the host's pick added."""
    toy.world.drones["alpha"].battery_pct, toy.world.drones["bravo"].battery_pct = 54.0, 91.0
    wrong = "Alpha has the most battery left with 54%."
    model = scripted(
        [
            call("get_battery", drone_id="alpha"),
            call("get_battery", drone_id="bravo"),
            call(ANSWER_TOOL, text=wrong),
            call(ANSWER_TOOL, text="Bravo has the most battery left, 91 %."),
        ]
    )
    _, result = await _run(toy, model, "Which drone has the most battery left?")
    assert _last_tool_text(model.requests[3]).startswith(
        "Not sent to the user yet: by this turn's readings bravo has the most battery "
        "(alpha 54 %, bravo 91 %)"
    )
    assert result.final_text == "Bravo has the most battery left, 91 %."
    reads = [call("get_battery", drone_id="alpha"), call("get_battery", drone_id="bravo")]
    lower = scripted([*reads, call(ANSWER_TOOL, text=wrong)])
    _, result = await _run(toy, lower, "Between alpha and bravo, which one is running lower on battery?")
    assert result.final_text == wrong  # it names alpha, the lower one: nothing held, nothing added
    again = scripted([*reads, call(ANSWER_TOOL, text=wrong), call(ANSWER_TOOL, text=wrong)])
    _, result = await _run(toy, again, "Which drone has the most battery left?")
    assert result.final_text == (
        f"{wrong} (Host: by this turn's readings bravo has the most battery (alpha 54 %, bravo 91 %).)"
    )


async def test_an_answer_with_a_height_the_drone_is_not_at_is_sent_back(toy, scripted) -> None:
    """Dev half (multi-hop-and-hover): the answer said a drone hovers at 15 m when it flew to 6 m."""
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=6),
            call(ANSWER_TOOL, text="Alpha is hovering at 15 m."),
            call("takeoff", drone_id="alpha", alt_m=15),
            call(ANSWER_TOOL, text="Alpha is hovering at 15 m."),
        ]
    )
    _, result = await _run(toy, model, "take alpha up to 15 m")
    note = _last_tool_text(model.requests[2])
    assert note.startswith(
        "Not sent to the user yet: your answer says alpha 'hovering at 15 m', but alpha is not there"
    ), note
    assert result.final_text == "Alpha is hovering at 15 m." and toy.world.drones["alpha"].alt_m == 15.0


async def test_a_turn_stuck_sending_a_finished_call_again_stops_and_the_host_answers(toy, scripted) -> None:
    """Dev half (cond-fuller-north): a takeoff already done sent back 19 times, to the step limit. The
    fifth time it comes back the turn ends, with the host's answer from the results."""
    model = scripted([call("takeoff", drone_id="alpha", alt_m=10)], repeat_last=True)
    events: list[AgentEvent] = []
    _, result = await run_on_toy(
        toy, model, "alpha up to 10 m and then land it", max_steps=20, events=events
    )  # unfinished: alpha is still flying (the toy's move_north speaks no north_m, so a leg is not checked)
    assert [c.status for c in result.tool_calls] == ["ok"] + ["repeat"] * 5
    assert result.outcome == "step_limit" and result.answered_by == "host"
    assert "the same call came back 5 times" in next(
        e.data["message"] for e in events if e.kind == "step_limit"
    )
    assert len(model.requests) == 6  # not 20


async def test_a_turn_stuck_sending_a_refused_call_again_stops_and_the_host_answers(toy, scripted) -> None:
    """Dev half with the 0.5B model (refuse-bravo-drained): a refused leg sent 31 times, about 220 s, to
    the step limit. The fifth time the same call is refused the turn ends, with the host's answer, which
    says what was refused and why."""
    model = scripted([call("takeoff", drone_id="alpha", alt_m=500)], repeat_last=True)
    events: list[AgentEvent] = []
    _, result = await run_on_toy(toy, model, "alpha up to 500 m", max_steps=20, events=events)
    assert [c.status for c in result.tool_calls] == ["error"] * 5
    assert result.answered_by == "host" and result.outcome == "answered"
    assert "max_altitude" in (result.final_text or "")
    assert "refused 5 times" in next(e.data["message"] for e in events if e.kind == "empty_answer")
    assert len(model.requests) == 5  # not 20
