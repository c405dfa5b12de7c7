"""How a declared tool presents its verb's result, by the result's model: the structured output (and
the outputSchema) and the one line of text. A verb whose result model has no presenter here cannot
declare a tool (`gateway.mcp.declared.tool_spec` says so at import).

- `OperationView`: an `OperationOut`, after waiting (capped, with progress) when the caller asked (a
  verb that waits itself, taking ``on_progress``, is fed the progress instead: `waits_itself`);
- `FleetView`: a `FleetOut` the same way (`monitor_fleet` continues it);
- `ActionResult`: an `ActionOut` whose text is the declaration's ``says``;
- `FleetHoldResult`: a `FleetHoldOut` naming who holds, who failed, who was not sent the hold;
- `ParamValue`: a `ParamOut` with the vehicle-sent name cleaned, its text the declaration's ``says``.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping
from dataclasses import dataclass

from pydantic import BaseModel

from gateway.fleet.commands.command_core import VERBS, Tool
from gateway.fleet.operations.routing import Verb
from gateway.fleet.operations.views import ActionResult, FleetHoldResult, FleetView, OperationView, ParamValue
from gateway.fleet.vehicles.vehicle_text import clean_vehicle_text
from gateway.mcp.access import ToolCall
from gateway.mcp.results import ActionOut, OperationOut, ParamOut, Result, action_out

#: the verb's result, the tool's declaration, its arguments (as the tool got them) and whether to wait
Present = Callable[[ToolCall, BaseModel, Tool, Mapping[str, object], bool], Awaitable[Result]]


@dataclass(frozen=True)
class Presenter:
    out: type[Result]
    present: Present
    #: the tool takes ``wait`` (wait until done, capped)
    waits: bool = False
    #: the declaration must give ``says`` (the text)
    needs_says: bool = False


# --- fleet operations ----------------------------------------------------------------------------------


class FleetOut(FleetView, Result):
    """A fleet operation: per-drone outcomes in ``drones``; 'running' means call monitor_fleet."""


class FleetHoldOut(FleetHoldResult, Result):
    """Which drones hold now, which failed, which were not sent the hold."""


def fleet_out(view: FleetView) -> FleetOut:
    out = FleetOut(**view.model_dump())
    rows = "; ".join(f"{m['drone_id']} {m['status']}{_told(m)}" for m in view.drones)
    skipped = f"; not sent: {', '.join(str(u['drone_id']) for u in view.not_sent)}" if view.not_sent else ""
    if view.running:
        eta = f", ETA {view.eta_s:.0f} s" if view.eta_s is not None else ""
        text = (
            f"{view.kind} {view.operation_id} still running ({view.progress:.0%}{eta}, phase "
            f"{view.phase} of {len(view.phases)}): {rows}{skipped}. Call "
            f"monitor_fleet(operation_id='{view.operation_id}') to keep waiting; send no other moves to "
            "these drones meanwhile."
        )
    else:
        text = f"{view.kind} {view.operation_id} {view.status}: {view.message}. {rows}{skipped}"
    return out.say(text)


def _told(member: Mapping[str, object]) -> str:
    """What one drone was told, in words: its altitude, the altitude it transits at, where it returns."""
    parts = []
    if member.get("transit_alt_m") is not None:
        parts.append(f"transit at {member['transit_alt_m']:g} m")
    if member.get("target_alt_m") is not None:
        parts.append(f"to {member['target_alt_m']:g} m")
    if member.get("rtl_alt_m") is not None:
        parts.append(f"returning at {member['rtl_alt_m']:g} m")
    return f" ({', '.join(parts)})" if parts else ""


async def finish_fleet(call: ToolCall, view: FleetView, wait: bool) -> FleetOut:
    """Wait for the fleet operation (capped, with progress) if asked, then present it."""
    if wait and view.running:

        async def progress(v: FleetView) -> None:
            await call.ctx.report_progress(round(v.progress, 3), 1.0, v.message)

        view = await call.commander.wait_fleet(
            view.operation_id, call.settings.mcp_wait_cap_s, progress, view.not_sent
        )
    return fleet_out(view)


def fleet_hold_out(result: FleetHoldResult) -> FleetHoldOut:
    text = f"holding: {', '.join(result.held) or 'none'}"
    if result.failed:
        text += "; failed: " + "; ".join(f"{f['drone_id']}: {f['message']}" for f in result.failed)
    if result.not_sent:
        text += "; not sent: " + "; ".join(f"{u['drone_id']}: {u['message']}" for u in result.not_sent)
    return FleetHoldOut(**result.model_dump()).say(text)


# --- parameters ------------------------------------------------------------------------------------------


def vehicle_param_name(name: str) -> str:
    """A parameter name as the vehicle sent it (MAVLink allows 16 characters of anything), made safe."""
    return clean_vehicle_text(name, limit=16)


# --- the table -------------------------------------------------------------------------------------------


def _text(tool: Tool, fields: Mapping[str, object], result: ActionResult | None = None) -> str:
    says = tool.says
    if callable(says):
        assert result is not None, f"tool {tool.name}: a function as says= presents an ActionResult only"
        return says(result)
    assert says is not None
    return says.format_map(dict(fields))


def waits_itself(verb: Verb) -> bool:
    """A verb that waits for its operation itself (it takes ``on_progress``, as ``monitor`` does): its
    tool offers no ``wait``, feeds the client's progress to the verb, and names the operation by its
    own kind (the tool reports an operation it did not start)."""
    return "on_progress" in verb.callbacks


async def _operation(
    call: ToolCall, result: BaseModel, tool: Tool, arguments: Mapping[str, object], wait: bool
) -> Result:
    assert isinstance(result, OperationView)
    return await call.finish(result, wait, None if waits_itself(VERBS[tool.verb]) else tool.name)


async def _action(
    call: ToolCall, result: BaseModel, tool: Tool, arguments: Mapping[str, object], wait: bool
) -> Result:
    assert isinstance(result, ActionResult)
    return action_out(result, _text(tool, result.model_dump() | dict(arguments), result))


async def _fleet(
    call: ToolCall, result: BaseModel, tool: Tool, arguments: Mapping[str, object], wait: bool
) -> Result:
    assert isinstance(result, FleetView)
    return await finish_fleet(call, result, wait)


async def _fleet_hold(
    call: ToolCall, result: BaseModel, tool: Tool, arguments: Mapping[str, object], wait: bool
) -> Result:
    assert isinstance(result, FleetHoldResult)
    return fleet_hold_out(result)


async def _param(
    call: ToolCall, result: BaseModel, tool: Tool, arguments: Mapping[str, object], wait: bool
) -> Result:
    assert isinstance(result, ParamValue)
    out = ParamOut(
        drone_id=result.drone_id, name=vehicle_param_name(result.name), value=result.value, type=result.type
    )
    return out.say(_text(tool, dict(arguments) | out.model_dump()))


PRESENTERS: dict[type[BaseModel], Presenter] = {
    OperationView: Presenter(OperationOut, _operation, waits=True),
    FleetView: Presenter(FleetOut, _fleet, waits=True),
    ActionResult: Presenter(ActionOut, _action, needs_says=True),
    FleetHoldResult: Presenter(FleetHoldOut, _fleet_hold),
    ParamValue: Presenter(ParamOut, _param, needs_says=True),
}

__all__ = [
    "PRESENTERS",
    "FleetHoldOut",
    "FleetOut",
    "Presenter",
    "finish_fleet",
    "fleet_hold_out",
    "fleet_out",
    "vehicle_param_name",
    "waits_itself",
]
