"""The formation planner's exact assignment: optimal against brute force and scipy; bad input named."""

from __future__ import annotations

import itertools
import math
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linear_sum_assignment

from gateway.fleet.formation.assignment import min_cost_assignment


def total(cost: list[list[float]], slot: list[int]) -> float:
    return sum(cost[i][j] for i, j in enumerate(slot))


@settings(max_examples=200, deadline=None)
@given(
    st.integers(min_value=1, max_value=6).flatmap(
        lambda n: st.lists(
            st.lists(st.floats(0, 1000, allow_nan=False), min_size=n, max_size=n), min_size=n, max_size=n
        )
    )
)
def test_optimal_against_every_permutation(cost: list[list[float]]) -> None:
    slot = min_cost_assignment(cost)
    assert sorted(slot) == list(range(len(cost)))  # a permutation: every slot taken once
    best = min(total(cost, list(p)) for p in itertools.permutations(range(len(cost))))
    assert total(cost, slot) == pytest.approx(best, abs=1e-6)


@pytest.mark.parametrize("n", [7, 20, 60])
def test_same_total_as_scipy_on_travel_distances(n: int) -> None:
    rng = random.Random(n)
    starts = [(rng.uniform(-200, 200), rng.uniform(-200, 200), rng.uniform(0, 40)) for _ in range(n)]
    slots = [(rng.uniform(-50, 50), rng.uniform(-50, 50), 20.0) for _ in range(n)]
    cost = [[math.dist(a, b) for b in slots] for a in starts]
    rows, cols = linear_sum_assignment(cost)
    assert total(cost, min_cost_assignment(cost)) == pytest.approx(
        sum(cost[r][c] for r, c in zip(rows, cols, strict=True)), rel=1e-9
    )


def test_ties_and_trivial_sizes() -> None:
    assert min_cost_assignment([]) == []
    assert min_cost_assignment([[5.0]]) == [0]
    assert sorted(min_cost_assignment([[1.0] * 4 for _ in range(4)])) == [0, 1, 2, 3]
    assert min_cost_assignment([[9.0, 1.0], [1.0, 9.0]]) == [1, 0]


def test_bad_input_is_named() -> None:
    with pytest.raises(ValueError, match="square matrix; got 2 rows of lengths \\[3, 3\\]"):
        min_cost_assignment([[1.0, 2.0, 3.0], [1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match="finite"):
        min_cost_assignment([[math.inf, math.inf], [1.0, 2.0]])
