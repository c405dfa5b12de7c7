"""Formation geometry on numpy arrays: slot offsets, segment distances and the altitude layering.

Imported by `gateway.fleet.formation.formation` when a formation is first planned, so a gateway that never
plans
one never loads numpy (about 17 MiB).
"""

from __future__ import annotations

import math

import numpy as np

from gateway.errors import InvalidArgument
from gateway.fleet.formation.shapes import FORMATIONS, TOL_M
from gateway.fleet.policy.safety_rules import Rule, fmt, refuse

# ------------------------------------------------------------------------------------------------
# geometry


def formation_offsets(
    formation: str, count: int, spacing_m: float, wedge_half_angle_deg: float = 45.0
) -> np.ndarray:
    """Slot offsets (forward, right) in metres in the formation's body frame, centroid at (0, 0).

    line: abreast, perpendicular to the heading; column: one behind the other along the heading;
    wedge: a V whose apex points along the heading, neighbours on each arm ``spacing_m`` apart;
    grid: rows of ceil(sqrt(n)) abreast, rows ``spacing_m`` behind each other; circle: equally spaced on a
    circle whose radius makes neighbours ``spacing_m`` apart, slot 0 ahead of the centre.
    """
    if formation not in FORMATIONS:
        raise InvalidArgument(f"unknown formation {formation!r}; choose one of {list(FORMATIONS)}")
    if count < 1:
        raise InvalidArgument("a formation needs at least one drone")
    s = spacing_m
    k = np.arange(count, dtype=float)
    if formation == "line":
        pts = np.column_stack([np.zeros(count), k * s])
    elif formation == "column":
        pts = np.column_stack([-k * s, np.zeros(count)])
    elif formation == "wedge":
        if not 30.0 <= wedge_half_angle_deg <= 90.0:
            raise InvalidArgument(f"wedge half-angle must be 30..90 degrees; got {wedge_half_angle_deg}")
        half = math.radians(wedge_half_angle_deg)
        rank = np.ceil(k / 2.0)
        side = np.where(k % 2 == 1, -1.0, 1.0)
        pts = np.column_stack([-rank * s * math.cos(half), side * rank * s * math.sin(half)])
    elif formation == "grid":
        cols = math.ceil(math.sqrt(count))
        pts = np.column_stack([-(k // cols) * s, (k % cols) * s])
    else:  # circle
        if count == 1:
            pts = np.zeros((1, 2))
        else:
            radius = s / (2.0 * math.sin(math.pi / count))
            angle = 2.0 * math.pi * k / count
            pts = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    centred: np.ndarray = pts - pts.mean(axis=0)
    return centred


def rotate_to_ned(offsets: np.ndarray, heading_deg: float) -> np.ndarray:
    """(forward, right) body offsets -> (north, east) for a formation facing ``heading_deg``."""
    h = math.radians(heading_deg)
    fwd, right = offsets[:, 0], offsets[:, 1]
    north = fwd * math.cos(h) - right * math.sin(h)
    east = fwd * math.sin(h) + right * math.cos(h)
    return np.column_stack([north, east])


def segment_distance(p1: np.ndarray, q1: np.ndarray, p2: np.ndarray, q2: np.ndarray) -> float:
    """Minimum distance between segments p1-q1 and p2-q2 (any dimension; degenerate segments allowed).

    Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = float(d1 @ d1), float(d2 @ d2), float(d2 @ r)
    eps = 1e-12
    if a <= eps and e <= eps:
        return float(np.linalg.norm(r))
    if a <= eps:
        s, t = 0.0, _clamp(f / e)
    else:
        c = float(d1 @ r)
        if e <= eps:
            s, t = _clamp(-c / a), 0.0
        else:
            b = float(d1 @ d2)
            denom = a * e - b * b
            s = _clamp((b * f - c * e) / denom) if denom > eps * a * e else 0.0
            t = (b * s + f) / e
            if t < 0.0:
                s, t = _clamp(-c / a), 0.0
            elif t > 1.0:
                s, t = _clamp((b - c) / a), 1.0
    return float(np.linalg.norm((p1 + d1 * s) - (p2 + d2 * t)))


def _clamp(x: float) -> float:
    return min(1.0, max(0.0, x))


def min_pairwise(points: np.ndarray) -> float:
    if len(points) < 2:
        return math.inf
    diff = points[:, None, :] - points[None, :, :]
    dist = np.linalg.norm(diff, axis=2)
    dist[np.diag_indices(len(points))] = np.inf
    return float(dist.min())


class Layering:
    """Greedy altitude layering: keep direct paths where they are clear, lift the rest onto layers."""

    def __init__(
        self,
        start: np.ndarray,
        target: np.ndarray,
        required: np.ndarray,
        alt_m: float,
        sep: float,
        max_alt: float,
        min_alt: float,
        ids: list[str],
    ) -> None:
        self.start, self.target, self.required = start, target, required
        self.n = len(start)
        self.ids = ids
        self.max_alt, self.min_alt, self.sep = max_alt, min_alt, sep
        levels = [alt_m + k * sep for k in range(int((max_alt - alt_m) / sep + TOL_M) + 1)]
        below = alt_m - sep
        while below >= min_alt - TOL_M:
            levels.append(below)
            below -= sep
        self.levels = [round(x, 6) for x in levels]

    def segments(self, i: int, transit: float | None) -> list[tuple[np.ndarray, np.ndarray]]:
        """Drone i's segment in each of the three phases (degenerate = standing still)."""
        s, t = self.start[i], self.target[i]
        if transit is None:
            return [(s, s), (s, t), (t, t)]
        a = np.array([s[0], s[1], transit])
        b = np.array([t[0], t[1], transit])
        return [(s, a), (a, b), (b, t)]

    def phase_segments(self, transit: list[float | None]) -> list[list[tuple[np.ndarray, np.ndarray]]]:
        per_drone = [self.segments(i, transit[i]) for i in range(self.n)]
        return [[per_drone[i][k] for i in range(self.n)] for k in range(3)]

    def pair_clearance(self, i: int, ti: float | None, j: int, tj: float | None) -> float:
        si, sj = self.segments(i, ti), self.segments(j, tj)
        return min(segment_distance(*si[k], *sj[k]) for k in range(3))

    def min_clearance(self, transit: list[float | None]) -> float:
        best = math.inf
        for i in range(self.n):
            for j in range(i + 1, self.n):
                best = min(best, self.pair_clearance(i, transit[i], j, transit[j]))
        return best

    def solve(self) -> tuple[list[float | None], list[tuple[int, int, float]]]:
        n = self.n
        conflicts: list[tuple[int, int, float]] = []
        degree = [0] * n
        for i in range(n):
            for j in range(i + 1, n):
                closest = self.pair_clearance(i, None, j, None)
                if closest < self.required[i, j] - TOL_M:
                    conflicts.append((i, j, closest))
                    degree[i] += 1
                    degree[j] += 1
        transit: list[float | None] = [None] * n
        if not conflicts:
            return transit, conflicts
        fixed = [i for i in range(n) if degree[i] == 0]
        lengths = np.linalg.norm(self.target - self.start, axis=1)
        order = sorted((i for i in range(n) if degree[i] > 0), key=lambda i: (-degree[i], -lengths[i], i))
        options: list[float | None] = [None, *self.levels]
        for i in order:
            worst: tuple[float, int] | None = None
            for option in options:
                clash = self._first_clash(i, option, fixed, transit)
                if clash is None:
                    transit[i] = option
                    break
                if worst is None or clash[0] > worst[0]:
                    worst = clash
            else:
                closest, other = worst if worst is not None else (0.0, i)
                raise refuse(
                    Rule.MIN_SEPARATION,
                    f"no transit altitude between {fmt(min(self.levels))} and "
                    f"{fmt(max(self.levels))} m keeps "
                    f"drone {self.ids[i]} {fmt(self.sep)} m from the other drones' paths (best found: "
                    f"{fmt(closest, 2)} m from drone {self.ids[other]}); spread the drones out, move them in "
                    "smaller steps or raise the altitude limit",
                    vehicle_id=self.ids[i],
                    closest_m=round(closest, 2),
                    limit_m=self.sep,
                )
            fixed.append(i)
        return transit, conflicts

    def _first_clash(
        self, i: int, option: float | None, fixed: list[int], transit: list[float | None]
    ) -> tuple[float, int] | None:
        for j in fixed:
            closest = self.pair_clearance(i, option, j, transit[j])
            if closest < self.required[i, j] - TOL_M:
                return closest, j
        return None
