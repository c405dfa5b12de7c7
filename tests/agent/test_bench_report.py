"""The mission benchmark's options and report (its end-to-end run is the harness self-check itself)."""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

BENCH = Path(__file__).resolve().parents[2] / "bench" / "nl_missions.py"


@pytest.fixture(scope="module")
def bench() -> Iterator[ModuleType]:
    """The script loaded as a module (dataclasses need it registered in sys.modules while loading)."""
    spec = importlib.util.spec_from_file_location("nl_missions", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["nl_missions"] = module
    try:
        spec.loader.exec_module(module)
        yield module
    finally:
        sys.modules.pop("nl_missions", None)


def _run(bench: ModuleType, mission: str, ok: bool, prompt: int | None = 100) -> object:
    return bench.MissionRun(mission=mission, ok=ok, detail="a | b", tool_calls=3, tool_errors=1 - ok,
                            parsed_from_text=1, prompt_tokens=prompt, completion_tokens=None if prompt is None
                            else 10, steps=4, outcome="answered", wall_s=2.5)  # fmt: skip


def test_without_a_model_it_is_the_self_check_and_refuses_to_write(bench, monkeypatch) -> None:
    monkeypatch.delenv("GATEWAY_AGENT_MODEL", raising=False)
    assert bench.parse_args([]).self_check
    with pytest.raises(SystemExit):
        bench.parse_args(["--write"])
    with pytest.raises(SystemExit):
        bench.parse_args(["--model", "m", "--self-check", "--write"])
    args = bench.parse_args(["--model", "qwen2.5:7b", "--write"])
    assert not args.self_check and args.write


def test_totals_and_markdown(bench, tmp_path, monkeypatch) -> None:
    runs = [_run(bench, "takeoff-land", True), _run(bench, "refuse-500m", False, prompt=None)]
    t = bench.totals(runs)
    assert (t["passed"], t["missions"], t["tool_calls"], t["tool_errors"]) == (1, 2, 6, 1)
    assert (t["prompt_tokens"], t["completion_tokens"]) == (100, 10)
    args = bench.parse_args(["--model", "qwen2.5:7b", "--toolsets", "flight,navigation"])
    args.tool_list = "17 of 46 tools, 1451 tokens (cl100k_base)"
    section = bench.markdown_section(runs, args)
    assert section.startswith("## NL missions: qwen2.5:7b\n")
    assert "toolsets: flight,navigation" in section and "Passed **1/2**" in section
    assert "| takeoff-land | yes | 3 | 0 | 1 | 100 | 10 | 2.5 | a / b |" in section
    assert "| refuse-500m | no | 3 | 1 | 1 | n/a | n/a | 2.5 | a / b |" in section
    docs = tmp_path / "docs" / "benchmarks.md"
    monkeypatch.setattr(bench, "DOCS", docs)
    bench.write_docs(section)
    bench.write_docs(section.replace("qwen2.5:7b", "llama3.1:8b"))
    text = docs.read_text()
    assert text.startswith("# Benchmarks\n") and text.count("## NL missions:") == 2


def test_unknown_mission_is_a_clear_error(bench) -> None:
    from rich.console import Console

    args = bench.parse_args(["--missions", "fly-to-the-moon"])
    with pytest.raises(SystemExit, match=r"unknown mission\(s\) \['fly-to-the-moon'\]"):
        import asyncio

        asyncio.run(bench.run_missions(args, Console(quiet=True)))
