"""A plan step read into the one call its words say, or into none (the model is then asked)."""
# ruff: noqa: E501  (one step and its call a line)

from __future__ import annotations

import pytest

from gateway.agent.step_calls import call_of_step

FLEET = ["alpha", "bravo", "charlie"]


@pytest.mark.parametrize(
    ("step", "call"),
    [
        ("alpha: take off to 20 m", ("takeoff", {"drone_id": "alpha", "alt_m": 20.0})),
        ("Bravo: land.", ("land", {"drone_id": "bravo"})),
        ("alpha: return home", ("return_to_launch", {"drone_id": "alpha"})),
        ("charlie: set back down", ("land", {"drone_id": "charlie"})),  # 0.5B's plan, dev half
        ("charlie: come straight back down", ("land", {"drone_id": "charlie"})),
        ("charlie: fly back to launch spot", ("return_to_launch", {"drone_id": "charlie"})),
        ("alpha: fly 50 m north", ("move_to_relative", {"drone_id": "alpha", "north_m": 50.0, "east_m": 0.0})),
        (
            "bravo: fly 30 m south and 40 m west at 12 m",
            ("move_to_relative", {"drone_id": "bravo", "north_m": -30.0, "east_m": -40.0, "alt_m": 12.0}),
        ),
        (
            "charlie: fly over 20 m north while climbing another 6 m",
            ("move_to_relative", {"drone_id": "charlie", "north_m": 20.0, "east_m": 0.0, "up_m": 6.0}),
        ),
        (
            "alpha: fly 10 m east and 3 m lower",
            ("move_to_relative", {"drone_id": "alpha", "north_m": 0.0, "east_m": 10.0, "up_m": -3.0}),
        ),
        # an altitude and nothing else: move_to_relative flies it from the ground (taking off first) and
        # in the air (0.5B's plans, dev half)
        ("alpha: climb to 30 m", ("move_to_relative", {"drone_id": "alpha", "north_m": 0.0, "east_m": 0.0, "alt_m": 30.0})),
        ("bravo: rise to 12 m", ("move_to_relative", {"drone_id": "bravo", "north_m": 0.0, "east_m": 0.0, "alt_m": 12.0})),
        ("charlie: drop down to 10 m there", ("move_to_relative", {"drone_id": "charlie", "north_m": 0.0, "east_m": 0.0, "alt_m": 10.0})),
        ("bravo: raise to 10 m", ("move_to_relative", {"drone_id": "bravo", "north_m": 0.0, "east_m": 0.0, "alt_m": 10.0})),
        ("charlie: up to 6 m first", ("move_to_relative", {"drone_id": "charlie", "north_m": 0.0, "east_m": 0.0, "alt_m": 6.0})),
        # the way home ends with a landing (return_to_launch lands)
        ("bravo: return to your take-off point and land there", ("return_to_launch", {"drone_id": "bravo"})),
        ("alpha: come back the way you came", ("return_to_launch", {"drone_id": "alpha"})),
        ("charlie: come 25 m back west", ("move_to_relative", {"drone_id": "charlie", "north_m": 0.0, "east_m": -25.0})),
        ("charlie: climb 10 m higher", ("move_to_relative", {"drone_id": "charlie", "north_m": 0.0, "east_m": 0.0, "up_m": 10.0})),
        (
            "alpha, bravo and charlie: wedge formation, 10 m apart, at 18 m, 30 m east",
            (
                "formation_goto",
                {"drone_ids": ["alpha", "bravo", "charlie"], "formation": "wedge", "spacing_m": 10.0,
                 "alt_m": 18.0, "east_m": 30.0},
            ),
        ),
    ],
)  # fmt: skip
def test_a_step_in_the_words_of_one_call_is_that_call(step: str, call: tuple[str, dict[str, object]]) -> None:
    assert call_of_step(step, FLEET) == call


@pytest.mark.parametrize(
    "step",
    [
        "alpha: fly 20 m",  # no direction: a height or a leg, the model tells
        "alpha: fly to 30 m",  # a height or a place 30 m away
        "alpha: climb to 30 m and hold there for a minute",  # a wait not read
        "bravo: fly 10 m above the ground",
        "bravo: fly up to 10 m and land",  # two actions
        "bravo: fly 20 m north, then 20 m south",  # the same axis twice: two moves
        "bravo: fly 20 m north and 5 m up at 15 m",  # a climb and an altitude that may disagree
        "the one with less battery: take off to 7 m",  # a choice the plan reads first
        "if above 55 %: alpha: climb 5 m",  # a condition the plan reads first
        "delta: land",  # not in the fleet
        "alpha: read battery",  # a reading: the plan's own
        "alpha, bravo: take off to 10 m",  # several drones and no formation
        "alpha, bravo: line formation, at 15 m",  # no spacing
        "alpha, bravo: line formation, 10 m apart, at 15 m, by the tower",  # a place not read
        "alpha: fly 30 m north to the tower",  # a word not read
    ],
)
def test_a_step_with_any_word_not_read_is_no_call(step: str) -> None:
    assert call_of_step(step, FLEET) is None


def test_a_leg_without_a_height_is_told_apart() -> None:
    from gateway.agent.step_calls import leg_without_height

    south = call_of_step("alpha: fly 45 m south", FLEET)
    assert south is not None and leg_without_height(south)
    for step in ("alpha: fly 45 m south at 12 m", "alpha: fly 45 m south and 12 m up", "alpha: land"):
        call = call_of_step(step, FLEET)
        assert call is not None and not leg_without_height(call), step


@pytest.mark.parametrize(
    ("step", "call"),
    [
        ("bravo: take off and stay up at 25 m", ("takeoff", {"drone_id": "bravo", "alt_m": 25.0})),
        ("bravo: take off to 12 m and hover there", ("takeoff", {"drone_id": "bravo", "alt_m": 12.0})),
        ("bravo: up 10 m", ("move_to_relative", {"drone_id": "bravo", "north_m": 0.0, "east_m": 0.0, "up_m": 10.0})),
        ("bravo: fly 20 m back east", ("move_to_relative", {"drone_id": "bravo", "north_m": 0.0, "east_m": 20.0})),
        ("bravo: go north 20 m at 10 m", ("move_to_relative", {"drone_id": "bravo", "north_m": 20.0, "east_m": 0.0, "alt_m": 10.0})),
    ],
)  # fmt: skip
def test_the_0_5b_models_step_words_from_the_dev_half(step: str, call: tuple[str, dict[str, object]]) -> None:
    assert call_of_step(step, FLEET) == call


def test_side_by_side_is_a_line() -> None:
    call = call_of_step("alpha, charlie: side by side, 15 m apart, at 20 m", FLEET)
    assert call == (
        "formation_goto",
        {"drone_ids": ["alpha", "charlie"], "formation": "line", "spacing_m": 15.0, "alt_m": 20.0},
    )


def test_kilometres_are_metres() -> None:
    call = call_of_step("alpha: fly 2 kilometres east at 20 m", FLEET)
    assert call == (
        "move_to_relative",
        {"drone_id": "alpha", "north_m": 0.0, "east_m": 2000.0, "alt_m": 20.0},
    )
    assert call_of_step("alpha: fly 1.5 km to the north", FLEET) == (
        "move_to_relative",
        {"drone_id": "alpha", "north_m": 1500.0, "east_m": 0.0},
    )
