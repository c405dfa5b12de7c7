"""How toolsets are declared and turned into MCP tools.

A tool is a plain async function ``fn(call: ToolCall, drone_id, ...) -> SomeResult``: written by hand
and registered on a :class:`Toolset` (``@toolset.tool()``), or generated from a verb's declaration
(``@command(tool=Tool(...))``, built by `gateway.mcp.declared`). :func:`register_toolset` wraps it so that

- the SDK injects the request ``Context`` and the wrapper hands the tool a `ToolCall` built from the
  server's lifespan state (the Commander) and the caller (principal, session);
- drone ids are made canonical ('Alpha' is alpha) before the tool runs;

- gateway errors become tool errors (``isError``) with the gateway's own message, and its code, rule and
  details as structured content (gateway/mcp/refusals.py);
- the result goes out as structured content (output schema from the result model) plus a one-line text;
- the audit record of the call learns the outcome (refused / error / running / ok).
"""

from __future__ import annotations

import functools
import inspect
import json
import logging
import typing
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Annotated, Any

from mcp.server.mcpserver import Context
from mcp.types import CallToolResult, TextContent, ToolAnnotations
from pydantic import Field, ValidationError

from gateway.errors import GatewayError, InvalidArgument, SafetyRefusal
from gateway.fleet.commands.arguments import AltFrame as AltFrame  # the shared types, re-exported for tools
from gateway.fleet.commands.arguments import DroneId as DroneId
from gateway.fleet.commands.arguments import Lat as Lat
from gateway.fleet.commands.arguments import Lon as Lon
from gateway.fleet.commands.arguments import Metres as Metres
from gateway.fleet.vehicles.ids import canonical_arguments
from gateway.mcp import sdk_private
from gateway.mcp.access import ToolCall, current_call
from gateway.mcp.refusals import gateway_error_result, refusal_result
from gateway.mcp.results import Result
from gateway.mcp.sdk_types import AnyServer, ToolContext

log = logging.getLogger(__name__)

# --- shared parameter types (short descriptions: the tool list's size is paid on every LLM turn) -----
# DroneId, Lat, Lon, Metres, AltFrame: `gateway.fleet.commands.arguments` (the verbs declare them too)

MAX_DRONE_ID = 64
#: what it means is said once, in the server's instructions (gateway/mcp/server.py), not in every tool
Wait = Annotated[bool, Field()]


# --- toolsets ------------------------------------------------------------------------------------


ToolFn = Callable[..., Awaitable[Result]]
#: a JSON schema (or a part of one), as the SDK's tools carry them
JsonSchema = dict[str, object]


@dataclass
class ToolSpec:
    fn: ToolFn
    name: str
    title: str | None
    annotations: ToolAnnotations
    # parameter -> the schema advertised for it, where a shorter one says enough (validation is unchanged)
    advertise: dict[str, JsonSchema] = field(default_factory=dict)


@dataclass
class Toolset:
    """A named group of tools; GATEWAY_MCP_TOOLSETS selects which toolsets a server exposes. A
    module's ``toolset`` holds its hand-written tools; `load_toolset` gives it complete, with the tools
    the verbs declare for it (`gateway.mcp.declared.complete`) where ``declared_here()`` was called."""

    name: str
    tools: list[ToolSpec] = field(default_factory=list)
    #: where the declared tools go in ``tools`` (None: after the hand-written ones)
    declared_at: int | None = None

    def declared_here(self) -> None:
        """Put the tools the verbs declare for this toolset here, in the order the verbs are declared
        (the order of tools/list, which a model reads)."""
        self.declared_at = len(self.tools)

    def tool(
        self,
        *,
        read_only: bool = False,
        destructive: bool = False,
        idempotent: bool = False,
        title: str | None = None,
        advertise: dict[str, JsonSchema] | None = None,
    ) -> Callable[[ToolFn], ToolFn]:
        """Declare a tool. Annotations must tell the truth: read-only tools change nothing.

        ``advertise`` replaces the schema shown to clients for some parameters, e.g. to point at
        another tool's item schema instead of repeating it; arguments are still validated in full."""
        annotations = annotations_of(read_only=read_only, destructive=destructive, idempotent=idempotent)

        def decorator(fn: ToolFn) -> ToolFn:
            self.tools.append(
                ToolSpec(
                    fn=fn, name=fn.__name__, title=title, annotations=annotations, advertise=advertise or {}
                )
            )
            return fn

        return decorator


def annotations_of(*, read_only: bool, destructive: bool, idempotent: bool) -> ToolAnnotations:
    """A tool's annotations: read-only tools change nothing (and touch only this gateway)."""
    if read_only:
        return ToolAnnotations(readOnlyHint=True, openWorldHint=False)
    return ToolAnnotations(
        readOnlyHint=False, destructiveHint=destructive, idempotentHint=idempotent, openWorldHint=True
    )


def check_drone_id(drone_id: str) -> None:
    if not 0 < len(drone_id) <= MAX_DRONE_ID:
        raise InvalidArgument(
            f"drone_id must be 1..{MAX_DRONE_ID} characters (got {len(drone_id)}); list ids in fleet://drones"
        )


def _wrap(spec: ToolSpec) -> Callable[..., Any]:  # Any: mcp SDK, add_tool takes any function
    """The handler the SDK registers: the tool's own parameters (without its ``ToolCall``) plus the
    SDK-injected ``ctx``."""
    fn = spec.fn
    hints = typing.get_type_hints(fn, include_extras=True)
    sig = inspect.signature(fn)
    result_model = hints["return"]
    params = [
        p.replace(annotation=hints.get(p.name, p.annotation))
        for p in list(sig.parameters.values())[1:]  # drop the ToolCall parameter
    ]
    if any(p.name == "ctx" for p in params):
        raise ValueError(f"tool {spec.name}: 'ctx' is the wrapper's; name the parameter otherwise")
    params.append(inspect.Parameter("ctx", inspect.Parameter.KEYWORD_ONLY, annotation=Context))
    return_annotation = Annotated[CallToolResult, result_model]

    @functools.wraps(fn)
    async def handler(ctx: ToolContext, **kwargs: Any) -> CallToolResult:  # Any: mcp SDK, its JSON arguments
        call = current_call.get()
        if call is not None and call.before_tool is not None:
            await call.before_tool()  # the audit row of a call that commands a drone, before it runs
        try:
            tool_call = ToolCall.of(ctx)
            drone_id = kwargs.get("drone_id")
            if isinstance(drone_id, str):
                check_drone_id(drone_id)
            # 'Alpha' is alpha: operations and locks are keyed by the exact id (gateway.fleet.vehicles.ids)
            kwargs = canonical_arguments(tool_call.commander.registry, kwargs)
            canonical_id = kwargs.get("drone_id")
            if isinstance(canonical_id, str) and call is not None:
                call.vehicle_id = canonical_id
            result: Result = await fn(tool_call, **kwargs)
        except GatewayError as exc:
            if call is not None:
                call.outcome = "refused" if isinstance(exc, SafetyRefusal) else "error"
                call.error = exc.message
            return gateway_error_result(exc)
        except ValidationError as exc:  # a model built inside the tool from its arguments (e.g. a waypoint)
            message = "invalid arguments: " + "; ".join(
                f"{'.'.join(str(p) for p in err['loc']) or 'value'}: {err['msg']}" for err in exc.errors()
            )
            if call is not None:
                call.outcome, call.error = "error", message
            return refusal_result(message, InvalidArgument.code, message)
        structured = result.model_dump(mode="json")
        if call is not None and structured.get("status") == "running":
            call.outcome = "running"
        return CallToolResult(
            content=[TextContent(type="text", text=result.text())], structured_content=structured
        )

    handler.__signature__ = sig.replace(parameters=params, return_annotation=return_annotation)  # type: ignore[attr-defined]
    handler.__annotations__ = {p.name: p.annotation for p in params} | {"return": return_annotation}
    del handler.__wrapped__  # the SDK must see the wrapper's own signature
    return handler


TOOLSET_META_KEY = "fleet-gateway/toolset"


def register_toolset(server: AnyServer, toolset: Toolset) -> list[str]:
    names = []
    for spec in toolset.tools:
        description = inspect.cleandoc(spec.fn.__doc__ or "")
        server.add_tool(
            _wrap(spec),
            name=spec.name,
            title=spec.title,
            description=description,
            annotations=spec.annotations,
            # lets any client offer a model only some toolsets (small context windows)
            meta={TOOLSET_META_KEY: toolset.name},
        )
        if spec.advertise:
            _advertise(sdk_private.tool(server, spec.name).parameters, spec.advertise)
        names.append(spec.name)
    return names


def _advertise(schema: JsonSchema, overrides: dict[str, JsonSchema]) -> None:
    props = schema.get("properties")
    if not isinstance(props, dict):
        raise ValueError("advertise: the tool's schema has no properties")
    for name, advertised in overrides.items():
        if name not in props:
            raise ValueError(f"advertise names an unknown parameter '{name}'")
        props[name] = advertised
    defs = schema.get("$defs")
    if isinstance(defs, dict):
        text = json.dumps(props)
        for key in list(defs):
            if f"#/$defs/{key}" not in text:
                del defs[key]
        if not defs:
            del schema["$defs"]


def strip_schema_titles(schema: object) -> None:
    """Remove pydantic's auto-generated 'title' keys: they repeat the property names and cost tokens."""
    if isinstance(schema, dict):
        props = schema.get("properties")
        schema.pop("title", None)
        for key, sub in schema.items():
            if key == "properties" and isinstance(sub, dict) and isinstance(props, dict):
                for prop in props.values():
                    strip_schema_titles(prop)
            else:
                strip_schema_titles(sub)
    elif isinstance(schema, list):
        for item in schema:
            strip_schema_titles(item)


def collapse_optional_nulls(schema: object) -> None:
    """Advertise an optional argument ``X | None = None`` as plain ``X`` (not ``anyOf [X, null]``).

    A model leaves such an argument out to mean "none"; the long form only costs tokens. The server
    still validates arguments against the tool's own signature, so an explicit null stays accepted."""
    if isinstance(schema, dict):
        props = schema.get("properties")
        if isinstance(props, dict):
            for name, prop in list(props.items()):
                props[name] = _collapsed(prop)
        for key, sub in schema.items():
            if key != "properties":
                collapse_optional_nulls(sub)
        if isinstance(props, dict):
            for prop in props.values():
                collapse_optional_nulls(prop)
    elif isinstance(schema, list):
        for item in schema:
            collapse_optional_nulls(item)


def _collapsed(prop: object) -> object:
    if not isinstance(prop, dict) or prop.get("default", ...) is not None:
        return prop
    variants = prop.get("anyOf")
    if not isinstance(variants, list) or len(variants) != 2 or {"type": "null"} not in variants:
        return prop
    [kept] = [v for v in variants if v != {"type": "null"}]
    merged = {k: v for k, v in prop.items() if k not in ("anyOf", "default")}
    return {**kept, **merged}


def nullable_type_lists(schema: object) -> object:
    """``anyOf: [{"type": X}, {"type": "null"}]`` written as ``"type": [X, "null"]`` (the same values).

    For output schemas, which every client that checks structured results validates each result
    against: a list of 100 drones is 1,300 nullable fields, and the ``anyOf`` form costs a validator
    two sub-schemas each (and costs tokens where a client shows the schema to a model)."""
    if isinstance(schema, list):
        return [nullable_type_lists(item) for item in schema]
    if not isinstance(schema, dict):
        return schema
    out = {k: nullable_type_lists(v) for k, v in schema.items()}
    variants = out.get("anyOf")
    if isinstance(variants, list) and len(variants) == 2 and {"type": "null"} in variants:
        [kept] = [v for v in variants if v != {"type": "null"}]
        if isinstance(kept, dict) and set(kept) == {"type"} and isinstance(kept["type"], str):
            del out["anyOf"]
            out["type"] = [kept["type"], "null"]
    return out
