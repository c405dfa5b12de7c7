"""Flat-earth geometry over short distances (offsets in metres, a pattern's legs, a polygon's corners): good
to a few centimetres over the few kilometres a gateway's policy lets a drone fly from home."""

from __future__ import annotations

import itertools
import math

EARTH_RADIUS_M = 6_371_008.8

#: unit vectors (north, east) of the compass directions a plan may name
_D = math.sqrt(0.5)
COMPASS = {"north": (1.0, 0.0), "south": (-1.0, 0.0), "east": (0.0, 1.0), "west": (0.0, -1.0),
           "northeast": (_D, _D), "northwest": (_D, -_D), "southeast": (-_D, _D),
           "southwest": (-_D, -_D)}  # fmt: skip

Offset = tuple[float, float]  # (north_m, east_m)


def offset_position(lat: float, lon: float, north_m: float, east_m: float) -> tuple[float, float]:
    """The point ``north_m`` north and ``east_m`` east of (lat, lon)."""
    dlat = math.degrees(north_m / EARTH_RADIUS_M)
    dlon = math.degrees(east_m / (EARTH_RADIUS_M * math.cos(math.radians(lat))))
    return lat + dlat, lon + dlon


def offset_between(lat1: float, lon1: float, lat2: float, lon2: float) -> Offset:
    """(north_m, east_m) from the first point to the second."""
    north = math.radians(lat2 - lat1) * EARTH_RADIUS_M
    east = math.radians(lon2 - lon1) * EARTH_RADIUS_M * math.cos(math.radians((lat1 + lat2) / 2))
    return north, east


def heading_vector(heading_deg: float) -> Offset:
    """The unit (north, east) vector of a heading in degrees from north, clockwise."""
    rad = math.radians(heading_deg)
    return math.cos(rad), math.sin(rad)


def compass_heading(direction: str) -> float:
    """A compass direction's heading in degrees from north, clockwise."""
    north, east = COMPASS[direction]
    return math.degrees(math.atan2(east, north)) % 360.0


def polygon_legs(
    sides: int, side_m: float, first_heading_deg: float = 0.0, clockwise: bool = True
) -> list[Offset]:
    """The legs of a closed regular polygon flown from one corner: ``sides`` legs of ``side_m``, turning
    by the exterior angle after each."""
    turn = 360.0 / sides * (1 if clockwise else -1)
    return [_scaled(heading_vector(first_heading_deg + i * turn), side_m) for i in range(sides)]


def rectangle_legs(
    length_m: float, width_m: float, first_heading_deg: float = 0.0, clockwise: bool = True
) -> list[Offset]:
    """A closed rectangle from one corner: ``length_m`` along the first heading, then ``width_m`` across."""
    along = heading_vector(first_heading_deg)
    across = heading_vector(first_heading_deg + (90.0 if clockwise else -90.0))
    return [_scaled(along, length_m), _scaled(across, width_m), _scaled(along, -length_m),
            _scaled(across, -width_m)]  # fmt: skip


def orbit_legs(
    radius_m: float, points: int = 12, clockwise: bool = True, start_deg: float = 0.0
) -> list[Offset]:
    """Out from the centre to the circle (towards ``start_deg``), round it in ``points`` chords, back in."""
    turn = 360.0 / points * (1 if clockwise else -1)
    corners = [_scaled(heading_vector(start_deg + i * turn), radius_m) for i in range(points + 1)]
    chords = [_scaled((b[0] - a[0], b[1] - a[1]), 1.0) for a, b in itertools.pairwise(corners)]
    return [corners[0], *chords, _scaled(corners[0], -1.0)]


def survey_legs(
    lines: int, length_m: float, spacing_m: float, first_heading_deg: float = 0.0, right: bool = True
) -> list[Offset]:
    """A lawnmower: ``lines`` parallel lines of ``length_m``, ``spacing_m`` apart, stepping to the right
    (to the left unless ``right``)."""
    along = heading_vector(first_heading_deg)
    across = heading_vector(first_heading_deg + (90.0 if right else -90.0))
    legs: list[Offset] = []
    for i in range(lines):
        sign = 1.0 if i % 2 == 0 else -1.0
        legs.append(_scaled(along, sign * length_m))
        if i < lines - 1:
            legs.append(_scaled(across, spacing_m))
    return legs


def _scaled(vector: Offset, length: float) -> Offset:
    return round(vector[0] * length, 2) + 0.0, round(vector[1] * length, 2) + 0.0
