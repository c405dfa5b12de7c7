"""readings: the conditions and choices a request puts on battery readings."""

from __future__ import annotations

import pytest

from gateway.agent.readings import asked_pick, pick_unsaid
from gateway.agent.turns import ToolCallRecord

FLEET = ("alpha", "bravo", "charlie")


@pytest.mark.parametrize(
    ("request_text", "expected"),
    [
        ("Out of the three, which drone has the most battery left?", ("most", list(FLEET))),
        (
            "Between alpha and charlie, which one is running lower on battery?",
            ("lower", ["alpha", "charlie"]),
        ),
        ("Which drone's charge is the lowest?", ("lowest", list(FLEET))),
        ("Which of bravo and charlie is better charged?", ("better", ["bravo", "charlie"])),
        ("What is bravo's battery?", None),
        ("Which drone is flying highest?", None),  # a height, not a battery
        ("Launch the one with the most battery", None),  # an order, not a question
    ],
)
def test_a_question_that_picks_a_drone_by_its_battery(request_text: str, expected: object) -> None:
    assert asked_pick(request_text, FLEET) == expected


def _read(drone: str, pct: float) -> ToolCallRecord:
    return ToolCallRecord(f"c-{drone}", "get_battery", {"drone_id": drone}, "ok", f"{drone} battery {pct:g}%")


def test_the_pick_is_said_only_when_the_answer_names_another_drone() -> None:
    calls = [_read("alpha", 54), _read("bravo", 69), _read("charlie", 91)]
    request = "Which drone has the most battery left?"
    assert pick_unsaid(request, calls, FLEET, "alpha has the most battery left with 54%") == (
        "charlie has the most battery (alpha 54 %, bravo 69 %, charlie 91 %)"
    )
    assert pick_unsaid(request, calls, FLEET, "Charlie, with 91 %.") is None
    assert pick_unsaid(request, calls[:2], FLEET, "alpha") is None  # charlie not read: no pick to judge by
    assert pick_unsaid("Which has the least charge?", calls, FLEET, "Charlie.") == (
        "alpha has the least battery (alpha 54 %, bravo 69 %, charlie 91 %)"
    )
