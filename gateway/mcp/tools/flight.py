"""Flight toolset: arm, takeoff, land, hold, return, kill, flight mode."""

from __future__ import annotations

from typing import Annotated, Any

from mcp.server.elicitation import AcceptedElicitation
from mcp.server.mcpserver import Context, Elicit, ElicitationResult, Resolve
from mcp.server.mcpserver.exceptions import ToolError
from pydantic import BaseModel, Field

from gateway.errors import GatewayError, SafetyRefusal
from gateway.fleet.views import ActionResult
from gateway.mcp.access import ToolCall, current_call
from gateway.mcp.results import ActionOut, OperationOut
from gateway.mcp.toolkit import DroneId, Toolset, Wait, check_drone_id

toolset = Toolset("flight")

Mode = Annotated[
    str,
    Field(
        description="HOLD, RTL, LAND, MISSION, GUIDED or TAKEOFF (mapped to the drone's autopilot), "
        "or one of its own modes",
        examples=["HOLD", "RTL", "LAND", "MISSION"],
        max_length=32,
    ),
]


def action_out(result: ActionResult, text: str) -> ActionOut:
    return ActionOut(
        drone_id=result.drone_id,
        action=result.action,
        message=result.message,
        superseded_operation=result.superseded_operation,
    ).say(text)


def hold_out(result: ActionResult) -> ActionOut:
    return action_out(result, f"{result.drone_id} {result.message}")


@toolset.tool(idempotent=True)
async def arm_drone(call: ToolCall, drone_id: DroneId) -> ActionOut:
    """Arm the motors (switches to GUIDED first). takeoff arms by itself."""
    result = await call.commander.arm(call.caller, drone_id, notify=call.notify)
    return action_out(result, f"{drone_id} armed")


@toolset.tool(idempotent=True)
async def disarm_drone(call: ToolCall, drone_id: DroneId) -> ActionOut:
    """Disarm the motors; only on the ground."""
    return action_out(await call.commander.disarm(call.caller, drone_id), f"{drone_id} disarmed")


@toolset.tool()
async def takeoff(
    call: ToolCall,
    drone_id: DroneId,
    altitude_m: Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False, description="m above home")],
    wait: Wait = True,
) -> OperationOut:
    """Arm if needed and climb to altitude_m above home; done when reached."""
    op = await call.commander.takeoff(call.caller, drone_id, altitude_m, notify=call.notify)
    return await call.finish(op, wait, "takeoff")


@toolset.tool(idempotent=True)
async def land(call: ToolCall, drone_id: DroneId, wait: Wait = True) -> OperationOut:
    """Land where the drone is; done when landed and disarmed."""
    return await call.finish(await call.commander.land(call.caller, drone_id), wait, "land")


@toolset.tool(idempotent=True)
async def return_to_launch(call: ToolCall, drone_id: DroneId, wait: Wait = True) -> OperationOut:
    """Fly home (RTL) and land; done when landed and disarmed."""
    op = await call.commander.return_to_launch(call.caller, drone_id)
    return await call.finish(op, wait, "return_to_launch")


@toolset.tool(idempotent=True)
async def hold_position(call: ToolCall, drone_id: DroneId) -> ActionOut:
    """Stop and hover where the drone is (GUIDED); ends the current action."""
    return hold_out(await call.commander.hold(call.caller, drone_id, "hold_position"))


class KillConfirm(BaseModel):
    confirm: bool = Field(description="true to cut the motors in flight")


def confirm_kill(drone_id: str, ctx: Context[Any, Any]) -> Elicit[KillConfirm] | KillConfirm:
    """Authorize first (policy), then ask a human; on the ground no question (it only disarms). Runs
    again on every round of the confirmation, so it changes nothing."""
    call = ToolCall.of(ctx)
    try:
        check_drone_id(drone_id)
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


@toolset.tool()
async def set_flight_mode(call: ToolCall, drone_id: DroneId, mode: Mode) -> ActionOut:
    """Set the flight mode. HOLD = hover in place. Prefer land/return_to_launch (they track progress)."""
    result = await call.commander.set_mode(call.caller, drone_id, mode)
    if "mode" not in result.facts:  # HOLD: the gateway's safe hold
        return hold_out(result)
    return action_out(result, f"{drone_id} now in {result.facts['mode']}")
