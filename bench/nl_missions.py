"""Natural-language mission benchmark: how well does a chat model fly the fleet through the gateway?

Runs a fixed set of missions worded as a person would say them against simulated drones, judges each by
the drones' true final state (and track), and prints per mission and in total: success, tool calls,
tokens in / out, wall time. Any OpenAI-compatible endpoint works (Ollama, LM Studio, vLLM, llama.cpp,
hosted providers).

  python bench/nl_missions.py --endpoint http://127.0.0.1:11434/v1 --model qwen2.5:7b [--write]
  python bench/nl_missions.py --endpoint ... --model ... --toolsets flight,navigation,fleet
  python bench/nl_missions.py --self-check          # no model: checks the harness itself

Without --model (and no GATEWAY_AGENT_MODEL) it runs the HARNESS SELF-CHECK: a scripted endpoint replays
the ideal call sequence of each mission. That verifies the sim, gateway, MCP, host loop and checks end to
end; its figures are not a model's and are never written to docs/benchmarks.md.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import datetime as dt
import json
import os
import signal
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # the repository root: bench.agent_harness

from bench.agent_harness.missions import Evidence, Mission, MissionContext, all_missions
from bench.agent_harness.pilot import SELF_CHECK_MODEL, ScriptedPilot
from bench.agent_harness.scripted import ScriptedModelServer
from bench.agent_harness.stack import GatewayTruth, LocalStack, Sampler, SimTruth, reset_drones
from gateway.agent.host import AgentEvent, AgentHost, ModelConfig
from gateway.agent.mcp_link import McpLink
from gateway.agent.settings import AgentSettings, split_list
from gateway.agent.toolbox import select_tools, tool_list_tokens

DOCS = Path(__file__).resolve().parent.parent / "docs" / "benchmarks.md"


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


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    env = AgentSettings()
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--endpoint", default=env.endpoint, help="OpenAI-compatible base URL")
    p.add_argument("--model", default=env.model, help="model name; omit for the harness self-check")
    p.add_argument("--self-check", action="store_true", help="scripted ideal pilot instead of a model")
    p.add_argument("--gateway-url", default=None, help="use this gateway's /mcp instead of starting one")
    p.add_argument("--token", default=env.token, help="bearer token for --gateway-url")
    p.add_argument(
        "--sim-control-url",
        default=None,
        help="with --gateway-url: the sim's control API for true state (else gateway telemetry); "
        "drone alpha is sim vehicle 0, bravo vehicle 1",
    )
    p.add_argument("--toolsets", default=None, help="comma-separated toolsets offered to the model")
    p.add_argument("--tools", default=None, help="comma-separated tool names offered to the model")
    p.add_argument("--missions", default=None, help="comma-separated mission ids (default: all)")
    p.add_argument("--max-steps", type=int, default=30, help="model requests per mission (default 30)")
    p.add_argument("--speedup", type=float, default=5.0, help="simulator speed-up of the own sim (default 5)")
    p.add_argument("--write", action="store_true", help="add the results table to docs/benchmarks.md")
    p.add_argument(
        "--json", dest="json_out", default=None, help="also write per-mission results as JSON here"
    )
    p.add_argument("--verbose", action="store_true", help="print every tool call while missions run")
    args = p.parse_args(argv)
    if not args.model:
        args.self_check = True
    if args.self_check and args.write:
        p.error("--write is refused for the harness self-check: its figures are not a model result")
    if args.max_steps < 1:
        p.error("--max-steps must be at least 1")
    return args


async def run_missions(args: argparse.Namespace, console: Console) -> list[MissionRun]:
    missions = all_missions()
    if args.missions:
        wanted = split_list(args.missions)
        unknown = sorted(set(wanted) - {m.id for m in missions})
        if unknown:
            raise SystemExit(f"unknown mission(s) {unknown}; known: {[m.id for m in missions]}")
        missions = [m for m in missions if m.id in wanted]
    drone_ids = sorted({d for m in missions for d in m.drones} | {"alpha", "bravo"})

    async with contextlib.AsyncExitStack() as stack:
        if args.gateway_url:
            mcp_url, token, truth_from_sim = args.gateway_url, args.token, args.sim_control_url
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
        tools = select_tools(all_tools, toolsets=split_list(args.toolsets), names=split_list(args.tools))
        if local is not None:
            truth: Any = local.truth()
        elif truth_from_sim:
            truth = SimTruth(truth_from_sim, {d: i for i, d in enumerate(drone_ids)})
            stack.push_async_callback(truth.aclose)
        else:
            truth = GatewayTruth(link)
        list_tokens, method = tool_list_tokens(tools)
        args.tool_list = f"{len(tools)} of {len(all_tools)} tools, {list_tokens} tokens ({method})"
        console.print(f"[dim]tool list: {args.tool_list}; truth from {truth.source}[/]")

        pilot: ScriptedPilot | None = None
        if args.self_check:
            pilot = ScriptedPilot(wait_tool=_wait_tool(all_tools), text_every=2)
            scripted = stack.enter_context(ScriptedModelServer([pilot], repeat_last=True))
            model = ModelConfig(scripted.base_url, SELF_CHECK_MODEL, max_retries=0)
        else:
            model = ModelConfig(args.endpoint, args.model, api_key=AgentSettings().resolved_api_key())

        runs = []
        for mission in missions:
            await reset_drones(link, truth, drone_ids, battery_pct=mission.battery_pct)
            runs.append(await run_one(mission, link, tools, truth, model, pilot, args, console))
        return runs


def _wait_tool(tools: list[Any]) -> str | None:
    names = {t.name for t in tools}
    for candidate in ("wait_operation", "monitor_flight", "check_arrival"):
        if candidate in names:
            return candidate
    return None


async def run_one(
    mission: Mission,
    link: McpLink,
    tools: list[Any],
    truth: Any,
    model: ModelConfig,
    pilot: ScriptedPilot | None,
    args: argparse.Namespace,
    console: Console,
) -> MissionRun:
    homes = await truth.homes(list(mission.drones))
    offered = {t.name: frozenset((t.input_schema or {}).get("properties", {})) for t in tools}
    ctx = MissionContext(homes=homes, tools=offered)
    prompt = mission.prompt(ctx)
    if pilot is not None:
        pilot.load(mission.plan(ctx), mission.answer)
    results: list[dict[str, Any]] = []

    def on_event(e: AgentEvent) -> None:
        if e.kind == "tool_result":
            results.append(e.data)
        if args.verbose and e.kind in ("tool_call", "tool_result", "final", "step_limit", "model_error"):
            console.print(f"[dim]  {mission.id} {e.kind}: {json.dumps(e.data, default=str)[:200]}[/]")

    host = AgentHost(model, link, tools, max_steps=args.max_steps, on_event=on_event)
    console.print(f"[bold]{mission.id}[/] {prompt}")
    sampler = Sampler(truth, list(mission.drones))
    async with sampler:
        started = time.monotonic()
        turn = await host.run_turn(prompt)
        wall = time.monotonic() - started
    final = await truth.snapshot(list(mission.drones))
    evidence = Evidence(final=final, track=sampler.tracks, tool_results=results, final_text=turn.final_text)
    verdict = mission.check(ctx, evidence)
    run = MissionRun(
        mission=mission.id,
        ok=verdict.ok and turn.outcome == "answered",
        detail=verdict.detail,
        tool_calls=len(turn.tool_calls),
        tool_errors=sum(c.status != "ok" for c in turn.tool_calls),
        parsed_from_text=turn.parsed_from_text,
        prompt_tokens=turn.usage.prompt_tokens,
        completion_tokens=turn.usage.completion_tokens,
        steps=turn.steps,
        outcome=turn.outcome,
        wall_s=wall,
        calls=[c.name for c in turn.tool_calls],
    )
    if turn.outcome != "answered":
        run.detail = f"{turn.outcome}: {run.detail}"
    mark = "[green]PASS[/]" if run.ok else "[red]FAIL[/]"
    console.print(f"  {mark} {run.detail} [dim]({run.tool_calls} calls, {wall:.1f} s)[/]")
    return run


def results_table(runs: list[MissionRun], title: str) -> Table:
    table = Table(title=title)
    for col in ("mission", "ok", "tool calls", "errors", "from text", "tokens in", "tokens out", "wall s"):
        table.add_column(col, justify="left" if col == "mission" else "right")
    for r in runs:
        table.add_row(
            r.mission,
            "yes" if r.ok else "NO",
            str(r.tool_calls),
            str(r.tool_errors),
            str(r.parsed_from_text),
            _n(r.prompt_tokens),
            _n(r.completion_tokens),
            f"{r.wall_s:.1f}",
        )
    t = totals(runs)
    table.add_row(
        "TOTAL",
        f"{t['passed']}/{t['missions']}",
        str(t["tool_calls"]),
        str(t["tool_errors"]),
        str(t["parsed_from_text"]),
        _n(t["prompt_tokens"]),
        _n(t["completion_tokens"]),
        f"{t['wall_s']:.1f}",
        style="bold",
    )
    return table


def totals(runs: list[MissionRun]) -> dict[str, Any]:
    def tok(key: str) -> int | None:
        vals = [getattr(r, key) for r in runs if getattr(r, key) is not None]
        return sum(vals) if vals else None

    return {
        "missions": len(runs),
        "passed": sum(r.ok for r in runs),
        "tool_calls": sum(r.tool_calls for r in runs),
        "tool_errors": sum(r.tool_errors for r in runs),
        "parsed_from_text": sum(r.parsed_from_text for r in runs),
        "prompt_tokens": tok("prompt_tokens"),
        "completion_tokens": tok("completion_tokens"),
        "wall_s": sum(r.wall_s for r in runs),
    }


def markdown_section(runs: list[MissionRun], args: argparse.Namespace) -> str:
    t = totals(runs)
    selection = args.toolsets or args.tools or "all tools"
    lines = [
        f"## NL missions: {args.model}",
        "",
        f"{dt.datetime.now(dt.UTC):%Y-%m-%d %H:%M} UTC, endpoint `{args.endpoint}`, toolsets: {selection}, "
        f"tool list {args.tool_list}, max steps {args.max_steps}, sim speed-up {args.speedup:g}. "
        f"Passed **{t['passed']}/{t['missions']}**.",
        "",
        "| mission | ok | tool calls | errors | parsed from text | tokens in | tokens out | wall s "
        "| detail |",
        "|---|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in runs:
        lines.append(
            f"| {r.mission} | {'yes' if r.ok else 'no'} | {r.tool_calls} | {r.tool_errors} | "
            f"{r.parsed_from_text} | {_n(r.prompt_tokens)} | {_n(r.completion_tokens)} | {r.wall_s:.1f} | "
            f"{r.detail.replace('|', '/')} |"
        )
    lines.append(
        f"| **total** | {t['passed']}/{t['missions']} | {t['tool_calls']} | {t['tool_errors']} | "
        f"{t['parsed_from_text']} | {_n(t['prompt_tokens'])} | {_n(t['completion_tokens'])} | "
        f"{t['wall_s']:.1f} | |"
    )
    return "\n".join(lines) + "\n"


def write_docs(section: str) -> None:
    DOCS.parent.mkdir(parents=True, exist_ok=True)
    existing = DOCS.read_text() if DOCS.exists() else "# Benchmarks\n"
    DOCS.write_text(existing.rstrip("\n") + "\n\n" + section)


def _n(v: int | None) -> str:
    return "n/a" if v is None else str(v)


async def _cancellable(coro: Any) -> Any:
    """Run ``coro`` so that SIGTERM cancels it like Ctrl-C does: the sim, gateway and sidecars it
    started are then stopped by their context managers instead of being orphaned."""
    task = asyncio.ensure_future(coro)
    with contextlib.suppress(NotImplementedError):
        asyncio.get_running_loop().add_signal_handler(signal.SIGTERM, task.cancel)
    return await task


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    console = Console() if sys.stdout.isatty() else Console(width=150)
    if args.self_check:
        console.print(
            "[bold yellow]HARNESS SELF-CHECK[/] scripted endpoint replaying each mission's ideal calls; "
            "these figures are NOT a model result."
        )
    try:
        runs = asyncio.run(_cancellable(run_missions(args, console)))
    except (asyncio.CancelledError, KeyboardInterrupt):
        console.print("[red]interrupted[/]: the sim and gateway it started were stopped")
        return 130
    title = (
        "HARNESS SELF-CHECK (scripted pilot, not a model; tokens = request size / 4)"
        if args.self_check
        else f"NL missions: {args.model} at {args.endpoint}"
    )
    console.print(results_table(runs, title))
    if args.json_out:
        Path(args.json_out).write_text(
            json.dumps(
                {
                    "model": SELF_CHECK_MODEL if args.self_check else args.model,
                    "self_check": args.self_check,
                    "runs": [r.__dict__ for r in runs],
                    "totals": totals(runs),
                },
                indent=2,
            )
        )
    if args.write:
        write_docs(markdown_section(runs, args))
        console.print(f"[dim]written to {DOCS}[/]")
    # The self-check is a harness test: any failed mission there is a harness defect.
    if args.self_check and not all(r.ok for r in runs):
        return 1
    return 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONUNBUFFERED", "1")
    sys.exit(main())
