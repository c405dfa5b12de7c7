"""``fleet-gateway agent``: a chat model flies the fleet through the gateway's MCP tools."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import logging
import sys
from collections.abc import Sequence
from typing import TextIO

from rich.console import Console
from rich.table import Table

from gateway.agent.autoprofile import ProfileChoice
from gateway.agent.autoprofile import resolve as resolve_profile
from gateway.agent.display import JsonLinesDisplay, RichDisplay
from gateway.agent.host import AgentHost
from gateway.agent.mcp_link import McpLink, McpLinkError
from gateway.agent.profiles import PROFILES, apply_profile, host_options_for, system_prompt_for
from gateway.agent.servers import ToolRouter, link_for
from gateway.agent.settings import AgentSettings, split_list
from gateway.agent.toolbox import ToolInfo, ToolSelectionError, select_tools
from gateway.agent.turns import AgentEvent, ModelConfig
from gateway.agent.wording import DEFAULT_SYSTEM_PROMPT
from gateway.cli_help import COMMAND_HELP

EXIT_OK, EXIT_FAILED, EXIT_USAGE, EXIT_STEP_LIMIT, EXIT_EMPTY_ANSWER = 0, 1, 2, 3, 4

_EPILOG = """\
examples:
  fleet-gateway agent --model qwen2.5:7b "take off alpha and bravo to 15 m, fly them 100 m north, then land"
  fleet-gateway agent --endpoint http://127.0.0.1:1234/v1 --model qwen2.5-7b-instruct     # interactive
  fleet-gateway agent --list-tools --toolsets flight,navigation
  fleet-gateway agent --model qwen2.5-coder-1.5b-instruct "take off alpha to 10 m"   # picks --profile small

environment: GATEWAY_AGENT_MCP_URL, GATEWAY_AGENT_TOKEN, GATEWAY_AGENT_ENDPOINT, GATEWAY_AGENT_MODEL,
GATEWAY_AGENT_API_KEY (else OPENAI_API_KEY), GATEWAY_AGENT_MAX_STEPS, GATEWAY_AGENT_TOOLSETS,
GATEWAY_AGENT_TOOLS, GATEWAY_AGENT_PROFILE (full, small or auto).
interactive commands: /reset (forget the conversation), /usage, /tools, /quit.
exit status (one-shot): 0 answered (by the model, or by the host from the gateway's results when the model
stopped replying after acting), 1 failed, 2 bad usage, 3 step limit reached, 4 nothing was done and the
model gave no answer (empty replies, even after being asked again twice).
"""


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser(
        "agent",
        help=COMMAND_HELP["agent"],
        description="A small MCP host: hands the gateway's tools to a chat model and runs the tool loop. "
        "With a PROMPT it runs one turn and exits; without one it keeps a conversation at a prompt.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_agent_arguments(parser)
    parser.set_defaults(func=run)


def add_agent_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("prompt", nargs="*", help="one-shot request (omit for interactive mode)")
    parser.add_argument(
        "--mcp-url",
        default=None,
        help="the gateway's MCP endpoint (default: GATEWAY_AGENT_MCP_URL or http://127.0.0.1:8765/mcp)",
    )
    parser.add_argument(
        "--mcp-mode",
        default="auto",
        choices=["auto", "legacy"],
        help="MCP protocol negotiation: auto (2026-07-28, falls back to a handshake) or legacy (2025-era)",
    )
    parser.add_argument("--token", default=None, help="bearer token for /mcp (default: GATEWAY_AGENT_TOKEN)")
    parser.add_argument(
        "--server",
        action="append",
        default=None,
        metavar="URL_OR_COMMAND",
        help="another MCP server whose tools are offered beside the gateway's (repeatable): a URL, or a "
        "command speaking MCP over stdio, e.g. --server 'python -m places_server'",
    )
    parser.add_argument(
        "--endpoint",
        default=None,
        help="OpenAI-compatible base URL, e.g. "
        "http://127.0.0.1:11434/v1 (Ollama), http://127.0.0.1:1234/v1 (LM Studio)",
    )
    parser.add_argument(
        "--model", default=None, help="model name at the endpoint (default: GATEWAY_AGENT_MODEL)"
    )
    parser.add_argument(
        "--max-steps",
        type=_positive_int,
        default=None,
        help="model requests per turn before stopping (default 12)",
    )
    parser.add_argument(
        "--toolsets", default=None, help="comma-separated toolsets to offer the model (flight,navigation,...)"
    )
    parser.add_argument("--tools", default=None, help="comma-separated tool names to offer the model")
    parser.add_argument(
        "--profile",
        default=None,
        choices=[*PROFILES, "auto"],
        help="small: about ten tools without advanced optional arguments, for models of a few billion "
        "parameters or less; full: every selected tool as the gateway describes it; auto (default): "
        "small when the endpoint (llama.cpp, Ollama) or the model's name says it is a small model",
    )
    parser.add_argument(
        "--no-roster",
        action="store_true",
        help="do not read the fleet (list_drones) before each model request nor limit drone ids to it",
    )
    parser.add_argument(
        "--temperature",
        type=float,
        default=0.0,
        help="sampling temperature (default 0; negative: leave it to the endpoint)",
    )
    parser.add_argument("--system", default=None, help="replace the default system prompt")
    parser.add_argument(
        "--model-timeout",
        type=float,
        default=300.0,
        help="seconds to wait for one model reply (default 300; CPU-only local models can be slow)",
    )
    parser.add_argument(
        "--max-tokens",
        type=_positive_int,
        default=None,
        help="longest reply the model may write, in tokens (default: the endpoint's)",
    )
    parser.add_argument(
        "--structured",
        action="store_true",
        help="also hand the model each result's structured content as JSON (more tokens)",
    )
    parser.add_argument("--json", action="store_true", help="print a JSON-lines transcript instead")
    parser.add_argument("--list-tools", action="store_true", help="list the selected tools and exit")


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


_CHATTY_LOGGERS = ("httpx", "httpx2", "mcp", "openai", "uvicorn")


def run(args: argparse.Namespace) -> int:
    # Request-by-request INFO logs would drown the transcript; the gateway logs its own side.
    if logging.getLogger().getEffectiveLevel() > logging.DEBUG:
        for name in _CHATTY_LOGGERS:
            logging.getLogger(name).setLevel(logging.WARNING)
    return asyncio.run(run_async(args))


async def run_async(
    args: argparse.Namespace, *, stdin: TextIO | None = None, console: Console | None = None
) -> int:
    """The command's body (separate from ``run`` so tests can drive it inside their event loop)."""
    env = AgentSettings()
    console = console or Console()
    err = Console(stderr=True) if console.file is sys.stdout else console
    mcp_url = args.mcp_url or env.mcp_url
    model_name = args.model or env.model
    prompt = " ".join(args.prompt).strip()
    if not args.list_tools and not model_name:
        err.print("[red]error:[/] no model given: use --model NAME or set GATEWAY_AGENT_MODEL")
        return EXIT_USAGE
    asked = args.profile or env.profile
    if asked == "auto" and not model_name:
        choice = ProfileChoice("full", "no model named")
    else:
        choice = await resolve_profile(
            asked, args.endpoint or env.endpoint, model_name or "", env.resolved_api_key()
        )
    profile = choice.profile
    if asked == "auto" and not args.json:
        err.print(f"[dim]profile {profile} (auto): {choice.reason}[/]")
    try:
        link_cm = McpLink(
            mcp_url, args.token or env.token, include_structured=args.structured, mode=args.mcp_mode
        )
        async with link_cm as link, contextlib.AsyncExitStack() as servers:
            router = ToolRouter(link)
            try:
                toolsets = split_list(args.toolsets if args.toolsets is not None else env.toolsets)
                names = split_list(args.tools if args.tools is not None else env.tools)
                offered = await link.list_tools()
                tools = select_tools(offered, toolsets=toolsets, names=names)
                tools = apply_profile(tools, profile, keep_selection=bool(toolsets or names))
            except ToolSelectionError as exc:
                err.print(f"[red]error:[/] {exc}")
                return EXIT_USAGE
            taken = {t.name for t in offered}
            for spec in args.server or ():
                await router.attach(await servers.enter_async_context(link_for(spec)), taken)
            tools = [*tools, *router.extra_tools]
            if args.list_tools:
                _print_tools(tools, console, as_json=args.json)
                return EXIT_OK
            display = (
                JsonLinesDisplay(console.file)
                if args.json
                else RichDisplay(console, echo_user=bool(prompt) or not _is_tty(stdin or sys.stdin))
            )
            if asked == "auto" and args.json:
                display(AgentEvent("profile", {"profile": profile, "auto": True, "reason": choice.reason}))
            if router.left_out:
                left = "tools of --server left out (their names are taken): " + ", ".join(router.left_out)
                if args.json:
                    display(AgentEvent("servers", {"left_out": router.left_out, "message": left}))
                else:
                    err.print(f"[yellow]{left}[/]")
            host = AgentHost(
                ModelConfig(
                    endpoint=args.endpoint or env.endpoint,
                    model=model_name or "",
                    api_key=env.resolved_api_key(),
                    temperature=None
                    if args.temperature is not None and args.temperature < 0
                    else args.temperature,
                    timeout_s=args.model_timeout,
                    max_tokens=args.max_tokens,
                ),
                router,
                tools,
                max_steps=args.max_steps or env.max_steps,
                system_prompt=args.system
                if args.system is not None
                else system_prompt_for(profile, DEFAULT_SYSTEM_PROMPT),
                on_event=display,
                roster=not args.no_roster,
                **host_options_for(profile),
            )
            try:
                if prompt:
                    result = await host.run_turn(prompt)
                    return {
                        "answered": EXIT_OK,
                        "step_limit": EXIT_STEP_LIMIT,
                        "empty_answer": EXIT_EMPTY_ANSWER,
                    }.get(result.outcome, EXIT_FAILED)
                return await _interactive(host, console, stdin or sys.stdin, as_json=args.json)
            finally:
                display.close()
    except McpLinkError as exc:
        err.print(f"[red]error:[/] {exc}")
        return EXIT_FAILED


async def _interactive(host: AgentHost, console: Console, stdin: TextIO, *, as_json: bool) -> int:
    if not as_json:
        console.print(
            f"[dim]{len(host.tools)} tools, model {host.model.model} at {host.model.endpoint}. "
            "/reset, /usage, /tools, /quit[/]"
        )
    while True:
        if not as_json and stdin.isatty():
            console.print("[bold cyan]> [/]", end="")
        line = await asyncio.to_thread(stdin.readline)
        if not line:
            return EXIT_OK
        text = line.strip()
        if not text:
            continue
        if text in ("/quit", "/exit"):
            return EXIT_OK
        if text == "/reset":
            host.reset()
            console.print("[dim]conversation cleared[/]")
            continue
        if text == "/usage":
            u = host.total_usage
            console.print(
                f"[dim]{u.model_calls} model calls, {u.prompt_tokens} in / {u.completion_tokens} out[/]"
            )
            continue
        if text == "/tools":
            console.print("[dim]" + ", ".join(sorted(host.tools)) + "[/]")
            continue
        try:
            await host.run_turn(text)
        except asyncio.CancelledError:
            # Ctrl-C at the prompt's turn: stop waiting, keep the session (a second Ctrl-C still exits).
            task = asyncio.current_task()
            if task is None or task.uncancel() > 0:
                raise


def _is_tty(stream: object) -> bool:
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


def _print_tools(tools: Sequence[ToolInfo], console: Console, *, as_json: bool) -> None:
    if as_json:
        for t in tools:
            console.file.write(
                json.dumps(
                    {
                        "name": t.name,
                        "toolset": t.toolset,
                        "description": t.description,
                        "input_schema": t.input_schema,
                    }
                )
                + "\n"
            )
        return
    table = Table("tool", "toolset", "description")
    for t in tools:
        table.add_row(t.name, t.toolset or "-", (t.description or "").split("\n")[0])
    console.print(table)
