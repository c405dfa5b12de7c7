"""The MCP tools the verbs declare (``@command(tool=Tool(...))``, `gateway.fleet.commands.command_core`).

A declared tool is a thin pass-through: it calls its verb through the Commander with the caller and
the tool's arguments, and presents the result. Its inputSchema is the verb's own signature after
``caller`` (the ``Annotated`` bounds and descriptions, `gateway.fleet.commands.arguments`), minus ``label``
(filled with the tool's name), the parameter a human's confirmation fills (``confirm=``,
`gateway.mcp.confirmation`) and the parameters the declaration omits. The result is presented by its
model's presenter (`gateway.mcp.presenters`): an `OperationView` or a `FleetView` also takes ``wait``
(wait until done, capped, with progress), an `ActionResult` is presented with the declared ``says``
text. The tool is then registered like any other (`gateway.mcp.toolkit.register_toolset`: the SDK
validates the arguments once, errors become tool errors, the audit row learns the outcome).

Every command is declared this way: MCP, REST (by name, `Commander.call`, or a route calling the verb)
and the CLI (through REST) run the same verb. Hand-written tools (`gateway.mcp.tools.<toolset>`) are
the reads, which are no commands: they send nothing to a drone, take no lock, write no audit row of a
command (the telemetry cache, operations and missions as they stand, parameters read, waits).
"""

from __future__ import annotations

import inspect
import typing
from typing import Any

from gateway.fleet.commands.command_core import TOOLS, VERBS, Tool
from gateway.fleet.commands.commander import Commander  # noqa: F401  (imports every verb module: fills TOOLS)
from gateway.fleet.operations.routing import Verb
from gateway.mcp.access import ToolCall
from gateway.mcp.confirmation import ANSWER, answer_parameter, confirmed
from gateway.mcp.presenters import PRESENTERS, Presenter, waits_itself
from gateway.mcp.results import Result
from gateway.mcp.toolkit import Toolset, ToolSpec, Wait, annotations_of

#: verb parameters a tool fills itself, never offered to the client
FILLED = ("label",)
#: the verb's callbacks a tool can feed (``notify``: what a command waits for, as progress at 0;
#: ``on_progress``: an operation the verb waits for itself, as progress)
CALLBACKS = frozenset({"notify", "on_progress"})


def complete(toolset: Toolset) -> Toolset:
    """``toolset`` with the tools the verbs declare for it, where its module said (``declared_here``)
    or after its hand-written tools: a new `Toolset` (the module's keeps its hand-written tools only). A
    hand-written tool of the same name as a declared one is refused: one tool, one way."""
    written = {spec.name for spec in toolset.tools}
    generated = [tool_spec(tool) for tool in declared(toolset.name)]
    twice = sorted(written & {spec.name for spec in generated})
    if twice:
        raise ValueError(
            f"toolset {toolset.name}: {', '.join(twice)} is declared by a verb and written by hand too"
        )
    at = len(toolset.tools) if toolset.declared_at is None else toolset.declared_at
    return Toolset(toolset.name, [*toolset.tools[:at], *generated, *toolset.tools[at:]])


def declared(toolset: str) -> list[Tool]:
    """The tools the verbs declare for ``toolset``, in the order the verbs were declared."""
    return [tool for tool in TOOLS.values() if tool.toolset == toolset]


def tool_spec(tool: Tool) -> ToolSpec:
    """The MCP tool of one declaration (see the module's docstring)."""
    verb = VERBS[tool.verb]
    presenter = _presenter(tool, verb)
    params = _parameters(tool, verb, presenter)
    confirm = tool.confirm
    filled = {"label": tool.name} if "label" in verb.signature.parameters else {}
    feeds_notify = "notify" in verb.callbacks
    feeds_progress = waits_itself(verb)
    waits = presenter.waits and not feeds_progress

    async def run(call: ToolCall, **arguments: Any) -> Result:  # Any: mcp SDK, its validated JSON
        wait = bool(arguments.pop("wait", True)) if waits else False
        extra: dict[str, object] = {"notify": call.notify} if feeds_notify else {}
        if feeds_progress:
            extra["on_progress"] = call.progress
        if confirm is not None:
            extra[confirm.into] = confirmed(arguments.pop(ANSWER, None))
        for name, takes in tool.takes.items():
            given = arguments.pop(takes.name, None)
            extra[name] = None if given is None else takes.convert(given)
        result = await verb.method(call.commander, call.caller, **arguments, **filled, **extra)
        return await presenter.present(call, result, tool, arguments, wait)

    run.__name__ = run.__qualname__ = tool.name
    run.__doc__ = tool.description or _summary(verb.declared.__doc__)
    run.__signature__ = inspect.Signature(params, return_annotation=presenter.out)  # type: ignore[attr-defined]
    run.__annotations__ = {p.name: p.annotation for p in params} | {"return": presenter.out}
    return ToolSpec(
        fn=run,
        name=tool.name,
        title=None,
        annotations=annotations_of(
            read_only=tool.read_only, destructive=tool.destructive, idempotent=tool.idempotent
        ),
        advertise={name: dict(schema) for name, schema in tool.advertise.items()},
    )


def _presenter(tool: Tool, verb: Verb) -> Presenter:
    """How the tool presents its verb's result; a declaration no tool can present is refused here."""
    presenter = PRESENTERS.get(verb.result)
    if presenter is None:
        known = ", ".join(sorted(t.__name__ for t in PRESENTERS))
        raise TypeError(
            f"tool {tool.name}: a declared tool presents one of {known}, not {verb.result.__name__}"
        )
    if presenter.needs_says and tool.says is None:
        raise TypeError(f"tool {tool.name}: an instant command's tool needs says= (its result's text)")
    if waits_itself(verb) and not presenter.waits:
        raise TypeError(f"tool {tool.name}: a verb that waits itself (on_progress) returns an operation")
    unfed = verb.callbacks - CALLBACKS
    if unfed:
        raise TypeError(f"tool {tool.name}: no tool can feed the verb's callbacks {', '.join(sorted(unfed))}")
    return presenter


def _parameters(tool: Tool, verb: Verb, presenter: Presenter) -> list[inspect.Parameter]:
    """The tool's parameters: its ``ToolCall``, a human's answer (``confirm``), the verb's own after
    ``caller`` (in the form ``takes`` says; minus those filled, omitted or answered), then ``wait``."""
    hints = typing.get_type_hints(verb.declared, include_extras=True)
    answered = () if tool.confirm is None else (tool.confirm.into,)
    params = [inspect.Parameter("call", inspect.Parameter.POSITIONAL_OR_KEYWORD, annotation=ToolCall)]
    if tool.confirm is not None:  # no default: first, after the ToolCall
        params.append(answer_parameter(verb, tool.confirm))
    for name, param in list(verb.signature.parameters.items())[2:]:  # after self, caller
        if param.kind is not inspect.Parameter.POSITIONAL_OR_KEYWORD:
            continue  # the callbacks (keyword-only)
        if name in FILLED or name in tool.omit or name in answered:
            if param.default is inspect.Parameter.empty:
                raise TypeError(f"tool {tool.name}: omitted parameter {name} of {verb.name} has no default")
            continue
        takes = tool.takes.get(name)
        if takes is None:
            params.append(param.replace(annotation=hints[name]))
        else:
            params.append(param.replace(name=takes.name, annotation=takes.annotation))
    if presenter.waits and not waits_itself(verb):
        params.append(
            inspect.Parameter("wait", inspect.Parameter.POSITIONAL_OR_KEYWORD, default=True, annotation=Wait)
        )
    return params


def _summary(doc: str | None) -> str:
    """A docstring's first paragraph: the tool's description (the rest is for developers)."""
    return inspect.cleandoc(doc or "").split("\n\n", 1)[0]


__all__ = ["complete", "declared", "tool_spec"]
