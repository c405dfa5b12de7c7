"""Argument repairs toward what the user said, each one shown in the transcript.

Measured with a 1.5B model: it copies coordinates from the request with fewer decimals (149.164955
becomes 149.165, 30 m off) and swaps latitude and longitude. The host puts back the user's own number
when exactly one number in the request rounds to what the model wrote, and names a swap in the
validation error, so the model can correct it."""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Sequence

from gateway.agent.toolbox import Arguments

_NUMBER_RE = re.compile(r"-?\d+\.\d+")
# (latitude argument, longitude argument) pairs of the gateway's tools.
LAT_LON_PAIRS = (("lat_deg", "lon_deg"), ("center_lat_deg", "center_lon_deg"))


def _decimals(value: float) -> int:
    text = repr(float(value))
    return len(text.split(".")[1]) if "." in text and "e" not in text else 0


def restore_request_numbers(arguments: Arguments, request: str) -> list[str]:
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


_ZERO_ZERO_RE = re.compile(r"(?<![\d.])0(?:\.0+)?\s*,\s*0(?:\.0+)?(?![\d.])")


def names_zero_zero(request: str) -> bool:
    """The request itself gives the point 0, 0."""
    return bool(_ZERO_ZERO_RE.search(request or ""))


def unplaced_optional_point(arguments: Arguments, request: str, required: Iterable[str]) -> list[str]:
    """Drop, in place, a latitude/longitude pair the tool does not require, both 0, when the request gives
    no point 0, 0: the model filled in a place the user never gave, and leaving it out is what the user
    said (the tool's default applies; formation_goto's is where the drones are). Measured on the corpus's
    dev half with the 1.5B model: "line up alpha, bravo and charlie ... right where they are", "... in a
    circle ..., here" and "alpha and charlie side by side ..., where they are now" each became
    formation_goto with center_lat_deg=0, center_lon_deg=0; refused, none of the three ever flew.
    Returns a note when it dropped one."""
    if names_zero_zero(request):
        return []
    needed = set(required)
    notes: list[str] = []
    for lat_name, lon_name in LAT_LON_PAIRS:
        if lat_name in needed or lon_name in needed:
            continue
        if arguments.get(lat_name) == 0 and arguments.get(lon_name) == 0:
            del arguments[lat_name], arguments[lon_name]
            notes.append(
                f"{lat_name}=0, {lon_name}=0 left out: the request names no point 0, 0, and without them the "
                "tool uses its default"
            )
    return notes


_DRONE_ARGUMENTS = frozenset({"drone_id", "drone_ids"})


def extras_of_a_drone_only_tool(arguments: Arguments, properties: Iterable[str]) -> list[str]:
    """Drop, in place, the arguments a tool that takes only drone ids (land, return_to_launch, get_battery)
    does not have: it can do nothing with them, so the call means the same without them. Measured on the
    corpus's dev half with the 1.5B model: land(drone_id="alpha", alt_m=15), refused for the unknown
    argument, sent three times unchanged; the drone was never landed. Returns a note when it dropped any."""
    accepted = set(properties)
    if not accepted or not accepted <= _DRONE_ARGUMENTS:
        return []
    extra = sorted(k for k in arguments if k not in accepted)
    for key in extra:
        del arguments[key]
    return (
        [f"{', '.join(extra)} left out: this tool takes only {', '.join(sorted(accepted))}"] if extra else []
    )


def null_island(arguments: Arguments, request: str, on_ground: bool = False) -> str | None:
    """A refusal for latitude 0, longitude 0 when the request gives no such point: a small model writes it
    for "go up to 15 m" or "fly 60 m north" (measured: every prompt variant tried with the 1.5B model).
    For a drone on the ground it names the takeoff to call, with the altitude the model asked for."""
    if names_zero_zero(request):
        return None
    for lat_name, lon_name in LAT_LON_PAIRS:
        if arguments.get(lat_name) == 0 and arguments.get(lon_name) == 0:
            drone, alt = arguments.get("drone_id"), arguments.get("alt_m")
            first = ""
            if on_ground and isinstance(drone, str) and isinstance(alt, int | float):
                takeoff = json.dumps({"name": "takeoff", "arguments": {"drone_id": drone, "alt_m": alt}})
                # the call itself, as JSON: the 1.5B model answered with the sentence instead of acting on
                # it; a model that copies this line sends the takeoff, which is the step it needs
                first = f" {drone} is on the ground: to go up to {alt:g} m, take off first:\n{takeoff}\n"
            return (
                f"{lat_name}=0, {lon_name}=0 is not a place in the request.{first} To go up, use takeoff "
                "(from the ground) or move_to_relative with up_m; to fly some metres north, "
                "south, east or west, use move_to_relative. Nothing was executed."
            )
    return None


def swap_hint(arguments: Arguments) -> str | None:
    """A sentence when a latitude is out of range but would be valid as the longitude and vice versa."""
    for lat_name, lon_name in LAT_LON_PAIRS:
        lat, lon = arguments.get(lat_name), arguments.get(lon_name)
        if isinstance(lat, int | float) and isinstance(lon, int | float) and abs(lat) > 90 >= abs(lon):
            return (
                f"{lat_name} {lat:g} is outside -90..90: latitude and longitude look swapped; "
                f"try {lat_name}={lon:g}, {lon_name}={lat:g}."
            )
    return None


# "50 m south", "10 metres higher", "25 m back west": a distance and a direction in the request
_MOVE_RE = re.compile(
    r"(\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\s+(?:(?:back|further|farther|more|due|to\s+the)\s+)*"
    r"(north|south|east|west|higher|up|lower|down)\b",
    re.IGNORECASE,
)
# the relative-move argument and sign a direction word names
DIRECTION_AXES: dict[str, tuple[str, int]] = {
    "north": ("north_m", 1),
    "south": ("north_m", -1),
    "east": ("east_m", 1),
    "west": ("east_m", -1),
    "higher": ("up_m", 1),
    "up": ("up_m", 1),
    "lower": ("up_m", -1),
    "down": ("up_m", -1),
}


# "climbing another 6 m", "climb 5 m", "drop a further 3 m", "up 10 m": a distance up or down named by its
# verb ("up to 10 m" is an altitude, not read here)
_CLIMB_RE = re.compile(
    r"\b(climb(?:s|ing)?|ris(?:e|es|ing)|ascend(?:s|ing)?|up|descend(?:s|ing)?|drop(?:s|ping)?|sink(?:s|ing)?|"
    r"down)\s+"
    r"(?:(?:another|a\s+further|an\s+extra)\s+)?(\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\b",
    re.IGNORECASE,
)


_KILOMETRES_RE = re.compile(r"(\d+(?:\.\d+)?)\s*(?:km|kilomet(?:re|er)s?)\b", re.IGNORECASE)


def in_metres(text: str) -> str:
    """The text with each distance in kilometres written in metres ("2 kilometres east": "2000 m east"),
    the unit the tools take (dev half: "fly alpha 2 kilometres east" was flown 2 m north)."""
    return _KILOMETRES_RE.sub(lambda m: f"{float(m.group(1)) * 1000:g} m", text)


def _moves(request: str) -> list[tuple[float, str, str, int]]:
    """(distance, phrase, axis argument, sign) of each "50 m south" or "climbing another 6 m" in the
    request, in the request's order."""
    request = in_metres(request or "")
    found = [
        (m.start(), (float(m.group(1)), m.group(0), *DIRECTION_AXES[m.group(2).lower()]))
        for m in _MOVE_RE.finditer(request or "")
    ]
    taken = [m.span() for m in _MOVE_RE.finditer(request or "")]
    for m in _CLIMB_RE.finditer(request or ""):
        if any(start <= m.start(2) < end for start, end in taken):
            continue  # "climb 10 m higher": the distance is already read with its direction
        sign = 1 if m.group(1).lower().startswith(("climb", "ris", "ascend", "up")) else -1
        found.append((m.start(), (float(m.group(2)), m.group(0), "up_m", sign)))
    return [move for _, move in sorted(found, key=lambda f: f[0])]


def request_climbs(request: str) -> set[float]:
    """The distances up or down the request names ("10 m higher", "climbing another 6 m"), signed."""
    return {sign * d for d, _, axis, sign in _moves(request) if axis == "up_m"}


def request_distances(request: str) -> set[float]:
    """The horizontal distances the request names ("50 m south": 50), whatever their direction."""
    return {d for d, _, axis, _ in _moves(request) if axis != "up_m"}


def _misplaced(
    arguments: Arguments, moves: list[tuple[float, str, str, int]], request: str, flown: Sequence[Arguments]
) -> tuple[str, float] | None:
    """The first relative-move argument whose value is a distance the request names, but on another axis
    or with the other sign (not the way back: see _WAY_BACK_RE); with the value it has."""
    for name, (own_axis, own_sign) in AXIS_ARGUMENTS.items():
        value = arguments.get(name)
        if not isinstance(value, int | float) or isinstance(value, bool) or value == 0:
            continue
        same = [m for m in moves if m[0] == abs(value)]
        meant = own_sign * value  # the metres along own_axis this argument asks for
        if not same or any(axis == own_axis and sign * abs(value) == meant for _, _, axis, sign in same):
            continue
        if _WAY_BACK_RE.search(request) and any(
            axis == own_axis and any(_carries(a, d, axis, sign) for a in flown) for d, _, axis, sign in same
        ):
            continue  # the leg flown back, after it was flown out
        return name, float(value)
    return None


# A request that speaks of coming back: a leg it names, flown the other way after it was flown out, is the
# way back (dev half: "fly 30 m north ..., come back the way you came" had its north_m=-30 read as
# north_m=30 and ended 60 m from home)
_WAY_BACK_RE = re.compile(r"\b(?:back|return\w*|retrace\w*|reverse|the way (?:it|you|they) came)\b", re.I)


# each relative-move argument: the axis it moves along and which way (west_m=40 is east_m=-40)
AXIS_ARGUMENTS = {
    "north_m": ("north_m", 1),
    "east_m": ("east_m", 1),
    "up_m": ("up_m", 1),
    "south_m": ("north_m", -1),
    "west_m": ("east_m", -1),
}


def horizontal_legs_left(request: str, attempted: list[Arguments]) -> list[str]:
    """The "25 m south" phrases of the request that no attempted call's arguments carry on that axis
    with that sign (north_m/south_m, east_m/west_m; each phrase on its own, so "30 m east, then 30 m
    back west" needs both). Climbs are left out: "8 m up" from the ground may be an altitude."""

    return [
        phrase
        for distance, phrase, axis, sign in _moves(request)
        if axis != "up_m" and not any(_carries(a, distance, axis, sign) for a in attempted)
    ]


def _carries(args: Arguments, distance: float, axis: str, sign: int) -> bool:
    """Whether a relative move's arguments fly ``distance`` along ``axis`` the way ``sign`` says."""
    along = 0.0
    for name, (own_axis, own_sign) in AXIS_ARGUMENTS.items():
        value = args.get(name)
        if own_axis == axis and isinstance(value, int | float) and not isinstance(value, bool):
            along += own_sign * value
    return abs(along - sign * distance) < 0.5


def restore_request_directions(
    arguments: Arguments, request: str, flown: Sequence[Arguments] = ()
) -> list[str]:
    """Move, in place, a distance the request names with a direction onto that direction's argument and
    sign (measured with the 1.5B model: "50 m south" sent as east_m=-50 three times after being told
    north_m=-50). Only when it is unambiguous: exactly one phrase names that distance and the argument it
    belongs to is not already used. ``flown``: the drone's relative moves that succeeded earlier in the
    turn. Returns a note per repair."""
    moves = _moves(request)
    notes: list[str] = []
    while (wrong := _misplaced(arguments, moves, request, flown)) is not None:
        name, value = wrong
        same = [m for m in moves if m[0] == abs(value)]
        distance, phrase, axis, sign = same[0]
        if len(same) != 1 or (axis != name and arguments.get(axis) not in (None, 0, 0.0)):
            break
        arguments[name] = 0.0
        arguments[axis] = sign * distance
        notes.append(f"{name}={value:g} read as {axis}={sign * distance:g} ('{phrase}' in the request)")
    return notes


def formation_offset_from_request(arguments: Arguments, request: str) -> list[str]:
    """A ``formation_goto`` placed where the drones are (no centre, ``north_m`` and ``east_m`` 0 or not
    given) when the request places it by compass distances ("25 m south of where they are"): those
    distances, set in place, each axis named once at most. Measured on the corpus's dev half with the 1.5B
    model (form-line-south): ``north_m=0``, the line formed in place, and the 25 m south never flown."""
    placed = ("north_m", "east_m", "south_m", "west_m", "center_lat_deg", "center_lon_deg")
    if any(arguments.get(k) not in (None, 0, 0.0) for k in placed):
        return []
    moves = [m for m in _moves(request) if m[2] in ("north_m", "east_m")]
    axes = [axis for _, _, axis, _ in moves]
    if not moves or len(set(axes)) != len(axes):
        return []
    notes: list[str] = []
    for distance, phrase, axis, sign in moves:
        arguments[axis] = sign * distance
        notes.append(f"{axis}={sign * distance:g} from the request's '{phrase}' (from where the drones are)")
    return notes


_HORIZONTAL = ("north_m", "east_m", "south_m", "west_m")


def _number(value: object) -> float | None:
    return float(value) if isinstance(value, int | float) and not isinstance(value, bool) else None


def shifted_request_moves(arguments: Arguments, request: str) -> list[str]:
    """Put back, in place, the request's distances when the call has exactly them, each on some other
    slot: every distance of the request's moves ("10 m east", "3 m lower") has a size of its own, the
    call's relative values (and an ``alt_m`` below zero) are those sizes and no others (one may stand
    twice), and at least one is on the wrong axis or sign. Measured on the corpus's dev half with the
    1.5B model (rel-east-lower): "nudge it 10 m east and 3 m lower" came as ``north_m=10, east_m=3,
    alt_m=-3`` twice, each number one slot along; the direction check named east_m=10, and the model
    answered with the error. Returns a note."""
    moves = _moves(request)
    sizes = [m[0] for m in moves]
    if len(moves) < 2 or len(set(sizes)) != len(sizes):
        return []
    slots = [*_HORIZONTAL, "up_m"]
    given = {name: v for name in slots if (v := _number(arguments.get(name)))}
    alt = _number(arguments.get("alt_m"))
    if alt is not None and alt < 0:
        given["alt_m"] = alt
    if {abs(v) for v in given.values()} != set(sizes):
        return []
    meant = {axis: sign * distance for distance, _, axis, sign in moves}
    if len(meant) != len(moves) or all(meant.get(name) == value for name, value in given.items()):
        return []
    for name in given:
        arguments.pop(name, None)
    arguments.update(meant)
    was = ", ".join(f"{n}={v:g}" for n, v in given.items())
    now = ", ".join(f"{n}={v:g}" for n, v in meant.items())
    said = ", ".join(f"'{phrase}'" for _, phrase, _, _ in moves)
    return [f"{was} read as {now} ({said} in the request)"]


def distance_written_as_altitude(arguments: Arguments, request: str) -> list[str]:
    """Move, in place, an ``alt_m`` below zero onto the horizontal leg of the request it is the size of
    ("25 m south" as alt_m=-25), when exactly one leg has that size and no horizontal argument is used;
    the drone keeps its altitude. An altitude below home is never a flight, so nothing else is meant.
    Measured on the corpus's dev half with the 1.5B model: "then 25 m south" was
    move_to_relative(alt_m=-25) twice, refused twice, and the leg was never flown. Returns a note."""
    alt = _number(arguments.get("alt_m"))
    if alt is None or alt >= 0 or any(_number(arguments.get(a)) for a in _HORIZONTAL):
        return []
    same = [m for m in _moves(request) if m[0] == abs(alt) and m[2] != "up_m"]
    if len(same) != 1:
        return []
    distance, phrase, axis, sign = same[0]
    del arguments["alt_m"]
    arguments[axis] = sign * distance
    return [f"alt_m={alt:g} read as {axis}={sign * distance:g} ('{phrase}' in the request)"]


_COMPASS_RE = re.compile(r"\b(?:north|south|east|west)\w*", re.IGNORECASE)


def altitude_written_as_distance(arguments: Arguments, request: str) -> list[str]:
    """Move, in place, the one horizontal distance of a relative move onto ``alt_m`` when the request
    names no compass direction at all and asks for that altitude ("take it to 10 m"): no leg was asked
    for, so the number is the height. Measured on the corpus's dev half with the 1.5B model: "take it to
    10 m" was move_to_relative(north_m=10, alt_m=0) for a drone on the ground, twice. Returns a note."""
    if _COMPASS_RE.search(request or "") or _number(arguments.get("up_m")):
        return []
    used = [(name, v) for name in _HORIZONTAL if (v := _number(arguments.get(name)))]
    if len(used) != 1:
        return []
    name, value = used[0]
    altitudes = {float(m) for m in _ALTITUDE_RE.findall(request or "")}
    alt = _number(arguments.get("alt_m"))
    if abs(value) not in altitudes or (alt and alt != abs(value)):
        return []
    arguments[name] = 0.0
    arguments["alt_m"] = abs(value)
    return [f"{name}={value:g} read as alt_m={abs(value):g}: no direction in the request, only that height"]


# "to 15 m", "at 30 m": an altitude the request asks for, not a distance to move
_ALTITUDE_RE = re.compile(
    r"\b(?:to|at)\s+(\d+(?:\.\d+)?)\s*(?:m|metres?|meters?)\b(?!\s+(?:north|south|east|west))", re.IGNORECASE
)


def altitude_not_a_climb(arguments: Arguments, request: str, alt_now: float | None) -> list[str]:
    """Set ``up_m`` to 0, in place, when its size is an altitude the request asks for ("take off to 15 m"),
    the drone already flies at about that altitude, and the request names no distance up or down
    (measured with the 1.5B model: "take off to 15 m, head 50 m south" planned as takeoff, then
    move_to_relative with up_m=-15, into the ground). Returns a note."""
    up = arguments.get("up_m")
    if not isinstance(up, int | float) or isinstance(up, bool) or up == 0 or alt_now is None:
        return []
    if any(axis == "up_m" for _, _, axis, _ in _moves(request)):
        return []
    altitudes = {float(m) for m in _ALTITUDE_RE.findall(request or "")}
    if abs(up) not in altitudes or abs(alt_now - abs(up)) > 3.0:
        return []
    arguments["up_m"] = 0.0
    return [f"up_m={up:g} read as up_m=0: the drone is already at the {abs(up):g} m the request asks for"]


def climb_written_as_altitude(arguments: Arguments, request: str, alt_now: float | None) -> list[str]:
    """Read, in place, an ``alt_m`` the size of the one climb (or descent) the request names as that climb
    (``up_m``), for a drone in the air whose altitude it is not already the sum of. Measured on a fifth-day
    dev request with the 1.5B model: "up to 6 m first, then over 20 m north while climbing another 6 m"
    came as move_to_relative(north_m=20, alt_m=6) at 6 m, a leg with no climb. Returns a note."""
    alt = _number(arguments.get("alt_m"))
    if alt is None or alt <= 0 or _number(arguments.get("up_m")) or alt_now is None:
        return []
    climbs = [m for m in _moves(request) if m[2] == "up_m"]
    if len(climbs) != 1 or climbs[0][0] != alt:
        return []
    distance, phrase, _, sign = climbs[0]
    if abs(alt_now + sign * distance - alt) <= 3.0 or alt_now + sign * distance <= 0:
        return []
    del arguments["alt_m"]
    arguments["up_m"] = sign * distance
    at = f"the drone is at {alt_now:.0f} m"
    return [f"alt_m={alt:g} read as up_m={sign * distance:g} ('{phrase}' in the request; {at})"]


def direction_mismatch(arguments: Arguments, request: str, flown: Sequence[Arguments] = ()) -> str | None:
    """A refusal when a relative move puts a distance the request names on the wrong axis or with the
    wrong sign and the host could not repair it (`restore_request_directions`)."""
    moves = _moves(request)
    wrong = _misplaced(arguments, moves, request, flown)
    if wrong is None:
        return None
    name, value = wrong
    distance, phrase, axis, sign = next(m for m in moves if m[0] == abs(value))
    return (
        f"{name}={value:g} does not match '{phrase}' in the request: that is {axis}={sign * distance:g} "
        "(north_m: + north, - south; east_m: + east, - west; up_m: + up, - down). Nothing was executed."
    )


_POINT_RE = re.compile(r"(-?\d{1,2}\.\d{3,})\s*,\s*(-?\d{1,3}\.\d{3,})")


def request_points(request: str) -> list[tuple[float, float]]:
    """The "lat, lon" pairs written in the request (three or more decimals each), in order."""
    return [(float(a), float(b)) for a, b in _POINT_RE.findall(request or "")]
