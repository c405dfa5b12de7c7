"""Flight toolset: arm, takeoff, land, hold, return, flight mode (declared with their verbs) and the
kill, which asks a human first."""

from __future__ import annotations

from typing import Annotated, Any

from mcp.server.elicitation import AcceptedElicitation
from mcp.server.mcpserver import Context, Elicit, ElicitationResult, Resolve
from mcp.server.mcpserver.exceptions import ToolError
from pydantic import BaseModel, Field

from gateway.errors import GatewayError, SafetyRefusal
from gateway.mcp.access import ToolCall, current_call
from gateway.mcp.results import ActionOut, action_out
from gateway.mcp.toolkit import DroneId, Toolset, check_drone_id

toolset = Toolset("flight")

# here: the tools the verbs declare for this toolset (@command(tool=Tool(..., "flight")), mostly in
# gateway/fleet/commands/drone_verbs.py), built by gateway/mcp/declared.py (the hand-written: this module)
toolset.declared_here()


class KillConfirm(BaseModel):
    confirm: bool = Field(description="true to cut the motors in flight")


def confirm_kill(drone_id: str, ctx: Context[Any, Any]) -> Elicit[KillConfirm] | KillConfirm:
    """Authorize first (policy), then ask a human; on the ground no question (it only disarms). Runs
    again on every round of the confirmation, so it changes nothing."""
    call = ToolCall.of(ctx)
    try:
        check_drone_id(drone_id)
        drone_id = call.commander.canonical_id(drone_id)
        if not call.commander.kill_needs_confirmation(call.caller, drone_id):
            return KillConfirm(confirm=True)
    except SafetyRefusal as exc:
        _mark("refused", exc.message)
        raise ToolError(f"Refused: {exc.message}") from None
    except GatewayError as exc:
        _mark("error", exc.message)
        raise ToolError(exc.message) from None
    alt = call.commander.vehicle(drone_id).telemetry.fresh("position")
    where = f" at {alt.rel_alt_m:.0f} m" if alt is not None else ""
    return Elicit(f"Cut the motors of {drone_id} in flight{where}? It will fall.", KillConfirm)


def _mark(outcome: Any, error: str) -> None:
    info = current_call.get()
    if info is not None:
        info.outcome, info.error = outcome, error


@toolset.tool(destructive=True)
async def kill_motors(
    call: ToolCall,
    drone_id: DroneId,
    answer: Annotated[ElicitationResult[KillConfirm], Resolve(confirm_kill)],
) -> ActionOut:
    """EMERGENCY: cut motors at once (falls if flying). In flight needs policy + human confirmation."""
    confirmed = isinstance(answer, AcceptedElicitation) and answer.data.confirm
    result = await call.commander.kill(call.caller, drone_id, confirmed=confirmed)
    return action_out(result, f"{drone_id}: {result.message}")
