"""Calls a small model writes for something else, read as what it means, and shown as such.

Measured with the 1.5B coder model (small profile, 3 runs of 12 missions): its first reply is usually the
whole plan, and the plan is right but for one call written with the wrong tool. "Go up to 15 m" became
``go_to_location(lat 0, lon 0, alt 15)`` in every run, and "send bravo to -35.318194, 149.165285"
became ``move_to_relative(east_m=-35.318194, up_m=149.165285)``. Refused, the plan stopped there and the
model rarely found its way back (empty replies, its own call again, the host's note as the answer). Read
as what they mean, the rest of the plan runs.

Each reading is narrow, uses only what the request and the fleet show, and returns the call to send
with a note the transcript shows. The gateway checks the new call like any other.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass

from gateway.agent.repair import (
    LAT_LON_PAIRS,
    altitude_not_a_climb,
    altitude_written_as_distance,
    climb_written_as_altitude,
    distance_written_as_altitude,
    formation_offset_from_request,
    names_zero_zero,
    request_distances,
    request_points,
    restore_request_directions,
    restore_request_numbers,
    shifted_request_moves,
)
from gateway.agent.roster import DroneEntry, normalise_drone_ids
from gateway.agent.toolbox import Arguments
from gateway.agent.turns import moves_of

# The drone as the gateway reports it now (the fleet read again), or None without a roster.
FreshEntry = Callable[[object], Awaitable[DroneEntry | None]]

_SAME_DEG = 1e-4  # about 10 m: a coordinate copied with a digit or two fewer is still the same one


@dataclass(frozen=True)
class Reading:
    """The call to send instead, and why."""

    name: str
    arguments: Arguments
    note: str


def zero_zero_as_here(name: str, args: Arguments, request: str, drone: DroneEntry | None) -> Reading | None:
    """``go_to_location`` to latitude 0, longitude 0, a point the request never gives, is the model's way
    of saying "here, at this altitude": a takeoff for a drone on the ground, the drone's own position for
    one that flies."""
    if name != "go_to_location" or args.get("lat_deg") != 0 or args.get("lon_deg") != 0:
        return None
    alt = args.get("alt_m")
    if names_zero_zero(request) or drone is None or not isinstance(alt, int | float) or isinstance(alt, bool):
        return None
    who = drone.drone_id
    if drone.flying is False:
        return Reading(
            "takeoff",
            {"drone_id": who, "alt_m": alt},
            f"go_to_location(0, 0, {alt:g} m) read as takeoff to {alt:g} m: {who} is on the ground and the "
            "request names no point 0, 0",
        )
    if drone.flying and drone.lat_deg is not None and drone.lon_deg is not None:
        here = {**args, "lat_deg": drone.lat_deg, "lon_deg": drone.lon_deg}
        return Reading(
            "go_to_location",
            here,
            f"lat_deg=0, lon_deg=0 read as where {who} is now ({drone.lat_deg:.6f}, {drone.lon_deg:.6f}): "
            "the request names no point 0, 0",
        )
    return None


def coordinates_as_metres(
    name: str, args: Arguments, request: str, drone: DroneEntry | None
) -> Reading | None:
    """``move_to_relative`` whose metres are the two numbers of a point in the request is a flight to that
    point: ``go_to_location`` there, at the altitude the drone flies at now."""
    if name != "move_to_relative" or drone is None or not drone.flying or drone.alt_m is None:
        return None
    values = [v for k in ("north_m", "east_m", "up_m") if isinstance(v := args.get(k), int | float) and v]
    for lat, lon in request_points(request):
        if len(values) == 2 and _close(values, (lat, lon)):
            alt = round(drone.alt_m, 1)
            return Reading(
                "go_to_location",
                {"drone_id": drone.drone_id, "lat_deg": lat, "lon_deg": lon, "alt_m": alt},
                f"move_to_relative by {values[0]} and {values[1]} m read as go_to_location({lat}, {lon}) at "
                f"{alt:g} m: those are the coordinates in the request, not metres",
            )
    return None


def metres_as_coordinates(name: str, args: Arguments, request: str) -> Reading | None:
    """``go_to_location`` whose latitude and longitude are distances the request names in metres, when it
    names no point: a relative move by them (north by the latitude, east by the longitude; the direction
    repair then puts each on the request's own axis). Measured on the corpus's dev half with the 1.5B model:
    "go 20 m east" came as go_to_location(lat 0, lon 20), refused 5,476 km from home, and the model never
    found the relative move after it."""
    lat, lon = args.get("lat_deg"), args.get("lon_deg")
    if name != "go_to_location" or request_points(request):
        return None
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in (lat, lon)):
        return None
    assert isinstance(lat, int | float) and isinstance(lon, int | float)
    given = [abs(float(v)) for v in (lat, lon) if v]
    if not given or not set(given) <= request_distances(request):
        return None
    moved: Arguments = {"drone_id": args.get("drone_id"), "north_m": float(lat), "east_m": float(lon)}
    if isinstance(args.get("alt_m"), int | float):
        moved["alt_m"] = args["alt_m"]
    return Reading(
        "move_to_relative",
        moved,
        f"go_to_location(lat {lat:g}, lon {lon:g}) read as move_to_relative(north_m={lat:g}, "
        f"east_m={lon:g}): the request gives those as metres, not a point",
    )


def _close(values: list[float], point: tuple[float, float]) -> bool:
    a, b = values
    lat, lon = point
    same = abs(a - lat) < _SAME_DEG and abs(b - lon) < _SAME_DEG
    crossed = abs(a - lon) < _SAME_DEG and abs(b - lat) < _SAME_DEG
    return same or crossed


def swapped_request_point(args: Arguments, request: str) -> list[str]:
    """Swap, in place, a latitude and longitude that are a point of the request the other way round (the
    latitude then out of -90..90); returns a note when it did."""
    notes: list[str] = []
    for lat_name, lon_name in LAT_LON_PAIRS:
        lat, lon = args.get(lat_name), args.get(lon_name)
        if not (isinstance(lat, int | float) and isinstance(lon, int | float)) or abs(lat) <= 90:
            continue
        for p_lat, p_lon in request_points(request):
            if abs(lon - p_lat) < _SAME_DEG and abs(lat - p_lon) < _SAME_DEG:
                args[lat_name], args[lon_name] = lon, lat
                notes.append(
                    f"{lat_name}={lat}, {lon_name}={lon} swapped: the request gives {p_lat}, {p_lon}"
                )
                break
    return notes


def superseded(name: str, args: Arguments, request: str, later: list[tuple[str, Arguments]]) -> str | None:
    """A ``formation_goto`` centred on 0, 0 (a point the request never names) whose every drone the same
    reply moves afterwards by metres: the later moves say where the model means them to go, so the
    formation step is left out. Returns the note, or None."""
    if name != "formation_goto" or args.get("center_lat_deg") != 0 or args.get("center_lon_deg") != 0:
        return None
    if names_zero_zero(request):
        return None
    drones = args.get("drone_ids")
    if not isinstance(drones, list) or not drones:
        return None
    moved = {a.get("drone_id") for n, a in later if n == "move_to_relative"}
    if not all(d in moved for d in drones):
        return None
    return (
        "formation_goto centred on 0, 0 left out: the request names no point 0, 0, and the moves that follow "
        f"in the same reply say where {', '.join(map(str, drones))} should go"
    )


async def read_call(
    name: str,
    args: Arguments,
    request: str,
    ids: Sequence[str],
    fresh_entry: FreshEntry,
    flown: Sequence[Arguments] = (),
) -> tuple[str, Arguments, Reading | None, list[str]]:
    """The call as the model meant it: ids, numbers and directions put back as the request gives them
    (repair.py), a call written with the wrong tool read as the one meant; with the notes that say so.
    ``args`` is corrected in place; the reading, when there is one, names the call to send instead.
    ``flown``: the relative moves that succeeded earlier in the turn (a leg flown back is no wrong sign)."""
    notes = normalise_drone_ids(args, ids) if ids else []
    notes += restore_request_numbers(args, request)
    notes += swapped_request_point(args, request)
    reading = await _read_as_meant(name, args, request, fresh_entry)
    if reading is not None:
        name, args = reading.name, reading.arguments
        notes.append(reading.note)
    if name == "formation_goto":
        notes += formation_offset_from_request(args, request)
    if name in ("move_to_relative",):
        notes += shifted_request_moves(args, request)
        notes += distance_written_as_altitude(args, request)
        notes += altitude_written_as_distance(args, request)
        notes += restore_request_directions(args, request, moves_of(flown, args.get("drone_id")))
        if args.get("up_m") or args.get("alt_m"):  # the fleet is read only when there is a height to judge
            drone = await fresh_entry(args.get("drone_id"))
            alt_now = drone.alt_m if drone is not None and drone.flying else None
            # the same call again is a repeat, held back as one, never a new climb
            if args not in moves_of(flown, args.get("drone_id")):
                notes += climb_written_as_altitude(args, request, alt_now)
            notes += altitude_not_a_climb(args, request, alt_now)
    return name, args, reading, notes


async def _read_as_meant(name: str, args: Arguments, request: str, fresh_entry: FreshEntry) -> Reading | None:
    """The call a small model meant by this one, read against the fleet as it is now (in a plan, the
    takeoff before this call has changed it since the last roster)."""
    zero = name == "go_to_location" and args.get("lat_deg") == 0 and args.get("lon_deg") == 0
    metres = name == "move_to_relative" and len(request_points(request)) > 0
    if not (zero or metres):
        return metres_as_coordinates(name, args, request)
    drone = await fresh_entry(args.get("drone_id"))
    return zero_zero_as_here(name, args, request, drone) or coordinates_as_metres(name, args, request, drone)
