"""A pilot or ground station always wins, end to end: the simulator's second ground station port (a real
pymavlink GCS) and its control API switch modes while an agent's MCP tool call waits; the gateway (real
sidecars, real MCP over HTTP, real SQLite) ends the operation, locks the drone for agents and leaves the
pilot's mode alone until an operator releases it over REST.

Figures (how long after the mode change the waiting call returned) are printed, never asserted."""

from __future__ import annotations

import asyncio
import time
from collections.abc import AsyncIterator
from datetime import UTC, datetime
from typing import Any

import httpx
import pytest
import pytest_asyncio
from pymavlink import mavutil

from tests.helpers.timing import eventually, scaled
from tests.mcp.conftest import Stack, error_text, gateway_stack, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

ARDUCOPTER_LOITER = 5


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    async with gateway_stack(
        tmp_path_factory.mktemp("takeover"), count=2, sim_args=("--gcs-base-port", "0")
    ) as s:
        yield s
        print(f"\nFIGURE takeover (simulator, speed-up 8): {s.figures}")


def gcs_set_mode(url: str, custom_mode: int) -> None:
    """Another ground station on the autopilot's second port switches its mode (SET_MODE, as Mission
    Planner's mode buttons do)."""
    address = url.removeprefix("tcpout://")
    conn = mavutil.mavlink_connection(f"tcp:{address}", source_system=250, source_component=190)
    try:
        if conn.wait_heartbeat(timeout=scaled(10)) is None:
            raise AssertionError(f"no HEARTBEAT on the second ground station port {address}")
        conn.mav.set_mode_send(
            conn.target_system, mavutil.mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, custom_mode
        )
    finally:
        conn.close()


async def release(stack: Stack, drone_id: str) -> dict[str, Any]:
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        r = await http.delete(f"/api/v1/vehicles/{drone_id}/takeover")
        r.raise_for_status()
        return dict(r.json())


async def test_a_second_ground_station_takes_a_drone_mid_goto(stack: Stack) -> None:
    home = await stack.true_state("d1")
    lat, lon = point_from(home, 400.0, 0.0)
    async with stack.client("auto", name="agent") as c:
        assert (
            structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 10}))["status"]
            == "succeeded"
        )
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
        waiting = asyncio.create_task(stack.call(c, "go_to_location", goto))
        await wait_until_true(stack, "d1", lambda s: s["ground_speed_mps"] > 2.0, "d1 on its way")
        assert not waiting.done()
        gcs_url = stack.sim.gcs_urls[0]
        await asyncio.to_thread(gcs_set_mode, gcs_url, ARDUCOPTER_LOITER)
        switched = time.monotonic()
        r = structured(await asyncio.wait_for(waiting, scaled(30)))
        stack.figures["goto returned after the mode change, s"] = round(time.monotonic() - switched, 2)
        assert r["status"] == "interrupted", r
        assert "the autopilot switched from GUIDED to LOITER" in r["message"], r
        assert "a pilot or another ground station took control" in r["message"], r
        arrival = structured(await stack.call(c, "check_arrival", {"drone_id": "d1"}))
        assert arrival["status"] == "interrupted" and "LOITER" in arrival["message"]
        monitor = structured(await stack.call(c, "monitor_flight", {"drone_id": "d1"}))
        assert monitor["status"] == "interrupted"

        # the agent keeps trying for 10 simulated seconds; the pilot keeps LOITER
        before_tries = datetime.now(UTC)
        t_sim = (await stack.true_state("d1"))["t_boot_s"]
        tries = 0
        while (await stack.true_state("d1"))["t_boot_s"] < t_sim + 10.0:
            for tool, args in (
                ("move_to_relative", {"drone_id": "d1", "north_m": 20, "east_m": 0}),
                ("hold_position", {"drone_id": "d1"}),
                ("set_flight_mode", {"drone_id": "d1", "mode": "GUIDED"}),
            ):
                text = error_text(await stack.call(c, tool, args))
                assert "taken_over" in text and "taken over in LOITER" in text, text
                assert "DELETE /api/v1/vehicles/d1/takeover" in text
                tries += 1
            assert (await stack.true_state("d1"))["mode"] == "LOITER"
        assert tries >= 3
        drones = structured(await stack.call(c, "list_drones", {}))
        row = next(d for d in drones["drones"] if d["drone_id"] == "d1")
        assert row["locked"] and "taken over in LOITER" in row["locked"]

        rest = await stack.rest("/vehicles/d1")
        assert rest["taken_over"] is not None and "LOITER" in rest["taken_over"]["reason"]
        assert [t["scope"] for t in (await stack.rest("/takeovers"))["items"]] == ["d1"]
        # rows up to the agent's first try (its refused calls may be hundreds, each audited)
        until = before_tries.isoformat()
        audit = (await stack.rest("/audit", vehicle_id="d1", until=until, limit=100))["items"]
        row = next(a for a in audit if a["action"] == "takeover")
        assert row["source"] == "gateway" and row["arguments"]["to_mode"] == "LOITER"

        # with the sticks untouched (SITL's throttle at minimum) LOITER comes down and disarms: the
        # pilot's choice, left alone; then an operator releases the drone and the agent flies it again
        landed = await wait_until_true(stack, "d1", lambda s: not s["armed"], "d1 down in LOITER")
        assert landed["mode"] == "LOITER"
        assert (await release(stack, "d1"))["was_locked"] is True
        again = structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 8}))
        assert again["status"] == "succeeded", again
        moved = structured(
            await stack.call(c, "move_to_relative", {"drone_id": "d1", "north_m": 10, "east_m": 0})
        )
        assert moved["status"] == "succeeded", moved
        assert (await stack.true_state("d1"))["mode"] == "GUIDED"
        assert structured(await stack.call(c, "land", {"drone_id": "d1"}))["status"] == "succeeded"


async def test_takeoff_and_mission_end_when_a_pilot_or_a_failsafe_switches(stack: Stack) -> None:
    home = await stack.true_state("d2")
    async with stack.client("auto", name="agent-2") as c:
        waiting = asyncio.create_task(stack.call(c, "takeoff", {"drone_id": "d2", "alt_m": 40}))
        await wait_until_true(stack, "d2", lambda s: s["rel_alt_m"] > 4.0, "d2 climbing")
        await stack.sim.control.pilot_mode(1, "LOITER")  # the pilot's RC mode switch
        r = structured(await asyncio.wait_for(waiting, scaled(30)))
        assert r["status"] == "interrupted" and "from GUIDED to LOITER" in r["message"], r
        assert "taken_over" in error_text(await stack.call(c, "initiate_mission", {"drone_id": "d2"}))
        # LOITER without RC throttle sinks: the drone lands and disarms, sooner or later as the machine is
        # loaded; the mission below starts from the air, so the drone takes off again first
        await wait_until_true(stack, "d2", lambda s: not s["armed"], "d2 down and disarmed in LOITER")
        await release(stack, "d2")
        took = structured(await stack.call(c, "takeoff", {"drone_id": "d2", "alt_m": 15}))
        assert took["status"] == "succeeded", took

        a, b = point_from(home, 150.0, 0.0), point_from(home, 300.0, 0.0)
        waypoints = [{"lat_deg": p[0], "lon_deg": p[1], "alt_m": 15} for p in (a, b)]
        waiting = asyncio.create_task(
            stack.call(c, "initiate_mission", {"drone_id": "d2", "waypoints": waypoints})
        )
        await wait_until_true(
            stack, "d2", lambda s: s["mode"] == "AUTO" and s["ground_speed_mps"] > 2.0, "d2 on its mission"
        )
        await stack.sim.control.set_param(1, "BATT_FS_LOW_ACT", 2)  # RTL
        await stack.sim.control.set_battery(1, 15.0)  # below BATT_LOW_VOLT: the autopilot's failsafe
        r = structured(await asyncio.wait_for(waiting, scaled(60)))
        # ended by whichever sees it first, never "succeeded": the mode watch (the autopilot left AUTO for
        # RTL: interrupted) or the mission's tracker (a failsafe in the autopilot's words: failed); both
        # name it in the autopilot's words: "Battery Failsafe", or its "Battery 1 is low ..." with it
        if r["status"] == "interrupted":
            assert "from AUTO to RTL: battery failsafe (autopilot says: 'Battery " in r["message"], r
        else:
            assert r["status"] == "failed", r
            assert "failsafe; the autopilot said: " in r["message"] and "Battery" in r["message"], r

        async def locked() -> bool:
            return bool((await stack.rest("/vehicles/d2"))["taken_over"])

        await eventually(locked, "d2 taken over")
        text = error_text(await stack.call(c, "return_to_launch", {"drone_id": "d2"}))
        assert "taken_over" in text and "battery failsafe" in text
        assert (await stack.true_state("d2"))["mode"] == "RTL"  # the failsafe's choice stands


async def test_the_gateways_own_commands_never_count_as_a_takeover(stack: Stack) -> None:
    async with stack.client("auto", name="agent-3") as c:
        structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 8}))
        home = await stack.true_state("d1")
        lat, lon = point_from(home, 0.0, 200.0)
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 8, "wait": False}
        structured(await stack.call(c, "go_to_location", goto))
        structured(await stack.call(c, "set_flight_mode", {"drone_id": "d1", "mode": "BRAKE"}))
        structured(await stack.call(c, "hold_position", {"drone_id": "d1"}))
        r = structured(await stack.call(c, "return_to_launch", {"drone_id": "d1"}))
        assert r["status"] == "succeeded", r
    assert (await stack.rest("/vehicles/d1"))["taken_over"] is None


def gcs_fly_to(url: str, lat: float, lon: float, alt_m: float) -> float:
    """Another ground station sends the drone elsewhere in GUIDED (SET_POSITION_TARGET_GLOBAL_INT, a
    ground station's "fly to here"): the mode stays GUIDED. Returns when it was sent (monotonic)."""
    address = url.removeprefix("tcpout://")
    conn = mavutil.mavlink_connection(f"tcp:{address}", source_system=250, source_component=190)
    try:
        if conn.wait_heartbeat(timeout=scaled(10)) is None:
            raise AssertionError(f"no HEARTBEAT on the second ground station port {address}")
        conn.mav.set_position_target_global_int_send(
            0, conn.target_system, 1, mavutil.mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, 0xDF8,
            round(lat * 1e7), round(lon * 1e7), alt_m, 0, 0, 0, 0, 0, 0, 0, 0,
        )  # fmt: skip
        return time.monotonic()
    finally:
        conn.close()


async def test_a_second_ground_station_sending_the_drone_elsewhere_in_guided_is_a_takeover(
    stack: Stack,
) -> None:
    async with stack.client("auto", name="agent") as c:
        took = structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 10}))
        assert took["status"] == "succeeded", took
        here = await stack.true_state("d1")
        lat, lon = point_from(here, 400.0, 0.0)
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
        waiting = asyncio.create_task(stack.call(c, "go_to_location", goto))
        await wait_until_true(stack, "d1", lambda s: s["ground_speed_mps"] > 2.0, "d1 on its way")
        elsewhere = point_from(here, 0.0, 150.0)
        sent = await asyncio.to_thread(gcs_fly_to, stack.sim.gcs_urls[0], *elsewhere, 10.0)
        r = structured(await asyncio.wait_for(waiting, scaled(30)))
        stack.figures["goto returned after another GCS's new target, s"] = round(time.monotonic() - sent, 2)
        assert r["status"] == "interrupted", r
        assert "the autopilot left the gateway's target while staying in GUIDED" in r["message"], r
        text = error_text(await stack.call(c, "move_to_relative", {"drone_id": "d1", "north_m": 5}))
        assert "taken_over" in text, text
        assert (await stack.true_state("d1"))["mode"] == "GUIDED"
        assert (await release(stack, "d1"))["was_locked"] is True
        assert structured(await stack.call(c, "land", {"drone_id": "d1"}))["status"] == "succeeded"


async def taken_over_after(stack: Stack, drone_id: str, sent: float) -> float:
    """Seconds from ``sent`` until REST shows ``drone_id`` taken over (polled every 50 ms)."""
    deadline = time.monotonic() + scaled(30)
    while not (await stack.rest(f"/vehicles/{drone_id}"))["taken_over"]:
        if time.monotonic() > deadline:
            raise AssertionError(f"{drone_id} not taken over 30 s after the pilot's new target")
        await asyncio.sleep(0.05)
    return time.monotonic() - sent


async def test_a_pilots_new_target_during_a_hold_in_the_same_mode_is_a_takeover(stack: Stack) -> None:
    """The agent held the drone in GUIDED; a pilot on the second port sends it 250 m away at 40 m,
    still in GUIDED (SET_POSITION_TARGET_GLOBAL_INT): a takeover, and the agent's next move is refused."""
    async with stack.client("auto", name="agent") as c:
        took = structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 10}))
        assert took["status"] == "succeeded", took
        structured(await stack.call(c, "hold_position", {"drone_id": "d1"}))
        held = await stack.true_state("d1")

        async def still_held() -> bool:  # its own target reported for 2 s: no takeover
            return (await stack.rest("/vehicles/d1"))["taken_over"] is None

        loop = asyncio.get_running_loop()
        until = loop.time() + 2.0
        while loop.time() < until:
            assert await still_held()
            await asyncio.sleep(0.2)
        elsewhere = point_from(held, 250.0, 0.0)
        sent = await asyncio.to_thread(gcs_fly_to, stack.sim.gcs_urls[0], *elsewhere, 40.0)
        stack.figures["hold taken over after another GCS's new target, s"] = round(
            await taken_over_after(stack, "d1", sent), 2
        )
        taken = (await stack.rest("/vehicles/d1"))["taken_over"]
        assert "the autopilot left the gateway's target" in taken["reason"], taken
        back = {"drone_id": "d1", "lat_deg": held["lat"], "lon_deg": held["lon"], "alt_m": 10}
        text = error_text(await stack.call(c, "go_to_location", back))
        assert "taken_over" in text, text
        assert (await stack.true_state("d1"))["mode"] == "GUIDED"
        assert (await release(stack, "d1"))["was_locked"] is True
        assert structured(await stack.call(c, "land", {"drone_id": "d1"}))["status"] == "succeeded"
