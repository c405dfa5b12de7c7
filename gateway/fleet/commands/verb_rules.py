"""The small flight rules and deadlines the verbs judge a context with: who may ask, whether the drone
flies, an altitude in the caller's frame as metres above home, and how long an arming command waits.
Declaring and routing verbs is `gateway.fleet.commands.command_core`; the verbs are `drone_verbs`,
`navigation_verbs`, `mission_verbs`, `fleet_verbs`, `operator_verbs` and `zone_verbs`."""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable

from gateway.config import Settings
from gateway.errors import InvalidArgument, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.commands.arguments import AltFrame
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.policy.safety_rules import Rule, refuse
from gateway.fleet.vehicles.protocols import FlyingVehicle, Notify


def operator_only(caller: Caller, what: str) -> None:
    """Refused (rule operator_lock) unless an operator asks (REST, the console): ``what`` says what
    only an operator may do, and why agents may not."""
    if not caller.is_operator:
        raise refuse(Rule.OPERATOR_LOCK, f"only an operator may {what}", via=caller.via)


def require_airborne(ctx: VehicleContext, action: str) -> None:
    if not (ctx.in_air and ctx.armed):
        raise VehicleNotReady(
            f"{ctx.vehicle_id} is on the ground; {action} needs a flying drone. Call takeoff first."
        )


def relative_alt(ctx: VehicleContext, alt_m: float, alt_frame: AltFrame) -> float:
    """A caller's altitude -> metres above home (the frame conversion lives in geo)."""
    geo.check_finite("alt_m", alt_m)
    if alt_frame == "home":
        return alt_m
    if ctx.home is None:
        raise VehicleNotReady(f"{ctx.vehicle_id} has no home position yet; cannot convert an AMSL altitude")
    relative = geo.amsl_to_relative(alt_m, ctx.home[2])
    if relative <= 0:  # a small model set alt_frame='amsl' whenever it had coordinates
        raise InvalidArgument(
            f"alt_frame='amsl' means above sea level (home is {ctx.home[2]:.0f} m), so alt_m={alt_m:g} "
            f"is {-relative:.0f} m below home; leave alt_frame out for metres above home "
            f"(e.g. alt_m={alt_m:g})"
        )
    return relative


def arming_deadline(settings: Settings) -> float:
    """When a command that arms (arm, takeoff, fleet takeoff) stops waiting for its drones to be able
    to arm: one deadline, the MCP wait cap from now, for initialising and arming together."""
    return asyncio.get_running_loop().time() + settings.mcp_wait_cap_s


def left(deadline: float) -> float:
    return max(0.0, deadline - asyncio.get_running_loop().time())


def wait_initialised(deadline: float, notify: Notify | None) -> Callable[[FlyingVehicle], Awaitable[None]]:
    """A ``prepare`` step of the pass: wait until ``deadline`` for a drone still initialising,
    ``notify`` hearing what it waits for. A drone that is still initialising then is left to its arming
    attempt, whose refusal says why in the autopilot's words; one in no state to arm raises
    VehicleNotReady naming why."""

    async def prepare(vehicle: FlyingVehicle) -> None:
        await vehicle.wait_initialised(left(deadline), notify)

    return prepare
