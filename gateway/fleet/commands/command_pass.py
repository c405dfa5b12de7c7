"""The one pass every drone command takes: resolve, judge, send, track, audit.

`CommandPass.run` is the only place a command on one drone is sent from (kill, which never waits for
the command lock, is `CommandPass.run` with ``locked=False``). In this order, each step once:

1. the takeover lock first (rule taken_over: an agent's command on a drone a pilot, another ground
   station or a failsafe took is refused before anything else), then resolve the drone in the
   (scoped) registry: UnknownVehicle names the known ids;
   the drone to command (`VehicleDirectory.flown`: refused in words when another node flies it or
   its autopilot has no dialect here);
2. ``prepare``: what must happen before the drone is judged (arm and takeoff wait for a drone that is
   still initialising, within the wait cap); then its readiness (`Need`): VehicleNotReady names why;
3. build ONE `VehicleContext` from its fresh telemetry (`gateway.fleet.vehicles.readings.vehicle_context`);
4. the policy on that context: the takeoff guard (rule takeoff_in_progress, except for the safety
   actions), then the command's own checks
   (``decide``: altitude, geofence, battery, parameter rules param_limit / param_not_allowed...), which
   also say what to send: an `Order`;
5. under the drone's command lock (the takeoff guard again, inside it: a takeoff still being sent is
   seen), send the order through the vehicle (its dialect): a tracked operation when the order has a
   tracker (`OperationManager.start`), else an instant command that may end the running operation;
6. audit: a call that starts an operation has its audit row written as soon as the operation is sent,
   naming it, and the store completes the row when the operation ends (`AUDIT_SENT`), so a crash while
   the operation flies loses no call.

Fleet commands compose this pass per drone (`gateway.fleet.commands.fleet_verbs`), adding their fleet-level
checks (separation, the altitude band, who takes part) in front of it.
"""

from __future__ import annotations

import inspect
from collections.abc import Awaitable, Callable
from contextvars import ContextVar
from dataclasses import dataclass, field
from enum import Enum

from gateway.config import Settings
from gateway.fleet.operations.operation_state import Operation
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.operations.routing import Router
from gateway.fleet.operations.trackers import Tracker
from gateway.fleet.operations.views import ActionResult, OperationView
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.operator_locks import LockBook, taken_over_text
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import RunningOperation, VehicleContext
from gateway.fleet.policy.safety_rules import Rule as SafetyRule
from gateway.fleet.policy.safety_rules import refuse
from gateway.fleet.vehicles.protocols import FlyingVehicle, VehicleDirectory
from gateway.fleet.vehicles.readings import vehicle_context
from gateway.util.json_types import JsonMapping, JsonObject

RECOVERY_KINDS = ("land", "return_to_launch")

#: set by a door for the call it runs: told the operation id once the call's first operation is sent,
#: so the call's audit row is written then (outcome running) and completed when the operation ends
AUDIT_SENT: ContextVar[Callable[[str], None] | None] = ContextVar("audit_sent", default=None)


class Need(Enum):
    """How ready the drone must be for a command."""

    ANY = "any"
    """In any state (reads, arming: the vehicle says why it cannot)."""
    READY = "ready"
    """Able to fly (VehicleNotReady names its state and why otherwise)."""
    RECOVERY = "recovery"
    """Land, return, hold, kill: an operator's goes in any state, an agent's needs a ready drone."""


@dataclass
class Order:
    """What a command sends, decided by its checks from the one context."""

    send: Callable[[], Awaitable[object]]
    tracker: Tracker | None = None
    """A tracked operation (an `OperationView` to wait on); None: an instant command."""
    params: JsonMapping = field(default_factory=dict)
    """The operation's parameters (stored with it)."""
    ends_operation: bool = False
    """An instant command that supersedes the drone's running operation (hold, mode, disarm)."""
    commands: str | None = None
    modes: frozenset[str] | None = None
    """With ``ends_operation``: what the drone is expected to do now (the takeover watch reads it)."""


@dataclass
class Sent:
    """What the pass did: the drone, the context it was judged on, and what the send gave."""

    vehicle: FlyingVehicle
    context: VehicleContext
    operation: Operation | None = None
    """The tracked operation started."""
    result: object = None
    """What an instant command's send returned."""
    ended: Operation | None = None
    """The operation an instant command superseded."""

    def view(self) -> OperationView:
        """The operation a tracked command started, as the doors show it."""
        assert self.operation is not None, "an instant command has no operation"
        return OperationView.of(self.operation, self.vehicle)

    @property
    def ended_id(self) -> str | None:
        return None if self.ended is None else self.ended.id


Decide = Callable[[FlyingVehicle, VehicleContext], "Order | Awaitable[Order]"]


@dataclass
class CommandPass:
    """The one pass (see the module docstring); one per Commander, over its collaborators. ``router``:
    on a cluster node, where the drones this node does not own are run."""

    settings: Settings
    registry: VehicleDirectory
    operations: OperationManager
    safety: SafetyPolicy
    locks: LockBook
    router: Router | None = None

    async def instant(
        self,
        caller: Caller,
        drone_id: str,
        action: str,
        decide: Decide,
        message: str,
        facts: JsonObject | None = None,
    ) -> ActionResult:
        """`run` an instant command (done when the drone accepts it) and say what it did."""
        await self.run(caller, drone_id, action, decide)
        return ActionResult(drone_id=drone_id, action=action, message=message, facts=facts or {})

    async def run(
        self,
        caller: Caller,
        drone_id: str,
        action: str,
        decide: Decide,
        *,
        need: Need = Need.READY,
        safety_action: bool = False,
        prepare: Callable[[FlyingVehicle], Awaitable[None]] | None = None,
        locked: bool = True,
        audited: bool = True,
    ) -> Sent:
        """Run one command on one drone. ``action`` is how the caller names it (in refusals and in the
        operation it supersedes); ``safety_action``: land, return, hold, kill, disarm and the landing
        modes, never held by the takeoff guard; ``locked=False`` sends without the command lock (kill
        only); ``audited=False``: a step of a fleet operation, whose call is audited as the fleet's."""
        if not caller.is_operator:
            self.refuse_taken_over(drone_id)  # before any other check: the pilot's word comes first
        vehicle = self.registry.flown(drone_id)  # refused in words when this node cannot fly it
        if prepare is not None:
            await prepare(vehicle)
        if need is Need.READY or (need is Need.RECOVERY and not caller.is_operator):
            vehicle.require_ready()
        ctx = vehicle_context(vehicle)
        if not safety_action:
            self.guard_takeoff(caller, ctx, action)
        order = decide(vehicle, ctx)
        if inspect.isawaitable(order):
            order = await order
        sent = Sent(vehicle, ctx)
        if order.tracker is not None:
            sent.operation = await self._track(caller, vehicle, ctx, order, action)
            if audited:
                note = AUDIT_SENT.get()
                if note is not None:
                    note(sent.operation.id)
            return sent
        if not locked:
            sent.result = await order.send()
            return sent
        async with self.operations.command_lock(vehicle.id):
            if not safety_action:
                self.guard_takeoff(caller, ctx, action)
            sent.result = await order.send()
            if order.ends_operation:
                sent.ended = await self.operations.supersede(vehicle.id, action)
                self.operations.mode_watch.expect(vehicle, order.commands, modes=order.modes)
        return sent

    async def _track(
        self, caller: Caller, vehicle: FlyingVehicle, ctx: VehicleContext, order: Order, action: str
    ) -> Operation:
        assert order.tracker is not None
        tracker = order.tracker

        def precheck() -> None:  # inside the command lock
            if tracker.kind not in RECOVERY_KINDS:
                self.guard_takeoff(caller, ctx, action)

        return await self.operations.start(
            vehicle, tracker, order.send, order.params, caller.session, precheck
        )

    # ------------------------------------------------------------------------------------------------
    # the rules every command shares
    # ------------------------------------------------------------------------------------------------

    def refuse_taken_over(self, drone_id: str) -> None:
        """Rule taken_over: a pilot, another ground station or a failsafe took the drone
        (`gateway.fleet.policy.takeover`); every actuating agent command on it is refused until an operator
        releases it (the policy's `check_actuation` says the same, for fleet steps and direct calls)."""
        taken = self.locks.takeover_for(drone_id)
        if taken is not None:
            raise refuse(SafetyRule.TAKEN_OVER, taken_over_text(drone_id, taken), vehicle_id=drone_id)

    def running(self, drone_id: str, kind: str | None = None) -> RunningOperation | None:
        """The drone's running operation, here or (a drone owned elsewhere) as its owner published it."""
        if self.router is not None and not self.router.owns(drone_id):
            running = self.router.running(drone_id)
            return running if running is not None and (kind is None or running.kind == kind) else None
        return self.operations.running_facts(drone_id, kind)

    def guard_takeoff(self, caller: Caller, ctx: VehicleContext, action: str) -> None:
        """Rule takeoff_in_progress, one rule for every command: while the drone's takeoff climbs, an
        agent's command that acts on the drone is refused, except the safety actions (land, RTL, hold,
        and the modes that are them: HOLD, LAND, RTL; kill; disarm). So motion, yaw, speed, mode
        changes, parameter writes, missions (upload, clear, start, resume, next item), arming and
        formations wait for the climb. Judged before the command's own checks and again inside the
        command lock, just before sending."""
        self.safety.check_takeoff_finished(
            ctx, self.running(ctx.vehicle_id, "takeoff"), action, caller.policy_via
        )
