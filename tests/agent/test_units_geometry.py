"""Units and geometry of the plan compiler: what the model never computes."""

from __future__ import annotations

import math

import pytest

from fleet_agent import geometry
from fleet_agent.units import Unit, to_metres


@pytest.mark.parametrize(
    ("value", "unit", "metres"),
    [
        (100, "ft", 30.48),
        (1.5, "km", 1500.0),
        (1, "mi", 1609.34),
        (10, "yd", 9.14),
        (1, "nmi", 1852.0),
        (7, "m", 7.0),
        (40, "cm", 0.4),
    ],
)
def test_lengths_convert_to_metres(value: float, unit: str, metres: float) -> None:
    assert to_metres(value, unit) == metres


def test_an_unknown_unit_is_refused() -> None:
    with pytest.raises(ValueError, match="'parsec' is not a valid Unit"):
        to_metres(1, "parsec")
    assert Unit("ft") is Unit.ft


def _closes(legs: list[tuple[float, float]]) -> bool:
    return abs(sum(n for n, _ in legs)) < 0.05 and abs(sum(e for _, e in legs)) < 0.05


def test_a_square_is_four_equal_legs_turning_right_from_north() -> None:
    legs = geometry.polygon_legs(4, 20.0)
    assert legs == [(20.0, 0.0), (0.0, 20.0), (-20.0, 0.0), (0.0, -20.0)]
    left = geometry.polygon_legs(4, 20.0, first_heading_deg=90.0, clockwise=False)
    assert left[0] == (0.0, 20.0) and left[1] == (20.0, 0.0)


@pytest.mark.parametrize("sides", [3, 5, 6, 8])
def test_every_polygon_closes_with_sides_of_its_length(sides: int) -> None:
    legs = geometry.polygon_legs(sides, 30.0)
    assert len(legs) == sides and _closes(legs)
    assert all(abs(math.hypot(n, e) - 30.0) < 0.05 for n, e in legs)


def test_an_orbit_goes_out_round_and_back() -> None:
    legs = geometry.orbit_legs(50.0, points=12)
    assert legs[0] == (50.0, 0.0) and legs[-1] == (-50.0, 0.0) and len(legs) == 14
    assert _closes(legs)
    chord = 2 * 50.0 * math.sin(math.pi / 12)
    assert all(abs(math.hypot(n, e) - chord) < 0.05 for n, e in legs[1:-1])


def test_an_orbit_starts_on_the_side_its_heading_names_and_turns_its_way() -> None:
    """Round a spot from its west side, clockwise: out west, then north of west first; left, south first."""
    west = geometry.compass_heading("west")
    right, left = geometry.orbit_legs(20.0, start_deg=west), geometry.orbit_legs(20.0, 12, False, west)
    assert right[0] == left[0] == (0.0, -20.0) and right[-1] == (0.0, 20.0) and _closes(right)
    assert right[1][0] > 0 and left[1][0] < 0


def test_a_rectangle_is_flown_along_its_length_first() -> None:
    assert geometry.rectangle_legs(40.0, 20.0) == [(40.0, 0.0), (0.0, 20.0), (-40.0, 0.0), (0.0, -20.0)]
    left = geometry.rectangle_legs(30.0, 10.0, geometry.compass_heading("east"), clockwise=False)
    assert left == [(0.0, 30.0), (10.0, 0.0), (0.0, -30.0), (-10.0, 0.0)]


def test_a_survey_is_a_lawnmower() -> None:
    legs = geometry.survey_legs(3, 40.0, 10.0)
    assert legs == [(40.0, 0.0), (0.0, 10.0), (-40.0, 0.0), (0.0, 10.0), (40.0, 0.0)]
    west_then_south = geometry.survey_legs(2, 30.0, 8.0, geometry.compass_heading("west"), right=False)
    assert west_then_south == [(0.0, -30.0), (-8.0, 0.0), (0.0, 30.0)]


def test_offsets_round_trip() -> None:
    lat, lon = geometry.offset_position(47.3977, 8.5456, 30.0, -20.0)
    north, east = geometry.offset_between(47.3977, 8.5456, lat, lon)
    assert abs(north - 30.0) < 0.01 and abs(east + 20.0) < 0.01
    assert geometry.compass_heading("east") == 90.0 and geometry.compass_heading("southwest") == 225.0
