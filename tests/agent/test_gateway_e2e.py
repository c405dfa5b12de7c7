"""End to end: scripted model -> typed plan -> the host's compiler and checks -> the gateway's /mcp ->
mavsdk_server -> simulated drones, judged by the simulator's true state."""

from __future__ import annotations

import json
from collections.abc import AsyncIterator, Callable

import pytest

from bench.agent_harness.scripted import ScriptedModelServer, say
from bench.agent_harness.stack import LocalStack
from fleet_agent.host import AgentHost
from fleet_agent.mcp_link import McpLink, McpLinkError
from fleet_agent.records import AgentEvent, ModelConfig, TurnResult
from gateway.fleet.geo import horizontal_distance_m, offset_position
from tests.helpers.timing import scaled

pytestmark = pytest.mark.timeout(scaled(240))


@pytest.fixture
async def stack() -> AsyncIterator[LocalStack]:
    async with LocalStack(["alpha", "bravo"], speedup=10) as s:
        yield s


def m(value: float, unit: str = "m") -> dict:
    return {"value": value, "unit": unit}


async def _turn(
    stack: LocalStack, scripted: Callable[..., ScriptedModelServer], request: str, plan: dict
) -> tuple[TurnResult, list[AgentEvent]]:
    """One turn of the host on the stack's gateway, the model replying with ``plan``."""
    model = scripted([say(json.dumps(plan))])
    events: list[AgentEvent] = []
    async with McpLink(stack.mcp_url, stack.token) as link:
        host = AgentHost(
            ModelConfig(model.base_url, "scripted", max_retries=0),
            link,
            await link.list_tools(),
            on_event=events.append,
        )
        return await host.run_turn(request), events


async def test_feet_a_leg_and_a_placement_beside_another_drone_fly_on_the_sim(
    stack: LocalStack, scripted
) -> None:
    truth = stack.truth()
    homes = await truth.homes(["alpha", "bravo"])
    plan = {
        "steps": [
            {"action": "takeoff", "drone": "alpha", "altitude": m(40, "ft")},
            {
                "action": "move",
                "after": "stay",
                "drone": "alpha",
                "legs": [{"distance": m(30), "direction": "north"}],
                "altitude": None,
                "origin": {"kind": "here"},
            },
            {
                "action": "move",
                "after": "stay",
                "drone": "bravo",
                "legs": [{"distance": m(20), "direction": "east"}],
                "altitude": m(18),
                "origin": {"kind": "drone", "drone": "alpha"},
            },
            {"action": "land", "drone": "alpha"},
        ]
    }
    result, events = await _turn(
        stack, scripted, "alpha 40 ft up, 30 m north, land; bravo 20 m east of it", plan
    )

    assert result.outcome == "answered", result
    actions = [
        (c.name, c.status) for c in result.tool_calls if c.name not in ("list_drones", "monitor_flight")
    ]
    want = ["takeoff", "move_to_relative", "takeoff", "go_to_location", "land"]
    assert actions == [(name, "ok") for name in want], result.tool_calls
    final = await truth.snapshot(["alpha", "bravo"])
    alpha_want = offset_position(homes["alpha"][0], homes["alpha"][1], 30.0, 0.0)
    assert horizontal_distance_m(final["alpha"].lat, final["alpha"].lon, *alpha_want) < 4.0, final["alpha"]
    assert final["alpha"].landed and not final["alpha"].armed
    # bravo went to 20 m east of where alpha was when the step ran (alpha's telemetry, read by the host)
    bravo_want = offset_position(*alpha_want, 0.0, 20.0)
    assert horizontal_distance_m(final["bravo"].lat, final["bravo"].lon, *bravo_want) < 5.0, final["bravo"]
    assert abs(final["bravo"].alt_rel_m - 18.0) < 1.5, final["bravo"]
    took_off = next(c for c in result.tool_calls if c.name == "takeoff")
    assert took_off.arguments == {"drone_id": "alpha", "alt_m": 12.19}
    assert any(e.kind == "progress" for e in events)


async def test_the_gateways_refusal_is_read_by_its_rule_and_nothing_flies(
    stack: LocalStack, scripted
) -> None:
    truth = stack.truth()
    plan = {
        "steps": [
            {"action": "takeoff", "drone": "bravo", "altitude": m(500)},
            {
                "action": "move",
                "after": "stay",
                "drone": "bravo",
                "legs": [{"distance": m(20), "direction": "north"}],
                "altitude": None,
                "origin": {"kind": "here"},
            },
        ]
    }
    result, _ = await _turn(stack, scripted, "bravo to 500 m and back", plan)
    refused = next(c for c in result.tool_calls if c.name == "takeoff")
    assert refused.status == "error" and refused.refusal is not None
    assert (refused.refusal.code, refused.refusal.rule) == ("safety_refusal", "max_altitude")
    assert refused.refusal.details["limit_m"] == 120.0
    assert [c.status for c in result.tool_calls if c.name == "move_to_relative"] == ["skipped"]
    assert "Refused: max_altitude" in (result.final_text or "")
    bravo = (await truth.snapshot(["bravo"]))["bravo"]
    assert bravo.landed and not bravo.armed
    with pytest.raises(McpLinkError, match="cannot open an MCP session"):
        async with McpLink(stack.mcp_url, "not-the-token"):
            pass


async def test_stack_moves_on_when_its_port_is_taken(monkeypatch) -> None:
    """A port picked free can be taken before the gateway binds it: the stack must not talk to the
    squatter, it must notice its own gateway failed to bind and use another port."""
    import socket

    from gateway import localstack as stack_module

    squatter = socket.socket()
    squatter.bind(("127.0.0.1", 0))
    squatter.listen()
    taken = squatter.getsockname()[1]
    real = stack_module.free_tcp_port
    ports = iter([taken])
    monkeypatch.setattr(stack_module, "free_tcp_port", lambda: next(ports, None) or real())
    try:
        async with LocalStack(["alpha"], speedup=10) as s:
            assert s.api_url != f"http://127.0.0.1:{taken}"
            async with McpLink(s.mcp_url, s.token) as link:
                assert "takeoff" in {t.name for t in await link.list_tools()}
    finally:
        squatter.close()
