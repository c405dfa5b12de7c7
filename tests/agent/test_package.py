"""The agent host is its own package: it reaches the gateway over MCP only, and stays small."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "fleet_agent"
MAX_LINES = 2500
MAX_DATA_LINES = 200
MAX_POOL_EXAMPLES = 300


def _modules() -> list[Path]:
    return sorted(PACKAGE.glob("*.py"))


def test_it_imports_nothing_of_the_gateway() -> None:
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else []
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            assert not [n for n in names if n == "gateway" or n.startswith("gateway.")], (path.name, names)


def test_it_stays_within_its_size_and_reads_no_words_with_rules() -> None:
    """At most 2,500 lines of Python, beside at most 200 of data (the words the lexicon reads, the system
    prompt and the worked examples, one a line) and a pool of at most 300 examples shown by nearness."""
    lines = sum(len(p.read_text().splitlines()) for p in _modules())
    assert lines <= MAX_LINES, lines
    data = [PACKAGE / name for name in ("words.toml", "system_prompt.txt", "examples.jsonl")]
    assert sum(len(p.read_text().splitlines()) for p in data) <= MAX_DATA_LINES
    assert len((PACKAGE / "pool.jsonl").read_text().splitlines()) <= MAX_POOL_EXAMPLES
    regex_calls = 0
    for path in _modules():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "re":
                regex_calls += 1
    assert regex_calls == 0  # no module reads the request's words: the model writes the plan


def test_the_gateway_command_loads_it_lazily() -> None:
    """``fleet-gateway agent`` works, and the gateway's own import never pulls the agent in."""
    code = "import sys, gateway.cli; assert 'fleet_agent' not in sys.modules; print('ok')"
    assert (
        subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
        == "ok\n"
    )
    out = subprocess.run(
        [sys.executable, "-m", "gateway.cli", "agent", "--help"], capture_output=True, text=True, check=False
    )
    if out.returncode != 0 and "No module named" in out.stderr:
        pytest.skip(f"gateway.cli cannot run as a module here: {out.stderr.strip()[:200]}")
    assert out.returncode == 0, out.stderr
    assert "--decoding" in out.stdout


async def test_the_command_runs_one_turn(toy, scripted, monkeypatch) -> None:
    import argparse
    import io
    import json

    from bench.agent_harness.scripted import say
    from fleet_agent.cli import add_agent_arguments, run_async
    from tests.agent.toy_mcp import TOKEN

    plan = {"steps": [{"action": "takeoff", "drone": "bravo", "altitude": {"value": 7, "unit": "m"}}]}
    server = scripted([say(json.dumps(plan))])
    parser = argparse.ArgumentParser()
    add_agent_arguments(parser)
    args = parser.parse_args(["--mcp-url", toy.url, "--token", TOKEN, "--endpoint", server.base_url,
                              "--model", "scripted", "bravo up to 7 m"])  # fmt: skip
    out = io.StringIO()
    assert await run_async(args, out=out) == 0
    assert toy.world.calls == [("takeoff", {"drone_id": "bravo", "alt_m": 7.0})]
    assert "bravo: takeoff(alt_m=7) done." in out.getvalue()
    monkeypatch.delenv("GATEWAY_AGENT_MODEL", raising=False)
    no_model = parser.parse_args(["--mcp-url", toy.url, "x"])
    assert await run_async(no_model, out=out) == 2


def test_the_image_ships_the_agent_with_its_extra() -> None:
    """deploy/Dockerfile copies the package, installs the [agent] extra and checks the command starts."""
    text = (PACKAGE.parent / "deploy" / "Dockerfile").read_text()
    assert "COPY fleet_agent ./fleet_agent" in text and "pip install .[agent]" in text
    assert "fleet-gateway agent --help" in text
