"""Exact minimum-cost assignment of drones to formation slots (the Hungarian method, O(n^3)).

The formation planner's one use of an assignment solver: n drones, n slots, a cost matrix of travel
distances. A fleet is tens of drones, so this short exact solver replaces scipy (about 145 MB in an
image) for that one function; tests/fleet/test_assignment.py checks it against brute force and scipy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence


def min_cost_assignment(cost: Sequence[Sequence[float]]) -> list[int]:
    """``slot[i]`` for each row ``i`` of a square cost matrix, minimising the summed cost.

    Shortest augmenting paths with row/column potentials (Kuhn-Munkres as Jonker and Volgenant write
    it): each row is added in turn and the assignment stays optimal for the rows added so far.
    """
    n = len(cost)
    if any(len(row) != n for row in cost):
        raise ValueError(f"cost must be a square matrix; got {n} rows of lengths {[len(r) for r in cost]}")
    if n == 0:
        return []
    # 1-based internally; index 0 is the virtual column a new row's path starts from
    u = [0.0] * (n + 1)  # row potentials
    v = [0.0] * (n + 1)  # column potentials
    row_of = [0] * (n + 1)  # row assigned to column j (0: none)
    way = [0] * (n + 1)  # previous column on the shortest path
    for i in range(1, n + 1):
        row_of[0] = i
        j0 = 0
        min_to = [math.inf] * (n + 1)
        used = [False] * (n + 1)
        while True:
            used[j0] = True
            i0 = row_of[j0]
            delta, j1 = _nearest_column(cost[i0 - 1], u[i0], v, used, min_to, way, j0)
            if not math.isfinite(delta):
                raise ValueError("cost must be finite")
            for j in range(n + 1):
                if used[j]:
                    u[row_of[j]] += delta
                    v[j] -= delta
                else:
                    min_to[j] -= delta
            j0 = j1
            if row_of[j0] == 0:
                break
        while j0:  # augment along the path
            j1 = way[j0]
            row_of[j0] = row_of[j1]
            j0 = j1
    slot = [0] * n
    for j in range(1, n + 1):
        slot[row_of[j] - 1] = j - 1
    return slot


def _nearest_column(
    cost_row: Sequence[float],
    u_row: float,
    v: list[float],
    used: list[bool],
    min_to: list[float],
    way: list[int],
    j0: int,
) -> tuple[float, int]:
    """Relax the reduced costs from column ``j0``'s row; the smallest reduced cost to an unused
    column, and that column (0 when none is finite)."""
    delta = math.inf
    j1 = 0
    for j in range(1, len(v)):
        if used[j]:
            continue
        reduced = cost_row[j - 1] - u_row - v[j]
        if reduced < min_to[j]:
            min_to[j] = reduced
            way[j] = j0
        if min_to[j] < delta:
            delta = min_to[j]
            j1 = j
    return delta, j1
