"""What a model reads when its tool arguments are wrong: one line per argument naming it, what was
given and what is accepted (from the tool's own JSON schema), instead of pydantic's multi-line dump with
class names and URLs. Also puts the limits the safety policy enforces into the advertised schemas."""

from __future__ import annotations

import difflib
from collections.abc import Sequence
from typing import Any

from mcp.server.mcpserver.exceptions import ToolError
from mcp.server.mcpserver.tools import Tool
from mcp.types import CallToolResult
from pydantic import ValidationError

from gateway.config import Settings
from gateway.errors import InvalidArgument
from gateway.mcp import sdk_private
from gateway.mcp.refusals import refusal_result
from gateway.mcp.sdk_types import SdkArguments, SdkSchema
from gateway.mcp.strict_json import shown_value, strict_problems

#: argument names that are altitudes above home, bounded by the policy's max_altitude_m
ALTITUDE_ARGUMENTS = ("alt_m", "rtl_alt_m")


def install_argument_messages(tool: Tool) -> None:
    """Answer a tool's bad arguments with an error result the model can act on (its text) and any client
    can read (code ``invalid_argument`` and the arguments at fault, as structured content). The arguments
    are validated once, by the SDK's own run (`Tool.run`): its validation error is re-worded here, one
    line per argument; an argument the tool does not have (which the SDK would drop) is refused first, and
    so is one whose JSON type is not its schema's (`gateway.mcp.strict_json`: no "10" for a number). A
    ToolError the tool raises itself keeps its own words."""
    run = tool.run
    schema = tool.parameters
    known = frozenset(schema.get("properties", {}))

    # Any: mcp SDK, Tool.run's context and result
    async def run_checked(arguments: SdkArguments, context: Any, convert_result: bool = False) -> Any:
        unknown = [name for name in arguments if name not in known]
        if unknown:
            return _invalid(describe_unknown(tool.name, unknown, schema), unknown)
        problems = strict_problems(arguments, schema, _accepted)
        if problems:  # before the SDK's lax validation turns "10" into 10 or true into 1
            wrong = [name for name, value in arguments.items() if strict_problems({name: value}, schema)]
            message = f"invalid arguments for {tool.name}: " + "; ".join(problems) + "; nothing was sent"
            return _invalid(message, wrong)
        try:
            return await run(arguments, context, convert_result=convert_result)
        except ToolError as exc:
            # the SDK raises its argument validation's error as a ToolError caused by it; a tool body's
            # own failures arrive otherwise (a ToolError caused by a ToolError, or UnexpectedToolError)
            if isinstance(exc.__cause__, ValidationError):
                wrong = sorted(
                    {_path([p for p in e.get("loc", ()) if p != "arguments"]) for e in exc.__cause__.errors()}
                )
                return _invalid(describe_invalid(tool.name, exc.__cause__, schema), wrong)
            if type(exc) is ToolError and type(exc.__cause__) is ToolError:
                # raised on purpose by the tool or a resolver (a refusal, a failure in its words): the
                # model reads those words, not the SDK's "Error executing tool <name>:" in front of them
                raise ToolError(str(exc.__cause__)) from None
            raise

    sdk_private.replace_run(tool, run_checked)


def _invalid(message: str, arguments: list[str]) -> CallToolResult:
    return refusal_result(message, InvalidArgument.code, message, details={"arguments": arguments})


def describe_unknown(tool_name: str, unknown: list[str], schema: SdkSchema) -> str:
    """One line naming each argument the tool does not have, its closest real name, and the tool's
    arguments: nothing is sent (a silently dropped argument let a model believe it set something)."""
    known = list(schema.get("properties", {}))
    parts = []
    for name in unknown:
        shown = shown_value(name)
        close = difflib.get_close_matches(str(name), known, n=1, cutoff=0.6)
        parts.append(
            f"{shown} is not an argument of {tool_name}" + (f" (did you mean {close[0]}?)" if close else "")
        )
    return (
        f"invalid arguments for {tool_name}: "
        + "; ".join(parts)
        + f"; nothing was sent. Its arguments: {', '.join(known) or 'none'}"
    )


def describe_invalid(tool_name: str, exc: ValidationError, schema: SdkSchema) -> str:
    lines: list[str] = []
    seen: set[str] = set()
    for err in exc.errors():
        loc = [part for part in err.get("loc", ()) if part != "arguments"]
        name = _path(loc) or "arguments"
        if name in seen:  # a union reports each alternative: one line per argument is enough
            continue
        seen.add(name)
        prop = _property(schema, loc)
        accepted = _accepted(name, prop) if prop is not None else None
        if err.get("type") == "missing":
            lines.append(f"{name} is required" + (f": {accepted}" if accepted else ""))
        elif err.get("type") == "extra_forbidden":
            known = ", ".join(schema.get("properties", {})) or "none"
            lines.append(f"{name} is not an argument of {tool_name}; its arguments: {known}")
        elif accepted:
            lines.append(f"{name} must be {accepted} (got {shown_value(err.get('input'))})")
        else:
            message = str(err.get("msg", "is not valid")).removeprefix("Value error, ")
            lines.append(f"{name}: {message} (got {shown_value(err.get('input'))})")
    return f"invalid arguments for {tool_name}: " + "; ".join(lines)


def advertise_policy_limits(tool: Tool, settings: Settings) -> None:
    """An altitude above home advertises the policy's maximum (the model sees the real bound before it
    calls). Where alt_frame may switch to AMSL the bound is said in the description instead."""
    props = tool.parameters.get("properties", {})
    limit = float(settings.max_altitude_m)
    for name in ALTITUDE_ARGUMENTS:
        prop = props.get(name)
        if not isinstance(prop, dict):
            continue
        if "alt_frame" in props:
            note = f"policy limit {limit:g} m above home"
            description = prop.get("description", "")
            if note not in description:
                prop["description"] = f"{description}; {note}" if description else note
            continue
        target = _number_schema(prop)
        if target is not None:
            target["maximum"] = min(float(target.get("maximum", limit)), limit)
    stagger = props.get("stagger_m")
    if isinstance(stagger, dict):  # its default follows the configured minimum separation
        from gateway.fleet.operations.fleet_steps import FORMATION_TOLERANCE_M

        stagger["default"] = settings.min_separation_m + 2 * FORMATION_TOLERANCE_M


def _number_schema(prop: SdkSchema) -> SdkSchema | None:
    if prop.get("type") in ("number", "integer"):
        return prop
    for option in prop.get("anyOf", []):
        if isinstance(option, dict) and option.get("type") in ("number", "integer"):
            return option
    return None


def _path(loc: Sequence[int | str]) -> str:
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _property(schema: SdkSchema, loc: Sequence[int | str]) -> SdkSchema | None:
    """The JSON schema of the argument at ``loc`` (following arrays, objects and $refs)."""
    node: object = schema
    for part in loc:
        node = _resolve(schema, node)
        if isinstance(part, int):
            node = node.get("items") if isinstance(node, dict) else None
        else:
            node = node.get("properties", {}).get(part) if isinstance(node, dict) else None
        if node is None:
            return None
    resolved = _resolve(schema, node) if isinstance(node, dict) else None
    return resolved if isinstance(resolved, dict) else None


def _resolve(schema: SdkSchema, node: object) -> object:
    if isinstance(node, dict) and isinstance(node.get("$ref"), str):
        key = node["$ref"].rsplit("/", 1)[-1]
        return schema.get("$defs", {}).get(key, node)
    if isinstance(node, dict) and "anyOf" in node:  # Optional[X]: describe X
        options = [o for o in node["anyOf"] if not (isinstance(o, dict) and o.get("type") == "null")]
        if len(options) == 1:
            merged = {k: v for k, v in node.items() if k != "anyOf"}
            inner = _resolve(schema, options[0])
            return {**inner, **merged} if isinstance(inner, dict) else merged
    return node


def _accepted(name: str, prop: SdkSchema) -> str | None:
    if "enum" in prop:
        return "one of " + ", ".join(str(v) for v in prop["enum"])
    if "const" in prop:
        return f"{prop['const']!r}"
    kind = prop.get("type")
    description = prop.get("description")
    about = f" ({description})" if description else ""
    if kind in ("number", "integer"):
        noun = "an integer" if kind == "integer" else "a number"
        bounds = _bounds(name, prop)
        return f"{noun}{about}" + (f", {bounds}" if bounds else "")
    if kind == "string":
        size = f" of at most {prop['maxLength']} characters" if "maxLength" in prop else ""
        pattern = f" matching {prop['pattern']}" if "pattern" in prop else ""
        return f"a string{size}{pattern}{about}"
    if kind == "boolean":
        return f"true or false{about}"
    if kind == "array":
        size = f" of at most {prop['maxItems']} items" if "maxItems" in prop else ""
        return f"a list{size}{about}"
    if kind == "object":
        return f"an object{about}"
    return None


def _bounds(name: str, prop: SdkSchema) -> str:
    low = (
        f"{_num(prop['exclusiveMinimum'])} < " if "exclusiveMinimum" in prop
        else f"{_num(prop['minimum'])} <= " if "minimum" in prop else ""
    )  # fmt: skip
    high = (
        f" < {_num(prop['exclusiveMaximum'])}" if "exclusiveMaximum" in prop
        else f" <= {_num(prop['maximum'])}" if "maximum" in prop else ""
    )  # fmt: skip
    return f"{low}{name}{high}" if low or high else ""


def _num(value: object) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)
