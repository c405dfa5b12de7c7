"""Argument repairs toward what the user said, each one shown in the transcript.

Measured with a 1.5B model: it copies coordinates from the request with fewer decimals (149.164955
becomes 149.165, 30 m off) and swaps latitude and longitude. The host puts back the user's own number
when exactly one number in the request rounds to what the model wrote, and names a swap in the
validation error, so the model can correct it."""

from __future__ import annotations

import re
from typing import Any

_NUMBER_RE = re.compile(r"-?\d+\.\d+")
# (latitude argument, longitude argument) pairs of the gateway's tools.
LAT_LON_PAIRS = (("latitude_deg", "longitude_deg"), ("center_lat", "center_lon"), ("lat_deg", "lon_deg"))


def _decimals(value: float) -> int:
    text = repr(float(value))
    return len(text.split(".")[1]) if "." in text and "e" not in text else 0


def restore_request_numbers(arguments: dict[str, Any], request: str) -> list[str]:
    """Replace in place each number with at least two decimals that is the rounded form of exactly one
    longer number in the request; returns a note per replacement."""
    given = {float(m) for m in _NUMBER_RE.findall(request or "")}
    notes: list[str] = []
    for name, value in list(arguments.items()):
        if not isinstance(value, float) or isinstance(value, bool):
            continue
        places = _decimals(value)
        if places < 2:
            continue
        matches = {g for g in given if _decimals(g) > places and round(g, places) == value}
        if len(matches) == 1:
            exact = matches.pop()
            arguments[name] = exact
            notes.append(f"{name} {value!r} read as {exact!r} (the number in the request)")
    return notes


def null_island(arguments: dict[str, Any], request: str, on_ground: bool = False) -> str | None:
    """A refusal for latitude 0, longitude 0 when the request gives no such point: a small model writes it
    for "go up to 15 m" or "fly 60 m north" (measured: every prompt variant tried with the 1.5B model).
    For a drone on the ground it names the takeoff to call, with the altitude the model asked for."""
    if re.search(r"(?<![\d.])0(?:\.0+)?\s*,\s*0(?:\.0+)?(?![\d.])", request or ""):
        return None
    for lat_name, lon_name in LAT_LON_PAIRS:
        if arguments.get(lat_name) == 0 and arguments.get(lon_name) == 0:
            drone, alt = arguments.get("drone_id"), arguments.get("altitude_m") or arguments.get("alt_m")
            first = ""
            if on_ground and isinstance(drone, str) and isinstance(alt, int | float):
                first = (
                    f" {drone} is on the ground: to go up to {alt:g} m, call takeoff with "
                    f'drone_id "{drone}" and altitude_m {alt:g} first.'
                )
            return (
                f"{lat_name}=0, {lon_name}=0 is not a place in the request.{first} To go up, use takeoff "
                "(from the ground) or move_to_relative with a negative down_m; to fly some metres north, "
                "south, east or west, use move_to_relative. Nothing was executed."
            )
    return None


def swap_hint(arguments: dict[str, Any]) -> str | None:
    """A sentence when a latitude is out of range but would be valid as the longitude and vice versa."""
    for lat_name, lon_name in LAT_LON_PAIRS:
        lat, lon = arguments.get(lat_name), arguments.get(lon_name)
        if isinstance(lat, int | float) and isinstance(lon, int | float) and abs(lat) > 90 >= abs(lon):
            return (
                f"{lat_name} {lat:g} is outside -90..90: latitude and longitude look swapped; "
                f"try {lat_name}={lon:g}, {lon_name}={lat:g}."
            )
    return None
