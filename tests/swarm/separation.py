"""Closest approach between drones from sampled positions (live telemetry, recorded tracks).

Each drone's samples are (t, lat, lon, alt_rel_m); altitudes are above each drone's own home, and the
homes of the swarm are at one elevation, so they share a vertical frame. Between two sample instants a
drone is taken to move in a straight line; for each pair of drones the relative position is then linear
on every interval of the merged timeline, and its exact minimum on the interval is taken (so a crossing
between samples is not missed, as it would be by comparing samples only).
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from gateway.fleet import geo

Sample = tuple[float, float, float, float]  # t (s), lat, lon, alt_rel_m


@dataclass(frozen=True)
class Approach:
    a: str
    b: str
    distance_m: float
    t: float


def _local(samples: Sequence[Sample], ref: tuple[float, float]) -> list[tuple[float, float, float, float]]:
    out = []
    for t, lat, lon, alt in samples:
        north, east = geo.ned_offset(ref[0], ref[1], lat, lon)
        out.append((t, north, east, alt))
    return out


def _at(track: list[tuple[float, float, float, float]], times: list[float], t: float) -> tuple[float, ...]:
    i = bisect.bisect_right(times, t)
    if i <= 0:
        return track[0][1:]
    if i >= len(track):
        return track[-1][1:]
    (t0, *p0), (t1, *p1) = track[i - 1], track[i]
    f = 0.0 if t1 == t0 else (t - t0) / (t1 - t0)
    return tuple(a + (b - a) * f for a, b in zip(p0, p1, strict=True))


def closest_approach(tracks: Mapping[str, Sequence[Sample]]) -> Approach | None:
    """The smallest distance between any two drones while both have samples (overlapping time only)."""
    usable = {k: sorted(v) for k, v in tracks.items() if len(v) >= 1}
    if len(usable) < 2:
        return None
    first = next(iter(usable.values()))[0]
    ref = (first[1], first[2])
    local = {k: _local(v, ref) for k, v in usable.items()}
    times = {k: [s[0] for s in v] for k, v in local.items()}
    best: Approach | None = None
    ids = sorted(local)
    for i, a in enumerate(ids):
        for b in ids[i + 1 :]:
            start = max(times[a][0], times[b][0])
            end = min(times[a][-1], times[b][-1])
            if end < start:
                continue
            instants = sorted({start, end, *(t for t in times[a] + times[b] if start <= t <= end)})
            previous = None
            for t in instants:
                pa, pb = _at(local[a], times[a], t), _at(local[b], times[b], t)
                rel = tuple(x - y for x, y in zip(pa, pb, strict=True))
                if previous is not None:
                    d, when = _segment_min(previous[1], rel, previous[0], t)
                else:
                    d, when = math.dist(pa, pb), t
                if best is None or d < best.distance_m:
                    best = Approach(a, b, d, when)
                previous = (t, rel)
    return best


def _segment_min(r0: tuple[float, ...], r1: tuple[float, ...], t0: float, t1: float) -> tuple[float, float]:
    """Minimum norm of r(s) = r0 + s (r1 - r0), s in [0, 1], and when it occurs."""
    d = [y - x for x, y in zip(r0, r1, strict=True)]
    dd = sum(x * x for x in d)
    s = 0.0 if dd == 0 else max(0.0, min(1.0, -sum(x * y for x, y in zip(r0, d, strict=True)) / dd))
    point = [x + s * y for x, y in zip(r0, d, strict=True)]
    return math.hypot(*point), t0 + s * (t1 - t0)
