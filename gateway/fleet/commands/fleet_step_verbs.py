"""One drone's step of a fleet operation, as one run of the pass on the node that owns the drone: the
fleet operations (`gateway.fleet.operations.fleet_ops`) run each step here, or on the drone's owner in
a cluster through the routed verbs ``run_step`` / ``hold_step``."""

from __future__ import annotations

from gateway.fleet.commands.command_core import OperationDesk, routed
from gateway.fleet.commands.command_pass import CommandPass, Need, Order
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.operations.fleet_steps import StepSpec, build_step
from gateway.fleet.operations.operation_state import Operation
from gateway.fleet.operations.views import ActionResult, OperationView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.vehicles.protocols import FlyingVehicle


class FleetStepVerbs:
    """The steps of the fleet commands (`gateway.fleet.commands.fleet_verbs`) on one drone each."""

    def __init__(self, commands: CommandPass, desk: OperationDesk, fleet: FleetOperations) -> None:
        self.commands = commands
        self.desk = desk
        self.registry = commands.registry
        fleet.run_steps_with(self.step_here, self.hold_here)

    async def step_here(self, caller: Caller, drone_id: str, spec: StepSpec) -> Operation:
        """One drone's step of a fleet operation (`gateway.fleet.operations.fleet_steps.build_step`), as
        one run of the pass on this node: the takeover lock, the takeoff guard (named by the step's ``guard``;
        none for a recovery step) before and inside the command lock, then the step's operation."""
        guard = spec.get("guard")
        action = str(guard or spec.get("kind") or "fleet step")

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            step = build_step(vehicle, spec)
            return Order(step.send, step.tracker, step.params)

        sent = await self.commands.run(
            caller, drone_id, action, decide, need=Need.ANY, safety_action=not guard, audited=False
        )
        assert sent.operation is not None
        return sent.operation

    async def hold_here(self, caller: Caller, drone_id: str, reason: str) -> Operation | None:
        """Hold a drone whose fleet operation was stopped (one run of the pass); the operation it ended."""

        def decide(vehicle: FlyingVehicle, ctx: VehicleContext) -> Order:
            return Order(vehicle.hold, ends_operation=True, commands="hold")

        sent = await self.commands.run(
            caller, drone_id, reason, decide, need=Need.ANY, safety_action=True, audited=False
        )
        return sent.ended

    @routed
    async def run_step(self, caller: Caller, drone_id: str, spec: StepSpec) -> OperationView:
        """Start one drone's step here, for the node coordinating the fleet operation (`step_here`)."""
        op = await self.step_here(caller, drone_id, spec)
        return OperationView.of(op, self.registry.get(drone_id))

    @routed
    async def hold_step(self, caller: Caller, drone_id: str, reason: str) -> ActionResult:
        """Hold a drone whose fleet operation (coordinated by another node) was stopped."""
        sup = await self.hold_here(caller, drone_id, reason)
        return ActionResult(
            drone_id=drone_id, action="hold", message="held", superseded_operation=sup and sup.id
        )
