"""What the host tells the model is still left of a request: distances not flown, a landing not done,
and where nothing was done at all (dev-half measurements in each docstring)."""

from __future__ import annotations

from typing import Any

from bench.agent_harness.scripted import ScriptedModelServer, call
from gateway.agent.answer import ANSWER_TOOL
from gateway.agent.checks import to_land, told_to_stay, untouched
from gateway.agent.repair import horizontal_legs_left
from gateway.agent.roster import DroneEntry, Roster
from gateway.agent.toolbox import ToolInfo
from gateway.agent.turns import ToolCallRecord, TurnResult
from gateway.agent.wording import not_an_answer
from tests.agent.test_loop import run_on_toy
from tests.agent.toy_mcp import ToyServer

REQUEST = "All three in a row, 12 m between each, at 20 m, 25 m south of where they are."


def _turn(*calls: tuple[Any, ...]) -> TurnResult:
    """A turn of (tool, arguments, status[, text]) records."""
    result = TurnResult(outcome="answered", final_text=None, steps=1)
    for i, (name, args, status, *text) in enumerate(calls):
        result.tool_calls.append(ToolCallRecord(f"c{i}", name, args, status, "", text="".join(text)))
    return result


def test_a_distance_is_left_until_a_call_carries_it_on_its_axis_with_its_sign() -> None:
    assert horizontal_legs_left(REQUEST, [{"north_m": 0, "east_m": 0}]) == ["25 m south"]
    assert horizontal_legs_left(REQUEST, [{"north_m": -25}]) == []
    assert horizontal_legs_left(REQUEST, [{"south_m": 25}]) == []
    assert horizontal_legs_left(REQUEST, [{"north_m": 25}]) == ["25 m south"]


def test_each_leg_of_there_and_back_is_its_own() -> None:
    request = "Fly alpha 30 m east at 12 m, then 30 m back west, then land it."
    assert horizontal_legs_left(request, [{"east_m": 30}]) == ["30 m back west"]
    assert horizontal_legs_left(request, [{"east_m": 30}, {"west_m": 30}]) == []


def test_climbs_are_not_legs() -> None:
    assert horizontal_legs_left("move alpha 25 m north and 8 m up", [{"north_m": 25, "alt_m": 8}]) == []


ROSTER = Roster(tuple(DroneEntry(d, flying=True, alt_m=20.0, battery_pct=99.0) for d in ("alpha", "bravo")))
TOOLS = {"formation_goto": ToolInfo("formation_goto", "f", {"type": "object"})}


def test_untouched_names_a_distance_no_call_flew_once_something_acted() -> None:
    """Measured on the dev half (form-line-south): formed up in place with north_m=0, then "done"."""
    formed = _turn(("formation_goto", {"drone_ids": ["alpha", "bravo"], "north_m": 0, "east_m": 0}, "ok"))
    facts = untouched(formed, REQUEST, ROSTER, TOOLS, answering=True)
    assert facts == "Distances the request names that no call has flown yet: 25 m south."
    assert untouched(_turn(), REQUEST, ROSTER, TOOLS, answering=True) == ""  # nothing acted yet


def test_a_refused_leg_is_not_left_to_fly() -> None:
    request = "Bravo: 1500 m north at 30 m please, then land."
    refused = _turn(
        ("takeoff", {"drone_id": "bravo", "alt_m": 30}, "ok"),
        ("move_to_relative", {"drone_id": "bravo", "north_m": 1500}, "error", "Refused: max_distance: ..."),
    )
    assert "1500 m north" not in untouched(refused, request, ROSTER, TOOLS)


def test_a_restated_request_with_nothing_done_is_told_to_act() -> None:
    """Measured on the dev half (cond-bravo-seventy, cond-charlie-sixty): the condition restated as the
    answer, twice, when told to say what was done."""
    told = not_an_answer("bravo has at least 70 % battery, put it up at 20 m", False, _turn())
    assert told.startswith("Not an answer: that only repeats the request, and nothing has been read or done")
    read = _turn(("get_battery", {"drone_id": "bravo"}, "ok"))
    assert not_an_answer("bravo has 85 %", False, read).startswith(
        "Not an answer: that only repeats the request or"
    )


async def test_a_repeated_step_is_told_what_is_left(toy: ToyServer, scripted: Any) -> None:
    """Measured on the dev half (compound-two-climbs): the step already done sent again three times, and
    the landing the request ends with never."""
    model: ScriptedModelServer = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call("takeoff", drone_id="alpha", alt_m=10),
            call("land", drone_id="alpha"),
            call(ANSWER_TOOL, text="Alpha went up to 10 m and landed."),
        ]
    )
    _, result = await run_on_toy(toy, model, "take alpha up to 10 m, then land it", answer_tool=True)
    told = [m for m in model.requests[2]["messages"] if m["role"] == "tool"][-1]["content"]
    assert told.startswith("Not sent again: this takeoff call already succeeded"), told
    assert "Still to do: The request asks to land or come home, and alpha is still flying." in told, told
    assert result.final_text == "Alpha went up to 10 m and landed."


def test_a_drone_told_to_stay_is_not_left_and_only_the_drones_a_landing_is_said_of_must_land() -> None:
    """Measured on the corpus's dev half: "Bravo stays down for now. Take alpha up to 14 m and land it,
    and send charlie to 22 m" had its answer held back for bravo ("nothing has been done with it") and
    for charlie ("still flying")."""
    request = "Bravo stays down for now. Take alpha up to 14 m and land it, and send charlie to 22 m."
    three = ("alpha", "bravo", "charlie")
    assert [d for d in three if told_to_stay(request, d)] == ["bravo"]
    assert to_land(request, list(three)) == ["alpha"]
    roster = Roster(
        tuple(DroneEntry(d, d == "charlie", 22.0 if d == "charlie" else 0.0, 90.0) for d in three)
    )
    done = _turn(
        ("takeoff", {"drone_id": "alpha", "alt_m": 14}, "ok"),
        ("land", {"drone_id": "alpha"}, "ok"),
        ("takeoff", {"drone_id": "charlie", "alt_m": 22}, "ok"),
    )
    assert untouched(done, request, roster, TOOLS, answering=True) == ""
    # a number in the clause: the drone has something to do ("alpha stays at 20 m" is no stay on the ground)
    assert not told_to_stay("Alpha climbs to 20 m and stays there.", "alpha")
    # a landing said of them all, or a request naming one drone: every named drone lands
    assert to_land("Send charlie 30 m north and alpha 30 m south, then land both.", ["alpha", "charlie"]) == [
        "alpha",
        "charlie",
    ]
    # "back down" is a landing (as the plan's landing gap reads it), "back down to 5 m" a descent
    assert to_land("Take alpha up to 14 m and bring it back down.", ["alpha"]) == ["alpha"]
    assert to_land("Take alpha up to 14 m and bring it back down to 5 m.", ["alpha"]) == []
    assert to_land("Take alpha up to 14 m and fly it 20 m north.", ["alpha"]) == []
    assert to_land("Take alpha up to 14 m and land it.", ["alpha"]) == ["alpha"]
