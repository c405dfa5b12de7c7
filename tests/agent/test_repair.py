"""Argument repairs toward what the user said (pure functions) and their use by the host."""

from __future__ import annotations

from bench.agent_harness.scripted import call, say
from gateway.agent.host import AgentEvent, AgentHost, ModelConfig
from gateway.agent.mcp_link import McpLink
from gateway.agent.repair import null_island, restore_request_numbers, swap_hint
from tests.agent.toy_mcp import TOKEN

REQUEST = "Launch bravo to 20 m and send it to -35.362855, 149.164955. Keep it hovering there."


def test_a_shortened_coordinate_gets_the_users_digits_back() -> None:
    args = {"drone_id": "bravo", "latitude_deg": -35.3629, "longitude_deg": 149.165, "altitude_m": 20}
    notes = restore_request_numbers(args, REQUEST)
    assert args == {
        "drone_id": "bravo",
        "latitude_deg": -35.362855,
        "longitude_deg": 149.164955,
        "altitude_m": 20,
    }
    assert notes == [
        "latitude_deg -35.3629 read as -35.362855 (the number in the request)",
        "longitude_deg 149.165 read as 149.164955 (the number in the request)",
    ]


def test_numbers_are_left_alone_unless_exactly_one_request_number_rounds_to_them() -> None:
    two = "first to -35.362855, 149.1, then to -35.362860, 149.2"
    args = {"latitude_deg": -35.3629, "longitude_deg": 149.17, "altitude_m": 20.0, "north_m": 1.5}
    assert restore_request_numbers(args, two) == []  # -35.3629: two candidates; 149.17: none
    assert args == {"latitude_deg": -35.3629, "longitude_deg": 149.17, "altitude_m": 20.0, "north_m": 1.5}
    exact = {"latitude_deg": -35.362855}
    assert restore_request_numbers(exact, REQUEST) == [] and exact == {"latitude_deg": -35.362855}


def test_swapped_latitude_and_longitude_are_named() -> None:
    hint = swap_hint({"latitude_deg": 149.171, "longitude_deg": -35.317878})
    assert hint == (
        "latitude_deg 149.171 is outside -90..90: latitude and longitude look swapped; "
        "try latitude_deg=-35.3179, longitude_deg=149.171."
    )
    assert swap_hint({"center_lat": 95.0, "center_lon": 10.0}) is not None
    assert swap_hint({"latitude_deg": -35.3, "longitude_deg": 149.1}) is None


def test_latitude_and_longitude_zero_is_refused_unless_the_user_said_it() -> None:
    zero = {"drone_id": "alpha", "latitude_deg": 0, "longitude_deg": 0, "altitude_m": 15}
    refusal = null_island(zero, "Alpha: go up to 15 m, fly 60 metres north, and land there.")
    assert refusal is not None and refusal.startswith("latitude_deg=0, longitude_deg=0 is not a place in the")
    assert "move_to_relative" in refusal and "Nothing was executed" in refusal
    assert null_island(zero, "fly alpha to 0, 0 at 15 m") is None
    on_ground = null_island(zero, "Alpha: go up to 15 m", on_ground=True)
    assert on_ground is not None
    assert (
        'alpha is on the ground: to go up to 15 m, call takeoff with drone_id "alpha" and altitude_m 15'
        in on_ground
    )
    assert null_island({**zero, "latitude_deg": 0.5}, "go up") is None


async def test_the_host_sends_the_users_number_and_says_so(toy, scripted) -> None:
    model = scripted(
        [
            call("takeoff", drone_id="alpha", altitude_m=10),
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
