"""Flight toolset: arm, takeoff, land, hold, return, kill, flight mode."""

from __future__ import annotations

from typing import Annotated, Any

from mcp.server.mcpserver import Context, Elicit, ElicitationResult, Resolve
from mcp.server.mcpserver.exceptions import ToolError
from pydantic import BaseModel, Field

from gateway.errors import GatewayError, InvalidArgument, SafetyRefusal
from gateway.fleet.modes import LAUNCHING_MODES
from gateway.fleet.operations import LandingTracker, TakeoffTracker, is_landed_and_disarmed, position, value
from gateway.mcp.access import FleetAccess
from gateway.mcp.results import ActionOut, OperationOut
from gateway.mcp.toolkit import DroneId, Toolset, Wait, check_drone_id, current_call

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


@toolset.tool(idempotent=True)
async def arm_drone(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ActionOut:
    """Arm the motors (switches to GUIDED first). takeoff arms by itself."""
    v = await fa.ready_to_arm(drone_id, ctx)
    fa.safety.check_arm(fa.context(v))
    await v.arm()
    return ActionOut(drone_id=drone_id, action="arm", message="armed").say(f"{drone_id} armed")


@toolset.tool(idempotent=True)
async def disarm_drone(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ActionOut:
    """Disarm the motors; only on the ground."""
    v = fa.ready(drone_id)
    if value(v, "in_air"):
        raise InvalidArgument(f"{drone_id} is in the air; call land first (disarm only works on the ground)")
    fa.safety.check_actuation(fa.context(v))
    await v.disarm()
    sup = await fa.operations.supersede(drone_id, "disarm_drone")
    return ActionOut(
        drone_id=drone_id, action="disarm", message="disarmed", superseded_operation=sup and sup.id
    ).say(f"{drone_id} disarmed")


@toolset.tool()
async def takeoff(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    altitude_m: Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False, description="m above home")],
    wait: Wait = True,
) -> OperationOut:
    """Arm if needed and climb to altitude_m above home; done when reached."""
    v = await fa.ready_to_arm(drone_id, ctx)
    fa.guard_takeoff(v, "takeoff")
    if value(v, "in_air"):
        pos = position(v)
        alt = f" at {pos[2]:.1f} m" if pos else ""
        raise InvalidArgument(f"{drone_id} is already flying{alt}; use go_to_location to change altitude")
    ctx_v = fa.context(v)
    fa.safety.check_actuation(ctx_v)
    fa.safety.check_takeoff(ctx_v, altitude_m)
    return await fa.run(
        ctx,
        v,
        TakeoffTracker(altitude_m),
        lambda: v.takeoff(altitude_m),
        {"altitude_m": altitude_m},
        wait,
        "takeoff",
    )


@toolset.tool(idempotent=True)
async def land(fa: FleetAccess, ctx: Context, drone_id: DroneId, wait: Wait = True) -> OperationOut:
    """Land where the drone is; done when landed and disarmed."""
    v = fa.ready(drone_id)
    if is_landed_and_disarmed(v):
        raise InvalidArgument(f"{drone_id} is already on the ground and disarmed")
    fa.safety.check_actuation(fa.context(v))
    return await fa.run(ctx, v, LandingTracker(kind="land"), v.land, {}, wait, "land")


@toolset.tool(idempotent=True)
async def return_to_launch(
    fa: FleetAccess, ctx: Context, drone_id: DroneId, wait: Wait = True
) -> OperationOut:
    """Fly home (RTL) and land; done when landed and disarmed."""
    v = fa.ready(drone_id)
    fa.require_airborne(v, "return_to_launch")
    fa.safety.check_actuation(fa.context(v))
    return await fa.run(
        ctx, v, LandingTracker(kind="return_to_launch"), v.return_to_launch, {}, wait, "return_to_launch"
    )


async def hold(fa: FleetAccess, drone_id: str, action: str) -> ActionOut:
    """GUIDED reposition to the current position (never LOITER/ALT_HOLD, which sink without RC)."""
    v = fa.ready(drone_id)
    fa.require_airborne(v, action)
    fa.safety.check_actuation(fa.context(v))
    await v.hold()
    sup = await fa.operations.supersede(drone_id, action)
    pos = position(v)
    where = f" at {pos[2]:.1f} m above home" if pos else ""
    stopped = f"; stopped {sup.kind} {sup.id}" if sup else ""
    return ActionOut(
        drone_id=drone_id,
        action=action,
        message=f"holding position{where}{stopped}",
        superseded_operation=sup and sup.id,
    ).say(f"{drone_id} holding position{where}{stopped}")


@toolset.tool(idempotent=True)
async def hold_position(fa: FleetAccess, ctx: Context, drone_id: DroneId) -> ActionOut:
    """Stop and hover where the drone is (GUIDED); ends the current action."""
    return await hold(fa, drone_id, "hold_position")


class KillConfirm(BaseModel):
    confirm: bool = Field(description="true to cut the motors in flight")


def _access(ctx: Context) -> FleetAccess:
    return ctx.mcp_server.fleet_access  # type: ignore[attr-defined]


def confirm_kill(drone_id: str, ctx: Context) -> Elicit[KillConfirm] | KillConfirm:
    """Authorize first (policy), then ask a human; on the ground no question (it only disarms)."""
    fa = _access(ctx)
    try:
        check_drone_id(drone_id)
        v = fa.ready(drone_id)
        if not value(v, "in_air"):
            return KillConfirm(confirm=True)
        fa.safety.check_kill(fa.context(v), via="mcp")
    except SafetyRefusal as exc:
        _mark("refused", exc.message)
        raise ToolError(f"Refused: {exc.message}") from None
    except GatewayError as exc:
        _mark("error", exc.message)
        raise ToolError(exc.message) from None
    pos = position(v)
    alt = f" at {pos[2]:.0f} m" if pos else ""
    return Elicit(f"Cut the motors of {drone_id} in flight{alt}? It will fall.", KillConfirm)


def _mark(outcome: Any, error: str) -> None:
    call = current_call.get()
    if call is not None:
        call.outcome, call.error = outcome, error


@toolset.tool(destructive=True)
async def kill_motors(
    fa: FleetAccess,
    ctx: Context,
    drone_id: DroneId,
    answer: Annotated[ElicitationResult[KillConfirm], Resolve(confirm_kill)],
) -> ActionOut:
    """EMERGENCY: cut motors at once (falls if flying). In flight needs policy + human confirmation."""
    data = getattr(answer, "data", None)
    if data is None or not data.confirm:
        raise SafetyRefusal(
            "kill_not_confirmed", f"kill_not_confirmed: kill of {drone_id} was not confirmed; nothing sent"
        )
    v = fa.ready(drone_id)
    in_air = bool(value(v, "in_air"))
    if in_air:
        fa.safety.check_kill(fa.context(v), via="mcp")
        await v.kill()
        message = "motors killed in flight"
    else:
        fa.safety.check_kill(fa.context(v), via="mcp")  # locks and simulators-only hold on the ground too
        await v.disarm()
        message = "on the ground: disarmed"
    sup = await fa.operations.supersede(drone_id, "kill_motors")
    return ActionOut(
        drone_id=drone_id, action="kill", message=message, superseded_operation=sup and sup.id
    ).say(f"{drone_id}: {message}")


@toolset.tool()
async def set_flight_mode(fa: FleetAccess, ctx: Context, drone_id: DroneId, mode: Mode) -> ActionOut:
    """Set the flight mode. HOLD = hover in place. Prefer land/return_to_launch (they track progress)."""
    v = fa.ready(drone_id)
    choice = v.resolve_mode(mode)
    if choice.requested == "HOLD":
        return await hold(fa, drone_id, "set_flight_mode HOLD")
    if choice.native in LAUNCHING_MODES:
        fa.guard_takeoff(v, f"set_flight_mode {choice.requested}")
    fa.safety.check_mode(fa.context(v), choice.requested)
    fa.safety.check_mode(fa.context(v), choice.native)
    await v.set_flight_mode(mode)
    sup = await fa.operations.supersede(drone_id, f"set_flight_mode {choice.requested}")
    named = choice.native if choice.native == choice.requested else f"{choice.requested} ({choice.native})"
    return ActionOut(
        drone_id=drone_id,
        action="set_flight_mode",
        message=f"mode {named}",
        superseded_operation=sup and sup.id,
    ).say(f"{drone_id} now in {named}")
