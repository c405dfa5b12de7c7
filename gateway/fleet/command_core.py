"""The common core of the Commander: collaborators, resolving drones, the one context builder, the
takeoff guard, starting and waiting on tracked operations. The verbs live in `drone_verbs` and
`fleet_verbs`; `gateway.fleet.commander` puts them together (see its docstring for the order every verb
follows and for the cluster seam)."""

from __future__ import annotations

import contextlib
import logging
from collections.abc import Awaitable, Callable
from typing import Any, Literal

from gateway.config import Settings
from gateway.errors import GatewayError, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.caller import Caller
from gateway.fleet.fleet_ops import FleetOperations
from gateway.fleet.operations import Operation, OperationManager, Tracker
from gateway.fleet.protocols import FlyingVehicle, VehicleDirectory
from gateway.fleet.readings import vehicle_context
from gateway.fleet.safety import LockBook, SafetyPolicy, VehicleContext
from gateway.fleet.views import OperationView
from gateway.registry.store import Store

log = logging.getLogger(__name__)

AltFrame = Literal["home", "amsl"]
OnProgress = Callable[[OperationView], Awaitable[None]]
Notify = Callable[[str], Awaitable[None]]
"""Told, in words, what a command waits for before it can be sent (e.g. a drone still initialising)."""

NAV_KINDS = ("goto", "reposition", "move_to_relative")
RECOVERY_KINDS = ("land", "return_to_launch")


class CommandCore:
    """What every verb shares; built once by the runtime `Gateway` (as a `Commander`)."""

    def __init__(
        self,
        settings: Settings,
        registry: VehicleDirectory,
        store: Store | None,
        operations: OperationManager,
        fleet: FleetOperations,
        safety: SafetyPolicy,
        locks: LockBook,
    ) -> None:
        self.settings = settings
        self.registry = registry
        self.store = store
        self.operations = operations
        self.fleet = fleet
        self.safety = safety
        self.locks = locks

    # ------------------------------------------------------------------------------------------------
    # resolving drones and judging them
    # ------------------------------------------------------------------------------------------------

    def vehicle(self, drone_id: str) -> FlyingVehicle:
        """The registered drone, in whatever state (for reads); UnknownVehicle lists the known ids."""
        return self.registry.get(drone_id)

    def ready(self, drone_id: str) -> FlyingVehicle:
        """The drone, if it can fly (VehicleNotReady names its state and why otherwise)."""
        vehicle = self.registry.get(drone_id)
        vehicle.require_ready()
        return vehicle

    def _for_recovery(self, caller: Caller, drone_id: str) -> FlyingVehicle:
        """Land, RTL, hold and kill: an operator's goes to the drone in any state (the vehicle still
        needs a session to send it); an agent's needs a ready drone."""
        return self.registry.get(drone_id) if caller.is_operator else self.ready(drone_id)

    @staticmethod
    def context(vehicle: FlyingVehicle) -> VehicleContext:
        return vehicle_context(vehicle)

    def _guard_takeoff(self, caller: Caller, vehicle: FlyingVehicle, action: str) -> None:
        """Rule takeoff_in_progress; also run inside the command lock, just before sending."""
        self.safety.check_takeoff_finished(
            self.context(vehicle), self.operations.running_facts(vehicle.id, "takeoff"), action,
            caller.policy_via,
        )  # fmt: skip

    @staticmethod
    def _require_airborne(ctx: VehicleContext, action: str) -> None:
        if not (ctx.in_air and ctx.armed):
            raise VehicleNotReady(
                f"{ctx.vehicle_id} is on the ground; {action} needs a flying drone. Call takeoff first."
            )

    @staticmethod
    def _relative_alt(ctx: VehicleContext, altitude_m: float, alt_frame: AltFrame) -> float:
        """A caller's altitude -> metres above home (the frame conversion lives in geo)."""
        geo.check_finite("altitude_m", altitude_m)
        if alt_frame == "home":
            return altitude_m
        if ctx.home is None:
            raise VehicleNotReady(
                f"{ctx.vehicle_id} has no home position yet; cannot convert an AMSL altitude"
            )
        return geo.amsl_to_relative(altitude_m, ctx.home[2])

    async def _wait_initialised(self, vehicle: FlyingVehicle, notify: Notify | None) -> None:
        waiting = vehicle.initialising()
        if waiting is not None and notify is not None:
            with contextlib.suppress(Exception):  # a courtesy; the wait happens regardless
                await notify(f"{vehicle.id}: {waiting}")
        await vehicle.wait_initialised()

    # ------------------------------------------------------------------------------------------------
    # operations
    # ------------------------------------------------------------------------------------------------

    async def _track(
        self,
        caller: Caller,
        vehicle: FlyingVehicle,
        tracker: Tracker,
        send: Callable[[], Awaitable[Any]],
        params: dict[str, Any],
        action: str,
    ) -> OperationView:
        def precheck() -> None:
            if tracker.kind not in RECOVERY_KINDS:
                self._guard_takeoff(caller, vehicle, action)

        op = await self.operations.start(vehicle, tracker, send, params, caller.session, precheck)
        return OperationView.of(op, vehicle)

    def view(self, op: Operation) -> OperationView:
        try:
            vehicle: FlyingVehicle | None = self.registry.get(op.vehicle_id)
        except GatewayError:  # removed since: the operation is still worth reporting
            vehicle = None
        return OperationView.of(op, vehicle)

    def operation(self, operation_id: str) -> OperationView:
        return self.view(self.operations.get(operation_id))

    def latest_operation(self, drone_id: str) -> OperationView | None:
        """The drone's most recent operation, running or finished."""
        self.registry.get(drone_id)
        op = self.operations.latest(drone_id)
        return None if op is None else self.view(op)

    async def wait(
        self, operation_id: str, cap_s: float | None = None, on_progress: OnProgress | None = None
    ) -> OperationView:
        """Wait until the operation has finished or ``cap_s`` passed (default: the MCP wait cap),
        reporting progress on each change. Cancelling the waiter stops nothing on the drone."""
        op = self.operations.get(operation_id)

        async def report(o: Operation) -> None:
            if on_progress is not None:
                await on_progress(self.view(o))

        return self.view(await self.operations.wait(op, cap_s, report if on_progress else None))

    async def _supersede(self, drone_id: str, by: str) -> Operation | None:
        return await self.operations.supersede(drone_id, by)
