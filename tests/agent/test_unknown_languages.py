"""A request in a language the lexicon does not know is flown as the model planned it: the host's
rewriting (`fleet_agent.consistency.read_plan`) keeps the plan's landing and the drones the request means
without naming each. The requests are written for these tests."""

from __future__ import annotations

from typing import Any

import pytest

from fleet_agent.consistency import read_plan
from fleet_agent.plan import Plan, parse_plan

FLEET = ["alpha", "bravo", "charlie"]


def _m(value: float) -> dict[str, Any]:
    return {"value": value, "unit": "m"}


def _up(drone: str, value: float, after: str = "stay") -> dict[str, Any]:
    return {"action": "takeoff", "drone": drone, "altitude": _m(value), "after": after}


def _leg(drone: str, value: float, direction: str, after: str) -> dict[str, Any]:
    legs = [{"distance": _m(value), "direction": direction}]
    return {
        "action": "move",
        "drone": drone,
        "origin": "here",
        "legs": legs,
        "altitude": None,
        "after": after,
    }


def _read(request: str, steps: list[dict[str, Any]]) -> tuple[Plan, Plan]:
    """The plan the host compiles, and the plan as the model wrote it."""
    plan, _ = read_plan(request, FLEET, {"steps": steps})
    return plan, parse_plan({"steps": steps}, FLEET)


LANDINGS = [
    ("Vzlétni s alpha na 12 m, přeleť 30 m na východ a pak přistaň.", "alpha", "east", "land"),  # Czech
    ("Lyft bravo till 12 m, flyg 30 m söderut och sätt ner den där.", "bravo", "south", "land"),  # Swedish
    ("charlie'yi 12 m yükselt, 30 m kuzeye uçur ve orada indir.", "charlie", "north", "land"),  # Turkish
    ("alphaを12 mまで上昇させ、西へ30 m飛んでから着陸させてください。", "alpha", "west", "land"),  # Japanese
    ("Vzlétni s bravo na 12 m, přeleť 30 m na západ a vrať se domů.", "bravo", "west", "return_home"),
]


@pytest.mark.parametrize(
    ("request_text", "drone", "direction", "after"), LANDINGS, ids=["cs", "sv", "tr", "ja", "cs-home"]
)
def test_the_ending_of_a_request_in_an_unknown_language_is_kept(
    request_text: str, drone: str, direction: str, after: str
) -> None:
    plan, written = _read(request_text, [_up(drone, 12), _leg(drone, 30, direction, after)])
    assert plan == written
    assert plan.steps[-1].after == after  # type: ignore[union-attr]


def test_a_landing_written_as_its_own_step_is_kept() -> None:
    steps = [_up("charlie", 8), {"action": "land", "drone": "charlie"}]
    plan, written = _read("charlie'yi 8 m havalandır, sonra yere indir.", steps)  # Turkish
    assert plan == written and plan.steps[-1].action == "land"


DRONES_MEANT = [
    "Skicka upp bravo och de andra två till 20 m och landa sedan alla.",  # Swedish: "and the other two"
    "Bravo a ostatní drony vzlétnou na 20 m a pak všechny přistanou.",  # Czech: "and the other drones"
    "bravo ve diğerleri 20 m'ye çıksın, sonra hepsi insin.",  # Turkish: "and the others"
    "bravoと他の機体を20 mまで上げて、全機を着陸させて。",  # Japanese: "and the other aircraft"
]


@pytest.mark.parametrize("request_text", DRONES_MEANT, ids=["sv", "cs", "tr", "ja"])
def test_the_drones_a_request_means_without_naming_them_are_kept(request_text: str) -> None:
    steps = [_up(d, 20, after="land") for d in ("bravo", "alpha", "charlie")]
    plan, written = _read(request_text, steps)
    assert plan == written
    assert [s.drone for s in plan.steps] == ["bravo", "alpha", "charlie"]  # type: ignore[union-attr]


def test_a_step_that_cannot_be_meant_is_still_dropped_in_any_language() -> None:
    """The one drone a Czech request names climbs to its 12 m; a step of another drone to 25 m, a number
    the request does not give, is not the request's."""
    steps = [_up("alpha", 12, after="land"), _up("charlie", 25)]
    plan, _ = _read("Vzlétni s alpha na 12 m a pak přistaň.", steps)
    assert [s.drone for s in plan.steps] == ["alpha"]  # type: ignore[union-attr]
    assert plan.steps[0].after == "land"  # type: ignore[union-attr]
