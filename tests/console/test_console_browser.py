"""The operator console in a real browser (headless Chromium) against a real gateway with simulated drones,
an agent flying them over MCP with its token, and an operator (or viewer) at the console.

The module shares one gateway and one browser; each test opens its own page. A test sets up what it needs
(a drone in the air, a finished flight) itself, so each can run alone.
"""

from __future__ import annotations

import math
import re
from collections.abc import AsyncIterator
from datetime import datetime
from typing import Any

import pytest
import pytest_asyncio
from mcp import Client

from gateway.fleet import geo
from tests.console.conftest import (
    AGENT_TOKEN,
    OPERATOR_TOKEN,
    VIEWER_TOKEN,
    agent,
    screenshot,
    ui_timeout_ms,
)
from tests.helpers.timing import eventually, scaled, settled
from tests.mcp.conftest import Stack, error_text, point_from, structured, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

expect: Any = None  # playwright.async_api.expect, imported once the browser fixture found Playwright


@pytest_asyncio.fixture(scope="module", loop_scope="module", autouse=True)
async def browser_first(browser: Any) -> Any:
    """Probe for the browser before the gateway starts: without Chromium the module skips at once."""
    return browser


@pytest_asyncio.fixture(loop_scope="module")
async def context(browser: Any) -> AsyncIterator[Any]:
    global expect
    from playwright.async_api import expect as playwright_expect

    expect = playwright_expect
    ctx = await browser.new_context(viewport={"width": 1440, "height": 900})
    try:
        yield ctx
    finally:
        await ctx.close()


class Watched:
    """A page with every URL it requested and every JavaScript error it raised."""

    def __init__(self, page: Any) -> None:
        self.page = page
        self.urls: list[str] = []
        self.errors: list[str] = []
        page.on("request", lambda request: self.urls.append(request.url))
        page.on("pageerror", lambda error: self.errors.append(str(error)))
        page.on("console", self._console)

    def _console(self, message: Any) -> None:
        # the first request of a page without a token is answered 401: that is what shows the login form
        if message.type == "error" and "status of 401" not in message.text:
            self.errors.append(message.text)


async def open_console(context: Any, stack: Stack, token: str | None) -> Watched:
    """The console page, logged in with ``token``, once its stream is live."""
    watched = Watched(await context.new_page())
    page = watched.page
    await page.goto(f"{stack.base_url}/console")
    if token is not None:
        await page.fill("input[name=token]", token)
        await page.press("input[name=token]", "Enter")
    await expect(page.locator(".topbar .link.live")).to_be_visible(timeout=ui_timeout_ms())
    return watched


async def marker_local(page: Any, drone: str) -> dict[str, float] | None:
    """Where the map has drawn ``drone``'s marker, in metres east/north of the fleet's home."""
    return await page.evaluate(
        """id => {
            const entry = window.fleetMap && window.fleetMap.markers.get(id);
            return entry ? window.fleetMap.toLocal(entry.marker.getLatLng()) : null;
        }""",
        drone,
    )


async def ensure_airborne(stack: Stack, client: Client, drone: str, alt_m: float = 10.0) -> None:
    state = await stack.true_state(drone)
    if state["armed"] and not state["landed"] and state["rel_alt_m"] > 2.0:
        return
    result = structured(await client.call_tool("takeoff", {"drone_id": drone, "alt_m": alt_m}))
    assert result["status"] == "succeeded", result


async def unlock_all(stack: Stack) -> None:
    """Leave no lock behind for the next test (REST, as an operator would with curl)."""
    import httpx

    headers = {"Authorization": f"Bearer {OPERATOR_TOKEN}"}
    async with httpx.AsyncClient(base_url=stack.base_url, headers=headers, timeout=scaled(30)) as http:
        for lock in (await http.get("/api/v1/locks")).json()["items"]:
            path = "/api/v1/fleet/lock" if lock["scope"] == "*" else f"/api/v1/vehicles/{lock['scope']}/lock"
            (await http.delete(path)).raise_for_status()


async def operator_get(stack: Stack, path: str, **params: Any) -> Any:
    import httpx

    headers = {"Authorization": f"Bearer {OPERATOR_TOKEN}"}
    async with httpx.AsyncClient(base_url=stack.base_url, headers=headers, timeout=scaled(30)) as http:
        response = await http.get(f"/api/v1{path}", params=params)
        response.raise_for_status()
        return response.json()


def audit_row(page: Any, action: str, outcome: str) -> Any:
    return page.locator(f".audit-panel tr.audit-row.outcome-{outcome}", has_text=action)


# --- tests -------------------------------------------------------------------------------------------


async def test_login_then_a_viewer_watches_every_drone_without_actions(
    console_stack: Stack, context: Any
) -> None:
    page = await context.new_page()
    await page.goto(f"{console_stack.base_url}/console")
    await page.fill("input[name=token]", AGENT_TOKEN)  # an agent token is not a console token
    await page.press("input[name=token]", "Enter")
    await expect(page.locator(".login .error")).to_contain_text("not accepted", timeout=ui_timeout_ms())
    await screenshot(page, "login")
    await page.close()

    watched = await open_console(context, console_stack, VIEWER_TOKEN)
    page = watched.page
    await expect(page.locator(".topbar .who")).to_contain_text("viewer")
    rows = page.locator(".fleet-table tbody tr[data-drone]")
    await expect(rows).to_have_count(3, timeout=ui_timeout_ms())
    for drone in ("d1", "d2", "d3"):
        await expect(page.locator(f".leaflet-marker-icon .drone[data-drone={drone}]")).to_be_visible()
        await expect(page.locator(f".fleet-table tr[data-drone={drone}]")).to_contain_text("ready")
    await expect(page.locator(".home-icon").first).to_be_visible()
    await expect(page.locator("path.fence.keep-in")).to_have_count(1)
    await expect(page.locator("path.fence.keep-out")).to_have_count(1)
    await expect(page.locator(".leaflet-tile")).to_have_count(0)  # no tile server configured: none asked
    await expect(page.locator(".leaflet-control-scale-line")).to_contain_text("m")
    await expect(page.locator(".cursor-readout")).to_contain_text("fleet's home")
    await expect(page.locator("button.map-button")).to_have_text("Following fleet")  # until a pan or zoom
    # a viewer sees the buttons but cannot use them (the REST API would answer 403 anyway)
    await expect(page.locator("button.estop")).to_be_disabled()
    await expect(page.locator("button.lock-fleet")).to_be_disabled()
    await page.locator(".fleet-table tr[data-drone=d2]").click()
    await expect(page.locator(".detail button.act-land")).to_be_disabled()
    # everything came from the gateway itself (no CDN, no tile server), and no URL carried the token
    assert watched.urls and all(url.startswith(console_stack.base_url) for url in watched.urls), watched.urls
    assert not [url for url in watched.urls if VIEWER_TOKEN in url or "token" in url.lower()]
    assert watched.errors == []


async def test_tiles_are_drawn_only_from_the_configured_server(console_stack: Stack, context: Any) -> None:
    """GATEWAY_CONSOLE_TILES_URL switches the map to that tile server (here a file the gateway serves)."""
    tiles = "/console/static/vendor/leaflet/images/layers.png?z={z}&x={x}&y={y}"
    console_stack.settings.console_tiles_url = tiles  # read by /api/v1/console at each page load
    try:
        watched = await open_console(context, console_stack, VIEWER_TOKEN)
        page = watched.page
        await expect(page.locator("img.leaflet-tile-loaded").first).to_be_visible(timeout=ui_timeout_ms())
        await expect(page.locator(".leaflet-marker-icon .drone[data-drone=d1]")).to_be_visible()
        tile_urls = [url for url in watched.urls if "layers.png?z=" in url]
        assert tile_urls and all(url.startswith(console_stack.base_url) for url in watched.urls)
        assert all(re.search(r"z=\d+&x=\d+&y=\d+$", url) for url in tile_urls), tile_urls[:3]
    finally:
        console_stack.settings.console_tiles_url = None


async def test_fleet_table_sorts_and_filters_by_tag(console_stack: Stack, context: Any) -> None:
    page = (await open_console(context, console_stack, VIEWER_TOKEN)).page
    rows = page.locator(".fleet-table tbody tr[data-drone]")
    await expect(rows).to_have_count(3, timeout=ui_timeout_ms())
    await page.locator(".fleet-table th[data-sort=id]").click()  # already by id: now descending
    assert [await r.get_attribute("data-drone") for r in await rows.all()] == ["d3", "d2", "d1"]
    await page.select_option("select[name=tag-filter]", "north")
    await expect(rows).to_have_count(2)
    assert sorted([await r.get_attribute("data-drone") for r in await rows.all()]) == ["d1", "d2"]
    await page.select_option("select[name=tag-filter]", "south")
    await expect(rows).to_have_count(1)
    await expect(rows.first).to_have_attribute("data-drone", "d3")


async def test_a_drone_whose_link_is_lost_is_shown_as_stale(console_stack: Stack, context: Any) -> None:
    page = (await open_console(context, console_stack, VIEWER_TOKEN)).page
    row = page.locator(".fleet-table tr[data-drone=d3]")
    await expect(row).to_contain_text("on the ground", timeout=ui_timeout_ms())
    await console_stack.sim.control.link_down(console_stack.index("d3"))
    try:
        await expect(row).to_contain_text("link lost", timeout=ui_timeout_ms())
        await expect(page.locator(".drone.st-stale[data-drone=d3]")).to_be_visible()
        await row.click()
        await expect(page.locator(".detail")).to_contain_text("stale")
    finally:
        await console_stack.sim.control.link_up(console_stack.index("d3"))
    await expect(row).to_contain_text("on the ground", timeout=ui_timeout_ms(60))
    await expect(page.locator(".drone.st-ground[data-drone=d3]")).to_be_visible()


async def test_mcp_takeoff_and_goto_move_the_marker(console_stack: Stack, context: Any) -> None:
    watched = await open_console(context, console_stack, OPERATOR_TOKEN)
    page = watched.page
    await page.locator(".fleet-table tr[data-drone=d1]").click()
    label = page.locator(".drone[data-drone=d1] .label .alt")
    await expect(label).to_have_text(re.compile(r"^-?0\.\d m$"), timeout=ui_timeout_ms())
    before = await marker_local(page, "d1")
    assert before is not None
    home = await console_stack.true_state("d1")
    lat, lon = point_from(home, 40.0, 15.0)
    async with agent(console_stack) as client:
        await ensure_airborne(console_stack, client, "d1", 12.0)
        # the marker's label follows the altitude, pushed by the stream (no reload)
        await expect(label).to_have_text(re.compile(r"^1[12]\.\d m$"), timeout=ui_timeout_ms())
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 12, "wait": False}
        assert structured(await client.call_tool("go_to_location", goto))["status"] == "running"
        # the running operation shows with its progress in the drone's detail
        await expect(page.locator(".detail .operation .op-kind")).to_have_text(
            "goto", timeout=ui_timeout_ms()
        )

        async def moved() -> dict[str, float] | None:
            here = await marker_local(page, "d1")
            return here if here and here["north"] - before["north"] > 30.0 else None

        after = await eventually(moved, "the d1 marker moved 30 m north", within_s=60)
        assert after["east"] - before["east"] > 8.0, (before, after)
    # the current flight's track is drawn from take-off to here
    points = await page.evaluate("() => window.fleetMap.tracks.get('d1').line.getLatLngs().length")
    assert points >= 3
    await expect(page.locator(".detail")).to_contain_text("recording")
    await expect(page.locator(".fleet-table tr[data-drone=d1]")).to_contain_text("flying")
    assert watched.errors == []


async def test_an_agents_refused_call_appears_in_the_audit_stream(console_stack: Stack, context: Any) -> None:
    page = (await open_console(context, console_stack, OPERATOR_TOKEN)).page
    async with agent(console_stack, "audit-watcher") as client:
        refused = await client.call_tool("takeoff", {"drone_id": "d3", "alt_m": 500})
        assert "max_altitude" in error_text(refused)
    row = audit_row(page, "takeoff", "refused").filter(has_text="d3")
    await expect(row.first).to_be_visible(timeout=ui_timeout_ms())
    await expect(row.first.locator(".reason")).to_contain_text("max_altitude")
    await expect(row.first.locator(".who")).to_contain_text("agent-")
    await expect(row.first).to_contain_text("mcp")


async def test_lock_button_makes_the_next_mcp_takeoff_refused(console_stack: Stack, context: Any) -> None:
    page = (await open_console(context, console_stack, OPERATOR_TOKEN)).page
    try:
        await page.locator("button.lock-fleet").click()
        dialog = page.locator("dialog[data-kind=lock-fleet]")
        await expect(dialog).to_be_visible()
        await expect(dialog.locator("button.confirm-button")).to_be_disabled()  # a reason is required
        await dialog.locator("input[name=reason]").fill("people on the field")
        await screenshot(page, "lock-dialog")
        await dialog.locator("button.confirm-button").click()
        await expect(page.locator(".fleet-lock[data-locked=true]")).to_contain_text(
            "people on the field", timeout=ui_timeout_ms()
        )
        async with agent(console_stack, "locked-out") as client:
            refused = await client.call_tool("takeoff", {"drone_id": "d2", "alt_m": 10})
            message = error_text(refused)
            assert "operator_lock" in message and "people on the field" in message, message
            await expect(
                audit_row(page, "takeoff", "refused").filter(has_text="people on the field").first
            ).to_be_visible(timeout=ui_timeout_ms())
            await expect(audit_row(page, "rest.lock_fleet", "ok").first).to_be_visible()
            rows = (await operator_get(console_stack, "/audit", limit=200))["items"]
            locks = [r for r in rows if r["action"] == "rest.lock_fleet" and r["outcome"] == "ok"]
            assert locks and locks[0]["source"] == "console", locks  # the click is audited as the console's
            state = await console_stack.true_state("d2")
            assert not state["armed"], state

            # unlock from the page: the agent may fly again
            await page.locator("button.unlock-fleet").click()
            await page.locator("dialog[data-kind=unlock-fleet] button.confirm-button").click()
            await expect(page.locator(".fleet-lock[data-locked=false]")).to_be_visible(
                timeout=ui_timeout_ms()
            )
            await ensure_airborne(console_stack, client, "d2", 10.0)

            # a drone lock from its detail panel holds that drone only
            await page.locator(".fleet-table tr[data-drone=d3]").click()
            await page.locator(".detail button.act-lock").click()
            await page.locator("dialog[data-kind=lock-drone] input[name=reason]").fill("battery swap")
            await page.locator("dialog[data-kind=lock-drone] button.confirm-button").click()
            await expect(page.locator(".fleet-table tr[data-drone=d3] .lockmark")).to_be_visible(
                timeout=ui_timeout_ms()
            )
            refused = await client.call_tool("takeoff", {"drone_id": "d3", "alt_m": 10})
            assert "battery swap" in error_text(refused)
            await page.locator(".detail button.act-unlock").click()
            await page.locator("dialog[data-kind=unlock-drone] button.confirm-button").click()
            await expect(page.locator(".fleet-table tr[data-drone=d3] .lockmark")).to_have_count(
                0, timeout=ui_timeout_ms()
            )
    finally:
        await unlock_all(console_stack)


async def rest_position(stack: Stack, drone: str) -> dict[str, Any]:
    """Where the gateway says the drone is (GET /api/v1/vehicles/{id}: its telemetry cache)."""
    return (await stack.rest(f"/vehicles/{drone}"))["telemetry"]["position"]


def apart_m(a: dict[str, Any], b: dict[str, Any]) -> float:
    """Horizontal metres between two positions given as lat_deg/lon_deg."""
    return geo.horizontal_distance_m(a["lat_deg"], a["lon_deg"], b["lat_deg"], b["lon_deg"])


async def newest_operation(stack: Stack, drone: str, kind: str) -> dict[str, Any] | None:
    items = (await stack.rest("/operations", vehicle_id=drone, limit=10))["items"]
    return next((op for op in items if op["kind"] == kind), None)


async def test_hold_and_land_buttons_act_on_their_drone_and_are_audited_as_the_console(
    console_stack: Stack, context: Any
) -> None:
    stack = console_stack
    page = (await open_console(context, stack, OPERATOR_TOKEN)).page
    async with agent(stack, "button-target") as client:
        await ensure_airborne(stack, client, "d1", 12.0)
        await ensure_airborne(stack, client, "d2", 10.0)
        # Hold on d2: the dialog is open before d2 sets off, so the click lands while it flies its leg
        await page.locator(".fleet-table tr[data-drone=d2]").click()
        await page.locator(".detail[data-drone=d2] button.act-hold").click()
        dialog = page.locator("dialog[data-kind=drone-action]")
        await expect(dialog).to_contain_text('Send "hold" to d2 now?')
        slow = {"drone_id": "d2", "speed_mps": 3.0}  # a leg that lasts seconds
        structured(await client.call_tool("set_max_speed", slow))
        lat, lon = point_from((await stack.true_state("d2"))["home"], -60.0, 120.0)
        start = await rest_position(stack, "d2")
        goto = {"drone_id": "d2", "lat_deg": lat, "lon_deg": lon, "alt_m": 10, "wait": False}
        leg = structured(await client.call_tool("go_to_location", goto))
        assert leg["status"] == "running", leg

        async def under_way() -> bool:
            return apart_m(await rest_position(stack, "d2"), start) > 5.0

        await eventually(under_way, "d2 under way on its leg", within_s=30)
        await dialog.locator("button.confirm-button").click()
        await expect(page.locator(".notice", has_text="Hold sent to d2")).to_be_visible(
            timeout=ui_timeout_ms()
        )

        async def leg_ended() -> str | None:
            op = await newest_operation(stack, "d2", "goto")
            ended = op is not None and op["id"] == leg["operation_id"] and op["status"] != "running"
            return op["status"] if ended and op is not None else None

        assert await eventually(leg_ended, "d2's leg ended by the hold") == "superseded"
        held = await settled(
            lambda: rest_position(stack, "d2"),
            lambda a, b: apart_m(a, b) < 0.5,
            "d2 holding where it was",
        )
        assert apart_m(held, {"lat_deg": lat, "lon_deg": lon}) > 30.0, held
        assert held["rel_alt_m"] > 8.0, held  # held in the air, not landed

    # Land on d1: it comes down where it is and disarms (its operation, as REST reports it)
    await page.locator(".fleet-table tr[data-drone=d1]").click()
    await page.locator(".detail[data-drone=d1] button.act-land").click()
    dialog = page.locator("dialog[data-kind=drone-action]")
    await expect(dialog).to_contain_text('Send "land" to d1 now?')
    above = await rest_position(stack, "d1")
    await dialog.locator("button.confirm-button").click()
    await expect(page.locator(".notice", has_text="Land sent to d1")).to_be_visible(timeout=ui_timeout_ms())

    async def landed_and_disarmed() -> dict[str, Any] | None:
        op = await newest_operation(stack, "d1", "land")
        return op if op and op["status"] == "succeeded" else None

    landing = await eventually(
        landed_and_disarmed, "d1's landing succeeded (landed and disarmed)", within_s=90
    )
    telemetry = (await stack.rest("/vehicles/d1"))["telemetry"]
    assert telemetry["armed"]["value"] is False and telemetry["position"]["rel_alt_m"] < 1.0, telemetry
    assert apart_m(telemetry["position"], above) < 3.0, (above, telemetry["position"])
    assert (await stack.true_state("d2"))["armed"]  # the other drone still holds in the air
    # each click is one REST call audited as the console's, with the operator's principal
    for drone, action in (("d2", "rest.hold_vehicle"), ("d1", "rest.land_vehicle")):
        rows = [r for r in (await stack.rest("/audit", vehicle_id=drone))["items"] if r["action"] == action]
        assert len(rows) == 1 and rows[0]["outcome"] == "ok", rows
        assert rows[0]["source"] == "console" and rows[0]["principal"], rows
        assert OPERATOR_TOKEN not in str(rows[0])
    # the land's row names its operation and took until the drone had landed, not the time to send it
    [land_row] = [
        r
        for r in (await stack.rest("/audit", vehicle_id="d1"))["items"]
        if r["action"] == "rest.land_vehicle"
    ]
    assert land_row["operation_id"] == landing["id"], (land_row, landing)
    landing_ms = (
        datetime.fromisoformat(landing["finished_at"]) - datetime.fromisoformat(landing["created_at"])
    ).total_seconds() * 1000
    assert land_row["duration_ms"] >= landing_ms, (land_row, landing)
    shown = audit_row(page, "rest.land_vehicle", "ok").first
    await expect(shown).to_contain_text("console")
    await expect(shown.locator("td.num")).to_have_text(f"{math.floor(land_row['duration_ms'] + 0.5)} ms")


async def test_emergency_stop_lands_the_fleet(console_stack: Stack, context: Any) -> None:
    page = (await open_console(context, console_stack, OPERATOR_TOKEN)).page
    fleet = ("d1", "d2", "d3")
    spread = {"d2": (-25.0, 35.0), "d3": (20.0, -30.0)}  # metres north, east of their homes
    try:
        async with agent(console_stack, "estop-victim") as client:
            for drone, alt in zip(fleet, (12.0, 10.0, 15.0), strict=True):
                await ensure_airborne(console_stack, client, drone, alt)
            for drone, (north, east) in spread.items():
                lat, lon = point_from((await console_stack.true_state(drone))["home"], north, east)
                goto = {"drone_id": drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
                assert structured(await client.call_tool("go_to_location", goto))["status"] == "succeeded"
        for drone in fleet:
            await expect(page.locator(f".fleet-table tr[data-drone={drone}]")).to_contain_text(
                "flying", timeout=ui_timeout_ms()
            )
        await page.locator(".fleet-table tr[data-drone=d2]").click()
        # where d2 is, from its own home (its goto was 25 m south, 35 m east of it)
        await expect(page.locator(".detail .facts")).to_contain_text(
            re.compile(r"E 3[45]\.\d m, N -2[45]\.\d m")
        )
        await screenshot(page, "console")
        await page.locator("button.estop").click()
        dialog = page.locator("dialog[data-kind=stop]")
        await expect(dialog).to_be_visible()
        await dialog.locator("input[name=stop-action][value=land]").check()
        await expect(dialog.locator("input[name=stop-lock]")).to_be_checked()
        await screenshot(page, "emergency-stop")
        await dialog.locator("button.confirm-button").click()
        await expect(page.locator(".notice")).to_contain_text("sent to d1, d2, d3", timeout=ui_timeout_ms())
        await expect(page.locator(".fleet-lock[data-locked=true]")).to_contain_text("emergency stop")
        for drone in fleet:
            await wait_until_true(
                console_stack, drone, lambda s: not s["armed"], f"{drone} landed and disarmed after the stop"
            )
            await expect(page.locator(f".fleet-table tr[data-drone={drone}]")).to_contain_text(
                "on the ground", timeout=ui_timeout_ms()
            )
        await expect(audit_row(page, "rest.fleet_stop", "ok").first).to_be_visible()
        # while the fleet is locked after the stop, the agent cannot take off again
        async with agent(console_stack, "estop-victim") as client:
            refused = await client.call_tool("takeoff", {"drone_id": "d1", "alt_m": 10})
            assert "emergency stop" in error_text(refused)
    finally:
        await unlock_all(console_stack)


async def test_replay_of_a_past_flight_shows_its_track_texts_and_calls(
    console_stack: Stack, context: Any
) -> None:
    headers = {"Authorization": f"Bearer {OPERATOR_TOKEN}"}
    import httpx

    async def finished_flight() -> dict[str, Any] | None:
        base = console_stack.base_url
        async with httpx.AsyncClient(base_url=base, headers=headers, timeout=scaled(30)) as http:
            items = (await http.get("/api/v1/flights", params={"limit": 50})).json()["items"]
        return next((f for f in items if f["ended_at"] and (f["distance_m"] or 0) > 10.0), None)

    if await finished_flight() is None:  # run alone: fly one that goes somewhere
        async with agent(console_stack, "replay-maker") as client:
            await ensure_airborne(console_stack, client, "d3", 8.0)
            lat, lon = point_from(await console_stack.true_state("d3"), 0.0, 25.0)
            goto = {"drone_id": "d3", "lat_deg": lat, "lon_deg": lon, "alt_m": 8}
            assert structured(await client.call_tool("go_to_location", goto))["status"] == "succeeded"
            assert structured(await client.call_tool("land", {"drone_id": "d3"}))["status"] == "succeeded"
    flight = await eventually(finished_flight, "a finished flight that moved, in the flight log", within_s=30)

    page = (await open_console(context, console_stack, OPERATOR_TOKEN)).page
    await page.locator("nav.tabs button[data-tab=flights]").click()
    row = page.locator(f".flights tr[data-flight='{flight['id']}']")
    await expect(row).to_be_visible(timeout=ui_timeout_ms())
    await row.locator("button.replay-button").click()
    panel = page.locator(".panel.replay")
    await expect(panel).to_contain_text(f"flight #{flight['id']}", timeout=ui_timeout_ms())
    # the status texts the drone sent and the agent's calls during the flight, on one timeline
    await expect(panel.locator(".timeline li", has_text="takeoff").first).to_be_visible()
    await expect(panel.locator(".timeline li .kind", has_text="info").first).to_be_visible()
    await expect(page.locator("path.replay-track")).to_have_count(1)
    first = await page.evaluate("() => window.fleetMap.replayMarker.getLatLng()")
    slider = panel.locator("input[name=replay-position]")
    last_index = int(await slider.get_attribute("max"))
    assert last_index >= 3
    await slider.fill(str(last_index))
    await expect(panel.locator(".timeline li.past").last).to_be_visible()

    async def marker_moved() -> dict[str, float] | None:  # the map follows the slider after a frame
        here = await page.evaluate("() => window.fleetMap.replayMarker.getLatLng()")
        return here if (here["lat"], here["lng"]) != (first["lat"], first["lng"]) else None

    await eventually(marker_moved, "the replay marker at the flight's last sample", within_s=10)
    await slider.fill(str(last_index // 2))
    await screenshot(page, "replay")
