"""Shared steps of the real-autopilot tests: waits with deadlines, and a mission flown while its track is
recorded."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from dataclasses import dataclass, field

from gateway.fleet import geo
from gateway.fleet.mission import MissionItem
from gateway.fleet.vehicle import Vehicle
from tests.helpers.timing import scaled


async def until(what: str, check: Callable[[], object], within_s: float, v: Vehicle) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    while not check():
        if loop.time() > deadline:
            texts = [f"{t.severity}: {t.text}" for t in list(v.telemetry.status_texts)[-8:]]
            raise AssertionError(
                f"{v.id}: {what} not reached within {scaled(within_s):g} s; {v.status()}; {texts}"
            )
        await asyncio.sleep(0.2)


def rel_alt(v: Vehicle) -> float | None:
    pos = v.telemetry.fresh("position")
    return None if pos is None else pos.rel_alt_m


def square(v: Vehicle, side_m: float, alt_m: float) -> list[MissionItem]:
    """Three waypoints: north, north-east, east of home, ``side_m`` apart, at ``alt_m`` above home."""
    home = v.telemetry.home
    assert home is not None
    points = [(side_m, 0.0), (side_m, side_m), (0.0, side_m)]
    return [
        MissionItem(lat=lat, lon=lon, alt_rel_m=alt_m)
        for lat, lon in (geo.offset_position(home.value.lat_deg, home.value.lon_deg, n, e) for n, e in points)
    ]


def same_items(got: list[MissionItem], sent: list[MissionItem]) -> bool:
    """Items equal as the wire carries them (positions in 1e-7 degrees)."""
    return len(got) == len(sent) and all(
        (g.kind, g.alt_rel_m) == (s.kind, s.alt_rel_m)
        and abs(g.lat - s.lat) < 2e-7
        and abs(g.lon - s.lon) < 2e-7
        for g, s in zip(got, sent, strict=True)
    )


@dataclass
class Track:
    """Positions sampled while a mission is flown, with the user item being flown at each."""

    samples: list[tuple[int, float, float, float]] = field(default_factory=list)  # item, lat, lon, alt

    def closest_to(self, lat: float, lon: float) -> float:
        """The flown track's smallest horizontal distance to a point, metres."""
        return min(geo.horizontal_distance_m(la, lo, lat, lon) for _k, la, lo, _a in self.samples)

    def lowest_from(self, item: int) -> float:
        alts = [alt for k, _lat, _lon, alt in self.samples if k >= item]
        assert alts, f"no sample while flying item {item} or later"
        return min(alts)


async def fly_mission(v: Vehicle, within_s: float) -> Track:
    """Start the uploaded mission and record the track until the autopilot says it is finished."""
    track = Track()
    await v.start_mission()
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    while True:
        pos = v.telemetry.fresh("position")
        prog = v.telemetry.mission_progress
        if pos is not None and prog is not None:
            track.samples.append((int(prog.value.current), pos.lat_deg, pos.lon_deg, pos.rel_alt_m))
        if await v.is_mission_finished():
            return track
        if loop.time() > deadline:
            raise AssertionError(
                f"{v.id}: mission not finished within {scaled(within_s):g} s; {track.samples[-3:]}"
            )
        await asyncio.sleep(0.25)
