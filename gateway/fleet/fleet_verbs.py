"""The Commander's verbs on several drones: formation, fleet takeoff, land, return, hold, the emergency
stop, and the operator locks.

Who takes part (the same rule for every fleet verb, also in docs/fleet.md):
- formation_goto and fleet_takeoff change the fleet's geometry: every named drone is checked first and
  if any cannot take part (unknown, not ready, locked, busy, low battery, on the ground...) nothing is
  sent and the error names each such drone with the reason (rule and numbers).
- fleet_land, fleet_return_to_launch and fleet_hold bring drones down or stop them: they go to every
  drone that can take them, and the result lists the others (not_sent) with the reason.
- stop_all is the operator's emergency stop: it locks the fleet (unless told not to), ends every
  running fleet operation first (so a formation's own abort cannot race it), then tells every airborne
  drone to hold, land or return, each as a tracked operation where the action has one. Each drone's
  stop goes under its command lock like every command (kill is the one exception): a command still
  being sent to the drone finishes first, so that the stop is the last word the drone hears rather
  than being overtaken by it.
"""

from __future__ import annotations

import asyncio
import contextlib
import dataclasses
import logging
from collections.abc import Awaitable, Callable, Sequence
from datetime import UTC, datetime
from typing import Any, Literal

from gateway.errors import GatewayError, InvalidArgument, NoOwner, NotRun, SafetyRefusal, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.caller import Caller
from gateway.fleet.command_core import routed
from gateway.fleet.drone_verbs import DroneVerbs
from gateway.fleet.fleet_ops import (
    FORMATION_TOLERANCE_M,
    FleetOperation,
    Unable,
    build_step,
    check_drone_ids,
    collect_members,
    default_rtl_base_m,
    formation_phases,
    land_phase,
    refuse_fleet,
    rtl_order,
    rtl_phases,
    slot_summaries,
    takeoff_phase,
)
from gateway.fleet.formation import DroneStart, plan_formation, rtl_altitudes, takeoff_altitudes
from gateway.fleet.geofence import FLEET
from gateway.fleet.protocols import Notify, VehicleView
from gateway.fleet.readings import home, is_landed_and_disarmed, position
from gateway.fleet.safety import Rule, refuse
from gateway.fleet.takeover import Takeover
from gateway.fleet.views import (
    ActionResult,
    FleetHoldResult,
    FleetView,
    LockResult,
    OperationView,
    StopOutcome,
    StopResult,
    UnlockResult,
)
from gateway.registry.records import AuditEntry

log = logging.getLogger(__name__)

Formation = Literal["line", "column", "wedge", "grid", "circle"]
StopAction = Literal["hold", "land", "rtl"]
OnFleetProgress = Callable[[FleetView], Awaitable[None]]
STOP_LOCK_REASON = "emergency stop"
#: the stop's answer says whether its lock is stored if the database answers within this (else: later)
STORE_LOCK_WAIT_S = 1.0
_STORING: set[asyncio.Task[bool]] = set()


class FleetVerbs(DroneVerbs):
    """Commands on several drones at once, and the operator locks."""

    # ------------------------------------------------------------------------------------------------
    # fleet operations: views and waiting
    # ------------------------------------------------------------------------------------------------

    def fleet_view(self, fop: FleetOperation, not_sent: Sequence[Unable] = ()) -> FleetView:
        d = fop.to_dict()
        plan = None
        if fop.plan is not None:
            plan = {
                k: fop.plan[k] for k in ("formation", "spacing_m", "heading_deg", "alt_m", "min_clearance_m")
            }
            plan["conflicts_resolved"] = len(fop.plan.get("conflicts", []))
        return FleetView(**d, not_sent=[u.to_dict() for u in not_sent], plan=plan)

    def fleet_operation(self, operation_id: str | None = None) -> FleetView:
        """A fleet operation by id, or the latest one."""
        fop = self.fleet.get(operation_id) if operation_id else self.fleet.latest()
        if fop is None:
            raise InvalidArgument("no fleet operation has been started yet")
        return self.fleet_view(fop)

    async def wait_fleet(
        self,
        operation_id: str,
        cap_s: float | None = None,
        on_progress: OnFleetProgress | None = None,
        not_sent: Sequence[dict[str, object]] = (),
    ) -> FleetView:
        """Wait until the fleet operation has finished or ``cap_s`` passed, reporting progress; the
        drones that were not sent the command (``not_sent`` of the starting result) stay in the view."""
        fop = self.fleet.get(operation_id)
        cap = self.settings.mcp_wait_cap_s if cap_s is None else cap_s

        async def report(f: FleetOperation) -> None:
            if on_progress is not None:
                await on_progress(self.fleet_view(f))

        done = await self.fleet.wait(fop, cap, report if on_progress else None)
        return self.fleet_view(done).model_copy(update={"not_sent": list(not_sent)})

    # ------------------------------------------------------------------------------------------------
    # checks shared by the fleet verbs
    # ------------------------------------------------------------------------------------------------

    def _all_ids(self, drone_ids: Sequence[str] | None) -> list[str]:
        if drone_ids is None:
            ids = [v.id for v in self.registry.all()]
            if not ids:
                raise InvalidArgument("no drones are registered")
            return ids
        return check_drone_ids(drone_ids)

    def _busy(self, vehicle: VehicleView, action: str) -> None:
        self.safety.check_not_busy(self.context(vehicle), self._running(vehicle.id), action)

    def _stagger(self, stagger_m: float | None) -> float:
        """Default: the minimum separation plus 1 m of altitude-holding error for each of two drones."""
        return self.settings.min_separation_m + 2 * FORMATION_TOLERANCE_M if stagger_m is None else stagger_m

    def _recovery_members(
        self, drone_ids: Sequence[str] | None, action: str, check: Callable[[VehicleView], None]
    ) -> tuple[list[str], dict[str, VehicleView], list[Unable]]:
        ids = self._all_ids(drone_ids)
        vehicles, unable = collect_members(ids, self.registry.get, check)
        if not vehicles:
            raise refuse_fleet(action, unable, len(ids))
        return ids, vehicles, unable

    async def _initialised(self, ids: Sequence[str], notify: Notify | None, deadline: float) -> None:
        """Drones still initialising (connected, waiting for a position estimate) are waited for until
        ``deadline``, all at once, ``notify`` hearing what each waits for; whatever they are then is
        judged by the members' checks."""
        waits = []
        for drone_id in ids:
            with contextlib.suppress(GatewayError):
                waits.append(self.registry.get(drone_id).wait_initialised(self._left(deadline), notify))
        await asyncio.gather(*waits, return_exceptions=True)

    # ------------------------------------------------------------------------------------------------
    # formation and fleet takeoff: all drones or none
    # ------------------------------------------------------------------------------------------------

    async def formation_goto(
        self,
        caller: Caller,
        drone_ids: list[str],
        formation: Formation,
        center_lat_deg: float | None,
        center_lon_deg: float | None,
        alt_m: float,
        spacing_m: float = 10.0,
        heading_deg: float | None = None,
        north_m: float = 0.0,
        east_m: float = 0.0,
        *,
        notify: Notify | None = None,
    ) -> FleetView:
        """Fly drones into a formation around a point, kept apart; all must join or nothing is sent. The
        point: the centre given, else the drones' own centre (where they are), moved ``north_m`` and
        ``east_m``. Drones on the ground take off first (a first phase, to staggered altitudes as in
        `fleet_takeoff`); then the three phases with barriers of `gateway.fleet.formation`."""
        ids = check_drone_ids(drone_ids)
        if (center_lat_deg is None) != (center_lon_deg is None):
            raise InvalidArgument(
                "give both center_lat_deg and center_lon_deg, or neither (the formation is then centred "
                "where the drones are, moved north_m/east_m)"
            )
        for name, metres in (("north_m", north_m), ("east_m", east_m)):
            geo.check_finite(name, metres)
        policy = self.safety
        via = caller.policy_via
        deadline = self._arming_deadline()
        grounded = [d for d in ids if self._on_ground(d)]
        if grounded:
            await self._initialised(grounded, notify, deadline)
        low, high = policy.altitude_band(ids)
        climbs = takeoff_altitudes(grounded, alt_m, self._stagger(None), high) if grounded else {}

        def check(v: VehicleView) -> None:
            v.require_ready()
            self._guard_takeoff(caller, v, "formation_goto")
            ctx = self.context(v)
            if v.id in climbs:
                policy.check_takeoff(ctx, climbs[v.id], via)
            else:
                self._require_airborne(ctx, "formation_goto")
            self._busy(v, "formation_goto")
            if ctx.position is None:
                raise VehicleNotReady(f"no position received from {v.id} yet")
            policy.check_actuation(ctx, via)

        vehicles, unable = collect_members(ids, self.registry.get, check)
        if unable:
            raise refuse_fleet("formation_goto", unable, len(ids))
        contexts = {d: self.context(v) for d, v in vehicles.items()}
        starts = [
            DroneStart(d, pos[0], pos[1], climbs.get(d, pos[2]))
            for d in ids
            if (pos := contexts[d].position) is not None
        ]
        if center_lat_deg is None or center_lon_deg is None:
            center_lat_deg = sum(s.lat for s in starts) / len(starts)
            center_lon_deg = sum(s.lon for s in starts) / len(starts)
        if north_m or east_m:
            center_lat_deg, center_lon_deg = geo.offset_position(
                center_lat_deg, center_lon_deg, north_m, east_m
            )
        if heading_deg is None:
            heading_deg = _travel_heading(starts, center_lat_deg, center_lon_deg)
        plan = plan_formation(
            starts,
            formation,
            center_lat_deg,
            center_lon_deg,
            alt_m,
            spacing_m,
            heading_deg,
            self.settings.min_separation_m,
            max_altitude_m=high,
            min_transit_alt_m=low,
        )
        for slot in plan.slots:  # per drone first, so every refused drone is named
            try:
                policy.check_formation(
                    {slot.drone_id: contexts[slot.drone_id]}, dataclasses.replace(plan, slots=[slot]), via
                )
            except SafetyRefusal as exc:
                unable.append(Unable.from_error(slot.drone_id, exc))
        if unable:
            raise refuse_fleet("formation_goto", unable, len(ids))
        policy.check_formation(contexts, plan, via)
        params: dict[str, Any] = {
            "formation": formation,
            "center_lat_deg": center_lat_deg,
            "center_lon_deg": center_lon_deg,
            "alt_m": alt_m,
            "spacing_m": spacing_m,
            "heading_deg": round(plan.heading_deg, 1),
        }
        guard = lambda v: self._guard_takeoff(caller, v, "formation_goto")  # noqa: E731
        phases = formation_phases(plan, vehicles, guard)
        if climbs:
            params["took_off_first"] = climbs
            first = takeoff_phase(
                {d: vehicles[d] for d in climbs}, climbs, guard, self._left(deadline), "formation_goto"
            )
            phases = [
                dataclasses.replace(first, name="take off the drones on the ground", abort_on_failure=True),
                *phases,
            ]
        fop = await self.fleet.start(
            "formation_goto",
            ids,
            phases,
            params,
            caller.session,
            caller=caller,
            plan=plan.to_dict(),
            slots=slot_summaries(plan),
            notes=plan.notes,
        )
        return self.fleet_view(fop)

    def _on_ground(self, drone_id: str) -> bool:
        """A drone known to be on the ground (an unknown one is left to the members' checks)."""
        try:
            vehicle = self.registry.get(drone_id)
        except GatewayError:
            return False
        return vehicle.on_ground() is True

    async def fleet_takeoff(
        self,
        caller: Caller,
        drone_ids: list[str],
        alt_m: float,
        stagger_m: float | None = None,
        *,
        notify: Notify | None = None,
    ) -> FleetView:
        """Take off drones at once to alt_m, alt_m + stagger, ... (in the order given); all must be able,
        or none go. Drones still initialising are waited for first (``notify`` hears what each waits
        for); that wait and the drones' arming share one deadline, the wait cap."""
        ids = check_drone_ids(drone_ids)
        policy = self.safety
        _low, high = policy.altitude_band(ids)
        altitudes = takeoff_altitudes(ids, alt_m, self._stagger(stagger_m), high)
        deadline = self._arming_deadline()
        await self._initialised(ids, notify, deadline)

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = self.context(v)
            if ctx.in_air:
                raise InvalidArgument(f"{v.id} is already flying; use formation_goto or go_to_location")
            self._busy(v, "fleet_takeoff")
            policy.check_takeoff(ctx, altitudes[v.id], caller.policy_via)

        vehicles, unable = collect_members(ids, self.registry.get, check)
        if unable:
            raise refuse_fleet("fleet_takeoff", unable, len(ids))
        fop = await self.fleet.start(
            "fleet_takeoff",
            ids,
            [
                takeoff_phase(
                    vehicles,
                    altitudes,
                    lambda v: self._guard_takeoff(caller, v, "fleet_takeoff"),
                    arm_within_s=self._left(deadline),
                )
            ],
            {"alt_m": alt_m, "altitudes_m": altitudes},
            caller.session,
            caller=caller,
            slots={d: {"target_alt_m": a} for d, a in altitudes.items()},
        )
        return self.fleet_view(fop)

    # ------------------------------------------------------------------------------------------------
    # recovery: to every drone that can take it
    # ------------------------------------------------------------------------------------------------

    async def fleet_land(self, caller: Caller, drone_ids: list[str] | None = None) -> FleetView:
        """Land drones in place, all at once; done when disarmed. Those that cannot are in not_sent."""

        def check(v: VehicleView) -> None:
            v.require_ready()
            if is_landed_and_disarmed(v):
                raise InvalidArgument(f"{v.id} is already on the ground and disarmed")
            self.safety.check_actuation(self.context(v), caller.policy_via)

        ids, vehicles, unable = self._recovery_members(drone_ids, "fleet_land", check)
        fop = await self.fleet.start(
            "fleet_land",
            list(vehicles),
            [land_phase(vehicles)],
            {"drone_ids": ids},
            caller.session,
            caller=caller,
        )
        return self.fleet_view(fop, unable)

    async def fleet_return_to_launch(
        self,
        caller: Caller,
        drone_ids: list[str] | None = None,
        rtl_alt_m: float | None = None,
        stagger_m: float | None = None,
    ) -> FleetView:
        """Fly drones home at separate altitudes (climbing or descending in place first) and land.
        Those that cannot are in not_sent."""
        stagger = self._stagger(stagger_m)
        sep = self.settings.min_separation_m
        self.safety.check_stagger(stagger)

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = self.context(v)
            self._require_airborne(ctx, "fleet_return_to_launch")
            if ctx.position is None:
                raise VehicleNotReady(f"no position received from {v.id} yet")
            self.safety.check_actuation(ctx, caller.policy_via)
            self.safety.check_param_write(
                v.return_altitude_param()[0], via=caller.policy_via, vehicle_id=v.id, governed=v.limit_params
            )

        ids, vehicles, unable = self._recovery_members(drone_ids, "fleet_return_to_launch", check)
        positions = {d: pos for d, v in vehicles.items() if (pos := position(v)) is not None}
        homes = {d: (h[0], h[1]) for d, v in vehicles.items() if (h := home(v)) is not None}
        order, notes = rtl_order(positions, homes, sep)
        base = rtl_alt_m if rtl_alt_m is not None else default_rtl_base_m(positions.values())
        _low, high = self.safety.altitude_band(order)
        try:
            altitudes = rtl_altitudes(order, base, stagger, high)
        except SafetyRefusal:
            if stagger_m is not None or stagger <= sep:
                raise
            # many drones: the default margin does not fit under the limit; the separation itself may
            altitudes = rtl_altitudes(order, base, sep, high)
            notes.append(
                f"return altitudes {sep:g} m apart (the minimum separation): {stagger:g} m did not fit"
            )
        fop = await self.fleet.start(
            "fleet_return_to_launch",
            order,
            rtl_phases(vehicles, altitudes, positions),
            {"drone_ids": ids, "rtl_altitudes_m": altitudes},
            caller.session,
            caller=caller,
            slots={d: {"rtl_alt_m": a} for d, a in altitudes.items()},
            notes=notes,
        )
        return self.fleet_view(fop, unable)

    async def fleet_hold(self, caller: Caller, drone_ids: list[str] | None = None) -> FleetHoldResult:
        """Stop drones where they are (GUIDED hover), ending their operations and any fleet operation
        they are part of. Those that cannot are in not_sent."""

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = self.context(v)
            self._require_airborne(ctx, "fleet_hold")
            self.safety.check_actuation(ctx, caller.policy_via)

        _ids, vehicles, unable = self._recovery_members(drone_ids, "fleet_hold", check)
        superseded = await self.fleet.supersede(vehicles, "fleet_hold")
        failed: list[dict[str, object]] = []

        async def hold(drone_id: str, v: VehicleView) -> None:
            try:
                await self.hold_step(caller, drone_id, "fleet_hold")  # on its owner, in a cluster
            except GatewayError as exc:
                failed.append({"drone_id": drone_id, "code": exc.code, "message": exc.message})

        await asyncio.gather(*(hold(d, v) for d, v in vehicles.items()))
        failed_ids = {f["drone_id"] for f in failed}
        return FleetHoldResult(
            held=[d for d in vehicles if d not in failed_ids],
            failed=failed,
            not_sent=[u.to_dict() for u in unable],
            superseded_fleet_operations=[f.id for f in superseded],
        )

    # ------------------------------------------------------------------------------------------------
    # one drone's step of a fleet operation coordinated by another cluster node
    # ------------------------------------------------------------------------------------------------

    @routed
    async def run_step(self, caller: Caller, drone_id: str, spec: dict[str, Any]) -> OperationView:
        """Start one drone's step (`gateway.fleet.fleet_ops.build_step`) as its operation here, with the
        takeoff guard inside its command lock, for the node coordinating the fleet operation."""
        vehicle = self.flown(drone_id)
        guard = spec.get("guard")
        precheck = None if not guard else (lambda v: self._guard_takeoff(caller, v, str(guard)))
        step = build_step(vehicle, spec, precheck)
        op = await self.operations.start(
            vehicle, step.tracker, step.send, step.params, caller.session, step.precheck
        )
        return OperationView.of(op, vehicle)

    @routed
    async def hold_step(self, caller: Caller, drone_id: str, reason: str) -> ActionResult:
        """Hold a drone whose fleet operation (coordinated by another node) was stopped."""
        vehicle = self.flown(drone_id)
        _, sup = await self._instant(
            caller, vehicle, reason, vehicle.hold, safety_action=True, ends_operation=True, commands="hold"
        )
        return ActionResult(
            drone_id=drone_id, action="hold", message="held", superseded_operation=sup and sup.id
        )

    # ------------------------------------------------------------------------------------------------
    # the operator's emergency stop and locks
    # ------------------------------------------------------------------------------------------------

    def _operator_only(self, caller: Caller, what: str) -> None:
        if not caller.is_operator:
            raise refuse(
                Rule.OPERATOR_LOCK,
                f"only an operator may {what}; agents cannot change locks or stop the fleet",
                via=caller.via,
            )

    async def lock(self, caller: Caller, scope: str, reason: str) -> LockResult:
        """Lock one drone (its id) or the fleet ("*") against agents' actuating commands: at once on this
        node and every node that hears the broadcast; stored (later, if the database is unreachable)."""
        self._operator_only(caller, "lock drones")
        result = await self._lock_now(caller, scope, reason)
        result.stored = await self._store_lock(result)
        return result

    async def _lock_now(self, caller: Caller, scope: str, reason: str) -> LockResult:
        """The lock in memory and on the bus: it holds before anything is written."""
        if scope != FLEET:
            self.registry.get(scope)  # UnknownVehicle names the known ids
        lock = self.locks.lock(scope, reason, caller.principal, at=datetime.now(UTC))
        log.warning(
            "operator %s locked %s: %s", lock.by, "the fleet" if scope == FLEET else scope, lock.reason
        )
        result = LockResult(scope=lock.scope, reason=lock.reason, by=lock.by, locked_at=lock.locked_at)
        if self.router is not None:  # every node refuses agents from now on
            await self.router.announce("lock", result.model_dump(mode="json", exclude={"stored"}))
        return result

    async def _store_lock(self, lock: LockResult) -> bool:
        """True when the lock is in the database now; False when it is kept until the database is back."""
        if self.store is None:
            return True
        stored = await self.store.save_lock(lock.scope, lock.reason, lock.by, lock.locked_at)
        if stored is None:
            log.warning("the lock of %s is kept on this node until the database is back", lock.scope)
        return stored is not None

    async def unlock(self, caller: Caller, scope: str) -> UnlockResult:
        self._operator_only(caller, "unlock drones")
        removed = self.locks.unlock(scope)
        stored = await self.store.delete_lock(scope) if self.store is not None else False
        if self.router is not None:
            await self.router.announce("unlock", {"scope": scope})
        if removed or stored:
            log.warning("operator %s unlocked %s", caller.principal, "the fleet" if scope == FLEET else scope)
        return UnlockResult(scope=scope, was_locked=removed is not None or stored)

    # ------------------------------------------------------------------------------------------------
    # takeover locks: a pilot, another ground station or a failsafe took a drone (gateway.fleet.takeover)
    # ------------------------------------------------------------------------------------------------

    async def taken_over(self, vehicle: VehicleView, takeover: Takeover) -> None:
        """The OperationManager saw a mode change the gateway did not command (its operation already
        ended as interrupted): lock the drone for agents, persist and audit the lock, tell the other
        nodes. Nothing is sent to the drone."""
        lock = self.locks.take_over(vehicle.id, takeover.lock_reason(), at=takeover.at)
        if self.store is not None:
            try:
                await self.store.save_takeover(lock.scope, lock.reason, lock.by, lock.locked_at)
                await self.store.add_audit(
                    AuditEntry(
                        principal="autopilot",
                        source="gateway",
                        vehicle_id=vehicle.id,
                        action="takeover",
                        arguments=takeover.to_record(),
                        outcome="ok",
                        error=takeover.message(),
                        t=takeover.at,
                        operation_id=takeover.operation_id,
                    )
                )
            except Exception:  # the lock holds in memory whatever the database says
                log.exception("could not store the takeover of %s", vehicle.id)
        if self.router is not None:
            await self.router.announce(
                "takeover",
                {"scope": lock.scope, "reason": lock.reason, "by": lock.by, "at": lock.locked_at.isoformat()},
            )

    async def release(self, caller: Caller, drone_id: str) -> UnlockResult:
        """An operator gives a taken-over drone back to agents (the pilot is done with it)."""
        self._operator_only(caller, "release a drone taken over by a pilot or ground station")
        self.registry.get(drone_id)
        removed = self.locks.release(drone_id)
        stored = await self.store.delete_takeover(drone_id) if self.store is not None else False
        if self.router is not None:
            await self.router.announce("release", {"scope": drone_id})
        if removed or stored:
            log.warning("operator %s released %s after a takeover", caller.principal, drone_id)
        return UnlockResult(scope=drone_id, was_locked=removed is not None or stored)

    async def stop_all(
        self, caller: Caller, action: StopAction = "hold", lock: bool = True, lock_reason: str | None = None
    ) -> StopResult:
        """Emergency stop: lock the fleet (unless ``lock`` is false and no reason is given), end every
        running fleet operation, then every airborne drone holds, lands or returns, all at once."""
        self._operator_only(caller, "stop the fleet")
        # Nothing here waits on the database: the lock holds in memory (and on every node that hears the
        # broadcast) before the drones are told, and is stored beside the stops, later if need be.
        fleet_lock = None
        storing: asyncio.Task[bool] | None = None
        if lock or lock_reason:
            fleet_lock = await self._lock_now(caller, FLEET, lock_reason or STOP_LOCK_REASON)
            storing = asyncio.create_task(self._store_lock(fleet_lock))
            _STORING.add(storing)  # it may outlive this call (a database that hangs)
            storing.add_done_callback(_STORING.discard)
        vehicles = list(self.registry.all())
        superseded = await self.fleet.supersede([v.id for v in vehicles], f"operator stop ({action})")
        if self.router is not None:  # fleet operations coordinated by other nodes end there too
            await self.router.announce("stop", {"action": action, "by": caller.principal})

        async def one(vehicle: VehicleView) -> StopOutcome:
            state = str(vehicle.state)
            if getattr(vehicle, "remote", False) and getattr(vehicle, "owner", None) is None:
                return StopOutcome(
                    drone_id=vehicle.id,
                    action=action,
                    outcome="unreached",
                    message="no node holds its link right now (its node was lost or could not renew its "
                    "lease): nothing was sent",
                )
            if state in ("registered", "failed"):
                return StopOutcome(
                    drone_id=vehicle.id, action=action, outcome="skipped", message=f"not connected ({state})"
                )
            if vehicle.on_ground() is True:
                return StopOutcome(
                    drone_id=vehicle.id, action=action, outcome="skipped", message="on the ground"
                )
            try:
                return await self.stop_one(caller, vehicle.id, action)
            except (NotRun, NoOwner) as exc:
                return StopOutcome(
                    drone_id=vehicle.id, action=action, outcome="unreached", message=exc.message
                )
            except GatewayError as exc:
                return StopOutcome(drone_id=vehicle.id, action=action, outcome="failed", message=exc.message)
            except Exception as exc:  # one drone's failure must not stop the others
                log.exception("fleet stop: %s failed on %s", action, vehicle.id)
                return StopOutcome(drone_id=vehicle.id, action=action, outcome="failed", message=repr(exc))

        results = await asyncio.gather(*(one(v) for v in vehicles))
        if fleet_lock is not None and storing is not None:
            done, _ = await asyncio.wait({storing}, timeout=STORE_LOCK_WAIT_S)
            fleet_lock.stored = bool(done and not storing.exception() and storing.result())
        return StopResult(
            action=action,
            fleet_lock=fleet_lock,
            superseded_fleet_operations=[f.id for f in superseded],
            results=list(results),
        )

    async def stop_one(self, caller: Caller, drone_id: str, action: StopAction) -> StopOutcome:
        """One drone's part of a stop: hold (ends its operation), land or RTL (tracked operations that
        supersede it). The REST hold/land/RTL routes are this too."""
        previous = self._running(drone_id)
        if action == "hold":
            held = await self.hold(caller, drone_id, "operator hold")
            return StopOutcome(
                drone_id=drone_id,
                action=action,
                outcome="sent",
                superseded_operation=held.superseded_operation,
            )
        op = await (
            self.land(caller, drone_id) if action == "land" else self.return_to_launch(caller, drone_id)
        )
        return StopOutcome(
            drone_id=drone_id,
            action=action,
            outcome="sent",
            superseded_operation=None if previous is None else previous.operation_id,
            operation_id=op.operation_id,
        )


def _travel_heading(starts: Sequence[DroneStart], lat: float, lon: float) -> float:
    """Bearing from the drones' centroid to the formation centre (0 when already there)."""
    c_lat = sum(s.lat for s in starts) / len(starts)
    c_lon = sum(s.lon for s in starts) / len(starts)
    if geo.horizontal_distance_m(c_lat, c_lon, lat, lon) < 1.0:
        return 0.0
    return round(geo.bearing_deg(c_lat, c_lon, lat, lon) % 360.0, 1)
