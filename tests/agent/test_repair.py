"""Argument repairs toward what the user said (pure functions) and their use by the host."""

from __future__ import annotations

from bench.agent_harness.scripted import call, say
from gateway.agent.host import AgentHost
from gateway.agent.mcp_link import McpLink
from gateway.agent.repair import (
    altitude_written_as_distance,
    direction_mismatch,
    distance_written_as_altitude,
    extras_of_a_drone_only_tool,
    formation_offset_from_request,
    null_island,
    restore_request_directions,
    restore_request_numbers,
    shifted_request_moves,
    swap_hint,
    unplaced_optional_point,
)
from gateway.agent.turns import AgentEvent, ModelConfig
from tests.agent.toy_mcp import TOKEN

REQUEST = "Launch bravo to 20 m and send it to -35.362855, 149.164955. Keep it hovering there."


def test_a_shortened_coordinate_gets_the_users_digits_back() -> None:
    args = {"drone_id": "bravo", "lat_deg": -35.3629, "lon_deg": 149.165, "alt_m": 20}
    notes = restore_request_numbers(args, REQUEST)
    assert args == {
        "drone_id": "bravo",
        "lat_deg": -35.362855,
        "lon_deg": 149.164955,
        "alt_m": 20,
    }
    assert notes == [
        "lat_deg -35.3629 read as -35.362855 (the number in the request)",
        "lon_deg 149.165 read as 149.164955 (the number in the request)",
    ]


def test_numbers_are_left_alone_unless_exactly_one_request_number_rounds_to_them() -> None:
    two = "first to -35.362855, 149.1, then to -35.362860, 149.2"
    args = {"lat_deg": -35.3629, "lon_deg": 149.17, "alt_m": 20.0, "north_m": 1.5}
    assert restore_request_numbers(args, two) == []  # -35.3629: two candidates; 149.17: none
    assert args == {"lat_deg": -35.3629, "lon_deg": 149.17, "alt_m": 20.0, "north_m": 1.5}
    exact = {"lat_deg": -35.362855}
    assert restore_request_numbers(exact, REQUEST) == [] and exact == {"lat_deg": -35.362855}


def test_swapped_latitude_and_longitude_are_named() -> None:
    hint = swap_hint({"lat_deg": 149.171, "lon_deg": -35.317878})
    assert hint == (
        "lat_deg 149.171 is outside -90..90: latitude and longitude look swapped; "
        "try lat_deg=-35.3179, lon_deg=149.171."
    )
    assert swap_hint({"center_lat_deg": 95.0, "center_lon_deg": 10.0}) is not None
    assert swap_hint({"lat_deg": -35.3, "lon_deg": 149.1}) is None


def test_latitude_and_longitude_zero_is_refused_unless_the_user_said_it() -> None:
    zero = {"drone_id": "alpha", "lat_deg": 0, "lon_deg": 0, "alt_m": 15}
    refusal = null_island(zero, "Alpha: go up to 15 m, fly 60 metres north, and land there.")
    assert refusal is not None and refusal.startswith("lat_deg=0, lon_deg=0 is not a place in the")
    assert "move_to_relative" in refusal and "Nothing was executed" in refusal
    assert null_island(zero, "fly alpha to 0, 0 at 15 m") is None
    on_ground = null_island(zero, "Alpha: go up to 15 m", on_ground=True)
    assert on_ground is not None
    assert (
        "alpha is on the ground: to go up to 15 m, take off first:\n"
        '{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15}}\n'
    ) in on_ground
    assert null_island({**zero, "lat_deg": 0.5}, "go up") is None


async def test_the_host_sends_the_users_number_and_says_so(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=10),
            call("move_north", drone_id="alpha", distance_m=20.12),
            say("done"),
        ]
    )
    events: list[AgentEvent] = []
    async with McpLink(toy.url, TOKEN) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0),
            link,
            await link.list_tools(),
            on_event=events.append,
        )
        await host.run_turn("take alpha up 10 m and fly it 20.1234 m north")
    assert toy.world.calls[-1] == ("move_north", {"drone_id": "alpha", "distance_m": 20.1234})
    assert [e.data["notes"] for e in events if e.kind == "arguments_corrected"] == [
        ["distance_m 20.12 read as 20.1234 (the number in the request)"]
    ]


def test_a_named_distance_on_the_wrong_axis_or_sign_is_refused_with_the_right_one() -> None:
    south = "Bravo, take off to 15 m, head 50 m south, then return to launch."
    refusal = direction_mismatch({"drone_id": "bravo", "north_m": 0, "east_m": -50}, south)
    assert refusal is not None and refusal.startswith(
        "east_m=-50 does not match '50 m south' in the request: that is north_m=-50"
    )
    assert direction_mismatch({"drone_id": "bravo", "north_m": -50, "east_m": 0}, south) is None
    climb = "Take bravo up to 10 m, then move it 30 m east and 10 m higher, and hold it there."
    refusal = direction_mismatch({"north_m": 0, "east_m": 30, "up_m": -10}, climb)
    assert refusal is not None and "that is up_m=10" in refusal
    assert direction_mismatch({"north_m": 0, "east_m": 30, "up_m": 10}, climb) is None
    # numbers the request does not tie to a direction are not judged
    assert direction_mismatch({"north_m": 0, "east_m": 0, "up_m": -5}, climb) is None
    assert direction_mismatch({"north_m": 12, "east_m": 0}, "Fly alpha north a bit.") is None


def test_a_way_back_named_with_back_or_further_is_a_direction_of_its_own() -> None:
    """A return leg ("25 m back south") names its own direction: the call that flies it is right and is
    neither rewritten onto the outbound leg's direction nor refused."""
    there_and_back = "Fly bravo 25 m north at 10 m, then bring it 25 m back south and land it."
    back = {"drone_id": "bravo", "north_m": -25, "east_m": 0}
    assert restore_request_directions(dict(back), there_and_back) == []
    assert direction_mismatch(back, there_and_back) is None
    assert direction_mismatch({"drone_id": "bravo", "north_m": 25}, there_and_back) is None
    further = "Move charlie 15 metres further east."
    assert direction_mismatch({"east_m": -15}, further) is not None
    moved: dict[str, object] = {"north_m": 15, "east_m": 0}
    assert restore_request_directions(moved, further) and moved["east_m"] == 15


def test_a_leg_flown_back_after_it_was_flown_out_is_the_way_back() -> None:
    """ "Come back the way you came" names no direction: after the drone flew the leg out, the same leg
    with the other sign is the way back, neither rewritten onto the outbound direction nor refused. Before
    the leg was flown out, the other sign is still a wrong direction."""
    request = "Alpha: fly 30 m north at 15 m, come back the way you came, and land."
    out = {"drone_id": "alpha", "north_m": 30, "east_m": 0, "alt_m": 15}
    back = {"drone_id": "alpha", "north_m": -30, "east_m": 0}
    assert restore_request_directions(dict(back), request, [out]) == []
    assert direction_mismatch(back, request, [out]) is None
    first = dict(back)
    assert restore_request_directions(first, request) == [
        "north_m=-30 read as north_m=30 ('30 m north' in the request)"
    ]
    # a request with no way back: the other sign is wrong even after the leg was flown
    assert direction_mismatch(back, "Alpha: fly 30 m north at 15 m and land.", [out]) is not None


def test_an_unambiguous_misplaced_distance_is_moved_where_the_request_puts_it() -> None:
    south = "Bravo, take off to 15 m, head 50 m south, then return to launch."
    args = {"drone_id": "bravo", "north_m": 0, "east_m": -50}
    assert restore_request_directions(args, south) == [
        "east_m=-50 read as north_m=-50 ('50 m south' in the request)"
    ]
    assert args == {"drone_id": "bravo", "north_m": -50.0, "east_m": 0.0}
    climb = "Take bravo up to 10 m, then move it 30 m east and 10 m higher, and hold it there."
    args = {"north_m": 0, "east_m": 30, "up_m": -10}
    assert restore_request_directions(args, climb) == [
        "up_m=-10 read as up_m=10 ('10 m higher' in the request)"
    ]
    # two phrases with the same distance: not repaired (the refusal names the right argument instead)
    both = "Fly alpha 50 m north and bravo 50 m west."
    args = {"drone_id": "alpha", "north_m": 0, "east_m": 50}
    assert restore_request_directions(args, both) == [] and args["east_m"] == 50
    assert direction_mismatch(args, both) is not None


def test_west_m_and_south_m_are_judged_as_the_directions_they_name() -> None:
    """The gateway takes west_m/south_m as a request says them; a sign against the request's direction
    is repaired or refused like north_m/east_m."""
    west = "Take alpha and charlie 40 m west at 15 m altitude and land them over there."
    assert direction_mismatch({"drone_id": "alpha", "west_m": 40, "alt_m": 15}, west) is None
    assert restore_request_directions({"drone_id": "alpha", "west_m": 40}, west) == []
    args: dict[str, object] = {"drone_id": "alpha", "west_m": -40, "east_m": 0}
    notes = restore_request_directions(args, west)
    assert notes == ["west_m=-40 read as east_m=-40 ('40 m west' in the request)"]
    assert args == {"drone_id": "alpha", "west_m": 0.0, "east_m": -40.0}
    south = "Fly bravo 30 m south at 10 m."
    assert direction_mismatch({"south_m": 30}, south) is None
    assert direction_mismatch({"south_m": -30, "north_m": 5}, south) is not None


def test_an_optional_point_at_zero_zero_the_request_never_gives_is_left_out() -> None:
    """Measured on the dev half (form-line-here, form-circle-here, form-pair-abreast): formation_goto for
    "right where they are" came with center_lat_deg=0, center_lon_deg=0."""
    args = {"drone_ids": ["alpha"], "alt_m": 20, "center_lat_deg": 0, "center_lon_deg": 0, "north_m": 0}
    request = "Line up alpha at 20 m, right where they are."
    notes = unplaced_optional_point(args, request, ["drone_ids", "formation", "alt_m"])
    assert args == {"drone_ids": ["alpha"], "alt_m": 20, "north_m": 0}
    assert notes and notes[0].startswith("center_lat_deg=0, center_lon_deg=0 left out")
    # a required pair stays (go_to_location: the host's own checks refuse or read it), a point 0, 0 the
    # request gives stays, and so does any other point
    kept = {"drone_id": "alpha", "lat_deg": 0, "lon_deg": 0, "alt_m": 20}
    assert unplaced_optional_point(kept, request, ["drone_id", "lat_deg", "lon_deg", "alt_m"]) == []
    named = {"center_lat_deg": 0, "center_lon_deg": 0}
    assert unplaced_optional_point(named, "a line centred on 0, 0", []) == [] and len(named) == 2
    other = {"center_lat_deg": 0, "center_lon_deg": 149.1}
    assert unplaced_optional_point(other, request, []) == [] and len(other) == 2


def test_arguments_a_drone_only_tool_does_not_have_are_left_out() -> None:
    """Measured on the dev half (multi-west-and-land): land(drone_id="alpha", alt_m=15), refused for the
    unknown argument, sent three times unchanged."""
    args = {"drone_id": "alpha", "alt_m": 15, "speed": 3}
    notes = extras_of_a_drone_only_tool(args, {"drone_id": {"type": "string"}})
    assert args == {"drone_id": "alpha"} and notes == ["alt_m, speed left out: this tool takes only drone_id"]
    # a tool with arguments of its own keeps an unknown one, for the gateway's clear refusal
    moved = {"drone_id": "alpha", "alt_m": 15, "height": 3}
    assert extras_of_a_drone_only_tool(moved, {"drone_id": {}, "alt_m": {}}) == [] and "height" in moved
    assert extras_of_a_drone_only_tool({"x": 1}, {}) == []


def test_a_leg_written_into_the_altitude_is_moved_onto_its_axis() -> None:
    """Measured on the dev half (compound-south-then-home): "then 25 m south" was alt_m=-25, twice."""
    request = "Could you take alpha up to 14 m, then 25 m south, then have it return home?"
    args = {"drone_id": "alpha", "north_m": 0, "east_m": 0, "up_m": 0, "alt_m": -25}
    assert distance_written_as_altitude(args, request) == [
        "alt_m=-25 read as north_m=-25 ('25 m south' in the request)"
    ]
    assert args == {"drone_id": "alpha", "north_m": -25, "east_m": 0, "up_m": 0}
    # left alone: a horizontal argument already used, no leg of that size, two legs of that size
    used = {"north_m": -25, "alt_m": -25}
    assert distance_written_as_altitude(used, request) == [] and used["alt_m"] == -25
    assert distance_written_as_altitude({"alt_m": -7}, request) == []
    assert distance_written_as_altitude({"alt_m": -20}, "20 m east, then 20 m south") == []


def test_a_height_written_as_a_leg_is_the_altitude_when_the_request_names_no_direction() -> None:
    """Measured on the dev half (cond-alpha-sixty-go): "take it to 10 m" was north_m=10, alt_m=0."""
    request = "Check alpha's battery; if it's at least 60 %, take it to 10 m, otherwise say how much is left."
    args = {"drone_id": "alpha", "north_m": 10, "alt_m": 0}
    notes = altitude_written_as_distance(args, request)
    assert args == {"drone_id": "alpha", "north_m": 0.0, "alt_m": 10} and len(notes) == 1
    # left alone: a request with a direction, a number that is no asked altitude, a climb given
    assert altitude_written_as_distance({"north_m": 10}, "alpha to 10 m, then 10 m north") == []
    assert altitude_written_as_distance({"north_m": 12}, request) == []
    assert altitude_written_as_distance({"north_m": 10, "up_m": 5}, request) == []


def test_a_formation_formed_in_place_gets_the_requests_compass_distances() -> None:
    """Dev half (form-line-south): "25 m south of where they are" came as north_m=0, formed in place."""
    south = "All three in a row, 12 m between each, at 20 m, 25 m south of where they are."
    args = {"drone_ids": ["alpha", "bravo", "charlie"], "formation": "line", "spacing_m": 12, "north_m": 0}
    assert formation_offset_from_request(args, south) == [
        "north_m=-25 from the request's '25 m south' (from where the drones are)"
    ]
    assert args["north_m"] == -25
    both = {"drone_ids": ["alpha", "bravo"], "formation": "line"}
    assert len(formation_offset_from_request(both, "a line 30 m north and 10 m west of here")) == 2
    assert (both["north_m"], both["east_m"]) == (30, -10)
    # placed already, a centre given, no compass distance, or one axis named twice: left as it is
    assert formation_offset_from_request({"north_m": 10}, south) == []
    assert formation_offset_from_request({"center_lat_deg": -35.3, "center_lon_deg": 149.1}, south) == []
    assert formation_offset_from_request({}, "a line 12 m apart at 20 m") == []
    assert formation_offset_from_request({}, "30 m north, then 20 m south, in a line") == []


def test_the_requests_distances_shifted_one_slot_along_are_put_back() -> None:
    """Dev half (rel-east-lower): "nudge it 10 m east and 3 m lower" as north_m=10, east_m=3, alt_m=-3."""
    request = "Take alpha up to 12 m, then nudge it 10 m east and 3 m lower."
    args = {"drone_id": "alpha", "north_m": 10, "east_m": 3, "alt_m": -3}
    assert shifted_request_moves(args, request) == [
        "north_m=10, east_m=3, alt_m=-3 read as east_m=10, up_m=-3 ('10 m east', '3 m lower' in the request)"
    ]
    assert args == {"drone_id": "alpha", "east_m": 10, "up_m": -3}
    # right already, another number, one move only, or two moves of one size: left as it is
    for kept, asked in (
        ({"east_m": 10, "up_m": -3}, request),
        ({"north_m": 10, "east_m": 4}, request),
        ({"north_m": 10}, "fly alpha 10 m east"),
        ({"north_m": 30, "east_m": -30}, "30 m east, then 30 m back west"),
    ):
        before = dict(kept)
        assert shifted_request_moves(kept, asked) == [] and kept == before


def test_up_and_down_before_a_distance_are_climbs_and_up_to_is_an_altitude() -> None:
    """Dev half (compound-west-and-back): "Bravo: up 10 m, 20 m west, ..." names a climb of 10 m."""
    from gateway.agent.repair import request_climbs

    assert request_climbs("Bravo: up 10 m, 20 m west, then 20 m back east, then put it down.") == {10.0}
    assert request_climbs("Take it down 4 m, then land.") == {-4.0}
    assert request_climbs("Take bravo up to 10 m and hold it there.") == set()


def test_a_distance_in_kilometres_is_read_in_metres() -> None:
    from gateway.agent.repair import in_metres, request_distances

    assert (
        in_metres("Fly alpha 2 kilometres east, then 1.5 km north")
        == "Fly alpha 2000 m east, then 1500 m north"
    )
    assert request_distances("Fly alpha 2 kilometres east at 20 m.") == {2000.0}
    assert (
        direction_mismatch({"north_m": 2000, "east_m": 0}, "Fly alpha 2 kilometres east at 20 m.") is not None
    )
