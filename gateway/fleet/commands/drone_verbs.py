"""The flight commands on one drone: arm, disarm, takeoff, land, return, hold, kill, mode.

Each is a declaration run by the one pass (`gateway.fleet.commands.command_pass.CommandPass.run`): it gives
the
pass its checks and what to send (``decide``, judged on the one `VehicleContext` the pass builds), and
the pass resolves the drone, applies the policy, sends under the drone's command lock, tracks and
audits. Only kill sends without the lock (see `kill`). Messages name what to do next; ``label`` is how
the caller names the command (its MCP tool name), used in those messages and in the superseded
operation's reason. Every command on one drone is ``@routed``: on a cluster node it runs on the node
that owns the drone. Navigation is `navigation_verbs`, missions and parameters `mission_verbs`.
"""

from __future__ import annotations

import contextlib
from typing import Annotated

from pydantic import Field

from gateway.errors import CommandFailed, InvalidArgument, StateConflict
from gateway.fleet.commands.arguments import DroneId, FlightMode
from gateway.fleet.commands.command_core import Confirm, OperationDesk, Tool, command, routed
from gateway.fleet.commands.command_pass import CommandPass, Need, Order
from gateway.fleet.commands.mission_start import resume_item, verify_held
from gateway.fleet.commands.routes import Route, TakeoffIn
from gateway.fleet.commands.verb_rules import arming_deadline, left, require_airborne, wait_initialised
from gateway.fleet.dialects.modes import ModeChoice
from gateway.fleet.operations.trackers import LandingTracker, TakeoffTracker
from gateway.fleet.operations.views import ActionResult, OperationView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.vehicles.protocols import FlyingVehicle, Notify, VehicleView
from gateway.fleet.vehicles.readings import is_landed_and_disarmed, position, vehicle_context


def _mode_text(result: ActionResult) -> str:
    """The tool's line after a mode change: HOLD is the safe hold, which says where it holds."""
    if "mode" not in result.facts:
        return f"{result.drone_id} {result.message}"
    return f"{result.drone_id} now in {result.facts['mode']}"


class FlightVerbs:
    """The flight commands on one drone."""

    def __init__(self, commands: CommandPass, desk: OperationDesk) -> None:
        self.commands = commands
        self.desk = desk

    @command(tool=Tool("arm_drone", "flight", idempotent=True, says="{drone_id} armed"))
    @routed
    async def arm(self, caller: Caller, drone_id: DroneId, *, notify: Notify | None = None) -> ActionResult:
        """Arm the motors (switches to GUIDED first). takeoff arms by itself.

        A drone still initialising is waited for, within the wait cap (see `Vehicle.arm`)."""
        deadline = arming_deadline(self.commands.settings)

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_arm(ctx, caller.policy_via)
            return Order(lambda: vehicle.arm(left(deadline), notify))

        await self.commands.run(
            caller,
            drone_id,
            "arm_drone",
            decide,
            need=Need.ANY,
            prepare=wait_initialised(deadline, notify),
        )
        return ActionResult(drone_id=drone_id, action="arm", message="armed")

    @command(tool=Tool("disarm_drone", "flight", idempotent=True, says="{drone_id} disarmed"))
    @routed
    async def disarm(self, caller: Caller, drone_id: DroneId, label: str = "disarm_drone") -> ActionResult:
        """Disarm the motors; only on the ground."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            if ctx.in_air:
                raise InvalidArgument(
                    f"{drone_id} is in the air; call land first (disarm only works on the ground)"
                )
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            return Order(vehicle.disarm, ends_operation=True)

        sent = await self.commands.run(caller, drone_id, label, decide, safety_action=True)
        return ActionResult(
            drone_id=drone_id, action="disarm", message="disarmed", superseded_operation=sent.ended_id
        )

    @command(
        tool=Tool("takeoff", "flight"),
        route=Route("takeoff", "Take off (operator)", body=TakeoffIn, renames={"alt_rel_m": "alt_m"}),
    )
    @routed
    async def takeoff(
        self,
        caller: Caller,
        drone_id: DroneId,
        alt_m: Annotated[float, Field(gt=0, le=10_000, allow_inf_nan=False, description="m above home")],
        *,
        notify: Notify | None = None,
    ) -> OperationView:
        """Arm if needed and climb to alt_m above home; done when reached."""
        deadline = arming_deadline(
            self.commands.settings
        )  # initialising and arming wait together, within the cap

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            if ctx.in_air:
                raise InvalidArgument(
                    _already_flying(drone_id, ctx.position[2] if ctx.position else None, alt_m)
                )
            self.commands.safety.check_takeoff(ctx, alt_m, caller.policy_via)
            return Order(
                lambda: vehicle.takeoff(alt_m, left(deadline), notify),
                TakeoffTracker(alt_m),
                {"alt_m": alt_m},
            )

        sent = await self.commands.run(
            caller,
            drone_id,
            "takeoff",
            decide,
            need=Need.ANY,
            prepare=wait_initialised(deadline, notify),
        )
        return sent.view()

    @command(tool=Tool("land", "flight", idempotent=True))
    @routed
    async def land(self, caller: Caller, drone_id: DroneId) -> OperationView:
        """Land where the drone is; done when landed and disarmed."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            if is_landed_and_disarmed(vehicle):
                raise StateConflict(
                    f"{drone_id} is already on the ground and disarmed: nothing to do, it is landed as "
                    "asked (do not take it off again unless the request says so)"
                )
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            return Order(vehicle.land, LandingTracker(kind="land"))

        sent = await self.commands.run(
            caller, drone_id, "land", decide, need=Need.RECOVERY, safety_action=True
        )
        return sent.view()

    @command(tool=Tool("return_to_launch", "flight", idempotent=True))
    @routed
    async def return_to_launch(self, caller: Caller, drone_id: DroneId) -> OperationView:
        """Fly home (RTL) and land; done when landed and disarmed."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            if not caller.is_operator:
                require_airborne(ctx, "return_to_launch")
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            return Order(vehicle.return_to_launch, LandingTracker(kind="return_to_launch"))

        sent = await self.commands.run(
            caller, drone_id, "return_to_launch", decide, need=Need.RECOVERY, safety_action=True
        )
        return sent.view()

    @command(
        tool=(
            Tool("hold_position", "flight", idempotent=True, says="{drone_id} {message}"),
            Tool(
                "hold_mission_position",
                "mission",
                idempotent=True,
                says="{drone_id} {message}",
                description="Hover in place (GUIDED) during a mission; resume_mission continues.",
            ),
        )
    )
    @routed
    async def hold(self, caller: Caller, drone_id: DroneId, label: str = "hold_position") -> ActionResult:
        """Stop and hover where the drone is (GUIDED); ends the current action.

        A GUIDED reposition to the current position (never LOITER/ALT_HOLD, which sink without RC)."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            if not caller.is_operator:
                require_airborne(ctx, label)
            self.commands.safety.check_actuation(ctx, caller.policy_via)
            return Order(vehicle.hold, ends_operation=True, commands="hold")

        sent = await self.commands.run(
            caller, drone_id, label, decide, need=Need.RECOVERY, safety_action=True
        )
        pos = position(sent.vehicle)
        where = f" at {pos[2]:.1f} m above home" if pos else ""
        stopped = f"; stopped {sent.ended.kind} {sent.ended.id}" if sent.ended else ""
        return ActionResult(
            drone_id=drone_id,
            action=label,
            message=f"holding position{where}{stopped}",
            superseded_operation=sent.ended_id,
        )

    def kill_needs_confirmation(self, caller: Caller, drone_id: str) -> bool:
        """Whether a kill by this caller must first be confirmed by a human: an agent's kill of an
        airborne drone, when the policy allows agents to kill at all (else it is refused here, before
        anyone is asked). Judges only: nothing is sent."""
        vehicle = self.commands.registry.get(drone_id)
        if not caller.is_operator:
            vehicle.require_ready()
        return self.commands.safety.check_kill(vehicle_context(vehicle), caller.policy_via)

    def kill_question(self, caller: Caller, drone_id: str) -> str | None:
        """What a human is asked before this caller's kill (None: no question, as on the ground, where
        it only disarms). Judges only; a kill the policy refuses raises here, before anyone is asked."""
        if not self.kill_needs_confirmation(caller, drone_id):
            return None
        position = self.commands.registry.get(drone_id).telemetry.fresh("position")
        where = f" at {position.rel_alt_m:.0f} m" if position is not None else ""
        return f"Cut the motors of {drone_id} in flight{where}? It will fall."

    @command(
        tool=Tool(
            "kill_motors",
            "flight",
            destructive=True,
            says="{drone_id}: {message}",
            confirm=Confirm(question="kill_question", into="confirmed"),
        ),
        route=Route("kill", "Stop the motors at once (operator)", fills={"confirmed": True}),
    )
    @routed
    async def kill(self, caller: Caller, drone_id: DroneId, confirmed: bool = False) -> ActionResult:
        """EMERGENCY: cut motors at once (falls if flying). In flight needs policy + human confirmation.

        An agent's: only with ``confirmed`` (a human said yes), and on the ground it
        only disarms. An operator's: at once, wherever the drone is.

        The one command sent without the drone's command lock: the lock is held while a command is
        sent, and a send can last long (a takeoff or mission start whose arming the autopilot refuses
        while it initialises retries for up to a minute; a mission upload takes up to 30 s). Cutting
        the motors must not wait behind that. It ends whatever operation is recorded; a command still
        being sent may complete after it (nothing can call back what is already on its way)."""
        said: list[str] = []

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_kill_confirmed(ctx, confirmed, caller.policy_via)
            self.commands.safety.check_kill(
                ctx, caller.policy_via
            )  # locks and simulators-only hold on the ground too
            if caller.is_operator or ctx.airborne:
                said.append("motors killed in flight" if ctx.airborne else "motors killed")
                return Order(vehicle.kill)
            said.append("on the ground: disarmed")
            return Order(vehicle.disarm)

        await self.commands.run(
            caller, drone_id, "kill_motors", decide, need=Need.RECOVERY, safety_action=True, locked=False
        )
        sup = await self.commands.operations.supersede(drone_id, "kill_motors")
        self.commands.operations.forget(drone_id)
        return ActionResult(
            drone_id=drone_id,
            action="kill",
            message=said[0],
            superseded_operation=None if sup is None else sup.id,
        )

    @command(tool=Tool("set_flight_mode", "flight", says=_mode_text))
    @routed
    async def set_mode(self, caller: Caller, drone_id: DroneId, mode: FlightMode) -> ActionResult:
        """Set the flight mode. HOLD = hover in place. Prefer land/return_to_launch (they track progress).

        A common name (HOLD, RTL, LAND, MISSION...) or the autopilot's own; HOLD is the gateway's safe
        hold (`hold`)."""
        vehicle = self.commands.registry.get(drone_id)
        vehicle.require_ready()
        choice = vehicle.resolve_mode(mode)
        if choice.requested == "HOLD":
            return await self.hold(caller, drone_id, "set_flight_mode HOLD")
        label = f"set_flight_mode {choice.requested}"
        radius_m = await _pattern_radius(self.commands.registry.flown(drone_id), choice)

        async def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            self.commands.safety.check_mode(ctx, choice.requested, caller.policy_via)
            self.commands.safety.check_mode(ctx, choice.native, caller.policy_via)
            self.commands.safety.check_mode_choice(ctx, choice, caller.policy_via, radius_m)
            if _is_mode(vehicle, choice, "MISSION"):  # the autopilot flies the mission it holds
                starts = [1, resume_item(vehicle)] if ctx.airborne else [1]
                await verify_held(self.commands.safety, caller, vehicle, ctx, starts)
            commands, modes = _commanded(vehicle, choice)
            return Order(
                lambda: vehicle.set_flight_mode(mode), ends_operation=True, commands=commands, modes=modes
            )

        sent = await self.commands.run(
            caller, drone_id, label, decide, safety_action=_is_landing_mode(vehicle, choice)
        )
        named = (
            choice.native if choice.native == choice.requested else f"{choice.requested} ({choice.native})"
        )
        return ActionResult(
            drone_id=drone_id,
            action="set_flight_mode",
            message=f"mode {named}",
            superseded_operation=sent.ended_id,
            facts={"mode": named},
        )


async def _pattern_radius(vehicle: FlyingVehicle, choice: ModeChoice) -> float | None:
    """The radius in metres a pattern mode would fly (the first of its radius parameters the vehicle
    has), or None: not a pattern mode, or none could be read (the policy then refuses it in the air)."""
    for name, per_metre in choice.pattern_radius:
        try:
            value, _kind = await vehicle.get_param(name)
        except CommandFailed:
            continue
        return float(value) / per_metre
    return None


def _commanded(vehicle: VehicleView, choice: ModeChoice) -> tuple[str, frozenset[str] | None]:
    """What a mode change commands, for the takeover watch: the mission, return, landing or takeoff
    mode is judged as that operation is (the autopilot's own next modes included: PX4 holds after a
    mission), any other mode as itself."""
    for common, kind in (
        ("MISSION", "mission"),
        ("RTL", "return_to_launch"),
        ("LAND", "land"),
        ("TAKEOFF", "takeoff"),
    ):
        with contextlib.suppress(InvalidArgument):
            if vehicle.resolve_mode(common).native == choice.native:
                return kind, None
    return f"set_flight_mode {choice.native}", frozenset({choice.native})


def _is_mode(vehicle: VehicleView, choice: ModeChoice, common: str) -> bool:
    """Whether ``choice`` is the drone's ``common`` mode (e.g. MISSION: AUTO, AUTO.MISSION)."""
    with contextlib.suppress(InvalidArgument):
        return vehicle.resolve_mode(common).native == choice.native
    return False


def _is_landing_mode(vehicle: VehicleView, choice: ModeChoice) -> bool:
    """Whether ``choice`` is the drone's LAND or RTL mode, by whichever name it was asked for: a safety
    action, never refused by the takeoff guard."""
    for name in ("LAND", "RTL"):
        with contextlib.suppress(InvalidArgument):
            if vehicle.resolve_mode(name).native == choice.native:
                return True
    return False


def _already_flying(drone_id: str, alt_m: float | None, wanted_m: float) -> str:
    """The refusal of a takeoff in the air, naming the call that changes altitude, with its numbers
    (a small model read "use go_to_location to change altitude" and flew to latitude 0, longitude 0)."""
    if alt_m is None:
        return (
            f"{drone_id} is already flying; to change altitude use "
            f"move_to_relative(drone_id='{drone_id}', north_m=0, east_m=0, up_m=<metres up, negative down>)"
        )
    change = wanted_m - alt_m
    if abs(change) < 1.0:
        return f"{drone_id} already flies at {alt_m:.0f} m, the altitude asked for: nothing to do"
    verb = "climb" if change > 0 else "descend"
    return (
        f"{drone_id} already flies at {alt_m:.0f} m; to {verb} to {wanted_m:g} m use "
        f"move_to_relative(drone_id='{drone_id}', north_m=0, east_m=0, up_m={change:.0f})"
    )
