"""Calls a small model writes with the wrong tool, read as what they mean (pure functions); their use on the
real gateway is in test_gateway_e2e.py."""

from __future__ import annotations

from gateway.agent.intent import (
    coordinates_as_metres,
    metres_as_coordinates,
    read_call,
    superseded,
    swapped_request_point,
    zero_zero_as_here,
)
from gateway.agent.repair import altitude_not_a_climb, climb_written_as_altitude
from gateway.agent.roster import DroneEntry

UP_AND_NORTH = "Alpha: go up to 15 m, fly 60 metres north, and land there."
FAR = "Send bravo at 30 m to -35.318194, 149.165285, that's the farm 5 km north."


def _drone(flying: bool | None, alt: float | None = None, drone_id: str = "alpha") -> DroneEntry:
    return DroneEntry(drone_id, flying, alt, 90.0, "ready", None, -35.36, 149.16)


def test_zero_zero_on_the_ground_is_a_takeoff_to_that_altitude() -> None:
    args = {"drone_id": "alpha", "lat_deg": 0, "lon_deg": 0, "alt_m": 15}
    reading = zero_zero_as_here("go_to_location", args, UP_AND_NORTH, _drone(False, 0.0))
    assert reading is not None
    assert (reading.name, reading.arguments) == ("takeoff", {"drone_id": "alpha", "alt_m": 15})
    assert reading.note == (
        "go_to_location(0, 0, 15 m) read as takeoff to 15 m: alpha is on the ground and the request names "
        "no point 0, 0"
    )


def test_zero_zero_in_flight_is_the_drones_own_position() -> None:
    args = {"drone_id": "alpha", "lat_deg": 0.0, "lon_deg": 0.0, "alt_m": 25}
    reading = zero_zero_as_here("go_to_location", args, "alpha, climb to 25 m", _drone(True, 15.0))
    assert reading is not None and reading.name == "go_to_location"
    assert reading.arguments == {"drone_id": "alpha", "lat_deg": -35.36, "lon_deg": 149.16, "alt_m": 25}
    assert args["lat_deg"] == 0.0  # the model's own arguments are left as they were (shown in the log)


def test_zero_zero_is_left_alone_when_the_user_said_it_or_the_drone_is_unknown() -> None:
    args = {"drone_id": "alpha", "lat_deg": 0, "lon_deg": 0, "alt_m": 15}
    assert zero_zero_as_here("go_to_location", args, "fly alpha to 0, 0 at 15 m", _drone(False)) is None
    assert zero_zero_as_here("go_to_location", args, UP_AND_NORTH, None) is None
    assert zero_zero_as_here("go_to_location", args, UP_AND_NORTH, _drone(None)) is None
    assert zero_zero_as_here("go_to_location", {**args, "lat_deg": 1}, UP_AND_NORTH, _drone(False)) is None
    assert zero_zero_as_here("takeoff", args, UP_AND_NORTH, _drone(False)) is None
    assert zero_zero_as_here("go_to_location", {**args, "alt_m": "high"}, UP_AND_NORTH, _drone(False)) is None


def test_coordinates_given_as_metres_are_a_flight_to_that_point_at_the_altitude_flown() -> None:
    bravo = _drone(True, 29.64, "bravo")
    args = {"drone_id": "bravo", "north_m": 0, "east_m": -35.318194, "up_m": 149.165285}
    reading = coordinates_as_metres("move_to_relative", args, FAR, bravo)
    assert reading is not None and reading.name == "go_to_location"
    assert reading.arguments == {
        "drone_id": "bravo",
        "lat_deg": -35.318194,
        "lon_deg": 149.165285,
        "alt_m": 29.6,
    }
    assert "those are the coordinates in the request, not metres" in reading.note
    # swapped, or a digit short: still that point
    swapped = {"drone_id": "bravo", "north_m": 149.16529, "east_m": -35.31819, "up_m": 0}
    assert coordinates_as_metres("move_to_relative", swapped, FAR, bravo) is not None


async def test_metres_given_as_coordinates_are_a_relative_move() -> None:
    """Dev half (compound-corner-home): "go 20 m east" came as go_to_location(lat 0, lon 20), refused by the
    distance rule 5,476 km from home."""
    corner = "Take charlie to 15 m, go 20 m east, then 20 m south, then bring it home."
    args = {"drone_id": "charlie", "lat_deg": 0, "lon_deg": 20, "alt_m": 15}
    reading = metres_as_coordinates("go_to_location", args, corner)
    assert reading is not None and reading.name == "move_to_relative"
    assert reading.arguments == {"drone_id": "charlie", "north_m": 0.0, "east_m": 20.0, "alt_m": 15}
    assert reading.note.startswith(
        "go_to_location(lat 0, lon 20) read as move_to_relative(north_m=0, east_m=20)"
    )

    async def nobody(_drone_id: object) -> None:
        return None

    # on the request's own axis, by the direction repair the relative move goes through
    south = {"drone_id": "charlie", "lat_deg": 0, "lon_deg": 20, "alt_m": 15}
    name, sent, _, notes = await read_call("go_to_location", south, "charlie: 20 m south at 15 m", [], nobody)
    assert (name, sent["north_m"], sent["east_m"]) == ("move_to_relative", -20.0, 0.0), notes
    # numbers that are not the request's metres, a point the request gives, and 0, 0 are left to the others
    assert metres_as_coordinates("go_to_location", {**args, "lon_deg": 35}, corner) is None
    assert (
        metres_as_coordinates("go_to_location", {**args, "lat_deg": -35.318194, "lon_deg": 20}, FAR) is None
    )
    assert metres_as_coordinates("go_to_location", {**args, "lon_deg": 0}, corner) is None


def test_ordinary_metres_are_not_read_as_coordinates() -> None:
    bravo = _drone(True, 30.0, "bravo")
    args = {"drone_id": "bravo", "north_m": 35, "east_m": 149, "up_m": 0}
    assert coordinates_as_metres("move_to_relative", args, FAR, bravo) is None
    exact = {"drone_id": "bravo", "north_m": -35.318194, "east_m": 149.165285, "up_m": 0}
    assert coordinates_as_metres("move_to_relative", exact, "fly bravo 50 m north", bravo) is None
    assert coordinates_as_metres("move_to_relative", exact, FAR, _drone(False, 0.0, "bravo")) is None


def test_a_request_point_written_the_other_way_round_is_swapped_back() -> None:
    args = {"drone_id": "bravo", "lat_deg": 149.165285, "lon_deg": -35.318194, "alt_m": 30}
    assert swapped_request_point(args, FAR) == [
        "lat_deg=149.165285, lon_deg=-35.318194 swapped: the request gives -35.318194, 149.165285"
    ]
    assert (args["lat_deg"], args["lon_deg"]) == (-35.318194, 149.165285)
    # a latitude out of range that is not the request's point is left for the validation error to name
    other = {"lat_deg": 149.2, "lon_deg": -35.1}
    assert swapped_request_point(other, FAR) == [] and other == {"lat_deg": 149.2, "lon_deg": -35.1}


def test_a_zero_zero_formation_is_left_out_only_when_later_moves_place_every_drone() -> None:
    request = "Take off alpha and bravo to 15 m, fly them in a line 100 m north, then land."
    formation = {"drone_ids": ["alpha", "bravo"], "center_lat_deg": 0, "center_lon_deg": 0, "alt_m": 15}
    both = [
        ("move_to_relative", {"drone_id": "alpha", "north_m": 100}),
        ("move_to_relative", {"drone_id": "bravo", "north_m": 100}),
        ("land", {"drone_id": "alpha"}),
    ]
    note = superseded("formation_goto", formation, request, both)
    assert note is not None and note.startswith("formation_goto centred on 0, 0 left out")
    assert superseded("formation_goto", formation, request, both[:1]) is None  # bravo would not move
    assert superseded("formation_goto", formation, request, []) is None
    assert superseded("formation_goto", formation, "line them up at 0, 0", both) is None
    placed = {**formation, "center_lat_deg": -35.3, "center_lon_deg": 149.1}
    assert superseded("formation_goto", placed, request, both) is None


def test_an_altitude_written_as_a_climb_is_no_climb_once_the_drone_is_there() -> None:
    south = "Bravo, take off to 15 m, head 50 m south, then return to launch."
    args = {"drone_id": "bravo", "north_m": -50, "east_m": 0, "up_m": -15}
    assert altitude_not_a_climb(args, south, alt_now=14.6) == [
        "up_m=-15 read as up_m=0: the drone is already at the 15 m the request asks for"
    ]
    assert args["up_m"] == 0
    # a real climb: the drone is not at that altitude yet, or the request names the distance up
    low = {"north_m": 0, "east_m": 0, "up_m": 40}
    assert altitude_not_a_climb(low, "climb alpha to 40 m", alt_now=10.0) == [] and low["up_m"] == 40
    climb = {"north_m": 0, "east_m": 30, "up_m": 10}
    assert altitude_not_a_climb(climb, "bravo to 10 m, then 30 m east and 10 m higher", alt_now=10.0) == []
    assert altitude_not_a_climb({"up_m": -15}, south, alt_now=None) == []


def test_a_climb_named_by_its_verb_is_a_distance_up_not_the_altitude() -> None:
    """Seen on a fifth-day dev request with the self-check's ideal plan: "up to 6 m first, then over 20 m
    north while climbing another 6 m" had its up_m=6 zeroed as if 6 m were only the altitude."""
    request = "Charlie: up to 6 m first, then over 20 m north while climbing another 6 m."
    args = {"drone_id": "charlie", "north_m": 20, "east_m": 0, "up_m": 6}
    assert altitude_not_a_climb(args, request, alt_now=5.8) == [] and args["up_m"] == 6
    for said in ("climb 5 m", "then descend a further 3 m", "rising an extra 4 m"):
        assert altitude_not_a_climb({"up_m": 5}, f"take it up to 5 m, {said}", alt_now=5.0) == [], said
    # "climb to 6 m" names the altitude, not a distance up
    to = {"north_m": 20, "east_m": 0, "up_m": 6}
    assert altitude_not_a_climb(to, "climb to 6 m, then 20 m north", alt_now=5.9) != [] and to["up_m"] == 0


def test_an_altitude_the_size_of_the_requests_climb_is_that_climb() -> None:
    """Measured on a fifth-day dev request with the 1.5B model: the climb came as alt_m=6 at 6 m."""
    request = "Charlie: up to 6 m first, then over 20 m north while climbing another 6 m."
    args = {"drone_id": "charlie", "north_m": 20, "alt_m": 6}
    assert climb_written_as_altitude(args, request, alt_now=5.9) == [
        "alt_m=6 read as up_m=6 ('climbing another 6 m' in the request; the drone is at 6 m)"
    ]
    assert args == {"drone_id": "charlie", "north_m": 20, "up_m": 6}
    lower = {"north_m": 10, "alt_m": 3}
    assert climb_written_as_altitude(lower, "at 12 m go 10 m north and 3 m lower", alt_now=12.0) != []
    assert lower == {"north_m": 10, "up_m": -3}
    # left alone: the sum already, on the ground, no climb named, or an up_m given
    assert climb_written_as_altitude({"alt_m": 12}, request, alt_now=6.0) == []
    assert climb_written_as_altitude({"alt_m": 6}, request, alt_now=None) == []
    assert climb_written_as_altitude({"alt_m": 6}, "then 20 m north at 6 m", alt_now=6.0) == []
    assert climb_written_as_altitude({"alt_m": 6, "up_m": 6}, request, alt_now=6.0) == []
