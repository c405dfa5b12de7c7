"""``fleet-gateway agent``: a chat model writes a plan, the host flies it through the gateway's MCP tools."""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import sys
from typing import Any, TextIO

from fleet_agent.decoding import DECODINGS
from fleet_agent.host import AgentHost
from fleet_agent.mcp_link import McpLink, McpLinkError
from fleet_agent.records import AgentEvent, ModelConfig
from fleet_agent.settings import AgentSettings

HELP = "let a chat model plan a flight and the host fly it through the gateway's MCP tools"  # as cli_help
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2

_EPILOG = """\
examples:
  fleet-gateway agent --model qwen2.5:7b --decoding ollama "alpha: a square with 20 m sides, then land"
  fleet-gateway agent --endpoint http://127.0.0.1:8181/v1 --model qwen2.5-coder-1.5b-instruct-q4_k_m

environment: GATEWAY_AGENT_MCP_URL, GATEWAY_AGENT_TOKEN, GATEWAY_AGENT_ENDPOINT, GATEWAY_AGENT_MODEL,
GATEWAY_AGENT_API_KEY (else OPENAI_API_KEY), GATEWAY_AGENT_DECODING, GATEWAY_AGENT_PLACES_URL,
GATEWAY_AGENT_PLACES_TOOL. exit status (one-shot): 0 planned and flown (refusals are told in the answer),
1 no valid plan or the model failed, 2 bad usage.
"""


def register(subparsers: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    parser = subparsers.add_parser("agent", help=HELP, description=HELP, epilog=_EPILOG,
                                   formatter_class=argparse.RawDescriptionHelpFormatter)  # fmt: skip
    add_agent_arguments(parser)
    parser.set_defaults(func=run)


def add_agent_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("prompt", nargs="*", help="one-shot request (omit for interactive mode)")
    parser.add_argument("--mcp-url", default=None, help="the gateway's MCP endpoint")
    parser.add_argument("--token", default=None, help="bearer token for /mcp")
    parser.add_argument("--endpoint", default=None, help="OpenAI-compatible base URL of the model")
    parser.add_argument("--model", default=None, help="model name at the endpoint")
    parser.add_argument("--decoding", default=None, choices=DECODINGS, help="how the plan's schema is kept")
    parser.add_argument("--nearest", type=int, choices=range(9), default=None, metavar="0-8",
                        help="pool examples nearest the request shown to the model (default 0)")  # fmt: skip
    parser.add_argument("--places-url", default=None, help="an MCP server that knows named places")
    parser.add_argument("--model-timeout", type=float, default=300.0, help="seconds per model request")
    parser.add_argument("--json", action="store_true", help="print events as JSON lines")


def run(args: argparse.Namespace) -> int:
    return asyncio.run(run_async(args))


async def run_async(
    args: argparse.Namespace, *, stdin: TextIO | None = None, out: TextIO | None = None
) -> int:
    """The command's body (separate from ``run`` so tests can drive it inside their event loop)."""
    env = AgentSettings()
    out = out or sys.stdout
    model_name = args.model or env.model
    if not model_name:
        print("error: no model given: use --model NAME or set GATEWAY_AGENT_MODEL", file=sys.stderr)
        return EXIT_USAGE
    model = ModelConfig(
        base_url=args.endpoint or env.endpoint, model=model_name, api_key=env.resolved_api_key(),
        timeout_s=args.model_timeout, decoding=args.decoding or env.decoding,
        nearest=env.nearest if args.nearest is None else args.nearest,
    )  # fmt: skip
    try:
        async with contextlib.AsyncExitStack() as stack:
            link = await stack.enter_async_context(
                McpLink(args.mcp_url or env.mcp_url, args.token or env.token)
            )
            places = None
            if args.places_url or env.places_url:
                place_link = await stack.enter_async_context(McpLink(args.places_url or env.places_url or ""))
                places = (place_link, env.places_tool)
            host = AgentHost(
                model, link, await link.list_tools(), on_event=_printer(out, args.json), places=places
            )
            prompt = " ".join(args.prompt).strip()
            if prompt:
                result = await host.run_turn(prompt)
                return EXIT_OK if result.outcome == "answered" else EXIT_FAILED
            for line in stdin or sys.stdin:
                if line.strip():
                    await host.run_turn(line.strip())
            return EXIT_OK
    except McpLinkError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_FAILED


def _printer(out: TextIO, as_json: bool) -> Any:
    def show(event: AgentEvent) -> None:
        if as_json:
            print(json.dumps(event.to_json(), default=str), file=out, flush=True)
        elif event.kind == "plan":
            print(f"plan: {json.dumps(event.data['plan'], separators=(',', ':'))}", file=out, flush=True)
        elif event.kind == "tool_result":
            print(f"  {event.data['name']}: {event.data['status']}", file=out, flush=True)
        elif event.kind == "final":
            print(event.data["text"], file=out, flush=True)

    return show
