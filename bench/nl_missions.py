"""Natural-language mission benchmark: how well does a chat model fly the fleet through the gateway?

Runs a fixed set of missions worded as a person would say them against simulated drones, judges each by
the drones' true final state (and track), and prints per mission and in total: success, tool calls,
tokens in / out, wall time. Any OpenAI-compatible endpoint works (Ollama, LM Studio, vLLM, llama.cpp,
hosted providers).

  python bench/nl_missions.py --endpoint http://127.0.0.1:11434/v1 --model qwen2.5:7b [--write]
  python bench/nl_missions.py --endpoint http://127.0.0.1:11434/v1 --model qwen2.5:7b --decoding ollama
  python bench/nl_missions.py --serve-local 1.5b --runs 3 --write   # make bench-nl
  python bench/nl_missions.py --self-check          # no model: checks the harness itself
  python bench/nl_missions.py --half test --serve-local 1.5b --runs 3   # the corpus's test half, per class
  python bench/nl_missions.py --half dev --sitl      # the dev half on three ArduCopter SITL drones
  python bench/nl_missions.py --half test --endpoint URL --model M --resume out.json --json out.json
                                                     # go on from an interrupted bench's runs

--half dev|test|all runs the generalisation corpus (bench/nl_corpus.py: requests in twelve classes, a fixed
development/test split; its docstring says how many in each half) instead of the 12 missions, and reports
per half and per class (--classes a,b keeps those classes). --sitl flies on
three real ArduCopter SITL instances (``eval "$(/work/shared/sitl/install)"``) instead of the simulator;
the truth is then the gateway's telemetry, and requests that set a battery level are left out (SITL's
battery cannot be set by the harness).

Each mission runs --runs times (default 3); success is counted per run. A run passes only when the model
answered in words (an empty answer never passes) and the check of the drones' true state passes. A
failed run is classified: empty answer, step limit, model error, invented id, wrong tool, wrong
argument, repeat, gateway refusal, wrong outcome. --serve-local starts llm/serve-local-model of the shared
folder (--shared-dir, else $FLEET_SHARED_DIR, else ../shared beside the checkout; a measuring instrument
outside the project) and stops it afterwards.

Without --model (and no GATEWAY_AGENT_MODEL) it runs the HARNESS SELF-CHECK: a scripted endpoint replays
the ideal call sequence of each mission. That verifies the sim, gateway, MCP, host loop and checks end to
end; its figures are not a model's and are never written to docs/benchmarks.md.

--replay FILE serves back the model replies a --json results file recorded (each run keeps them in
``replies``), run by run, through the current host: a change of the host's checks or compiler judged on
what the model wrote, without the model (not a change of the prompt or schema it never saw).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import os
import signal
import statistics
import subprocess
import sys
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

from rich.console import Console
from rich.table import Table

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # the repository root: bench.agent_harness

from bench.agent_harness.missions import (
    Evidence,
    Mission,
    MissionContext,
    _all,
    all_missions,
    never_armed,
)
from bench.agent_harness.pilot import SELF_CHECK_MODEL, ScriptedPilot
from bench.agent_harness.replay import DIVERGED, ReplayPilot
from bench.agent_harness.scripted import ScriptedModelServer
from bench.agent_harness.stack import GatewayTruth, LocalStack, Sampler, SimTruth, reset_drones
from bench.agent_harness.tokens import cl100k_tokens, model_tokens
from bench.common import machine, write_section
from fleet_agent.decoding import DECODINGS
from fleet_agent.host import AgentHost
from fleet_agent.mcp_link import McpLink
from fleet_agent.prompt import system_prompt
from fleet_agent.records import AgentEvent, ModelConfig, TurnResult
from fleet_agent.settings import AgentSettings

VERBOSE_EVENTS = frozenset(
    {
        "model_reply",
        "tool_call",
        "tool_result",
        "final",
        "empty_reply",
        "empty_answer",
        "step_limit",
        "model_error",
    }
)
ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs" / "benchmarks.md"
DEFAULT_SHARED_DIR = ROOT.parent / "shared"
LOCAL_MODEL_SCRIPT = (
    DEFAULT_SHARED_DIR / "llm" / "serve-local-model"
)  # --shared-dir / FLEET_SHARED_DIR override
# Failure classes, most telling first: a run is labelled with the first one its transcript shows.
FAILURE_CLASSES = (
    "invalid_plan",
    "empty_answer",
    "step_limit",
    "model_error",
    "invented_id",
    "wrong_tool",
    "wrong_argument",
    "repeat",
    "gateway_refusal",
    "wrong_outcome",
)
READ_OR_WAIT = frozenset(
    {"fleet_status", "list_drones", "get_position", "get_battery", "monitor_flight", "monitor_fleet",
     "check_arrival", "get_telemetry", "get_in_air", "get_armed", "get_home_position"}
)  # fmt: skip


@dataclass
class MissionRun:
    mission: str
    ok: bool
    detail: str
    tool_calls: int
    tool_errors: int
    parsed_from_text: int
    prompt_tokens: int | None
    completion_tokens: int | None
    steps: int
    outcome: str
    wall_s: float
    calls: list[str] = field(default_factory=list)
    run: int = 1
    failure: str | None = None  # the first failure class (None when it passed)
    cls: str | None = None  # the corpus class (None for the 12 missions)
    half: str | None = None  # the corpus half: dev or test
    signals: list[str] = field(default_factory=list)  # every failure class the transcript shows
    replies: list[str] = field(default_factory=list)  # the model's replies, in order (for --replay)


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    env = AgentSettings()
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--endpoint", default=env.endpoint, help="OpenAI-compatible base URL")
    p.add_argument("--model", default=env.model, help="model name; omit for the harness self-check")
    p.add_argument("--self-check", action="store_true", help="scripted ideal pilot instead of a model")
    p.add_argument(
        "--replay",
        default=None,
        metavar="JSON",
        help="serve the model replies a --json results file recorded, run by run, through the current "
        "host (no model; judges host changes, not prompt or schema changes)",
    )
    p.add_argument(
        "--resume",
        default=None,
        metavar="JSON",
        help="go on from the runs a --json file of an interrupted bench recorded (the same model, half and "
        "vehicles): they count as they are, only the runs it lacks are flown",
    )
    p.add_argument("--gateway-url", default=None, help="use this gateway's /mcp instead of starting one")
    p.add_argument("--token", default=env.token, help="bearer token for --gateway-url")
    p.add_argument(
        "--sim-control-url",
        default=None,
        help="with --gateway-url: the sim's control API for true state (else gateway telemetry); "
        "drone alpha is sim vehicle 0, bravo vehicle 1",
    )
    p.add_argument(
        "--decoding",
        default=env.decoding,
        choices=DECODINGS,
        help="how the endpoint decodes the plan under its schema (default json_schema: llama.cpp, OpenAI)",
    )
    p.add_argument(
        "--nearest",
        type=int,
        choices=range(9),
        default=env.nearest,
        metavar="0-8",
        help="pool examples nearest each request shown to the model (fleet_agent.prompt.nearest)",
    )
    p.add_argument(
        "--missions", default=None, help="comma-separated mission ids, also of a corpus half (default: all)"
    )
    p.add_argument(
        "--half",
        choices=["dev", "test", "all"],
        default=None,
        help="run the generalisation corpus (bench/nl_corpus.py): its dev half, test half, or all",
    )
    p.add_argument(
        "--classes",
        default=None,
        help="with --half: comma-separated corpus classes to run (default: all)",
    )
    p.add_argument(
        "--sitl",
        action="store_true",
        help="fly three real ArduCopter SITL drones (alpha, bravo, charlie) instead of the simulator",
    )
    p.add_argument(
        "--shared-dir",
        default=os.environ.get("FLEET_SHARED_DIR"),
        help="the shared folder holding llm/serve-local-model (default: $FLEET_SHARED_DIR, else "
        "../shared beside the checkout)",
    )
    p.add_argument(
        "--runs", type=int, default=None, help="runs of each mission (default 3; the self-check: 1)"
    )
    p.add_argument(
        "--model-timeout",
        type=float,
        default=600.0,
        help="seconds to wait for one model reply (default 600: a CPU-only model on a busy machine is slow)",
    )
    p.add_argument(
        "--serve-local",
        choices=["1.5b", "0.5b"],
        default=None,
        help=f"start {LOCAL_MODEL_SCRIPT} with this model for the run and stop it afterwards",
    )
    p.add_argument("--max-tokens", type=int, default=512, help="longest plan in tokens (default 512)")
    p.add_argument("--threads", type=int, default=2, help="threads of the --serve-local model (default 2)")
    p.add_argument("--speedup", type=float, default=5.0, help="simulator speed-up of the own sim (default 5)")
    p.add_argument("--write", action="store_true", help="add the results table to docs/benchmarks.md")
    p.add_argument(
        "--json", dest="json_out", default=None, help="also write per-mission results as JSON here"
    )
    p.add_argument("--verbose", action="store_true", help="print every tool call while missions run")
    p.add_argument(
        "--events",
        dest="events_out",
        default=None,
        help="append every host event of every run (model replies, calls, results) as JSON lines here",
    )
    args = p.parse_args(argv)
    args.replayed = None
    if args.replay:
        if args.model or args.serve_local or args.self_check:
            p.error("--replay serves recorded replies: leave out --model, --serve-local and --self-check")
        if args.write:
            p.error("--write is refused for a replay: the host changed since the model wrote the replies")
        args.replayed = ReplayPilot.from_json(args.replay)
        args.model = f"{args.replayed.model} (replayed from {args.replay})"
        args.runs = max(run for run, _ in args.replayed.runs())
    if not args.model and not args.serve_local:
        args.self_check = True
    if args.self_check and args.write:
        p.error("--write is refused for the harness self-check: its figures are not a model result")
    if args.runs is None:
        args.runs = 1 if args.self_check else 3
    if args.runs < 1:
        p.error("--runs must be at least 1")
    args.completed = []  # the runs finished so far (run_missions appends; kept when interrupted)
    if args.sitl and args.gateway_url:
        p.error("--sitl starts its own gateway; leave out --gateway-url")
    return args


def resumed_runs(path: Path, args: argparse.Namespace) -> list[MissionRun]:
    """The runs a --json file recorded, when it is of this bench's model, half and vehicles (ValueError
    naming what differs otherwise: runs of another setup would not add up to one measurement)."""
    data = json.loads(path.read_text())
    vehicles = "ArduCopter SITL" if args.sitl else "simulator"
    wanted = {"model": args.model, "half": args.half, "vehicles": vehicles, "self_check": args.self_check}
    for key, value in wanted.items():
        if data.get(key) != value:
            raise ValueError(f"--resume {path}: its {key} is {data.get(key)!r}, this bench's is {value!r}")
    return [MissionRun(**run) for run in data["runs"]]


def local_model_script(args: argparse.Namespace) -> Path:
    """Where serve-local-model is: --shared-dir / $FLEET_SHARED_DIR, else ../shared beside the checkout."""
    if getattr(args, "shared_dir", None):
        return Path(args.shared_dir) / "llm" / "serve-local-model"
    return LOCAL_MODEL_SCRIPT


T = TypeVar("T")


def _named(items: list[T], names: str | None, id_of: Callable[[T], str]) -> tuple[list[T], list[str]]:
    """The items a comma-separated ``names`` lists (all of them without it), and the names matching none."""
    if not names:
        return items, []
    wanted = {n.strip() for n in names.split(",") if n.strip()}
    return [i for i in items if id_of(i) in wanted], sorted(wanted - {id_of(i) for i in items})


def chosen_missions(args: argparse.Namespace) -> tuple[list[Mission], dict[str, tuple[str, str]]]:
    """The missions to run, and for corpus entries their (class, half) by mission id."""
    if args.half is None:
        missions, unknown = _named(all_missions(), args.missions, lambda m: m.id)
        if unknown:
            raise SystemExit(f"unknown mission(s) {unknown}; known: {[m.id for m in all_missions()]}")
        return missions, {}
    from bench.nl_corpus import select

    entries = select(args.half)
    if getattr(args, "classes", None):
        wanted = {c.strip() for c in args.classes.split(",") if c.strip()}
        entries = [e for e in entries if e.cls in wanted]
        if not entries:
            raise SystemExit(f"--classes {args.classes!r} selects no request of the {args.half} half")
    entries, unknown = _named(entries, args.missions, lambda e: e.id)
    if unknown:
        raise SystemExit(f"--missions {','.join(unknown)!r} names no request of the {args.half} half")
    if args.sitl:  # SITL's battery cannot be set by the harness: requests that need a level are left out
        entries = [e for e in entries if not e.mission.battery_pct]
    return [e.mission for e in entries], {e.id: (e.cls, e.half) for e in entries}


async def run_missions(args: argparse.Namespace, console: Console) -> list[MissionRun]:
    missions, where = chosen_missions(args)
    drone_ids = sorted({d for m in missions for d in m.drones} | {"alpha", "bravo"})

    async with contextlib.AsyncExitStack() as stack:
        if args.gateway_url:
            mcp_url, token, truth_from_sim = args.gateway_url, args.token, args.sim_control_url
            local = None
        elif args.sitl:
            from bench.nl_sitl import SitlStack

            console.print(
                f"[dim]starting {len(drone_ids)} ArduCopter SITL drones (speed-up {args.speedup:g}) and a "
                "gateway...[/]"
            )
            sitl = await stack.enter_async_context(SitlStack(drone_ids, speedup=args.speedup))
            mcp_url, token, truth_from_sim = sitl.mcp_url, sitl.token, None
            local = None
        else:
            console.print(
                f"[dim]starting {len(drone_ids)} simulated drones (speed-up {args.speedup:g}) and a "
                "gateway...[/]"
            )
            local = await stack.enter_async_context(LocalStack(drone_ids, speedup=args.speedup))
            mcp_url, token, truth_from_sim = local.mcp_url, local.token, local.sim_control_url
        link = await stack.enter_async_context(McpLink(mcp_url, token))
        all_tools = await link.list_tools()
        tools = all_tools
        if local is not None:
            truth: Any = local.truth()
        elif truth_from_sim:
            truth = SimTruth(truth_from_sim, {d: i for i, d in enumerate(drone_ids)})
            stack.push_async_callback(truth.aclose)
        else:
            truth = GatewayTruth(link)
        args.system_prompt = system_prompt()
        asks_a_model = not (args.self_check or args.replayed)
        own = await model_tokens(args.endpoint, args.system_prompt) if asks_a_model else None
        cl100k = cl100k_tokens(args.system_prompt)
        args.tool_list = (
            f"plan decoding {args.decoding}; system prompt (template included) "
            f"{'n/a' if own is None else own} tokens in the model's own tokenizer, "
            f"{'n/a' if cl100k is None else cl100k} in cl100k"
        )
        console.print(f"[dim]tool list: {args.tool_list}; truth from {truth.source}[/]")

        pilot: ScriptedPilot | None = None
        replayed: ReplayPilot | None = args.replayed
        if args.self_check:
            pilot = ScriptedPilot()
            scripted = stack.enter_context(ScriptedModelServer([pilot], repeat_last=True))
            model = ModelConfig(scripted.base_url, SELF_CHECK_MODEL, max_retries=0, decoding="none")
        elif replayed is not None:
            scripted = stack.enter_context(ScriptedModelServer([replayed], repeat_last=True))
            model = ModelConfig(scripted.base_url, args.model, max_retries=0, decoding="none")
        else:
            model = ModelConfig(
                args.endpoint,
                args.model,
                api_key=AgentSettings().resolved_api_key(),
                timeout_s=args.model_timeout,
                max_retries=0,
                max_tokens=args.max_tokens,
                decoding=args.decoding,
                nearest=args.nearest,
            )

        runs: list[MissionRun] = args.completed  # kept by main: an interrupted bench reports what finished
        done = {(r.run, r.mission) for r in runs}  # a bench restarted after a crash goes on from there
        for n in range(1, args.runs + 1):
            for mission in missions:
                if (n, mission.id) in done:
                    continue
                if replayed is not None:
                    if (mission.id, n) not in replayed.recorded:
                        continue
                    replayed.load(mission.id, n)
                await reset_drones(
                    link, truth, drone_ids, battery_pct=mission.battery_pct, speedup=args.speedup
                )
                run = await run_one(mission, link, tools, truth, model, pilot, args, console, drone_ids)
                run.run = n
                if replayed is not None and replayed.diverged:
                    run.ok, run.detail = False, f"{DIVERGED}; {run.detail}"
                run.cls, run.half = where.get(mission.id, (None, None))
                runs.append(run)
                if args.json_out:  # written after every run: a crash or a kill loses none of them
                    write_json(args, runs, interrupted=True)
        return runs


async def run_one(
    mission: Mission,
    link: McpLink,
    tools: list[Any],
    truth: Any,
    model: ModelConfig,
    pilot: ScriptedPilot | None,
    args: argparse.Namespace,
    console: Console,
    fleet: list[str] | None = None,
) -> MissionRun:
    """One mission, judged from the drones' true state: its own check, and every drone of the fleet it
    does not name never armed (a drone flown unasked fails the run)."""
    homes = await truth.homes(list(mission.drones))
    watched = sorted(set(fleet or ()) | set(mission.drones))
    offered = {t.name: frozenset((t.input_schema or {}).get("properties", {})) for t in tools}
    ctx = MissionContext(homes=homes, tools=offered)
    prompt = mission.prompt(ctx)
    if pilot is not None:
        pilot.load(mission.plan(ctx), mission.answer)
    results: list[dict[str, Any]] = []
    replies: list[str] = []

    def on_event(e: AgentEvent) -> None:
        if e.kind == "tool_result":
            results.append(e.data)
        if e.kind == "model_reply":
            replies.append(str(e.data.get("content") or ""))
        if args.events_out:
            with open(args.events_out, "a", encoding="utf-8") as out:
                out.write(json.dumps({"mission": mission.id, **e.to_json()}, default=str) + "\n")
        if args.verbose and e.kind in VERBOSE_EVENTS:
            console.print(f"[dim]  {mission.id} {e.kind}: {json.dumps(e.data, default=str)[:200]}[/]")

    host = AgentHost(model, link, tools, on_event=on_event)
    console.print(f"[bold]{mission.id}[/] {prompt} [dim](load {os.getloadavg()[0]:.1f})[/]")
    sampler = Sampler(truth, watched)
    async with sampler:
        started = time.monotonic()
        turn = await host.run_turn(prompt)
        wall = time.monotonic() - started
    final = await truth.snapshot(watched)
    evidence = Evidence(final=final, track=sampler.tracks, tool_results=results, final_text=turn.final_text)
    unasked = [never_armed(evidence, d) for d in watched if d not in mission.drones]
    verdict = _all(mission.check(ctx, evidence), *(c for c in unasked if not c.ok))
    answered = turn.outcome == "answered" and bool((turn.final_text or "").strip())
    signals = classify(turn, results, mission, mission.plan(ctx), verdict.ok)
    run = MissionRun(
        mission=mission.id,
        ok=verdict.ok and answered,
        detail=verdict.detail,
        tool_calls=len(turn.tool_calls),
        tool_errors=sum(c.status != "ok" for c in turn.tool_calls),
        parsed_from_text=turn.parsed_from_text,
        prompt_tokens=turn.usage.prompt_tokens,
        completion_tokens=turn.usage.completion_tokens,
        steps=turn.steps,
        outcome=turn.outcome,
        wall_s=wall,
        calls=[_call_text(c) for c in turn.tool_calls],
        signals=signals,
        replies=replies,
    )
    if not run.ok:
        run.failure = signals[0] if signals else "wrong_outcome"
    if turn.outcome != "answered":
        run.detail = f"{turn.outcome}: {run.detail}"
    mark = "[green]PASS[/]" if run.ok else f"[red]FAIL {run.failure}[/]"
    console.print(f"  {mark} {run.detail} [dim]({run.tool_calls} calls, {wall:.1f} s)[/]")
    if not run.ok:
        console.print(f"  [dim]calls: {'; '.join(run.calls)[:600]}[/]")
    return run


def _call_text(c: Any) -> str:
    args = ",".join(f"{k}={v}" for k, v in (c.arguments or {}).items())
    return f"{c.name}({args})={c.status}"


def classify(
    turn: TurnResult,
    results: list[dict[str, Any]],
    mission: Mission,
    plan: list[tuple[str, dict[str, Any]]],
    check_ok: bool,
) -> list[str]:
    """Every failure class the run shows, in FAILURE_CLASSES order (empty when nothing went wrong).

    invalid_plan: no plan validated, even after the repair round; wrong_tool: an unknown tool, or an
    action tool the ideal plan does not use; wrong_argument: a call the host's checks held back, or the
    right tools with the drones ending in the wrong state; gateway_refusal: a refusal in a mission that
    expects none."""
    seen: set[str] = set()
    if turn.outcome in ("invalid_plan", "empty_answer", "step_limit", "model_error"):
        seen.add(turn.outcome)
    elif not (turn.final_text or "").strip():
        seen.add("empty_answer")
    planned = {name for name, _ in plan}
    for c in turn.tool_calls:
        if c.status == "unknown_tool":
            seen.add("wrong_tool")
        elif c.status == "invalid":
            text = next((r.get("text") or "" for r in results if r.get("id") == c.id), "")
            seen.add("invented_id" if "is not one of" in text and "drone_id" in text else "wrong_argument")
        elif c.status == "skipped":
            seen.add("wrong_argument")
        elif c.name not in planned and c.name not in READ_OR_WAIT:
            seen.add("wrong_tool")
        if c.status == "error" and "unsafe" not in mission.tags:
            seen.add("gateway_refusal")
    if not check_ok and not seen & {"wrong_tool", "invented_id"}:
        seen.add("wrong_argument" if planned <= {c.name for c in turn.tool_calls} else "wrong_outcome")
    return [k for k in FAILURE_CLASSES if k in seen]


def by_mission(runs: list[MissionRun]) -> dict[str, list[MissionRun]]:
    out: dict[str, list[MissionRun]] = {}
    for r in runs:
        out.setdefault(r.mission, []).append(r)
    return out


def _median(values: list[float]) -> float:
    return statistics.median(values) if values else float("nan")


def _mean_tokens(runs: list[MissionRun], key: str) -> int | None:
    vals = [getattr(r, key) for r in runs if getattr(r, key) is not None]
    return round(sum(vals) / len(vals)) if vals else None


def _failures(runs: list[MissionRun]) -> str:
    counts = Counter(r.failure for r in runs if r.failure)
    return ", ".join(f"{k} x{n}" if n > 1 else k for k, n in counts.most_common()) or "-"


def results_table(runs: list[MissionRun], title: str) -> Table:
    table = Table(title=title)
    cols = ("mission", "passed", "median s", "calls/run", "errors", "from text", "tokens in/run",
            "tokens out/run", "failures")  # fmt: skip
    for col in cols:
        table.add_column(col, justify="left" if col in ("mission", "failures") else "right")
    for mission, rs in by_mission(runs).items():
        table.add_row(*_row(mission, rs))
    t = totals(runs)
    table.add_row(
        "TOTAL",
        f"{t['passed']}/{t['runs']} ({t['pass_pct']:.0f} %)",
        f"{t['median_wall_s']:.1f}",
        f"{t['tool_calls'] / max(t['runs'], 1):.1f}",
        str(t["tool_errors"]),
        str(t["parsed_from_text"]),
        _n(_mean_tokens(runs, "prompt_tokens")),
        _n(_mean_tokens(runs, "completion_tokens")),
        _failures(runs),
        style="bold",
    )
    return table


def _row(mission: str, rs: list[MissionRun]) -> list[str]:
    return [
        mission,
        f"{sum(r.ok for r in rs)}/{len(rs)}",
        f"{_median([r.wall_s for r in rs]):.1f}",
        f"{sum(r.tool_calls for r in rs) / len(rs):.1f}",
        str(sum(r.tool_errors for r in rs)),
        str(sum(r.parsed_from_text for r in rs)),
        _n(_mean_tokens(rs, "prompt_tokens")),
        _n(_mean_tokens(rs, "completion_tokens")),
        _failures(rs),
    ]


def totals(runs: list[MissionRun]) -> dict[str, Any]:
    def tok(key: str) -> int | None:
        vals = [getattr(r, key) for r in runs if getattr(r, key) is not None]
        return sum(vals) if vals else None

    passed = sum(r.ok for r in runs)
    return {
        "runs": len(runs),
        "missions": len(by_mission(runs)),
        "passed": passed,
        "pass_pct": 100.0 * passed / len(runs) if runs else 0.0,
        "median_wall_s": _median([r.wall_s for r in runs]),
        "tool_calls": sum(r.tool_calls for r in runs),
        "tool_errors": sum(r.tool_errors for r in runs),
        "parsed_from_text": sum(r.parsed_from_text for r in runs),
        "prompt_tokens": tok("prompt_tokens"),
        "completion_tokens": tok("completion_tokens"),
        "wall_s": sum(r.wall_s for r in runs),
        "failures": dict(Counter(r.failure for r in runs if r.failure)),
    }


def by_class(runs: list[MissionRun]) -> dict[tuple[str, str], list[MissionRun]]:
    """Corpus runs grouped by (half, class), halves in order dev, test and classes in corpus order."""
    from bench.nl_corpus import CLASSES, HALVES

    out: dict[tuple[str, str], list[MissionRun]] = {}
    for half in HALVES:
        for cls in CLASSES:
            rs = [r for r in runs if r.half == half and r.cls == cls]
            if rs:
                out[(half, cls)] = rs
    return out


def class_rows(runs: list[MissionRun]) -> list[list[str]]:
    """One row per (half, class) and one total per half: half, class, passed, %, failures."""
    rows = []
    for (half, cls), rs in by_class(runs).items():
        passed = sum(r.ok for r in rs)
        rows.append([half, cls, f"{passed}/{len(rs)}", f"{100.0 * passed / len(rs):.0f} %", _failures(rs)])
    for half in ("dev", "test"):
        rs = [r for r in runs if r.half == half]
        if rs:
            passed = sum(r.ok for r in rs)
            rows.append(
                [half, "TOTAL", f"{passed}/{len(rs)}", f"{100.0 * passed / len(rs):.0f} %", _failures(rs)]
            )
    return rows


def class_table(runs: list[MissionRun], title: str) -> Table:
    table = Table(title=title)
    for col in ("half", "class", "passed", "%", "failures"):
        table.add_column(col, justify="right" if col in ("passed", "%") else "left")
    for row in class_rows(runs):
        table.add_row(*row, style="bold" if row[1] == "TOTAL" else None)
    return table


def failure_lines(runs: list[MissionRun]) -> list[str]:
    """One line per failed run: which request, which run, the failure class, the check, the calls made."""
    lines = []
    for r in runs:
        if not r.ok:
            calls = "; ".join(r.calls)
            calls = calls if len(calls) <= 300 else calls[:297] + "..."
            lines.append(f"- `{r.mission}` run {r.run}: {r.failure} - {r.detail}; calls: {calls or 'none'}")
    return lines


def markdown_section(runs: list[MissionRun], args: argparse.Namespace) -> str:
    t = totals(runs)
    lines = [
        f"Model `{args.model}` at `{args.endpoint}`, typed plan host; "
        f"{args.tool_list}; {args.runs} run(s) of each mission, model "
        f"timeout {args.model_timeout:g} s, {'ArduCopter SITL' if args.sitl else 'sim'} speed-up "
        f"{args.speedup:g}; load average (1 min) "
        f"{args.load_start:.1f} at the start, {args.load_end:.1f} at the end.",
        "",
        f"Passed **{t['passed']}/{t['runs']} runs ({t['pass_pct']:.0f} %)**, median mission "
        f"{t['median_wall_s']:.1f} s.",
        "",
        "| mission | passed | median s | calls/run | errors | parsed from text | tokens in/run | "
        "tokens out/run | failures |",
        "|---|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for mission, rs in by_mission(runs).items():
        lines.append("| " + " | ".join(c.replace("|", "/") for c in _row(mission, rs)) + " |")
    lines.append(
        f"| **total** | {t['passed']}/{t['runs']} | {t['median_wall_s']:.1f} | "
        f"{t['tool_calls'] / max(t['runs'], 1):.1f} | {t['tool_errors']} | {t['parsed_from_text']} | "
        f"{_n(_mean_tokens(runs, 'prompt_tokens'))} | {_n(_mean_tokens(runs, 'completion_tokens'))} | "
        f"{_failures(runs)} |"
    )
    if any(r.half for r in runs):
        lines += ["", "| half | class | passed | % | failures |", "|---|---|---:|---:|---|"]
        lines += ["| " + " | ".join(row) + " |" for row in class_rows(runs)]
    fails = failure_lines(runs)
    if fails:
        lines += ["", "Failed runs:", "", *fails]
    return "\n".join(lines) + "\n"


def write_docs(section: str, args: argparse.Namespace) -> None:
    """Replace this model's section of docs/benchmarks.md (another run keeps the others)."""
    name = f"nl:{args.model}:plan"
    title = f"NL missions: {args.model}, typed plan"
    if args.half:
        where = "ArduCopter SITL" if args.sitl else "simulator"
        name += f":corpus-{args.half}:{where}"
        title = f"NL corpus, {args.half} half ({where}): {args.model}, typed plan"
    write_section(name, title, section, machine())


def _n(v: int | None) -> str:
    return "n/a" if v is None else str(v)


async def _cancellable(coro: Any) -> Any:
    """Run ``coro`` so that SIGTERM cancels it like Ctrl-C does: the sim, gateway and sidecars it
    started are then stopped by their context managers instead of being orphaned."""
    task = asyncio.ensure_future(coro)
    with contextlib.suppress(NotImplementedError):
        asyncio.get_running_loop().add_signal_handler(signal.SIGTERM, task.cancel)
    return await task


class LocalModel:
    """``serve-local-model`` as a context manager: started in its own process group, stopped with it."""

    def __init__(self, which: str, threads: int, console: Console, script: Path | None = None) -> None:
        self.which, self.threads, self.console = which, threads, console
        self.script = script or LOCAL_MODEL_SCRIPT
        self.proc: subprocess.Popen[str] | None = None
        self.base_url = self.model = ""

    def __enter__(self) -> LocalModel:
        if not self.script.exists():
            raise SystemExit(
                f"--serve-local: {self.script} is not there; give an endpoint instead "
                "(--endpoint URL --model NAME, or make bench-nl ENDPOINT=URL MODEL=NAME), or the shared "
                "folder that holds llm/serve-local-model (--shared-dir DIR or FLEET_SHARED_DIR)"
            )
        port = free_port()
        self.console.print(f"[dim]starting {self.script.name} --model {self.which} on port {port}...[/]")
        self.proc = subprocess.Popen(
            [
                str(self.script),
                "--model",
                self.which,
                "--port",
                str(port),
                "--threads",
                str(self.threads),
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            start_new_session=True,
        )
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            if line.startswith("ready "):
                _, self.base_url, self.model = line.split()
                return self
        self.__exit__()
        raise SystemExit(f"--serve-local: {self.script.name} exited before it was ready")

    def __exit__(self, *exc: object) -> None:
        if self.proc is not None and self.proc.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()


def free_port() -> int:
    from gateway.util.ports import free_tcp_port

    return free_tcp_port()


#: how many times a bench whose stack failed (e.g. a read error of its MCP link) starts a new sim, gateway
#: and link and goes on with the runs not yet done
MAX_RESTARTS = 3


def run_with_restarts(args: argparse.Namespace, console: Console) -> tuple[list[MissionRun], bool]:
    """The runs, and whether the bench stopped before its end (Ctrl-C, SIGTERM, or a stack that kept
    failing). The runs that finished are kept in ``args.completed`` whatever happens."""
    for attempt in range(MAX_RESTARTS + 1):
        try:
            return asyncio.run(_cancellable(run_missions(args, console))), False
        except (asyncio.CancelledError, KeyboardInterrupt):
            console.print("[red]interrupted[/]: the sim and gateway it started were stopped")
            return args.completed, True
        except Exception as exc:  # the stack failed under the bench: start a new one, keep the runs
            args.restarts = [*getattr(args, "restarts", []), f"{type(exc).__name__}: {exc}"[:300]]
            console.print(f"[red]the bench's stack failed[/] ({args.restarts[-1]}); attempt {attempt + 1}")
    return args.completed, True


def write_json(args: argparse.Namespace, runs: list[MissionRun], interrupted: bool) -> None:
    Path(args.json_out).write_text(
        json.dumps(
            {
                "model": SELF_CHECK_MODEL if args.self_check else args.model,
                "self_check": args.self_check,
                "decoding": args.decoding,
                "nearest": args.nearest,
                "half": args.half,
                "vehicles": "ArduCopter SITL" if args.sitl else "simulator",
                "tool_list": getattr(args, "tool_list", None),
                "load_start": args.load_start,
                "load_end": getattr(args, "load_end", None) or os.getloadavg()[0],
                "interrupted": interrupted,
                "restarts": getattr(args, "restarts", []),
                "runs": [r.__dict__ for r in runs],
                "totals": totals(runs),
            },
            indent=2,
        )
    )


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    console = Console() if sys.stdout.isatty() else Console(width=150)
    if args.self_check:
        console.print(
            "[bold yellow]HARNESS SELF-CHECK[/] scripted endpoint replaying each mission's ideal calls; "
            "these figures are NOT a model result."
        )
    with contextlib.ExitStack() as serving:
        if args.serve_local:
            local = serving.enter_context(
                LocalModel(args.serve_local, args.threads, console, local_model_script(args))
            )
            args.endpoint, args.model = local.base_url, local.model
        if args.resume:  # once the model's name is known (--serve-local gives it here)
            try:
                args.completed = resumed_runs(Path(args.resume), args)
            except ValueError as exc:
                console.print(f"[red]{exc}[/]")
                return 2
            args.restarts = [f"resumed from {args.resume}: {len(args.completed)} runs recorded there"]
        args.load_start = os.getloadavg()[0]
        runs, interrupted = run_with_restarts(args, console)
        if interrupted:
            if not runs:
                return 130
            console.print(f"[yellow]reporting the {len(runs)} run(s) that finished (not written to docs)[/]")
        args.load_end = os.getloadavg()[0]
    title = (
        "HARNESS SELF-CHECK (scripted pilot, not a model; tokens = request size / 4)"
        if args.self_check
        else f"NL missions: {args.model}, typed plan"
        if args.replayed
        else f"NL missions: {args.model} at {args.endpoint}, typed plan"
    )
    console.print(results_table(runs, title))
    if any(r.half for r in runs):
        console.print(class_table(runs, "per half and class"))
    console.print(
        f"[dim]load average (1 min): {args.load_start:.1f} at the start, {args.load_end:.1f} at the end[/]"
    )
    if args.json_out:
        write_json(args, runs, interrupted)
    if interrupted:
        return 130
    if args.write:
        write_docs(markdown_section(runs, args), args)
    # The self-check is a harness test: any failed mission there is a harness defect.
    if args.self_check and not all(r.ok for r in runs):
        return 1
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    sys.exit(main())
