"""What the autopilot does with a setting, judged by its effect, through the real gateway (MCP for the
agent, REST and the Commander for the operator) over a simulated ArduCopter that flies RTL_CLIMB_MIN,
CIRCLE and the home reset at arming as ArduCopter does: parameters by their effect and range, pilot
modes refused in the air, a pattern judged by its extent, and a distance limit counted from an origin
the autopilot cannot move."""

from __future__ import annotations

import asyncio
from collections.abc import AsyncIterator
from typing import Any

import httpx
import pytest
import pytest_asyncio

from tests.helpers.timing import scaled
from tests.mcp.conftest import (
    WAIT_S,
    Stack,
    distance_m,
    error_text,
    gateway_stack,
    point_from,
    structured,
    wait_until_true,
)

pytestmark = pytest.mark.asyncio(loop_scope="module")

LIMIT_M = 300.0


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    async with gateway_stack(tmp_path_factory.mktemp("effects"), count=1, max_distance_m=LIMIT_M) as s:
        yield s


async def _finish(stack: Stack, c: Any, r: dict[str, Any]) -> dict[str, Any]:
    while r["status"] == "running":
        r = structured(await stack.call(c, "monitor_flight", {"drone_id": "d1"}))
    return r


async def _param(stack: Stack, c: Any, name: str) -> float:
    return float(structured(await stack.call(c, "get_parameter", {"drone_id": "d1", "name": name}))["value"])


async def test_parameters_are_refused_by_their_effect_and_range(stack: Stack) -> None:
    async with stack.client("auto", name="effects") as c:
        text = error_text(
            await stack.call(c, "set_parameter", {"drone_id": "d1", "name": "RTL_CLIMB_MIN", "value": 3000})
        )
        assert "param_limit: RTL_CLIMB_MIN 3000 cm (30 m) is added by the autopilot" in text, text
        assert "accepted: 0 cm" in text, text
        text = error_text(
            await stack.call(c, "set_parameter", {"drone_id": "d1", "name": "WPNAV_RADIUS", "value": 1e9})
        )
        assert "param_range: WPNAV_RADIUS 1000000000 cm is outside" in text and "5 to 1000 cm" in text, text
        assert await _param(stack, c, "RTL_CLIMB_MIN") == 0.0  # nothing reached the autopilot
        assert await _param(stack, c, "WPNAV_RADIUS") == 200.0
        r = structured(
            await stack.call(c, "set_parameter", {"drone_id": "d1", "name": "WPNAV_RADIUS", "value": 300})
        )
        assert r["value"] == 300.0


async def test_circle_is_refused_for_agents_in_the_air(stack: Stack) -> None:
    async with stack.client("auto", name="effects") as c:
        r = await _finish(
            stack, c, structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 12}))
        )
        assert r["status"] == "succeeded", r
        text = error_text(await stack.call(c, "set_flight_mode", {"drone_id": "d1", "mode": "CIRCLE"}))
        assert "mode_deny_in_air: mode CIRCLE reads the pilot's throttle and sticks" in text, text
        await asyncio.sleep(scaled(0.5))
        state = await stack.true_state("d1")
        assert state["mode"] == "GUIDED" and state["rel_alt_m"] > 11.0, state


async def test_the_distance_limit_counts_from_the_first_home_not_the_one_set_at_arming(stack: Stack) -> None:
    first = await stack.true_state("d1")
    first_home = first["home"]
    async with stack.client("auto", name="effects") as c:
        lat, lon = point_from(first, 250.0, 0.0)
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 12}
        assert (await _finish(stack, c, structured(await stack.call(c, "go_to_location", goto))))[
            "status"
        ] == "succeeded"
        assert (await _finish(stack, c, structured(await stack.call(c, "land", {"drone_id": "d1"}))))[
            "status"
        ] == "succeeded"
        await wait_until_true(stack, "d1", lambda s: not s["armed"], "disarmed")
        r = await _finish(
            stack, c, structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 12}))
        )
        assert r["status"] == "succeeded", r
        landed_far = await stack.true_state("d1")
        assert distance_m(landed_far, landed_far["home"]["lat"], landed_far["home"]["lon"]) < 5.0
        assert distance_m(landed_far, first_home["lat"], first_home["lon"]) > 240.0  # home moved at arming
        origin = await stack.rest("/vehicles/d1/origin")
        assert origin["source"] == "first_home" and origin["home_from_origin_m"] > 240.0, origin
        # 150 m on: 150 m from the new home, 400 m from the first one: refused, nothing flies
        lat, lon = point_from(landed_far, 150.0, 0.0)
        goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 12}
        text = error_text(await stack.call(c, "go_to_location", goto))
        assert "max_distance: target is 400" in text and "from its origin (the first home it reported" in text
        await asyncio.sleep(scaled(1.0))
        assert distance_m(await stack.true_state("d1"), landed_far["lat"], landed_far["lon"]) < 3.0
        # an operator moves the origin over REST (audited); then the same goto flies
        async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
            moved = await http.put(
                "/api/v1/vehicles/d1/origin",
                json={
                    "lat": landed_far["home"]["lat"],
                    "lon": landed_far["home"]["lon"],
                    "alt_amsl_m": 584.0,
                },
            )
            assert moved.status_code == 200, moved.text
            assert moved.json()["source"] == "operator"
            bad = await http.put("/api/v1/vehicles/d1/origin", json={"lat": "10", "lon": 0, "alt_amsl_m": 0})
            assert bad.status_code == 422, bad.text
        audit = await stack.rest("/audit", vehicle_id="d1", limit=50)
        assert any("origin" in str(row.get("action", "")) for row in audit["items"]), audit
        r = structured(await stack.call(c, "go_to_location", goto))
        assert (await _finish(stack, c, r))["status"] == "succeeded"
        assert (await _finish(stack, c, structured(await stack.call(c, "land", {"drone_id": "d1"}))))[
            "status"
        ] == "succeeded"
    assert WAIT_S > 0
