"""The mission benchmark's options, failure classes and report (its end-to-end run is the harness
self-check itself)."""

from __future__ import annotations

import importlib.util
import json
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

from fleet_agent.records import ToolCallRecord, TurnResult

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


def _run(bench: ModuleType, mission: str, ok: bool, prompt: int | None = 100, run: int = 1) -> object:
    return bench.MissionRun(mission=mission, ok=ok, detail="a | b", tool_calls=3, tool_errors=1 - ok,
                            parsed_from_text=1, prompt_tokens=prompt, completion_tokens=None if prompt is None
                            else 10, steps=4, outcome="answered", wall_s=2.5 + run, run=run,
                            failure=None if ok else "empty_answer")  # fmt: skip


def test_without_a_model_it_is_the_self_check_and_refuses_to_write(bench, monkeypatch) -> None:
    monkeypatch.delenv("GATEWAY_AGENT_MODEL", raising=False)
    assert bench.parse_args([]).self_check
    with pytest.raises(SystemExit):
        bench.parse_args(["--write"])
    with pytest.raises(SystemExit):
        bench.parse_args(["--model", "m", "--self-check", "--write"])
    args = bench.parse_args(["--model", "qwen2.5:7b", "--write"])
    assert not args.self_check and args.write and args.runs == 3 and args.model_timeout == 600
    assert not bench.parse_args(["--serve-local", "1.5b"]).self_check
    with pytest.raises(SystemExit):
        bench.parse_args(["--model", "m", "--runs", "0"])


def test_runs_are_counted_per_run_and_written_per_model(bench, tmp_path, monkeypatch) -> None:
    runs = [
        _run(bench, "takeoff-land", True, run=1),
        _run(bench, "takeoff-land", False, run=2),
        _run(bench, "refuse-500m", False, prompt=None),
    ]
    t = bench.totals(runs)
    assert (t["passed"], t["runs"], t["missions"], t["tool_calls"]) == (1, 3, 2, 9)
    assert t["failures"] == {"empty_answer": 2} and t["median_wall_s"] == 3.5
    args = bench.parse_args(["--model", "qwen", "--decoding", "ollama"])
    args.tool_list, args.load_start, args.load_end = "plan decoding ollama", 3.2, 4.1
    section = bench.markdown_section(runs, args)
    assert (
        "typed plan host; plan decoding ollama" in section
        and "load average (1 min) 3.2 at the start, 4.1 at the end" in section
    )
    assert "Passed **1/3 runs (33 %)**" in section
    assert "| takeoff-land | 1/2 | 4.0 | 3.0 | 1 | 2 | 100 | 10 | empty_answer |" in section
    assert "| refuse-500m | 0/1 | 3.5 | 3.0 | 1 | 1 | n/a | n/a | empty_answer |" in section
    docs = tmp_path / "benchmarks.md"
    common = sys.modules["bench.common"]
    monkeypatch.setattr(common, "DOCS", docs)
    monkeypatch.setattr(common, "ROOT", tmp_path)
    bench.write_docs(section, args)
    bench.write_docs(section.replace("1/2", "2/2"), args)  # the same model: replaced
    args.model = "llama"
    bench.write_docs(section, args)
    text = docs.read_text()
    assert text.count("## NL missions: qwen, typed plan") == 1 and "| 2/2 |" in text
    assert text.count("## NL missions: llama, typed plan") == 1


def _turn(outcome: str, final: str | None, *calls: tuple[str, str, dict]) -> TurnResult:
    records = [ToolCallRecord(id=str(i), name=n, arguments=a, status=s)
               for i, (n, s, a) in enumerate(calls)]  # fmt: skip
    return TurnResult(outcome=outcome, final_text=final, steps=len(calls) + 1, tool_calls=records)


def test_failures_are_classified(bench) -> None:
    from bench.agent_harness.missions import all_missions

    m = {x.id: x for x in all_missions()}
    hop = m["takeoff-land"]
    plan = [("takeoff", {}), ("land", {})]
    a = {"drone_id": "alpha"}

    def classes(turn: TurnResult, results: list[dict] | None = None, ok: bool = False, mission=hop) -> list:
        return bench.classify(turn, results or [], mission, plan, ok)

    assert classes(_turn("empty_answer", None, ("takeoff", "ok", a))) == ["empty_answer", "wrong_outcome"]
    assert classes(_turn("answered", "  ", ("takeoff", "ok", a)), ok=True) == ["empty_answer"]
    assert classes(_turn("invalid_plan", "No plan")) == ["invalid_plan", "wrong_outcome"]
    assert classes(_turn("answered", "ok", ("go_to_location", "ok", a)))[0] == "wrong_tool"
    assert classes(_turn("answered", "ok", ("takeoff", "ok", a), ("move_to_relative", "skipped", a),
                         ("land", "ok", a)), ok=True) == ["wrong_argument"]  # fmt: skip
    assert classes(_turn("answered", "ok", ("takeoff", "error", a)))[0] == "gateway_refusal"
    # In a mission that asks for something unsafe, the refusal is the expected outcome.
    assert (
        classes(_turn("answered", "refused", ("takeoff", "error", a)), ok=True, mission=m["refuse-500m"])
        == []
    )
    read_first = _turn("answered", "ok", ("fleet_status", "ok", {}), ("takeoff", "ok", a), ("land", "ok", a))
    assert classes(read_first, ok=True) == []
    landed_elsewhere = _turn("answered", "ok", ("takeoff", "ok", a), ("land", "ok", a))
    assert classes(landed_elsewhere) == ["wrong_argument"]


def test_unknown_mission_is_a_clear_error(bench) -> None:
    from rich.console import Console

    args = bench.parse_args(["--missions", "fly-to-the-moon"])
    with pytest.raises(SystemExit, match=r"unknown mission\(s\) \['fly-to-the-moon'\]"):
        import asyncio

        asyncio.run(bench.run_missions(args, Console(quiet=True)))


def test_serve_local_without_the_script_says_so(bench, monkeypatch, tmp_path) -> None:
    from rich.console import Console

    monkeypatch.setattr(bench, "LOCAL_MODEL_SCRIPT", tmp_path / "serve-local-model")
    with pytest.raises(SystemExit, match="serve-local-model is not there; give an endpoint instead"):
        bench.main(["--serve-local", "1.5b", "--runs", "1"])
    del Console


def test_a_failed_stack_is_started_again_and_no_finished_run_is_lost(bench, tmp_path, monkeypatch) -> None:
    """A read error of the bench's MCP link ended a bench and lost its runs: now a new stack goes on from
    the run not yet done, and the JSON is written after every run."""
    args = bench.parse_args(["--model", "m", "--runs", "2", "--json", str(tmp_path / "r.json")])
    args.load_start = 1.0
    failures = iter([RuntimeError("read error"), None])

    async def runs_then_fails(a, console):
        done = {(r.run, r.mission) for r in a.completed}
        for n in (1, 2):
            if (n, "takeoff-land") in done:
                continue
            a.completed.append(_run(bench, "takeoff-land", True, run=n))
            bench.write_json(a, a.completed, interrupted=True)
            failure = next(failures)
            if failure is not None:
                raise failure
        return a.completed

    monkeypatch.setattr(bench, "run_missions", runs_then_fails)
    runs, interrupted = bench.run_with_restarts(args, bench.Console())
    assert not interrupted and [r.run for r in runs] == [1, 2]
    assert args.restarts == ["RuntimeError: read error"]
    saved = json.loads((tmp_path / "r.json").read_text())
    assert [r["run"] for r in saved["runs"]] == [1, 2]

    def always_fails(a, console):
        raise RuntimeError("down")

    monkeypatch.setattr(bench, "run_missions", always_fails)
    runs, interrupted = bench.run_with_restarts(args, bench.Console())
    assert interrupted and len(runs) == 2 and len(args.restarts) == 1 + bench.MAX_RESTARTS + 1


def test_a_resumed_bench_keeps_the_recorded_runs_and_refuses_another_setup(bench, tmp_path) -> None:
    """--resume: the runs an interrupted bench wrote count, once, when the file is of the same model, half
    and vehicles; a file of another model says so and nothing runs."""
    first = bench.parse_args(["--model", "m", "--half", "test", "--json", str(tmp_path / "r.json")])
    first.load_start = 1.0
    recorded = [_run(bench, "takeoff-land", True, run=1), _run(bench, "refuse-500m", False, run=1)]
    bench.write_json(first, recorded, interrupted=True)

    again = bench.parse_args(["--model", "m", "--half", "test", "--resume", str(tmp_path / "r.json")])
    resumed = bench.resumed_runs(Path(again.resume), again)
    assert [(r.mission, r.run, r.ok) for r in resumed] == [
        ("takeoff-land", 1, True),
        ("refuse-500m", 1, False),
    ]
    other = bench.parse_args(["--model", "n", "--half", "test", "--resume", str(tmp_path / "r.json")])
    with pytest.raises(ValueError, match="its model is 'm', this bench's is 'n'"):
        bench.resumed_runs(Path(other.resume), other)
    other_half = bench.parse_args(["--model", "m", "--half", "dev", "--resume", str(tmp_path / "r.json")])
    with pytest.raises(ValueError, match="its half is 'test', this bench's is 'dev'"):
        bench.resumed_runs(Path(other_half.resume), other_half)
    assert bench.main(["--model", "n", "--half", "test", "--resume", str(tmp_path / "r.json")]) == 2
