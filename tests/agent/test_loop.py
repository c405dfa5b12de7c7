"""The host's turn over a real MCP server (the toy fleet) and a scripted endpoint: the plan is compiled,
checked, sent, followed; refusals are read as data; the answer tells what was done and read."""

from __future__ import annotations

import json

from bench.agent_harness.scripted import say
from fleet_agent.host import AgentHost
from fleet_agent.mcp_link import McpLink
from fleet_agent.records import AgentEvent, ModelConfig
from tests.agent.toy_mcp import TOKEN


def m(value: float, unit: str = "m") -> dict:
    return {"value": value, "unit": unit}


async def _turn(toy, scripted, request: str, *plans: dict):
    server = scripted([say(json.dumps(p)) for p in plans])
    events: list[AgentEvent] = []
    async with McpLink(toy.url, TOKEN) as link:
        host = AgentHost(
            ModelConfig(server.base_url, "scripted", max_retries=0),
            link,
            await link.list_tools(),
            on_event=events.append,
        )
        return await host.run_turn(request), events, server


async def test_a_plan_is_compiled_sent_and_answered(toy, scripted) -> None:
    plan = {"steps": [
        {"action": "takeoff", "drone": "alpha", "altitude": m(40, "ft")},
        {"action": "move", "drone": "alpha", "legs": [{"distance": m(20), "direction": "north"}],
         "after": "stay", "altitude": None, "origin": {"kind": "here"}},
        {"action": "land", "drone": "alpha"},
    ]}  # fmt: skip
    result, events, server = await _turn(toy, scripted, "alpha: up 40 ft, 20 m north, land", plan)
    assert result.outcome == "answered" and len(server.requests) == 1
    sent = [(n, a) for n, a in toy.world.calls]
    assert sent == [
        ("takeoff", {"drone_id": "alpha", "alt_m": 12.19}),
        ("move_to_relative", {"drone_id": "alpha", "north_m": 20.0, "east_m": 0.0}),
        ("land", {"drone_id": "alpha"}),
    ]
    # the fleet is read once before the plan, and again only after an action changed it
    names = [c.name for c in result.tool_calls]
    assert names == ["list_drones", "takeoff", "list_drones", "move_to_relative", "land"]
    assert toy.world.drones["alpha"].north_m == 20.0 and not toy.world.drones["alpha"].armed
    assert "alpha: takeoff(alt_m=12.19) done." in (result.final_text or "")
    kinds = {e.kind for e in events}
    assert {"model_reply", "plan", "tool_call", "progress", "tool_result", "final"} <= kinds


async def test_a_refusal_is_read_as_data_and_the_drone_left_alone(toy, scripted) -> None:
    plan = {"steps": [
        {"action": "takeoff", "drone": "bravo", "altitude": m(500)},
        {"action": "move", "drone": "bravo", "legs": [{"distance": m(9), "direction": "east"}],
         "after": "stay", "altitude": None, "origin": {"kind": "here"}},
        {"action": "land", "drone": "bravo"},
        {"action": "takeoff", "drone": "alpha", "altitude": m(5)},
    ]}  # fmt: skip
    result, events, _ = await _turn(toy, scripted, "bravo to 500 m and back; alpha to 5 m", plan)
    refused = next(c for c in result.tool_calls if c.status == "error")
    assert refused.refusal is not None and refused.refusal.rule == "max_altitude"
    assert refused.refusal.code == "safety_refusal"
    skipped = [c for c in result.tool_calls if c.status == "skipped"]
    # bravo's move built on the refused takeoff (compiled as a takeoff to the default height and the leg):
    # held back; its landing still goes (safe at any time)
    assert [c.name for c in skipped] == ["takeoff", "move_to_relative"]
    assert "bravo: the rest was not sent after the refusal" in skipped[0].text
    assert [n for n, _ in toy.world.calls] == ["takeoff", "land", "takeoff"]
    assert toy.world.drones["alpha"].alt_m == 5.0 and not toy.world.drones["bravo"].armed
    assert "Refused: altitude 500 m exceeds the limit of 120 m" in (result.final_text or "")
    reported = next(e for e in events if e.kind == "tool_result" and e.data["status"] == "error")
    assert reported.data["refusal"]["rule"] == "max_altitude"


async def test_questions_and_choices_read_the_fleet(toy, scripted) -> None:
    toy.world.drones["alpha"].battery_pct, toy.world.drones["bravo"].battery_pct = 64.0, 31.0
    plan = {"steps": [
        {"action": "report", "drones": ["alpha", "bravo"], "readings": ["battery"], "pick": "lowest"},
        {"action": "choose", "among": ["alpha", "bravo"], "reading": "battery", "pick": "highest",
         "then": [{"action": "takeoff", "drone": "bravo", "altitude": m(6)}]},
    ]}  # fmt: skip
    result, _, _ = await _turn(toy, scripted, "batteries? then fly the fuller one to 6 m", plan)
    text = result.final_text or ""
    assert "alpha: battery 64 %, on the ground." in text and "bravo has the lowest battery (31)." in text
    assert "alpha has the highest battery (64 %)." in text
    assert toy.world.calls == [("takeoff", {"drone_id": "alpha", "alt_m": 6.0})]


async def test_no_valid_plan_flies_nothing_and_says_why(toy, scripted) -> None:
    bad = {"steps": [{"action": "takeoff", "drone": "zulu", "altitude": m(5)}]}
    result, _, server = await _turn(toy, scripted, "zulu up", bad, bad)
    assert result.outcome == "invalid_plan" and len(server.requests) == 2 and toy.world.calls == []
    assert "drone 'zulu' is not in the fleet" in (result.final_text or "")


async def test_no_answer_from_the_model_endpoint_names_it_and_flies_nothing(toy) -> None:
    async with McpLink(toy.url, TOKEN) as link:
        model = ModelConfig("http://127.0.0.1:9/v1", "qwen-test", max_retries=0, timeout_s=5)
        result = await AgentHost(model, link, await link.list_tools()).run_turn("alpha up 10 m")
    assert result.outcome == "model_error" and result.final_text is not None
    assert result.final_text.startswith(
        "No plan could be made: the model endpoint http://127.0.0.1:9/v1 (model qwen-test) did not answer"
    ), result.final_text
    assert [n for n, _ in toy.world.calls if n != "list_drones"] == []


async def test_a_branch_s_steps_are_compiled_each_in_its_turn(toy, scripted) -> None:
    """A move after a takeoff in a branch is compiled once the takeoff flew: compiled together, the move
    read a drone on the ground and sent a second takeoff."""
    toy.world.drones["alpha"].battery_pct = 80.0
    west = {"action": "move", "drone": "alpha", "legs": [{"distance": m(25), "direction": "west"}],
            "after": "stay", "altitude": None, "origin": "here"}  # fmt: skip
    plan = {"steps": [
        {"action": "if", "drone": "alpha", "reading": "battery", "compare": "above", "value": 65,
         "then": [{"action": "altitude", "drone": "alpha", "altitude": m(12), "after": "stay"}, west],
         "otherwise": []},
    ]}  # fmt: skip
    result, _, _ = await _turn(toy, scripted, "if alpha has over 65 %, up to 12 m and 25 m west", plan)
    assert toy.world.calls == [
        ("takeoff", {"drone_id": "alpha", "alt_m": 12.0}),
        ("move_to_relative", {"drone_id": "alpha", "north_m": 0.0, "east_m": -25.0}),
    ]
    assert (result.final_text or "").startswith("alpha: battery 80 %, above 65: so.")
