"""A length's value may be arithmetic of the request's numbers, worked out by the host; nothing but numbers,
+ - * /, min() and max() runs, and anything else is refused with one line that says what is accepted."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from fleet_agent import arithmetic
from fleet_agent.compiler import sum_legs
from fleet_agent.consistency import read_plan
from fleet_agent.plan import Altitude, Leg, Length, parse_plan

FLEET = ["alpha", "bravo", "charlie"]


@pytest.mark.parametrize(
    ("text", "value"),
    [("(8+20)/2", 14.0), ("24/2", 12.0), ("12*90", 1080.0), ("120*(1+10/100)", 132.0), ("12 × 3", 36.0),
     ("7", 7.0), ("-3+5", 2.0), ("max(7,16,10)", 16.0), ("min(30, 20)/2", 10.0), ("max(2, 3) * 4", 12.0)],
)  # fmt: skip
def test_arithmetic_of_numbers_is_worked_out(text: str, value: float) -> None:
    assert arithmetic.evaluate(text) == pytest.approx(value)


@pytest.mark.parametrize(
    "text", ['__import__("os")', "(1).real", "x", "1/0", "9e308*10", "2**3", "True+1", '"a"+"b"', "20 m", "",
             "1+" * 40 + "1",
             "max", "max(1)", "max(*[1, 2])", "max(1, 2, key=None)", "abs(-3)", "max(alpha, bravo)",
             "max(1,2)(3)"],
)  # fmt: skip
def test_anything_but_arithmetic_of_numbers_is_refused_saying_what_is_accepted(text: str) -> None:
    with pytest.raises(ValueError, match=r"is not a number, or arithmetic of numbers with \+ - \* /"):
        arithmetic.evaluate(text)
    assert arithmetic.numbers(text) == [] or text in ("1/0", "9e308*10", "max(1)")


def test_a_length_in_arithmetic_converts_its_result_and_keeps_its_numbers() -> None:
    assert Length(value="(8+20)/2", unit="m").metres == 14.0
    assert Length(value="100/2", unit="ft").metres == 15.24
    leg = Leg.model_validate({"distance": {"value": "40/2", "unit": "m"}, "direction": "north"})
    assert sum_legs([leg]) == (20.0, 0.0, 0.0)
    assert sorted(arithmetic.numbers("(8+20)/2")) == [2.0, 8.0, 20.0]
    assert sorted(arithmetic.numbers("max(7,16,10)")) == [7.0, 10.0, 16.0]


def test_a_length_that_works_out_below_zero_or_is_not_arithmetic_is_an_invalid_plan() -> None:
    for value, said in (("8-20", "works out below 0"), ("eight", "is not a number")):
        step = {
            "action": "altitude",
            "drone": "alpha",
            "altitude": {"value": value, "unit": "m"},
            "after": "stay",
        }
        with pytest.raises(ValidationError, match=said):
            parse_plan({"in_english": "", "steps": [step]}, FLEET)


def test_the_numbers_an_arithmetic_value_is_worked_out_from_count_as_the_plans() -> None:
    """A plan that writes "halfway between 8 m and 20 m" as (8+20)/2 leaves neither number out."""
    request = "The trees top out at 8 m and the line runs at 20 m: put alpha halfway between, over its pad."
    step = {"action": "altitude", "drone": "alpha", "altitude": {"value": "(8+20)/2", "unit": "m"},
            "after": "stay"}  # fmt: skip
    plan, gaps = read_plan(request, FLEET, {"in_english": "Alpha climbs halfway.", "steps": [step]})
    assert gaps == []
    assert isinstance(plan.steps[0], Altitude) and plan.steps[0].altitude.metres == 14.0
    _, gaps = read_plan(request, FLEET, {"in_english": "Alpha climbs.", "steps": [{**step, "altitude":
                        {"value": 14, "unit": "m"}}]})  # fmt: skip
    assert gaps == ["the request gives 8, which no step of the plan has",
                    "the request gives 20, which no step of the plan has"]  # fmt: skip
