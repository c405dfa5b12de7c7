"""The small model's plan step: the request as numbered steps, and the step whose turn it is."""

from __future__ import annotations

import asyncio
from typing import Any, cast

from bench.agent_harness.missions import MissionContext
from bench.agent_harness.scripted import ScriptedModelServer, ScriptedReply, call, say
from bench.nl_corpus import DRONES, corpus
from gateway.agent.chat import ChatModel, ModelReply
from gateway.agent.planning import (
    MAX_STEPS,
    PLAN_EXAMPLES,
    PLAN_SYSTEM_PROMPT,
    Plan,
    asked_drones,
    carries_the_request,
    formation_for_drones,
    gaps_note,
    height_for_legs,
    height_steps_into_legs,
    home_for_landing,
    plan_gaps,
    plan_messages,
    plan_steps,
    split_steps,
    steps_as_meant,
    steps_from_reply,
)
from gateway.agent.turns import AgentEvent, ToolCallRecord, Usage
from tests.agent.test_loop import run_on_toy
from tests.agent.toy_mcp import ToyServer

FLEET = ["alpha", "bravo", "charlie"]


def _ok(name: str, text: str = "", **arguments: Any) -> ToolCallRecord:
    return ToolCallRecord(name, name, arguments, "ok", "", text=text)


def test_the_steps_are_the_numbered_lines_without_the_ones_that_call_for_nothing() -> None:
    reply = "Sure:\n1. alpha: take off to 12 m\n2) alpha: hover at 12 m\n3. alpha: fly 35 m west\nthanks"
    assert steps_from_reply(reply, FLEET) == ["alpha: take off to 12 m", "alpha: fly 35 m west"]
    most = "\n".join(f"{i}. alpha: climb 1 m" for i in range(1, MAX_STEPS + 1))
    assert len(steps_from_reply(most, FLEET)) == MAX_STEPS
    # a plan cut short would end the turn before the request's last steps
    assert steps_from_reply(f"{most}\n{MAX_STEPS + 1}. alpha: land", FLEET) == []
    assert steps_from_reply("", FLEET) == [] and steps_from_reply(None, FLEET) == []


def test_steps_that_copy_the_examples_drones_are_not_used() -> None:
    assert steps_from_reply("1. delta: take off to 14 m\n2. alpha: land", FLEET) == []
    # a fleet that has a drone named like one of the examples' keeps it
    own = steps_from_reply("1. delta: up to 5 m\n2. delta: land", ["delta"], "delta up to 5 m, then land")
    assert own == ["delta: up to 5 m", "delta: land"]


def test_one_step_is_no_plan_unless_its_words_say_its_call() -> None:
    """A request of one action is its own step: rewritten for the model, it only gains the planner's
    errors; a step that says its call exactly (or a reading) is the host's call, so the model only answers."""
    assert steps_from_reply("1. alpha, bravo: side by side, 8 m apart, above the tower", FLEET) == []
    assert steps_from_reply("1. alpha: climb over the tower\n2. alpha: hover", FLEET) == []
    # "climb to 10 m" says its call: an altitude, flown by move_to_relative from the ground or in the air
    assert steps_from_reply("1. alpha: climb to 10 m\n2. alpha: hover", FLEET) == ["alpha: climb to 10 m"]
    line = "Line up alpha, bravo and charlie at 20 m, 8 m apart, where they are."
    assert steps_from_reply("1. alpha, bravo, charlie: line formation, 8 m apart, at 20 m", FLEET, line) == [
        "alpha, bravo, charlie: line formation, 8 m apart, at 20 m"
    ]
    up = "Put alpha up at 10 m and keep it there"
    assert steps_from_reply("1. alpha: take off to 10 m\n2. alpha: hover", FLEET, up) == [
        "alpha: take off to 10 m"
    ]
    assert steps_from_reply("1. echo: read position", ["echo"], "where is echo?") == ["echo: read position"]


def test_the_examples_are_none_of_the_benchmarks_requests_nor_its_drones() -> None:
    """The plan step may not be tuned on the corpus: its examples are other requests, other drones."""
    ctx = MissionContext(homes={d: (47.397, 8.545 + 0.0001 * i, 488.0) for i, d in enumerate(DRONES)})
    requests = {e.mission.prompt(ctx).lower() for e in corpus()}
    for asked, steps in PLAN_EXAMPLES:
        assert asked.lower() not in requests
        assert not any(d in f"{asked} {steps}".lower() for d in DRONES), asked
    messages = plan_messages(FLEET, "alpha to 10 m")
    assert messages[0] == {"role": "system", "content": PLAN_SYSTEM_PROMPT}
    assert messages[-1]["content"] == "Drones: alpha, bravo, charlie\nRequest: alpha to 10 m"
    assert len(messages) == 2 + 2 * len(PLAN_EXAMPLES)


def test_a_step_is_done_by_a_call_of_its_kind_on_its_drone() -> None:
    """Measured on the dev half (multi-west-and-land): takeoff(alpha) for "alpha: fly 40 m west at 15 m"
    was counted as that step, and alpha's leg was never flown."""
    plan = Plan(["alpha: fly 40 m west at 15 m", "charlie: fly 40 m west at 15 m", "alpha: land"], FLEET)
    took_off = _ok("takeoff", drone_id="alpha", alt_m=15)
    assert plan.next_note([took_off]).startswith("Now step 1 of 3: alpha: fly 40 m west at 15 m.")
    moved = _ok("move_to_relative", drone_id="alpha", west_m=40, alt_m=15)
    assert plan.next_note([took_off, moved]).startswith("Now step 2 of 3: charlie:")
    wrong_drone = _ok("move_to_relative", drone_id="bravo", west_m=40, alt_m=15)
    assert plan.next_note([took_off, moved, wrong_drone]).startswith("Now step 2 of 3: charlie:")
    charlie = _ok("move_to_relative", drone_id="charlie", west_m=40, alt_m=15)
    landed = _ok("land", drone_id="alpha")
    assert plan.next_note([moved, charlie, landed]).startswith("Every step is done.")
    # a step that names only a height is done by a takeoff (dev half, compound-north-rtl: "bravo: fly 18 m")
    height = Plan(["bravo: fly 18 m", "bravo: fly 25 m north"], FLEET)
    assert height.next_note([_ok("takeoff", drone_id="bravo", alt_m=18)]).startswith("Now step 2 of 2")
    climb = Plan(["bravo: climb 5 m higher"], FLEET)
    assert climb.next_note([_ok("takeoff", drone_id="bravo", alt_m=5)]).startswith("Now step 1 of 1")
    # "fly 10 m up" is a height too (dev half, multi-two-heights: "alpha to 10 m" planned so)
    up = Plan(["alpha: fly 10 m up", "bravo: fly 20 m up"], FLEET)
    assert up.next_note([_ok("takeoff", drone_id="alpha", alt_m=10)]).startswith("Now step 2 of 2: bravo")
    # another server's tool (not one of the gateway's) counts for a step of any kind
    assert plan.next_note([_ok("move_north", drone_id="alpha")]).startswith("Now step 2 of 3")


def test_a_condition_on_the_battery_is_read_from_the_reading() -> None:
    """Measured on the dev half (cond-above-forty-hop): the 1.5B model read 45 % as "below 40 %"."""
    plan = Plan(["charlie: read battery", "if above 40 %: charlie: climb 12 m", "charlie: land"], FLEET)
    high = _ok("get_battery", "charlie battery 45%, 11.12 V", drone_id="charlie")
    assert plan.next_note([high]) == (
        "Now step 2 of 3 (the battery is above 40 %): charlie: climb 12 m. "
        "Reply with only the tool call for it."
    )
    climbed = _ok("move_to_relative", drone_id="charlie", up_m=12)
    assert plan.next_note([high, climbed]).startswith("Now step 3 of 3: charlie: land.")
    low = _ok("get_battery", "charlie battery 35%, 10.9 V", drone_id="charlie")
    assert plan.next_note([low]) == (
        "The condition does not hold (charlie battery 35 % is not above 40 %), so nothing is to be flown. "
        "Reply with the answer_user call saying so, with the reading."
    )
    unread = Plan(["if at least 70 %: bravo: take off to 20 m"], FLEET)
    assert "Read the battery first" in unread.next_note([])
    at_least = Plan(["if at least 70 %: bravo: take off to 20 m", "otherwise: tell the battery"], FLEET)
    exactly = _ok("get_battery", "bravo battery 70%, 11.9 V", drone_id="bravo")
    took_off = _ok("takeoff", drone_id="bravo", alt_m=20)
    assert at_least.next_note([exactly]).startswith("Now step 1 of 2 (the battery is at least 70 %)")
    # the condition held and its step is done: the "otherwise" branch is passed over
    assert at_least.next_note([exactly, took_off]).startswith("Every step is done.")
    # only the answer is left when every step is done or the condition does not hold
    assert at_least.finished([exactly, took_off]) and plan.finished([low])
    assert not at_least.finished([exactly]) and not unread.finished([])


def _plan_reply(body: dict[str, Any]) -> ScriptedReply:
    assert "tools" not in body, "the plan is asked without tools"
    return ScriptedReply(content="1. alpha: take off to 15 m\n2. alpha: fly 100 m north\n3. alpha: land")


async def test_the_host_asks_for_the_steps_first_and_says_whose_turn_it_is(toy: ToyServer, scripted) -> None:
    """On the toy server, with a real MCP client: the first request has no tools and the plan prompt; a
    step whose words say its call is made by the host (the takeoff, the landing), a step whose call is not
    offered (the toy server has no move_to_relative) is asked of the model as one user message, with what
    ran and the step whose turn it is."""
    model: ScriptedModelServer = scripted(
        [
            _plan_reply,
            call("move_north", drone_id="alpha", distance_m=100),
            say("alpha flew 100 m north and landed"),
        ]
    )
    events: list[AgentEvent] = []
    _, result = await run_on_toy(
        toy, model, "alpha up to 15 m, then 100 m north, then down", plan_first=True, events=events
    )
    assert result.outcome == "answered", result
    assert [c.name for c in result.tool_calls] == ["takeoff", "move_north", "land"]
    assert [e.data["name"] for e in events if e.kind == "plan_call"] == ["takeoff", "land"]
    assert model.requests[0]["messages"][0]["content"] == PLAN_SYSTEM_PROMPT
    second = model.requests[1]["messages"]
    # the turn so far is one user message (the conversation before the turn stays)
    assert [m["role"] for m in second] == ["system", "user"], second
    assert second[-1]["content"].startswith("Fleet now: ")
    assert (
        "\nalpha up to 15 m, then 100 m north, then down\n\nSteps:\n1. alpha: take off to 15 m\n"
        "2. alpha: fly 100 m north\n3. alpha: land" in second[-1]["content"]
    )
    assert (
        '\n\nDone so far:\n- {"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15.0}} -> '
        in (second[-1]["content"])
    )
    assert second[-1]["content"].endswith(
        "\n\nNow step 2 of 3: alpha: fly 100 m north. Reply with only the tool call for it."
    )
    told = model.requests[2]["messages"][-1]["content"]
    assert told.endswith("Every step is done. Reply with the answer_user call saying what was done."), told
    assert toy.world.calls[1] == ("move_north", {"drone_id": "alpha", "distance_m": 100})
    assert len(model.requests) == 3


async def test_no_steps_no_plan(toy: ToyServer, scripted) -> None:
    """A reply with no numbered steps (or a model that fails at it) leaves the turn as it was."""
    model = scripted([say("I cannot split this."), call("takeoff", drone_id="bravo", alt_m=10), say("up")])
    _, result = await run_on_toy(toy, model, "bravo to 10 m", plan_first=True)
    assert result.outcome == "answered" and result.final_text == "up", result
    assert "Steps:" not in model.requests[1]["messages"][-1]["content"]
    assert all(m["role"] != "user" or "Now step" not in m["content"] for m in model.requests[2]["messages"])


def test_a_step_for_several_drones_becomes_one_step_per_drone_asked() -> None:
    """Measured on the dev half (multi-west-and-land): "alpha, charlie: take off to 15 m" counted as done
    after alpha's takeoff, and charlie never flew; (multi-spread-out) a step for a drone never asked."""
    both = "Take alpha and charlie 40 m west at 15 m altitude and land them over there."
    reply = (
        "1. alpha, charlie: take off to 15 m\n2. alpha and charlie: fly 40 m west\n3. charlie, alpha: land"
    )
    assert steps_from_reply(reply, FLEET, both) == [
        "alpha: take off to 15 m",
        "charlie: take off to 15 m",
        "alpha: fly 40 m west",
        "charlie: fly 40 m west",
        "charlie: land",
        "alpha: land",
    ]
    spread = "Spread them out: alpha 25 m to the east and bravo 25 m to the north, both at 10 m."
    reply = "1. alpha: fly 25 m east at 10 m\n2. bravo: fly 25 m north at 10 m\n3. charlie: fly 10 m"
    kept = ["alpha: fly 25 m east at 10 m", "bravo: fly 25 m north at 10 m"]
    assert steps_from_reply(reply, FLEET, spread) == kept
    # a formation stays one step, for the drones the request names
    pair = "alpha and charlie side by side, 15 m apart, then land alpha"
    reply = "1. alpha, bravo, charlie: line formation, 15 m apart\n2. alpha: land"
    formed = steps_from_reply(reply, FLEET, pair)
    assert formed == ["alpha, charlie: line formation, 15 m apart", "alpha: land"]
    # words of drones placed together are a formation too, without the word (dev half, form-pair-abreast):
    # side by side is a line, so the one step is the host's formation call
    abreast = "Alpha and charlie side by side, 15 m apart, at 20 m, where they are now."
    side = ["alpha, charlie: side by side, 15 m apart, at 20 m"]
    assert steps_from_reply(f"1. {side[0]}", FLEET, abreast) == side
    # a request for the whole fleet may mean drones it does not name
    every = "all of them up to 20 m, then land alpha"
    reply = "1. alpha, bravo, charlie: take off to 20 m\n2. alpha: land"
    assert len(steps_from_reply(reply, FLEET, every)) == 4


async def test_an_empty_reply_after_the_last_step_gets_the_hosts_answer_at_once(
    toy: ToyServer, scripted
) -> None:
    """Measured with the 1.5B model: told "every step is done", it replied with nothing, twice more when
    asked again; the host answers from the results after the first empty reply."""
    model = scripted([_plan_reply, call("move_north", drone_id="alpha", distance_m=100), say("")])
    _, result = await run_on_toy(toy, model, "alpha up to 15 m, then 100 m north, then down", plan_first=True)
    assert len(model.requests) == 3 and result.answered_by == "host", result
    assert result.outcome == "answered" and result.final_text.startswith("(Answer from the host"), result


async def test_a_copy_of_a_done_line_is_not_sent_again_but_a_new_call_with_a_made_up_result_is(
    toy: ToyServer, scripted
) -> None:
    """Measured on the dev half (multi-west-and-land, form-pair-abreast): the 1.5B model copied the plan's
    "{call} -> result" lines back (read as calls, they flew finished steps again), and wrote a new call
    with a result it made up (that one is the step it means)."""
    took_off = '{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15.0}}'
    north = '{"name": "move_north", "arguments": {"drone_id": "alpha", "distance_m": 100}}'
    model = scripted([_plan_reply, say(f"{took_off} -> takeoff on alpha succeeded"),
                      say(f"{north} -> move_north on alpha succeeded: arrived"), say("done")])  # fmt: skip
    events: list[AgentEvent] = []
    _, result = await run_on_toy(
        toy, model, "alpha up to 15 m, then 100 m north, then down", plan_first=True, events=events
    )
    assert [c.name for c in result.tool_calls] == ["takeoff", "move_north", "land"], result
    assert [e.data["name"] for e in events if e.kind == "copied_record"] == ["takeoff"]
    assert [c[0] for c in toy.world.calls] == ["takeoff", "move_north", "land"]
    assert "Your reply only repeated my note." in model.requests[2]["messages"][-1]["content"]


def test_steps_that_drop_or_add_part_of_the_request_are_no_plan() -> None:
    """Measured on the dev half with the 1.5B model: "then bring it home" planned as a landing,
    "keep bravo up" given a flight home from the ground, "leave it hovering" given a landing, "both at 10 m"
    and "25 m south of where they are" dropped."""
    corner = "Take charlie to 15 m, go 20 m east, then 20 m south, then bring it home."
    legs = ["charlie: take off to 15 m", "charlie: fly 20 m east", "charlie: fly 20 m south"]
    assert not carries_the_request([*legs, "charlie: land"], corner)
    assert carries_the_request([*legs, "charlie: return home"], corner)
    hover = "Please launch alpha, climb to thirty metres and leave it hovering there."
    assert carries_the_request(["alpha: take off", "alpha: climb to 30 m"], hover)
    assert not carries_the_request(["alpha: take off", "alpha: climb to 30 m", "alpha: land"], hover)
    keep = "Get alpha and bravo both to 16 m, then bring alpha back down but keep bravo up."
    ups = ["alpha: take off to 16 m", "bravo: take off to 16 m"]
    assert carries_the_request([*ups, "alpha: land"], keep)
    assert not carries_the_request([*ups, "alpha: land", "alpha: return home"], keep)
    spread = "Spread them out: alpha 25 m to the east and bravo 25 m to the north, both at 10 m."
    assert not carries_the_request(["alpha: fly 25 m east", "bravo: fly 25 m north"], spread)
    south = "All three in a row, 12 m between each, at 20 m, 25 m south of where they are."
    assert not carries_the_request([f"{d}: fly 12 m south" for d in FLEET], south)
    # such steps are not used; a landing the request does not speak of is read as it meant first
    # (home_for_landing): the way home for "bring it home", else left out; and a way home it does not ask
    # for is the landing it speaks of (landing_for_home)
    keep_reply = (
        "1. alpha: take off to 16 m\n2. bravo: take off to 16 m\n3. alpha: land\n4. alpha: return home"
    )
    assert steps_from_reply(keep_reply, FLEET, keep) == [*ups, "alpha: land"]  # landed once, not sent home
    reply = "1. alpha: take off\n2. alpha: climb to 30 m\n3. alpha: land"
    assert steps_from_reply(reply, FLEET, hover) == ["alpha: take off", "alpha: climb to 30 m"]
    reply = "\n".join(f"{i}. {step}" for i, step in enumerate([*legs, "charlie: land"], 1))
    assert steps_from_reply(reply, FLEET, corner) == [*legs, "charlie: return home"]


def test_a_step_with_a_compass_direction_is_a_move_even_when_it_says_take_off() -> None:
    """Dev half (multi-west-and-land): "alpha: take off to 40 m west at 15 m altitude" was done by the
    takeoff, and the 40 m west never flown; a move takes off first from the ground."""
    plan = Plan(["alpha: take off to 40 m west at 15 m altitude", "alpha: land over there"], FLEET)
    assert plan.next_note([_ok("takeoff", drone_id="alpha", alt_m=15)]).startswith("Now step 1 of 2")
    moved = _ok("move_to_relative", drone_id="alpha", east_m=-40, alt_m=15)
    assert plan.next_note([moved]).startswith("Now step 2 of 2")


def test_a_step_that_only_tells_leaves_only_the_answer() -> None:
    """Dev half (cond-charlie-under-thirty): "if below 30 %: tell me the number" was answered with the
    battery read again, 19 times."""
    plan = Plan(
        ["charlie: read charge", "if below 30 %: tell me the number", "otherwise: charlie: up at 8 m"], FLEET
    )
    read = _ok("get_battery", "charlie battery 25%, 10.6 V", drone_id="charlie")
    assert plan.finished([read])
    assert plan.next_note([read]) == (
        "Now step 2 of 3 (the battery is below 30 %): tell me the number. Reply with the answer_user call, "
        "with the numbers read."
    )


async def test_a_finished_call_sent_again_when_only_the_answer_is_left_gets_the_hosts_answer(
    toy: ToyServer, scripted
) -> None:
    def steps(body: dict[str, Any]) -> ScriptedReply:
        return ScriptedReply(content="1. alpha: take off to 15 m\n2. alpha: land")

    model = scripted([steps, call("land", drone_id="alpha")])
    _, result = await run_on_toy(toy, model, "alpha up to 15 m, then land", plan_first=True)
    assert [(c.name, c.status) for c in result.tool_calls] == [
        ("takeoff", "ok"),
        ("land", "ok"),
        ("land", "repeat"),
    ]
    assert result.answered_by == "host" and result.outcome == "answered" and len(model.requests) == 2


def test_a_call_held_back_as_a_repeat_counts_for_the_step_whose_turn_it_is() -> None:
    """Dev half (multi-one-down-one-up): "keep bravo up" planned as "bravo: fly up"; the move that had put
    bravo there was sent again twelve times, to the step limit."""
    plan = Plan(["bravo: fly 16 m", "bravo: fly up"], FLEET)
    moved = _ok("move_to_relative", drone_id="bravo", alt_m=16)
    again = ToolCallRecord("again", "move_to_relative", {"drone_id": "bravo", "alt_m": 16}, "repeat", "")
    assert plan.next_note([moved]).startswith("Now step 2 of 2: bravo: fly up")
    assert plan.finished([moved, again])


async def test_steps_with_a_gap_are_sent_back_once_naming_it(toy: ToyServer, scripted) -> None:
    """Dev half (compound-corner-home): "then bring it home" planned without the way home; told what the
    steps leave out, the planner may write them again."""

    def gappy(body: dict[str, Any]) -> ScriptedReply:
        return ScriptedReply(content="1. alpha: take off to 15 m\n2. alpha: fly 15 m north")

    def fixed(body: dict[str, Any]) -> ScriptedReply:
        told = body["messages"][-1]["content"]
        assert told == gaps_note(["leave out the way home"]), told
        return ScriptedReply(content="1. alpha: take off to 15 m\n2. alpha: return home")

    model = scripted([gappy, fixed, call("takeoff", drone_id="alpha", alt_m=15), say("")])
    _, result = await run_on_toy(toy, model, "alpha up to 15 m, then bring it home", plan_first=True)
    assert (
        "Steps:\n1. alpha: take off to 15 m\n2. alpha: return home"
        in model.requests[2]["messages"][-1]["content"]
    )
    # with a gap again, there is no plan
    again = scripted([gappy, gappy, call("takeoff", drone_id="alpha", alt_m=15), say("up")])
    _, result = await run_on_toy(toy, again, "alpha up to 15 m, then bring it home", plan_first=True)
    assert "Steps:" not in again.requests[2]["messages"][-1]["content"] and result.final_text == "up"


def test_a_step_for_the_drone_with_more_or_less_battery_is_read_from_the_readings() -> None:
    """ "The one with less battery: take off to 7 m" waits for both readings, then is that drone's step;
    a get_battery call or a fleet_status table counts as a reading."""
    steps = ["bravo: read battery", "charlie: read battery", "the one with more battery: take off to 14 m"]
    plan = Plan(steps, FLEET, ["bravo", "charlie"])
    bravo = _ok("get_battery", "bravo battery 50%, 11.1 V", drone_id="bravo")
    assert "step 2 of 3: charlie: read battery" in plan.next_note([bravo])
    charlie = _ok("get_battery", "charlie battery 80%, 12.0 V", drone_id="charlie")
    note = plan.next_note([bravo, charlie])
    assert (
        "step 3 of 3 (charlie has the most battery: bravo 50 %, charlie 80 %): charlie: take off to 14 m"
        in note
    )
    assert not plan.finished([bravo, charlie])
    flown = _ok("takeoff", "takeoff on charlie succeeded", drone_id="charlie", alt_m=14)
    assert plan.finished([bravo, charlie, flown])
    # the wrong drone's takeoff does not carry the step out
    assert not plan.finished([bravo, charlie, _ok("takeoff", "takeoff on bravo succeeded", drone_id="bravo")])
    table = "id state arm air bat% alt_m mode action lock\nalpha ready n n 70 0.0 - - -"
    table += "\nbravo ready n n 30 0.0 - - -\ncharlie ready n n 85 0.0 - - -"
    least = Plan(
        ["alpha, bravo, charlie: read battery", "the one with the lowest battery: take off to 6 m"], FLEET
    )
    status = _ok("fleet_status", table)
    assert "bravo: take off to 6 m" in least.next_note([status])
    unread = Plan(["the one with less battery: land"], FLEET, ["alpha", "charlie"])
    assert "Read the battery of alpha, charlie first" in unread.next_note([])
    # the reads a step needs are made by the host: one drone's battery, or the table for several
    assert unread.call_due([]) == ("get_battery", {"drone_id": "alpha"})
    assert plan.call_due([]) == ("get_battery", {"drone_id": "bravo"})
    assert least.call_due([]) == ("fleet_status", {})
    assert Plan(["alpha: read position", "alpha: land"], FLEET).call_due([]) == (
        "get_position",
        {"drone_id": "alpha"},
    )
    # and the step the readings pick is the picked drone's call
    assert plan.call_due([bravo, charlie]) == ("takeoff", {"drone_id": "charlie", "alt_m": 14.0})
    assert plan.call_due([bravo, charlie, flown]) is None


def test_a_comparison_of_two_drones_takes_its_branch_or_the_otherwise_step() -> None:
    steps = [
        "alpha: read battery",
        "charlie: read battery",
        "if alpha > charlie: alpha: fly 20 m north at 12 m",
        "otherwise: charlie: fly 20 m north at 12 m",
    ]
    plan = Plan(steps, FLEET)
    alpha = _ok("get_battery", "alpha battery 45%", drone_id="alpha")
    charlie = _ok("get_battery", "charlie battery 75%", drone_id="charlie")
    assert "Now step 2 of 4: charlie: read battery" in plan.next_note([alpha])
    assert "Now step 4 of 4: charlie: fly 20 m north at 12 m" in plan.next_note([alpha, charlie])
    fuller = _ok("get_battery", "alpha battery 90%", drone_id="alpha")
    assert "Now step 3 of 4: alpha: fly 20 m north at 12 m" in plan.next_note([fuller, charlie])
    moved = _ok("move_to_relative", "arrived", drone_id="alpha", north_m=20, alt_m=12)
    assert plan.finished([fuller, charlie, moved])


def test_a_return_to_launch_is_the_way_home_and_the_landing_after_it() -> None:
    """ "Fly back to launch spot" is done by return_to_launch, and the landing step after it too (the drone
    is down); a land refused as "already on the ground" did its step."""
    plan = Plan(
        ["charlie: head 35 m north at 10 m", "charlie: fly back to launch spot", "charlie: land"], FLEET
    )
    out = _ok("move_to_relative", "arrived", drone_id="charlie", north_m=35, alt_m=10)
    home = _ok("return_to_launch", "landed and disarmed", drone_id="charlie")
    assert "Now step 2 of 3: charlie: fly back to launch spot" in plan.next_note([out])
    assert plan.finished([out, home])
    landed = ToolCallRecord(
        "land", "land", {"drone_id": "charlie"}, "error", "",
        text="charlie is already on the ground and disarmed: nothing to do, it is landed as asked",
    )  # fmt: skip
    back = _ok("move_to_relative", "arrived", drone_id="charlie", north_m=-35)
    assert "Now step 3 of 3: charlie: land" in plan.next_note([out, back])
    assert plan.finished([out, back, landed])
    failed = ToolCallRecord("land", "land", {"drone_id": "charlie"}, "error", "", text="charlie: no link")
    assert not plan.finished([out, back, failed])


async def test_the_reads_a_plan_needs_and_the_calls_its_steps_say_are_made_by_the_host(
    toy: ToyServer, scripted
) -> None:
    """A step that only reads ("alpha: read position") is the host's call, and so is a step whose words
    say its call ("alpha: take off to 15 m"): the model's first request after the plan already shows both
    results, and only the answer is asked for."""
    plan = ScriptedReply(content="1. alpha: read position\n2. alpha: take off to 15 m")
    model = scripted([plan, say("alpha is up at 15 m")])
    events: list[AgentEvent] = []
    _, result = await run_on_toy(
        toy, model, "where is alpha? then take it up to 15 m", plan_first=True, events=events
    )
    assert [c.name for c in result.tool_calls] == ["get_position", "takeoff"], result.tool_calls
    assert result.outcome == "answered" and result.final_text == "alpha is up at 15 m", result
    first = model.requests[1]["messages"][-1]["content"]
    assert '- {"name": "get_position", "arguments": {"drone_id": "alpha"}} -> ' in first, first
    assert "alpha flying at 15 m" in first, first  # the fleet as it is after the host's calls
    assert first.endswith("Every step is done. Reply with the answer_user call saying what was done.")
    assert [e.data["name"] for e in events if e.kind == "plan_call"] == ["get_position", "takeoff"]
    assert len(model.requests) == 2


async def test_a_call_the_host_made_for_a_step_is_not_made_again_when_it_failed(
    toy: ToyServer, scripted
) -> None:
    """A step's call that the gateway refused is not the host's again: the model is asked, with the
    refusal in what it reads."""
    plan = ScriptedReply(content="1. alpha: take off to 500 m\n2. alpha: land")
    model = scripted([plan, say("alpha cannot go to 500 m")])
    _, result = await run_on_toy(toy, model, "alpha up to 500 m then land", plan_first=True)
    assert [(c.name, c.status) for c in result.tool_calls][:1] == [("takeoff", "error")], result.tool_calls
    assert sum(c.name == "takeoff" for c in result.tool_calls) == 1
    asked = model.requests[1]["messages"][-1]["content"]
    assert '- {"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 500.0}} -> failed: ' in asked


def test_a_launch_step_is_written_in_the_words_of_the_tools() -> None:
    """ "Launch" is a takeoff; a takeoff with a compass direction is a flight (dev half, cond-fuller-north:
    "take off to 20 m north at 12 m" had the takeoff sent 17 times)."""
    assert split_steps("1. alpha: read battery\n2. charlie: take off to 20 m north at 12 m", FLEET, "x") == [
        "alpha: read battery",
        "charlie: fly 20 m north at 12 m",
    ]
    steps = "1. bravo: read battery\n2. the one with more battery: launch to 14 m\n3. bravo: return to launch"
    assert split_steps(steps, FLEET, "bravo") == [
        "bravo: read battery",
        "the one with more battery: take off to 14 m",
        "bravo: return to launch",
    ]


def test_a_hop_and_a_hover_from_the_ground_are_takeoffs_and_coming_down_is_a_landing() -> None:
    """Dev half (multi-hop-and-hover): the plan "charlie: hop to 6 m, charlie: return home, alpha: hover at
    15 m" lost alpha's step as no action and was dropped for a flight home nobody asked for; a formation
    then flew both drones to 6 m."""
    request = (
        "Have charlie do a quick hop to 6 m and come straight back down, and get alpha hovering at 15 m."
    )
    reply = "1. charlie: hop to 6 m\n2. charlie: return home\n3. alpha: hover at 15 m"
    assert steps_from_reply(reply, FLEET, request) == [
        "charlie: take off to 6 m",
        "charlie: land",
        "alpha: take off to 15 m",
    ]
    asked: list[int] = []

    class _Planner:
        async def ask(self, messages: Any, specs: Any, parameters: Any, usage: Usage) -> ModelReply:
            asked.append(len(messages))
            return ModelReply(content=reply)

    # the first reply is read so too, not sent back for its way home (as it was: "return home" was a gap)
    planned = asyncio.run(plan_steps(cast(ChatModel, _Planner()), FLEET, request, Usage()))
    assert planned == ["charlie: take off to 6 m", "charlie: land", "alpha: take off to 15 m"]
    assert len(asked) == 1
    # hovering after a step that put the drone up is still no step, and a request for home keeps its way home
    up = "1. bravo: take off to 18 m\n2. bravo: hover at 18 m\n3. bravo: fly 10 m north"
    assert split_steps(up, FLEET, "x") == ["bravo: take off to 18 m", "bravo: fly 10 m north"]
    home = "Take bravo up to 10 m, then bring it back home and land"
    assert steps_from_reply("1. bravo: take off to 10 m\n2. bravo: return home", FLEET, home)[-1] == (
        "bravo: return home"
    )


def test_a_landing_planned_for_bring_it_home_is_the_way_home() -> None:
    request = "Take charlie to 15 m, go 20 m east, then 20 m south, then bring it home."
    planned = [
        "charlie: take off to 15 m",
        "charlie: fly 20 m east",
        "charlie: fly 20 m south",
        "charlie: land",
    ]
    steps = home_for_landing(planned, request)
    assert steps[-1] == "charlie: return home" and carries_the_request(steps, request)
    # a request that speaks of a landing keeps it
    landing = "Take charlie to 15 m, go 20 m east, then land it."
    assert home_for_landing(planned, landing) == planned


def test_a_height_step_already_flown_by_the_move_before_is_done() -> None:
    """Dev half (rel-east-land-there): "50 m east, 10 m above the ground" planned as two steps; the move
    that flew east at 10 m did both."""
    plan = Plan(["bravo: fly 50 m east", "bravo: fly 10 m above the ground", "bravo: land"], FLEET)
    moved = _ok("move_to_relative", "arrived", drone_id="bravo", east_m=50, alt_m=10)
    assert plan.next_note([moved]).startswith("Now step 3 of 3: bravo: land")
    lower = _ok("move_to_relative", "arrived", drone_id="bravo", east_m=50, alt_m=20)
    assert plan.next_note([lower]).startswith("Now step 2 of 3")
    # a climb flown with the leg (dev half, rel-bravo-west-up: "40 m west ..., 10 m up" as two steps)
    west = Plan(["bravo: move 40 m west", "bravo: move 10 m up"], FLEET)
    assert west.finished([_ok("move_to_relative", "arrived", drone_id="bravo", east_m=-40, up_m=10)])
    # after a takeoff, a climb of the same size that the request names is a step of its own
    climb = Plan(
        ["charlie: take off to 10 m", "charlie: fly 10 m up"], FLEET, request="to 10 m, then 10 m up"
    )
    assert not climb.finished([_ok("takeoff", "reached 10 m", drone_id="charlie", alt_m=10)])


def test_a_choice_between_drones_names_the_drones_it_passed_over() -> None:
    steps = ["bravo: read battery", "charlie: read battery", "the one with more battery: take off to 14 m"]
    plan = Plan(steps, FLEET, ["bravo", "charlie"])
    reads = [
        _ok("get_battery", "bravo battery 50%", drone_id="bravo"),
        _ok("get_battery", "charlie battery 80%", drone_id="charlie"),
    ]
    assert plan.where(reads).passed_over == ("bravo",)
    assert plan.where(reads[:1]).passed_over == ()


async def test_a_call_on_a_drone_the_request_does_not_name_is_not_sent(toy: ToyServer, scripted) -> None:
    """Dev half (cond-better-charged-pair): "of bravo and charlie, launch the better charged one" took off
    alpha. An acting call on a drone the request does not name is held back, naming the ones it does."""
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=14),
            call("takeoff", drone_id="bravo", alt_m=14),
            say("bravo up"),
        ]
    )
    _, result = await run_on_toy(toy, model, "Take bravo up to 14 m, please")
    held, sent = result.tool_calls
    assert held.status == "invalid" and held.text.startswith(
        "Error: Not sent: the request does not name alpha; it names bravo. Nothing was executed."
    ), held
    assert sent.ok and [c[0] for c in toy.world.calls] == ["takeoff"]


def test_the_drones_asked_are_the_named_ones_unless_the_request_speaks_of_the_fleet() -> None:
    assert asked_drones("Of bravo and charlie, launch the better one and leave the other down", FLEET) == [
        "bravo",
        "charlie",
    ]
    assert asked_drones("Send charlie 30 m north and alpha 30 m south, each at 12 m", FLEET) == [
        "charlie",
        "alpha",
    ]
    assert asked_drones("Alpha to 10 m, the others to 20 m", FLEET) == FLEET
    assert asked_drones("Everyone up to 15 m", FLEET) == FLEET


def test_a_climb_the_request_does_not_name_is_not_the_hosts_call() -> None:
    """Dev half with the 0.5B model: "launch alpha, climb to thirty metres" planned as a takeoff and
    "alpha: climb 30 m"; made as written it flew alpha to 60 m. The host makes a climb only when the request
    names it; else the model is asked, and the request's checks read its call."""
    request = "Please launch alpha, climb to thirty metres and leave it hovering there."
    plan = Plan(["alpha: take off to 30 m", "alpha: climb 30 m"], FLEET, request=request)
    took_off = _ok("takeoff", drone_id="alpha", alt_m=30)
    assert plan.call_due([]) == ("takeoff", {"drone_id": "alpha", "alt_m": 30.0})
    assert plan.call_due([took_off]) is None
    named = Plan(
        ["alpha: take off to 10 m", "alpha: climb 5 m"], FLEET, request="alpha to 10 m, then climb 5 m"
    )
    assert named.call_due([took_off]) == (
        "move_to_relative",
        {"drone_id": "alpha", "north_m": 0.0, "east_m": 0.0, "up_m": 5.0},
    )


def test_a_step_for_another_drone_is_the_one_drone_the_request_speaks_of() -> None:
    """Dev half with the 0.5B model: "get charlie airborne, hover it at around 12 metres" planned as
    "alpha: hover at around 12 metres" (the first name of the fleet list)."""
    request = "Can you get charlie airborne? Hover it at around 12 metres."
    assert steps_from_reply("1. alpha: hover at around 12 metres", FLEET, request) == [
        "charlie: take off to 12 m"
    ]
    # a request naming two drones keeps its own: a step for a third is dropped
    two = "Take alpha and charlie up to 10 m and land them."
    reply = "1. alpha: take off to 10 m\n2. bravo: take off to 10 m\n3. alpha: land"
    assert steps_from_reply(reply, FLEET, two) == ["alpha: take off to 10 m", "alpha: land"]


def test_a_hover_height_after_a_bare_takeoff_is_the_takeoffs_height() -> None:
    """Dev half with the 0.5B model: "take off and stay up at 25 m" planned as "bravo: take off" and
    "bravo: stay up at 25 m"; the hover was dropped as no action and one bare takeoff was no plan."""
    request = "Bravo, take off and stay up at 25 m for now."
    reply = "1. bravo: take off\n2. bravo: stay up at 25 m"
    assert steps_from_reply(reply, FLEET, request) == ["bravo: take off to 25 m"]
    other = "1. bravo: take off\n2. alpha: stay up at 25 m"  # another drone's hover is its own takeoff
    assert split_steps(other, FLEET, "bravo up, and alpha at 25 m") == [
        "bravo: take off",
        "alpha: take off to 25 m",
    ]


def test_a_height_step_after_a_takeoff_to_it_is_done_unless_the_request_names_that_climb() -> None:
    """Dev half with the 0.5B model: "bravo and charlie both up to 18 m" planned as "bravo: take off to
    18 m", "bravo: fly 18 m up"; the second step is the same height again (a climb the request names is
    a step of its own)."""
    request = "Bravo and charlie both up to 18 m please, and keep them there."
    steps = ["bravo: take off to 18 m", "bravo: fly 18 m up", "charlie: take off to 18 m"]
    plan = Plan(steps, FLEET, request=request)
    took_off = _ok("takeoff", drone_id="bravo", alt_m=18)
    assert plan.call_due([took_off]) == ("takeoff", {"drone_id": "charlie", "alt_m": 18.0})
    climb = Plan(
        ["charlie: take off to 10 m", "charlie: fly 10 m up"], FLEET, request="charlie to 10 m, then 10 m up"
    )
    assert climb.next_note([_ok("takeoff", drone_id="charlie", alt_m=10)]).startswith("Now step 2 of 2")


async def test_a_call_that_is_no_call_after_the_last_step_gets_the_hosts_answer(
    toy: ToyServer, scripted
) -> None:
    """Dev half with the 0.5B model: every step done by the host, the model sent fleet_status with made-up
    arguments nine times instead of answering; the host answers from the results at the first."""
    plan = ScriptedReply(content="1. alpha: take off to 15 m")
    model = scripted([plan, call("hover_here", drone_id="alpha")])
    _, result = await run_on_toy(toy, model, "alpha up to 15 m and keep it there", plan_first=True)
    assert [(c.name, c.status) for c in result.tool_calls] == [
        ("takeoff", "ok"),
        ("hover_here", "unknown_tool"),
    ]
    assert result.answered_by == "host" and result.outcome == "answered" and len(model.requests) == 2


def test_a_step_that_acts_is_no_reading_whatever_else_it_says() -> None:
    """Dev half with the 1.5B model: the one step "alpha, bravo, charlie: line up at 20 m, 8 metres apart,
    right where they are" was read as a position read ("where"), made by the host, and the formation
    never flew."""
    request = "Line up alpha, bravo and charlie at 20 m, 8 metres apart, right where they are."
    step = "alpha, bravo, charlie: line up at 20 m, 8 metres apart, right where they are"
    assert steps_from_reply(f"1. {step}", FLEET, request) == []
    assert Plan([step, "alpha: land"], FLEET, request=request).call_due([]) is None
    assert Plan(["alpha: where is it now", "alpha: land"], FLEET).call_due([]) == (
        "get_position",
        {"drone_id": "alpha"},
    )


async def test_a_leg_with_no_height_for_a_drone_on_the_ground_is_asked_of_the_model(
    toy: ToyServer, scripted
) -> None:
    """The gateway refuses a leg from the ground with no height; the host does not make it, and the model
    (which reads the whole request) is asked for the step."""
    plan = ScriptedReply(content="1. alpha: fly 45 m south\n2. alpha: fly 12 m up")
    model = scripted([plan, say("alpha cannot fly that way")])
    events: list[AgentEvent] = []
    await run_on_toy(toy, model, "alpha 45 m south, 12 m up", plan_first=True, events=events)
    assert [e for e in events if e.kind == "plan_call"] == []
    asked = model.requests[1]["messages"][-1]["content"]
    assert asked.endswith(
        "Steps:\n1. alpha: fly 45 m south\n2. alpha: fly 12 m up\nCall one tool for each step, in this order."
    )


def test_the_0_5b_models_plan_shapes_from_the_dev_half() -> None:
    """Dev half with the 0.5B model: "the rest don't move" asked for as a step (charlie flown for it to the
    step limit); "straight back down" left out of the plan; "send it home to land" planned as a landing;
    "take up at 20 m" not carried by the takeoff to 20 m, which was sent again to the step limit."""
    hop = "Take the one lower on battery up to 6 m and straight back down; the rest don't move."
    lowest = "the one with the lowest battery"
    reply = f"1. alpha: read battery\n2. {lowest}: take off to 6 m\n3. the rest don't move"
    assert split_steps(reply, FLEET, hop) == ["alpha: read battery", f"{lowest}: take off to 6 m"]
    assert not carries_the_request(split_steps(reply, FLEET, hop), hop)  # the landing is left out
    assert carries_the_request([*split_steps(reply, FLEET, hop), f"{lowest}: land"], hop)
    # a condition's branch that does nothing stays: the plan reads it
    cond = "1. bravo: read battery\n2. if above 50 %: bravo: fly 30 m north at 15 m\n3. otherwise: don't fly"
    assert split_steps(cond, FLEET, "")[-1] == "otherwise: don't fly"
    home = "Get bravo to 18 m, move it 25 m north, and after that send it home to land."
    planned = "1. bravo: take off to 18 m\n2. bravo: fly 25 m north\n3. bravo: land"
    assert steps_from_reply(planned, FLEET, home) == [
        "bravo: take off to 18 m",
        "bravo: fly 25 m north",
        "bravo: return home",
    ]
    # a request that lands where it is keeps its landing
    there = "Get bravo to 18 m, move it 25 m north, and land it there."
    assert steps_from_reply(planned, FLEET, there)[-1] == "bravo: land"
    hop_down = "Hop charlie up to 6 m, then set it back down on the spot."
    assert carries_the_request(["charlie: take off 6 m", "charlie: set back down"], hop_down)
    plan = Plan(["bravo: read battery", "if at least 70 %: bravo: take up at 20 m"], FLEET)
    read = _ok("get_battery", "bravo battery 85%, 12.20 V", drone_id="bravo")
    assert not plan.finished([read])
    assert plan.finished([read, _ok("takeoff", drone_id="bravo", alt_m=20)])


def test_an_altitude_the_steps_leave_out_goes_to_each_drones_first_leg() -> None:
    """Dev half with the 0.5B model: "30 metres north and 30 metres west at 15 m" planned without the
    15 m, so the plan was dropped and the model flew without one."""
    hold = "Fly bravo 30 metres north and 30 metres west at 15 m and leave it there."
    reply = "1. bravo: fly 30 metres north and 30 metres west\n2. charlie: leave it there"
    assert steps_from_reply(reply, FLEET, hold) == ["bravo: fly 30 metres north and 30 metres west at 15 m"]
    both = "Alpha 25 m to the east and bravo 25 m to the north, both at 10 m."
    reply = "1. alpha: fly 25 m east\n2. bravo: fly 25 m north\n3. alpha: fly 5 m west"
    assert steps_from_reply(reply, FLEET, both)[:2] == [
        "alpha: fly 25 m east at 10 m",
        "bravo: fly 25 m north at 10 m",
    ]
    # steps that give the altitude, or a request with two, are left as written
    given = ["bravo: take off to 15 m", "bravo: fly 30 m north"]
    assert height_for_legs(given, "Bravo 30 m north at 15 m.", FLEET) == given
    two = ["alpha: fly 25 m east", "bravo: fly 25 m north"]
    assert height_for_legs(two, "Alpha 25 m east at 10 m, bravo 25 m north at 12 m.", FLEET) == two


def test_the_same_formation_words_for_each_drone_are_one_formation_step() -> None:
    """Dev half with the 0.5B model: a takeoff and "fly 8 metres apart" per drone, and "fly 15 m apart, at
    20 m" per drone written twice; both plans were dropped and no formation flew."""
    here = "Line up alpha, bravo and charlie at 20 m, 8 metres apart, right where they are."
    per_drone = [f"{d}: {a}" for d in FLEET for a in ("take off to 20 m", "fly 8 metres apart")]
    reply = "\n".join(f"{i}. {s}" for i, s in enumerate(per_drone, 1))
    assert steps_from_reply(reply, FLEET, here) == [
        "alpha, bravo, charlie: line formation, 8 metres apart, at 20 m"
    ]
    pair = "Alpha and charlie side by side, 15 m apart, at 20 m, where they are now."
    reply = "\n".join(f"{i}. {d}: fly 15 m apart, at 20 m" for i, d in enumerate(["alpha", "charlie"] * 2, 1))
    assert steps_from_reply(reply, FLEET, pair) == ["alpha, charlie: line formation, 15 m apart, at 20 m"]
    # no shape in the steps nor one in the request: left as written (then no plan)
    assert formation_for_drones(
        ["alpha: 5 m apart", "bravo: 5 m apart"], "Alpha and bravo 5 m apart.", FLEET
    ) == [
        "alpha: 5 m apart",
        "bravo: 5 m apart",
    ]


def test_a_height_step_next_to_a_leg_without_one_is_that_legs_altitude() -> None:
    """Dev half with the 0.5B model: "35 metres to the east, at 14 m" planned as a leg and "fly 14 m";
    "50 m east, 10 m above the ground" as a leg and "fly 10 m above the ground"."""
    hover = "Charlie: 35 metres to the east, at 14 m, and hover there."
    reply = "1. charlie: take off to 35 metres to the east\n2. charlie: fly 14 m\n3. charlie: hover there"
    assert steps_from_reply(reply, FLEET, hover) == ["charlie: fly 35 metres to the east at 14 m"]
    there = "Bravo should go 50 m east, 10 m above the ground, and then come down there."
    reply = "1. bravo: fly 10 m above the ground\n2. bravo: fly 50 m east\n3. bravo: land"
    assert steps_from_reply(reply, FLEET, there) == ["bravo: fly 50 m east at 10 m", "bravo: land"]
    # a height the request names as a climb, or another drone's, stays its own step
    climb = ["bravo: fly 50 m east", "bravo: fly 10 m"]
    assert height_steps_into_legs(climb, "Bravo 50 m east, then climb 10 m.", FLEET) == climb
    other = ["bravo: fly 50 m east", "alpha: fly 10 m"]
    assert height_steps_into_legs(other, "Bravo 50 m east at 10 m, alpha to 10 m.", FLEET) == other


def test_kilometres_are_read_as_metres() -> None:
    """Dev half with the 0.5B model: "2 kilometres east" flown 2 m north; the step is the host's call,
    refused by the distance rule."""
    plan = "1. alpha: fly 2 kilometres east at 20 m"
    assert steps_from_reply(plan, FLEET, "Fly alpha 2 kilometres east at 20 m.") == [plan[3:]]


def test_landing_them_is_a_landing_for_each_drone_named() -> None:
    """Dev half with the 0.5B model: "... and land them over there" planned with alpha's landing only."""
    west = "Take alpha and charlie 40 m west at 15 m altitude and land them over there."
    legs = [f"{d}: fly 40 m west at 15 m altitude" for d in ("alpha", "charlie")]
    reply = "\n".join(f"{i}. {s}" for i, s in enumerate([*legs, "alpha: land"], 1))
    assert steps_from_reply(reply, FLEET, west) == [*legs, "alpha: land", "charlie: land"]
    # one drone landed by name stays the only landing
    one = "Take alpha and charlie 40 m west at 15 m altitude and land alpha there."
    assert steps_from_reply(reply, FLEET, one) == [*legs, "alpha: land"]


def test_a_bare_height_the_request_names_as_an_altitude_is_that_altitude() -> None:
    """Dev half with the 0.5B model: "both at 10 m" planned as "alpha: spread out, 25 m to the east, 10 m"."""
    spread = "Spread them out: alpha 25 m to the east and bravo 25 m to the north, both at 10 m."
    reply = "1. alpha: spread out, 25 m to the east, 10 m\n2. bravo: spread out, 25 m to the north, 10 m"
    steps = steps_from_reply(reply, FLEET, spread)
    assert steps == [
        "alpha: spread out, 25 m to the east at 10 m",
        "bravo: spread out, 25 m to the north at 10 m",
    ]
    # a bare height the request does not name as an altitude stays as written
    assert steps_from_reply(reply, FLEET, "Alpha 25 m east and bravo 25 m north, then climb 10 m.") == [
        "alpha: spread out, 25 m to the east, 10 m",
        "bravo: spread out, 25 m to the north, 10 m",
    ]


def test_a_step_a_condition_does_again_is_only_under_the_condition() -> None:
    """Dev half with the 0.5B model: charlie flew at 30 % for "... but only if its battery is over 60 %"."""
    only_if = "Charlie goes up to 15 m, but only if its battery is over 60 %. Tell me what you decided."
    reply = "1. charlie: fly 15 m\n2. charlie: read battery\n3. if over 60 %: charlie: take off to 15 m"
    assert steps_from_reply(reply, FLEET, only_if) == [
        "charlie: read battery",
        "if over 60 %: charlie: take off to 15 m",
    ]


async def test_only_the_answer_is_offered_once_every_step_is_done(toy: ToyServer, scripted) -> None:
    """Dev half with the 0.5B model: "alpha just goes up to 8 m and lands again", every step made by the
    host, then alpha flown out again by the model's next call. Once the steps are done and the request
    asks for nothing more, the next reply is offered only answer_user; a call written anyway is not sent
    and the host answers."""
    plan = ScriptedReply(content="1. alpha: take off to 8 m\n2. alpha: land")
    model = scripted([plan, call("move_north", drone_id="alpha", distance_m=30)])
    request = "alpha just goes up to 8 m and lands again"
    _, result = await run_on_toy(toy, model, request, plan_first=True, answer_tool=True)
    offered = [t["function"]["name"] for t in model.requests[1]["tools"]]
    assert offered == ["answer_user"]
    assert [(c.name, c.status) for c in result.tool_calls] == [
        ("takeoff", "ok"),
        ("land", "ok"),
        ("move_north", "invalid"),
    ]
    assert "every step of the request is done" in result.tool_calls[-1].text
    assert result.answered_by == "host" and result.outcome == "answered"


async def test_all_the_tools_are_offered_while_the_request_asks_for_more(toy: ToyServer, scripted) -> None:
    """Steps done, but the request names bravo and no step flew it: the model keeps every tool."""
    plan = ScriptedReply(content="1. alpha: take off to 8 m")
    model = scripted(
        [plan, call("takeoff", drone_id="bravo", alt_m=8), call("answer_user", text="both at 8 m")]
    )
    request = "alpha up to 8 m, and bravo too"
    _, result = await run_on_toy(toy, model, request, plan_first=True, answer_tool=True)
    offered = {t["function"]["name"] for t in model.requests[1]["tools"]}
    assert {"takeoff", "land", "answer_user"} <= offered
    assert [(c.name, c.status) for c in result.tool_calls] == [("takeoff", "ok"), ("takeoff", "ok")]


def test_a_step_that_acts_and_lands_is_two_steps_and_the_way_home_lands_itself() -> None:
    """Dev half with the 0.5B model: "charlie: fly back to your launch spot and land" was flown as
    neither; a step of two actions is two steps, and the way home is one (return_to_launch lands)."""
    home = "Charlie, head 35 m north at 10 m, then fly back to your launch spot and land."
    assert steps_from_reply(
        "1. charlie: head 35 m north at 10 m\n2. charlie: fly back to your launch spot and land", FLEET, home
    ) == ["charlie: head 35 m north at 10 m", "charlie: fly back to your launch spot"]
    hop = "Bravo up to 10 m and land it; alpha to 5 m."
    assert steps_from_reply("1. bravo: fly up to 10 m and land\n2. alpha: take off to 5 m", FLEET, hop) == [
        "bravo: fly up to 10 m",
        "bravo: land",
        "alpha: take off to 5 m",
    ]
    # a take-off point is home, in the request as in the steps
    back = "Bravo, fly 30 m west at 20 m, then return to your take-off point and land there."
    steps = "1. bravo: fly 30 m west at 20 m\n2. bravo: return to your take-off point and land there"
    assert steps_from_reply(steps, FLEET, back) == [
        "bravo: fly 30 m west at 20 m",
        "bravo: return to your take-off point",
    ]


def test_a_condition_the_planner_left_out_is_read_from_the_request() -> None:
    """Dev half with the 0.5B model: "the better charged one" planned as a takeoff of each drone; "only if
    charlie is above 40 percent" planned with the takeoff first, the read after it, and the condition on
    another drone."""
    pair = "Of bravo and charlie, launch the better charged one to 14 m and leave the other on the pad."
    assert steps_from_reply("1. bravo: take off to 14 m\n2. charlie: take off to 14 m", FLEET, pair) == [
        "bravo: read battery",
        "charlie: read battery",
        "the one with more battery: take off to 14 m",
    ]
    only_if = "Only if charlie is above 40 percent, send it up to 12 m and land it. Otherwise leave it be."
    reply = (
        "1. charlie: take off to 12 m\n2. charlie: land\n3. charlie: read battery\n"
        "4. if above 40 percent: alpha: land"
    )
    assert steps_as_meant(reply, FLEET, only_if) == [
        "charlie: read battery",
        "if above 40 %: charlie: take off to 12 m",
        "if above 40 %: charlie: land",
    ]
    # the request says what to fly when the condition does not hold: left as the planner wrote it
    inverse = "If charlie's charge is under 30 percent, don't launch it; otherwise put it up at 8 m."
    assert steps_as_meant("1. charlie: read battery\n2. charlie: take off to 8 m", FLEET, inverse) == [
        "charlie: read battery",
        "charlie: take off to 8 m",
    ]
    # a question that picks a drone is no choice to fly
    asked = "Which of alpha and bravo has more battery? Then land alpha."
    assert steps_as_meant("1. alpha: read battery\n2. bravo: read battery\n3. alpha: land", FLEET, asked)[
        -1
    ] == ("alpha: land")


def test_a_move_of_one_drone_that_repeats_the_formation_before_it_is_no_step() -> None:
    """Dev half with the 0.5B model: "alpha: fly 12 m, 20 m east" before the line formation at 12 m, 20 m
    east flew alpha alone and the formation never."""
    line = "Put alpha, bravo and charlie in a line 10 m apart at 12 m, 20 m east of where they are."
    formation = "alpha, bravo, charlie: line formation, 10 m apart, at 12 m, 20 m east"
    assert steps_from_reply(f"1. alpha: fly 12 m, 20 m east\n2. {formation}", FLEET, line) == [formation]
    # a step with a number of its own, or after the formation, stays
    then = f"1. {formation}\n2. alpha: fly 20 m east"
    assert split_steps(then, FLEET) == [formation, "alpha: fly 20 m east"]
    own = f"1. alpha: fly 30 m north\n2. {formation}"
    assert split_steps(own, FLEET) == ["alpha: fly 30 m north", formation]


def test_settling_back_on_the_ground_and_back_down_are_landings() -> None:
    """Dev half with the 0.5B model: "bravo rises to 12 m and then settles back on the ground" planned
    without a landing and answered as done; "send it up to 12 m and back down" left charlie at 12 m, its
    plan's descent refused and the request read as finished."""
    from gateway.agent.checks import to_land

    settle = "Bravo rises to 12 m and then settles back on the ground. Charlie goes 15 m east at 10 m."
    assert plan_gaps(["bravo: rise to 12 m", "charlie: go 15 m east at 10 m"], settle) == [
        "leave out the landing"
    ]
    assert to_land(settle, ["bravo", "charlie"]) == ["bravo"]
    assert to_land("Only if charlie is above 40 percent, send it up to 12 m and back down.", ["charlie"]) == [
        "charlie"
    ]
    assert to_land("bring charlie back down to 5 m", ["charlie"]) == []


def test_formation_words_for_each_drone_take_the_requests_altitude_and_neighbour_spacing() -> None:
    """Dev half with the 0.5B model: "in a circle with 10 m between neighbours, at 25 m, here" planned as
    "fly 10 m between neighbours" for each drone, with no height; no plan was kept."""
    circle = "Arrange all three drones in a circle with 10 m between neighbours, at 25 m, here."
    each = "\n".join(f"{i}. {d}: fly 10 m between neighbours" for i, d in enumerate(FLEET, 1))
    step = "alpha, bravo, charlie: circle formation, 10 m between neighbours, at 25 m"
    assert steps_from_reply(each, FLEET, circle) == [step]
    assert Plan([step], FLEET, request=circle).call_due([]) == (
        "formation_goto",
        {"drone_ids": FLEET, "formation": "circle", "spacing_m": 10.0, "alt_m": 25.0},
    )
