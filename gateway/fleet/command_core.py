"""The common core of the Commander: collaborators, resolving drones, the one context builder, the
takeoff guard, starting and waiting on tracked operations. The verbs live in `drone_verbs` and
`fleet_verbs`; `gateway.fleet.commander` puts them together (see its docstring for the order every verb
follows and for the cluster seam)."""

from __future__ import annotations

import asyncio
import functools
import logging
from collections.abc import Awaitable, Callable
from typing import Any, Literal, TypeVar, cast

from pydantic_core import to_jsonable_python

from gateway.config import Settings
from gateway.errors import (
    GatewayError,
    InvalidArgument,
    NoOwner,
    NotFound,
    NotRun,
    OwnerTimeout,
    VehicleNotReady,
)
from gateway.fleet import geo
from gateway.fleet.caller import Caller
from gateway.fleet.fleet_ops import FleetOperations
from gateway.fleet.operations import Operation, OperationManager, Tracker
from gateway.fleet.protocols import FlyingVehicle, Notify, VehicleDirectory, VehicleView
from gateway.fleet.readings import vehicle_context
from gateway.fleet.routing import FORWARDED, Router, Verb
from gateway.fleet.safety import (
    LockBook,
    Rule,
    RunningOperation,
    SafetyPolicy,
    VehicleContext,
    refuse,
    taken_over_text,
)
from gateway.fleet.views import OperationView
from gateway.registry.store import Store

log = logging.getLogger(__name__)

AltFrame = Literal["home", "amsl"]
OnProgress = Callable[[OperationView], Awaitable[None]]

#: operations that fly to a point (their params: lat_deg, lon_deg, alt_m); a formation or fleet-climb leg
#: is one too, so check_arrival answers for a drone whose formation leg a pilot took over
NAV_KINDS = ("goto", "reposition", "move_to_relative", "formation", "fleet_climb")
RECOVERY_KINDS = ("land", "return_to_launch")
ELSEWHERE_KEPT = 2000
FOLLOW_RETRY_S = 0.5
"""How often a wait that lost its operation's node asks again (until a node has taken the drone over)."""
"""Operations started on other nodes whose drone this node remembers (to forward waits on them)."""
WAITER = Caller(via="cluster", principal="waiter")
"""Who forwards a wait: waiting changes nothing, whoever started the operation."""

VerbMethod = TypeVar("VerbMethod", bound=Callable[..., Awaitable[Any]])
T = TypeVar("T")

#: every verb on one drone that runs on the drone's owner, by name (filled by `routed`)
ROUTED: dict[str, Verb] = {}
#: the routed verbs that only read: allowed to agents on a drone a pilot or ground station took over
READ_VERBS = frozenset(
    {"arrival", "monitor", "download_mission", "mission_progress", "get_param", "list_params"}
)


def routed(method: VerbMethod) -> VerbMethod:
    """Run the verb where its drone is: here when this node owns it (or there is no cluster), else on
    its owner through the router, with the same arguments, callbacks (as progress messages) and result
    model. The drone is looked up here first, so an unknown drone (or one outside the agent's scope) is
    named by this node exactly as by the owner."""
    name = method.__name__

    @functools.wraps(method)
    async def run(self: CommandCore, *args: Any, **kwargs: Any) -> Any:
        bound = verb.signature.bind(self, *args, **kwargs)
        caller: Caller = bound.arguments["caller"]
        drone_id: str = bound.arguments["drone_id"]
        if name not in READ_VERBS and not caller.is_operator:
            self._refuse_taken_over(drone_id)  # before any other check: the pilot's word comes first
        router = self.router
        if router is None or router.owns(drone_id):
            return await method(self, *args, **kwargs)
        self.registry.get(drone_id)
        if FORWARDED.get():
            raise NoOwner(f"this node does not own drone '{drone_id}' (any more): retry in a few seconds")
        callbacks = {k: bound.arguments[k] for k in verb.callbacks if bound.arguments.get(k) is not None}
        arguments = {
            k: to_jsonable_python(v)
            for k, v in bound.arguments.items()
            if k not in ("self", "caller") and k not in verb.callbacks
        }
        wait_s = float(arguments.get("cap_s") or self.settings.mcp_wait_cap_s)
        relay = _relay(callbacks)
        seen: dict[str, str] = {}  # the operation the owner reported (its progress), to follow it

        async def watch(body: dict[str, Any]) -> None:
            view = body.get("view")
            if isinstance(view, dict) and isinstance(view.get("operation_id"), str):
                seen["operation_id"] = view["operation_id"]
            if relay is not None:
                await relay(body)

        started = asyncio.get_running_loop().time()
        try:
            result = await router.call(drone_id, name, caller, arguments, watch, wait_s=wait_s)
        except (NoOwner, OwnerTimeout):
            # the owner was lost while the verb waited on its operation: follow the operation to the
            # node that takes the drone over (same id), for what is left of the wait
            operation_id = seen.get("operation_id")
            if operation_id is None or verb.result is not OperationView:
                raise
            left = wait_s - (asyncio.get_running_loop().time() - started)
            self._remember_elsewhere(operation_id, drone_id)
            return await self._wait_elsewhere(
                drone_id, operation_id, max(0.0, left), callbacks.get("on_progress")
            )
        answer = verb.result.model_validate(result)
        if isinstance(answer, OperationView):
            self._remember_elsewhere(answer.operation_id, drone_id)
        return answer

    verb = ROUTED[name] = Verb(method, wrapper=run)
    return cast(VerbMethod, run)


def _relay(callbacks: dict[str, Any]) -> Callable[[dict[str, Any]], Awaitable[None]] | None:
    """The owner's progress messages to the verb's own callbacks (``notify``, ``on_progress``)."""
    if not callbacks:
        return None

    async def relay(body: dict[str, Any]) -> None:
        if "notice" in body and "notify" in callbacks:
            await callbacks["notify"](str(body["notice"]))
        elif "view" in body and "on_progress" in callbacks:
            await callbacks["on_progress"](OperationView.model_validate(body["view"]))

    return relay


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
        router: Router | None = None,
    ) -> None:
        """``router``: on a cluster node, where the drones this node does not own are run."""
        self.settings = settings
        self.registry = registry
        self.store = store
        self.operations = operations
        self.fleet = fleet
        self.safety = safety
        self.locks = locks
        self.router = router
        self._elsewhere: dict[str, str] = {}  # operation id -> drone id, of operations run elsewhere

    # ------------------------------------------------------------------------------------------------
    # resolving drones and judging them
    # ------------------------------------------------------------------------------------------------

    def vehicle(self, drone_id: str) -> VehicleView:
        """The registered drone, in whatever state (for reads); UnknownVehicle lists the known ids."""
        return self.registry.get(drone_id)

    def flown(self, drone_id: str) -> FlyingVehicle:
        """The drone, to command it (in whatever state): refused in words when this node cannot fly it
        (`VehicleDirectory.flown`: another node owns it, or its autopilot has no dialect here)."""
        return self.registry.flown(drone_id)

    def ready(self, drone_id: str) -> FlyingVehicle:
        """The drone, if it can fly (VehicleNotReady names its state and why otherwise)."""
        vehicle = self.registry.flown(drone_id)
        vehicle.require_ready()
        return vehicle

    def _for_recovery(self, caller: Caller, drone_id: str) -> FlyingVehicle:
        """Land, RTL, hold and kill: an operator's goes to the drone in any state (the vehicle still
        needs a session to send it); an agent's needs a ready drone."""
        return self.registry.flown(drone_id) if caller.is_operator else self.ready(drone_id)

    @staticmethod
    def context(vehicle: VehicleView) -> VehicleContext:
        return vehicle_context(vehicle)

    def _refuse_taken_over(self, drone_id: str) -> None:
        """Rule taken_over: a pilot, another ground station or a failsafe took the drone
        (`gateway.fleet.takeover`); every actuating agent verb on it is refused until an operator
        releases it (the policy's `check_actuation` says the same, for fleet verbs and direct calls)."""
        taken = self.locks.takeover_for(drone_id)
        if taken is not None:
            raise refuse(Rule.TAKEN_OVER, taken_over_text(drone_id, taken), vehicle_id=drone_id)

    def _running(self, drone_id: str, kind: str | None = None) -> RunningOperation | None:
        """The drone's running operation, here or (a drone owned elsewhere) as its owner published it."""
        if self.router is not None and not self.router.owns(drone_id):
            running = self.router.running(drone_id)
            return running if running is not None and (kind is None or running.kind == kind) else None
        return self.operations.running_facts(drone_id, kind)

    def _guard_takeoff(self, caller: Caller, vehicle: VehicleView, action: str) -> None:
        """Rule takeoff_in_progress, one rule for every verb: while the drone's takeoff climbs, an
        agent's command that acts on the drone is refused, except the safety actions (land, RTL, hold,
        and the modes that are them: HOLD, LAND, RTL; kill; disarm). So motion, yaw, speed, mode
        changes, parameter writes, missions (upload, clear, start, resume, next item), arming and
        formations wait for the climb. Runs inside the command lock, just before sending (`_track`,
        `_instant`); a verb may call it earlier too, to refuse before any other work."""
        self.safety.check_takeoff_finished(
            self.context(vehicle), self._running(vehicle.id, "takeoff"), action, caller.policy_via
        )

    @staticmethod
    def _require_airborne(ctx: VehicleContext, action: str) -> None:
        if not (ctx.in_air and ctx.armed):
            raise VehicleNotReady(
                f"{ctx.vehicle_id} is on the ground; {action} needs a flying drone. Call takeoff first."
            )

    @staticmethod
    def _relative_alt(ctx: VehicleContext, alt_m: float, alt_frame: AltFrame) -> float:
        """A caller's altitude -> metres above home (the frame conversion lives in geo)."""
        geo.check_finite("alt_m", alt_m)
        if alt_frame == "home":
            return alt_m
        if ctx.home is None:
            raise VehicleNotReady(
                f"{ctx.vehicle_id} has no home position yet; cannot convert an AMSL altitude"
            )
        relative = geo.amsl_to_relative(alt_m, ctx.home[2])
        if relative <= 0:  # a small model set alt_frame='amsl' whenever it had coordinates
            raise InvalidArgument(
                f"alt_frame='amsl' means above sea level (home is {ctx.home[2]:.0f} m), so alt_m={alt_m:g} "
                f"is {-relative:.0f} m below home; leave alt_frame out for metres above home "
                f"(e.g. alt_m={alt_m:g})"
            )
        return relative

    def _arming_deadline(self) -> float:
        """When a command that arms (arm, takeoff, fleet takeoff) stops waiting for its drones to be
        able to arm: one deadline, the MCP wait cap from now, for initialising and arming together."""
        return asyncio.get_running_loop().time() + self.settings.mcp_wait_cap_s

    @staticmethod
    def _left(deadline: float) -> float:
        return max(0.0, deadline - asyncio.get_running_loop().time())

    async def _wait_initialised(self, vehicle: VehicleView, notify: Notify | None, deadline: float) -> None:
        """Wait until ``deadline`` for a drone still initialising, ``notify`` hearing what it waits for.
        A drone that is still initialising then is left to its arming attempt, whose refusal says why
        in the autopilot's words; one in no state to arm raises VehicleNotReady naming why."""
        await vehicle.wait_initialised(self._left(deadline), notify)

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

    async def _instant(
        self,
        caller: Caller,
        vehicle: FlyingVehicle,
        action: str,
        send: Callable[[], Awaitable[T]],
        *,
        safety_action: bool = False,
        ends_operation: bool = False,
        commands: str | None = None,
        modes: frozenset[str] | None = None,
    ) -> tuple[T, Operation | None]:
        """An instant command, sent under the drone's command lock like `_track`'s (so it never
        overtakes a command still being sent to the drone): the takeoff guard inside the lock unless it
        is a ``safety_action``, the command, then (``ends_operation``) the drone's running operation is
        superseded by ``action`` and the gateway expects the drone in the mode the command brings
        (``commands``: what it is, e.g. "hold"; ``modes``: the modes it shows, when not that kind's;
        neither: nothing to judge, e.g. disarm). Returns what ``send`` returned and the operation it
        ended."""
        async with self.operations.command_lock(vehicle.id):
            if not safety_action:
                self._guard_takeoff(caller, vehicle, action)
            result = await send()
            ended = None
            if ends_operation:
                ended = await self._supersede(vehicle.id, action)
                self.operations.expect(vehicle, commands, modes=modes)
        return result, ended

    def view(self, op: Operation) -> OperationView:
        try:
            vehicle: VehicleView | None = self.registry.get(op.vehicle_id)
        except GatewayError:  # removed since: the operation is still worth reporting
            vehicle = None
        return OperationView.of(op, vehicle)

    def operation(self, operation_id: str) -> OperationView:
        return self.view(self.operations.get(operation_id))

    def current_operation(self, drone_id: str) -> dict[str, Any] | None:
        """The drone's latest operation (running or finished) as ``Operation.to_dict`` gives it: this
        node's own, or for a drone owned by another cluster node the one its owner published."""
        if self.router is not None and not self.router.owns(drone_id):
            published = self.router.published(drone_id)
            if published is None:
                return None
            return {
                "operation_id": str(published.get("id")),
                "drone_id": drone_id,
                "kind": str(published.get("kind")),
                "status": str(published.get("status")),
                "progress": published.get("progress"),
                "message": published.get("message"),
                "eta_s": published.get("eta_s"),
                "elapsed_s": published.get("elapsed_s"),
                "params": published.get("params") or {},
            }
        op = self.operations.latest(drone_id)
        return None if op is None else op.to_dict()

    def latest_operation(self, drone_id: str) -> OperationView | None:
        """The drone's most recent operation, running or finished."""
        self.registry.get(drone_id)
        op = self.operations.latest(drone_id)
        return None if op is None else self.view(op)

    async def wait(
        self, operation_id: str, cap_s: float | None = None, on_progress: OnProgress | None = None
    ) -> OperationView:
        """Wait until the operation has finished or ``cap_s`` passed (default: the MCP wait cap),
        reporting progress on each change. Cancelling the waiter stops nothing on the drone. An
        operation that runs on another cluster node is waited for there."""
        try:
            op = self.operations.get(operation_id)
        except NotFound:
            drone_id = await self._drone_of(operation_id)
            if drone_id is None or self.router is None or self.router.owns(drone_id):
                raise
            return await self._wait_elsewhere(drone_id, operation_id, cap_s, on_progress)

        async def report(o: Operation) -> None:
            if on_progress is not None:
                await on_progress(self.view(o))

        return self.view(await self.operations.wait(op, cap_s, report if on_progress else None))

    async def _supersede(self, drone_id: str, by: str) -> Operation | None:
        return await self.operations.supersede(drone_id, by)

    # ------------------------------------------------------------------------------------------------
    # operations that run on another cluster node
    # ------------------------------------------------------------------------------------------------

    def _remember_elsewhere(self, operation_id: str, drone_id: str) -> None:
        self._elsewhere[operation_id] = drone_id
        while len(self._elsewhere) > ELSEWHERE_KEPT:
            del self._elsewhere[next(iter(self._elsewhere))]

    async def _drone_of(self, operation_id: str) -> str | None:
        """The drone of an operation this node does not run: remembered, or from the database."""
        known = self._elsewhere.get(operation_id)
        if known is not None or self.store is None:
            return known
        record = await self.store.get_operation(operation_id)
        return None if record is None else record.vehicle_id

    async def _record_of(self, operation_id: str) -> Any:
        """The operation as the database holds it; None when unknown or the database is unreachable."""
        if self.store is None:
            return None
        try:
            return await self.store.get_operation(operation_id)
        except Exception:
            log.warning("could not read operation %s from the database", operation_id)
            return None

    async def _wait_elsewhere(
        self, drone_id: str, operation_id: str, cap_s: float | None, on_progress: OnProgress | None
    ) -> OperationView:
        """Forward the wait to the drone's owner, its progress back to ``on_progress``. If the owner is
        lost meanwhile, the wait follows the operation to the node that takes the drone over (which
        tracks it under the same id); when the wait's time is up first, the answer is what the database
        holds, saying so."""
        assert self.router is not None
        cap = self.settings.mcp_wait_cap_s if cap_s is None else cap_s
        relay = _relay({"on_progress": on_progress}) if on_progress is not None else None
        loop = asyncio.get_running_loop()
        deadline = loop.time() + cap
        while True:
            left = max(0.0, deadline - loop.time())
            try:
                result = await self.router.call(
                    drone_id,
                    "wait",
                    WAITER,
                    {"operation_id": operation_id, "cap_s": left},
                    relay,
                    wait_s=left,
                )
                return OperationView.model_validate(result)
            except (NoOwner, OwnerTimeout, NotRun, NotFound) as exc:
                # no owner yet (a takeover under way), or the new owner has not picked the operation up
                # yet; unless the database says it has ended (the new owner could not follow it)
                record = await self._record_of(operation_id)
                ended = record is not None and record.status != "running"
                retry = not ended and not isinstance(exc, OwnerTimeout)
                if retry and loop.time() + FOLLOW_RETRY_S < deadline:
                    await asyncio.sleep(FOLLOW_RETRY_S)
                    continue
                if record is None:
                    raise
                return OperationView.of_record(record, f"{record.message or record.status} ({exc.message})")
