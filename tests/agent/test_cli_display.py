"""`fleet-gateway agent` end to end in one process: options, one-shot, interactive, display, JSON lines."""

from __future__ import annotations

import argparse
import io
import json

import pytest
from rich.console import Console

from bench.agent_harness.scripted import ScriptedReply, call, say
from gateway.agent import cli
from tests.agent.toy_mcp import TOKEN
from tests.helpers.timing import scaled


def _parse(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command")
    cli.register(sub)
    return parser.parse_args(["agent", *argv])


def _console() -> tuple[Console, io.StringIO]:
    buf = io.StringIO()
    return Console(file=buf, force_terminal=False, width=200, color_system=None), buf


async def test_one_shot_shows_calls_progress_results_and_answer(toy, scripted, monkeypatch) -> None:
    monkeypatch.delenv("OPENAI_API_KEY", raising=False)
    model = scripted(
        [
            call("takeoff", drone_id="alpha", alt_m=15),
            ScriptedReply(
                content='<tool_call>{"name": "land", "arguments": {"drone_id": "alpha"}}</tool_call>'
            ),
            call("takeoff", drone_id="bravo", alt_m=500),
            say("Alpha hopped to 15 m and landed. Bravo was refused: 500 m exceeds the 120 m limit."),
        ]
    )
    console, buf = _console()
    args = _parse(
        [
            "--mcp-url",
            toy.url,
            "--token",
            TOKEN,
            "--endpoint",
            model.base_url,
            "--model",
            "m",
            "hop alpha to 15 m and land, then bravo to 500 m",
        ]
    )
    assert await cli.run_async(args, console=console) == cli.EXIT_OK
    out = buf.getvalue()
    expected_in_order = [
        "you hop alpha to 15 m",
        '→ takeoff(drone_id="alpha", alt_m=15)',
        "… takeoff 33% climbing 5.0/15 m",
        "… takeoff 100% climbing 15.0/15 m",
        "✓ status=reached",
        "parsed a tool call from text",
        '→ land(drone_id="alpha")',
        "✓ status=landed",
        '→ takeoff(drone_id="bravo", alt_m=500)',
        "✗ Error executing tool takeoff: refused by rule max_altitude",
        "model Alpha hopped to 15 m and landed.",
        "4 model step(s), 3 tool call(s),",
    ]
    pos = 0
    for needle in expected_in_order:
        found = out.find(needle, pos)
        assert found >= 0, f"{needle!r} missing (in order) from:\n{out}"
        pos = found
    assert model.requests[0]["model"] == "m" and model.requests[0]["temperature"] == 0.0


async def test_json_transcript(toy, scripted) -> None:
    model = scripted([call("land", drone_id="alpha"), say("landed")])
    console, buf = _console()
    args = _parse(
        [
            "--mcp-url",
            toy.url,
            "--token",
            TOKEN,
            "--endpoint",
            model.base_url,
            "--model",
            "m",
            "--json",
            "land alpha",
        ]
    )
    assert await cli.run_async(args, console=console) == cli.EXIT_OK
    events = [json.loads(line) for line in buf.getvalue().splitlines()]
    # --profile auto (the default): the choice and its reason first ("m" tells no size: full)
    assert events[0] == {
        "event": "profile",
        "profile": "full",
        "auto": True,
        "reason": "m: its size is not known (neither the endpoint nor its name tell)",
    }
    events = events[1:]
    assert [e["event"] for e in events] == [
        "turn_start",
        "roster",
        "model_reply",
        "tool_call",
        "tool_result",
        "roster",
        "model_reply",
        "final",
        "turn_end",
    ]
    assert events[1]["ids"] == ["alpha", "bravo"]
    assert events[3]["arguments"] == {"drone_id": "alpha"}
    assert events[4]["status"] == "ok" and events[4]["summary"] == "status=landed"
    assert events[-1]["prompt_tokens"] > 0 and events[-1]["tool_calls"] == 1


async def test_step_limit_exit_status(toy, scripted) -> None:
    model = scripted([call("get_position", drone_id="alpha")], repeat_last=True)
    console, _ = _console()
    args = _parse(
        [
            "--mcp-url",
            toy.url,
            "--token",
            TOKEN,
            "--endpoint",
            model.base_url,
            "--model",
            "m",
            "--max-steps",
            "2",
            "loop",
        ]
    )
    assert await cli.run_async(args, console=console) == cli.EXIT_STEP_LIMIT
    assert len(model.requests) == 2


async def test_interactive_keeps_the_conversation(toy, scripted) -> None:
    model = scripted([say("alpha is on the ground"), call("takeoff", drone_id="alpha", alt_m=5), say("up")])
    console, buf = _console()
    stdin = io.StringIO("where is alpha?\n\n/usage\nnow take it up 5 m\n/quit\nnever read\n")
    args = _parse(["--mcp-url", toy.url, "--token", TOKEN, "--endpoint", model.base_url, "--model", "m"])
    assert await cli.run_async(args, console=console, stdin=stdin) == cli.EXIT_OK
    assert len(model.requests) == 3
    history = [m.get("content") for m in model.requests[1]["messages"]]
    roster = "Fleet now: alpha on the ground, battery 90%; bravo on the ground, battery 90%.\n\n"
    assert history[-3:] == [
        roster + "where is alpha?",
        "alpha is on the ground",
        roster + "now take it up 5 m",
    ]
    assert "1 model calls" in buf.getvalue()
    assert toy.world.drones["alpha"].alt_m == 5.0


async def test_toolset_and_tool_selection(toy, scripted) -> None:
    model = scripted([say("ok")])
    console, _ = _console()
    args = _parse(
        [
            "--mcp-url",
            toy.url,
            "--token",
            TOKEN,
            "--endpoint",
            model.base_url,
            "--model",
            "m",
            "--toolsets",
            "flight",
            "--tools",
            "get_position",
            "hi",
        ]
    )
    assert await cli.run_async(args, console=console) == cli.EXIT_OK
    assert {t["function"]["name"] for t in model.requests[0]["tools"]} == {"takeoff", "land", "get_position"}


async def test_list_tools(toy) -> None:
    console, buf = _console()
    args = _parse(["--mcp-url", toy.url, "--token", TOKEN, "--list-tools", "--json"])
    assert await cli.run_async(args, console=console) == cli.EXIT_OK
    names = {json.loads(line)["name"] for line in buf.getvalue().splitlines()}
    assert names == {"takeoff", "move_north", "land", "get_position", "get_battery", "list_drones"}


@pytest.mark.parametrize(
    ("argv", "needle", "status"),
    [
        (["--toolsets", "warp"], "unknown toolset(s) ['warp']", cli.EXIT_USAGE),
        (["--tools", "warp"], "unknown tool(s) ['warp']", cli.EXIT_USAGE),
        (["--token", "nope"], "cannot open an MCP session", cli.EXIT_FAILED),
    ],
)
async def test_bad_input_is_a_clear_error(toy, argv, needle, status) -> None:
    console, buf = _console()
    base = ["--mcp-url", toy.url, "--endpoint", "http://127.0.0.1:9/v1", "--model", "m"]
    if "--token" not in argv:
        base += ["--token", TOKEN]
    assert await cli.run_async(_parse([*base, *argv, "hi"]), console=console) == status
    assert needle in buf.getvalue()


async def test_missing_model_is_a_usage_error(monkeypatch) -> None:
    monkeypatch.delenv("GATEWAY_AGENT_MODEL", raising=False)
    console, buf = _console()
    assert await cli.run_async(_parse(["hi"]), console=console) == cli.EXIT_USAGE
    assert "no model given" in buf.getvalue()


def test_max_steps_must_be_positive() -> None:
    with pytest.raises(SystemExit):
        _parse(["--max-steps", "0", "x"])


def test_console_entry_point_runs_the_agent(toy, scripted) -> None:
    """`fleet-gateway agent` as a separate process (the dispatcher lists the command module)."""
    import subprocess
    import sys

    model = scripted([call("land", drone_id="alpha"), say("alpha landed")])
    proc = subprocess.run(
        [sys.executable, "-m", "gateway.cli", "agent", "--mcp-url", toy.url, "--token", TOKEN,
         "--endpoint", model.base_url, "--model", "m", "--json", "land alpha"],
        capture_output=True, text=True, timeout=scaled(120),
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    events = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    assert events[-1]["event"] == "turn_end" and events[-1]["outcome"] == "answered"
    assert toy.world.calls == [("land", {"drone_id": "alpha"})]


async def test_legacy_mcp_mode(toy, scripted) -> None:
    model = scripted([call("get_position", drone_id="bravo"), say("bravo is home")])
    console, _ = _console()
    args = _parse(["--mcp-url", toy.url, "--token", TOKEN, "--mcp-mode", "legacy",
                   "--endpoint", model.base_url, "--model", "m", "where is bravo"])  # fmt: skip
    assert await cli.run_async(args, console=console) == cli.EXIT_OK
    assert "bravo: 0 m north" in model.requests[1]["messages"][-1]["content"]


async def test_small_profile_sends_its_tools_prompt_and_reply_cap(toy, scripted) -> None:
    from gateway.agent.planning import PLAN_SYSTEM_PROMPT
    from gateway.agent.profiles import SMALL_MODEL_SYSTEM_PROMPT

    # an answer before any call ran is sent back once with the small profile; the same answer again is taken
    # the small profile first asks for the request's steps, without tools (planning.py): none here
    model = scripted([say("no steps"), say("ok"), say("ok")])
    console, _ = _console()
    argv = ["--mcp-url", toy.url, "--token", TOKEN, "--endpoint", model.base_url, "--model", "m",
            "--profile", "small", "--max-tokens", "50", "hi"]  # fmt: skip
    assert await cli.run_async(_parse(argv), console=console) == cli.EXIT_OK
    assert (
        "tools" not in model.requests[0] and model.requests[0]["messages"][0]["content"] == PLAN_SYSTEM_PROMPT
    )
    request = model.requests[1]
    # The toy server offers three of the small profile's tools; move_north and list_drones are not in it.
    # The host adds its own answer_user, how a small model ends its turn.
    names = [t["function"]["name"] for t in request["tools"]]
    assert names == ["takeoff", "land", "get_position", "get_battery", "answer_user"]
    assert request["messages"][0]["content"] == SMALL_MODEL_SYSTEM_PROMPT
    assert request["max_tokens"] == 50


async def test_another_mcp_server_adds_its_tools_beside_the_gateways(toy, scripted) -> None:
    """A places server over stdio (a command): its find_place is offered and called there; its takeoff,
    a name the gateway already uses, is left out, so the gateway's takeoff still reaches the gateway."""
    import sys

    model = scripted(
        [
            call("find_place", place="the water tower"),
            call("takeoff", drone_id="bravo", alt_m=10),
            say("bravo is up; the water tower is at 47.3981, 8.5456"),
        ]
    )
    console, buf = _console()
    server = f"{sys.executable} -m tests.agent.places_mcp"
    base = ["--mcp-url", toy.url, "--token", TOKEN, "--endpoint", model.base_url, "--model", "m"]
    args = _parse([*base, "--server", server, "--json", "take bravo up and find the water tower"])
    assert await cli.run_async(args, console=console) == cli.EXIT_OK
    events = [json.loads(line) for line in buf.getvalue().splitlines()]
    results = {e["name"]: e for e in events if e["event"] == "tool_result"}
    assert results["find_place"]["status"] == "ok" and "47.3981" in results["find_place"]["text"], results
    assert toy.world.calls == [("takeoff", {"drone_id": "bravo", "alt_m": 10})]  # the gateway's own takeoff
    offered = {t["function"]["name"] for t in model.requests[0]["tools"]}
    assert {"find_place", "takeoff", "land", "move_north"} <= offered, offered
    assert next(e for e in events if e["event"] == "servers")["left_out"] == ["takeoff"]
