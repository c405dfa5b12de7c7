"""Through MCP over HTTP on the simulator (real sidecars, real SQLite): a mission another ground station
stored (pymavlink on the drone's second port) is read back and checked at every start, so a waypoint
200 m up is refused for initiate_mission, resume_mission, set_flight_mode AUTO/MISSION and
set_current_waypoint, on the ground and in the air; an item the gateway cannot check is refused by name;
loose input (numbers as strings or booleans, names with spaces, unknown nested fields, an empty list) is
refused at the door. Each judged at the simulator: nothing reached the drone."""

from __future__ import annotations

import asyncio
import time
from collections.abc import AsyncIterator
from typing import Any

import pytest
import pytest_asyncio
from pymavlink import mavutil

from tests.helpers.gcs_mission import GcsItem, upload
from tests.mcp.conftest import Stack, error_text, gateway_stack, point_from, structured

mav = mavutil.mavlink
DRONES = 2
pytestmark = pytest.mark.asyncio(loop_scope="module")


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    async with gateway_stack(
        tmp_path_factory.mktemp("mission-start"), count=DRONES, sim_args=("--gcs-base-port", "0")
    ) as s:
        yield s


async def another_gcs_stores(stack: Stack, drone: str, items: list[GcsItem]) -> None:
    await asyncio.to_thread(upload, str(stack.sim.gcs_urls[stack.index(drone)]), items)


def up_to_200_m(state: dict[str, Any]) -> list[GcsItem]:
    near, far = point_from(state, 50, 0), point_from(state, 100, 0)
    return [
        GcsItem(mav.MAV_CMD_NAV_TAKEOFF, alt=10),
        GcsItem(mav.MAV_CMD_NAV_WAYPOINT, *near, 30),
        GcsItem(mav.MAV_CMD_NAV_WAYPOINT, *far, 200),
    ]


async def refused(stack: Stack, c: Any, tool: str, args: dict[str, Any], needle: str) -> str:
    text = error_text(await stack.call(c, tool, args))
    assert needle in text, (tool, text[:400])
    return text


async def test_a_mission_another_ground_station_stored_is_checked_at_every_start(stack: Stack) -> None:
    before = await stack.true_state("d1")
    await another_gcs_stores(stack, "d1", up_to_200_m(before))
    d1 = {"drone_id": "d1"}
    altitude = "max_altitude: mission item 3: waypoint altitude 200 m exceeds the limit of 120 m"
    async with stack.client("auto", name="mission-start") as c:
        began = time.monotonic()
        await refused(stack, c, "initiate_mission", {**d1, "wait": False}, altitude)
        # printed, never asserted: the refusal includes reading the mission back from the autopilot
        print(
            f"\nFIGURE initiate_mission refused after reading back 3 items: {time.monotonic() - began:.2f} s"
        )
        await refused(stack, c, "initiate_mission", {**d1, "waypoints": []}, "waypoints is an empty list")
        await refused(stack, c, "resume_mission", d1, altitude)
        for mode in ("AUTO", "MISSION"):
            await refused(stack, c, "set_flight_mode", {**d1, "mode": mode}, altitude)
        ground = await stack.true_state("d1")
        assert not ground["armed"] and ground["mode"] == before["mode"], ground

        took = structured(await stack.call(c, "takeoff", {**d1, "alt_m": 10}))
        assert took["status"] == "succeeded", took
        await refused(stack, c, "resume_mission", d1, altitude)
        await refused(stack, c, "set_flight_mode", {**d1, "mode": "AUTO"}, altitude)
        await refused(stack, c, "set_current_waypoint", {**d1, "index": 2}, altitude)
        air = await stack.true_state("d1")
        assert air["mode"] == "GUIDED" and abs(air["rel_alt_m"] - 10) < 2, air

        # an item whose effect the gateway cannot check: refused by name, never as an altitude
        spot = point_from(before, 30, 0)
        await another_gcs_stores(
            stack,
            "d1",
            [
                GcsItem(mav.MAV_CMD_NAV_WAYPOINT, *spot, 20),
                GcsItem(mav.MAV_CMD_DO_AUX_FUNCTION, frame=mav.MAV_FRAME_MISSION, params=(31, 2, 0, 0)),
            ],
        )
        text = await refused(
            stack, c, "resume_mission", d1, "mission_unchecked: mission item 2: DO_AUX_FUNCTION (218) is a"
        )
        assert "altitude" not in text
        assert (await stack.true_state("d1"))["mode"] == "GUIDED"
        landed = structured(await stack.call(c, "land", d1))
        assert landed["status"] == "succeeded", landed


async def test_loose_input_is_refused_at_the_door_and_sends_nothing(stack: Stack) -> None:
    before = await stack.true_state("d2")
    d2 = {"drone_id": "d2"}
    here = point_from(before, 20, 0)
    waypoint = {"lat_deg": here[0], "lon_deg": here[1], "alt_m": 10}
    cases: list[tuple[str, dict[str, Any], str]] = [
        ("takeoff", {**d2, "alt_m": "10"}, '0 < alt_m <= 120 (got "10"): send a JSON number, not a string'),
        ("takeoff", {**d2, "alt_m": True}, "(got true): send a JSON number, not true or false"),
        (
            "set_parameter",
            {**d2, "name": "RTL_ALT", "value": "12000"},
            '(got "12000"): send a JSON number, not a string',
        ),
        ("set_parameter", {**d2, "name": "RTL_ALT", "value": True}, "(got true)"),
        ("set_flight_mode", {**d2, "mode": "  rtl  "}, "mode must be a string of at most 32 characters"),
        ("upload_mission", {**d2, "waypoints": [{**waypoint, "yaw": 90}]}, "waypoints[0].yaw is not a field"),
        ("upload_mission", {**d2, "waypoints": [{**waypoint, "alt_m": "10"}]}, "waypoints[0].alt_m must be"),
        ("upload_mission", {**d2, "waypoints": []}, "waypoints"),
        (
            "set_current_waypoint",
            {**d2, "index": 2.5},
            "index must be an integer (Item 1..N), 1 <= index <= 200 (got 2.5)",
        ),
    ]
    async with stack.client("auto", name="strict") as c:
        for tool, args, needle in cases:
            text = await refused(stack, c, tool, args, needle)
            assert "\n" not in text.strip() and "pydantic" not in text, text
    after = await stack.true_state("d2")
    assert (after["armed"], after["mode"]) == (before["armed"], before["mode"])
