"""The closest-approach measure the swarm test relies on: it finds crossings between samples."""

from __future__ import annotations

import pytest

from gateway.fleet import geo
from tests.swarm.separation import closest_approach

ORIGIN = (47.3977, 8.5456)


def _at(north: float, east: float) -> tuple[float, float]:
    return geo.offset_position(ORIGIN[0], ORIGIN[1], north, east)


def test_a_crossing_between_samples_is_found() -> None:
    # a flies west to east along north = 0, b south to north along east = 0, both through (0, 0) at t = 5,
    # sampled only at t = 0 and t = 10, where they are 70 m apart: the crossing is between the samples.
    a = [(0.0, *_at(0, -50), 20.0), (10.0, *_at(0, 50), 20.0)]
    b = [(0.0, *_at(-50, 0), 23.0), (10.0, *_at(50, 0), 23.0)]
    found = closest_approach({"a": a, "b": b})
    assert found is not None and found.distance_m == pytest.approx(3.0, abs=0.05)
    assert found.t == pytest.approx(5.0, abs=0.05)


def test_only_overlapping_times_count_and_unequal_sampling_is_interpolated() -> None:
    # b is at a's position, but only before a's samples begin: no overlap there
    a = [(10.0, *_at(0, 0), 10.0), (11.0, *_at(0, 10), 10.0), (12.0, *_at(0, 20), 10.0)]
    b = [(0.0, *_at(0, 0), 10.0), (10.5, *_at(8, 5), 10.0), (20.0, *_at(8, 5), 10.0)]
    found = closest_approach({"a": a, "b": b})
    assert found is not None and found.distance_m == pytest.approx(8.0, abs=0.3)
    assert closest_approach({"a": a}) is None
