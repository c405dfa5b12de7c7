"""The Commander's verbs on several drones: formation, fleet takeoff, land, return, hold (the
operator's locks and emergency stop are `gateway.fleet.commands.operator_verbs`).

Who takes part (the same rule for every fleet verb, also in docs/fleet.md):
- formation_goto and fleet_takeoff change the fleet's geometry: every named drone is checked first and
  if any cannot take part (unknown, not ready, locked, busy, low battery, on the ground...) nothing is
  sent and the error names each such drone with the reason (rule and numbers).
- fleet_land, fleet_return_to_launch and fleet_hold bring drones down or stop them: they go to every
  drone that can take them, and the result lists the others (not_sent) with the reason.
- stop_all (`operator_verbs`) is the operator's emergency stop, to every airborne drone.
"""

from __future__ import annotations

import asyncio
import contextlib
import dataclasses
import logging
from collections.abc import Awaitable, Callable, Sequence
from typing import Annotated, Literal

from pydantic import Field

from gateway.config import Settings
from gateway.errors import GatewayError, InvalidArgument, SafetyRefusal, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.commands.arguments import DroneIds, FleetAlt, Metres, SomeDrones
from gateway.fleet.commands.command_core import OperationDesk, Tool, command
from gateway.fleet.commands.command_pass import CommandPass
from gateway.fleet.commands.drone_verbs import FlightVerbs
from gateway.fleet.commands.fleet_step_verbs import FleetStepVerbs
from gateway.fleet.commands.verb_rules import arming_deadline, left, require_airborne
from gateway.fleet.formation.formation import DroneStart, plan_formation, rtl_altitudes, takeoff_altitudes
from gateway.fleet.operations.fleet_operation import FleetOperation
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.operations.fleet_refusals import Unable, check_drone_ids, collect_members, refuse_fleet
from gateway.fleet.operations.fleet_steps import (
    FORMATION_TOLERANCE_M,
    default_rtl_base_m,
    formation_phases,
    land_phase,
    rtl_order,
    rtl_phases,
    slot_summaries,
    takeoff_phase,
)
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.operations.routing import Router
from gateway.fleet.operations.views import (
    FleetHoldResult,
    FleetView,
)
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import VehicleContext
from gateway.fleet.vehicles.protocols import Notify, VehicleDirectory, VehicleView
from gateway.fleet.vehicles.readings import home, is_landed_and_disarmed, position, vehicle_context
from gateway.registry.store import Store
from gateway.util.json_types import JsonObject, json_list, json_object
from gateway.util.read_through import ReadThrough

log = logging.getLogger(__name__)

Formation = Literal["line", "column", "wedge", "grid", "circle"]
OnFleetProgress = Callable[[FleetView], Awaitable[None]]


class FleetVerbs:
    """Commands on several drones at once: fleet-level checks and plans, then the same pass per drone
    (`CommandPass.run`, through `FleetStepVerbs.step_here` / `hold_here` in
    `gateway.fleet.commands.fleet_step_verbs`, or the drone's owner in a cluster). The operator's locks
    and emergency stop are `gateway.fleet.commands.operator_verbs`."""

    store = ReadThrough[Store | None]("desk")  # the one the desk keeps the operations in
    # the pass's collaborators, read of it
    settings = ReadThrough[Settings]("commands")
    registry = ReadThrough[VehicleDirectory]("commands")
    router = ReadThrough[Router | None]("commands")
    safety = ReadThrough[SafetyPolicy]("commands")
    operations = ReadThrough[OperationManager]("commands")

    def __init__(
        self,
        commands: CommandPass,
        desk: OperationDesk,
        flight: FlightVerbs,
        fleet: FleetOperations,
        steps: FleetStepVerbs,
    ) -> None:
        self.commands = commands
        self.steps = steps
        self.desk = desk
        self.flight = flight
        self.fleet = fleet

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
            conflicts = fop.plan.get("conflicts")
            plan["conflicts_resolved"] = len(conflicts) if isinstance(conflicts, list) else 0
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

    def _busy(self, ctx: VehicleContext, action: str) -> None:
        self.safety.check_not_busy(ctx, self.commands.running(ctx.vehicle_id), action)

    def _stagger(self, stagger_m: float | None) -> float:
        """Default: the minimum separation plus 1 m of altitude-holding error for each of two drones."""
        return self.settings.min_separation_m + 2 * FORMATION_TOLERANCE_M if stagger_m is None else stagger_m

    def _members(
        self, caller: Caller, ids: Sequence[str], check: Callable[[VehicleView], None]
    ) -> tuple[dict[str, VehicleView], list[Unable]]:
        """Every drone looked up and checked; a drone a pilot took over is named as taken over before any
        other check (an agent's answer says who has it, not that its link is down meanwhile)."""

        def pilot_first(vehicle: VehicleView) -> None:
            if not caller.is_operator:
                self.commands.refuse_taken_over(vehicle.id)
            check(vehicle)

        return collect_members(ids, self.registry.get, pilot_first)

    def _recovery_members(
        self,
        caller: Caller,
        drone_ids: Sequence[str] | None,
        action: str,
        check: Callable[[VehicleView], None],
    ) -> tuple[list[str], dict[str, VehicleView], list[Unable]]:
        ids = self._all_ids(drone_ids)
        vehicles, unable = self._members(caller, ids, check)
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
                waits.append(self.registry.get(drone_id).wait_initialised(left(deadline), notify))
        await asyncio.gather(*waits, return_exceptions=True)

    # ------------------------------------------------------------------------------------------------
    # formation and fleet takeoff: all drones or none
    # ------------------------------------------------------------------------------------------------

    @command(
        tool=Tool(
            "formation_goto",
            "fleet",
            description="Fly drones into a formation at a centre (default: theirs), kept apart; grounded "
            "ones take off first.",
        )
    )
    async def formation_goto(
        self,
        caller: Caller,
        drone_ids: DroneIds,
        formation: Formation,
        alt_m: FleetAlt,
        center_lat_deg: Annotated[float | None, Field(ge=-90, le=90, allow_inf_nan=False)] = None,
        center_lon_deg: Annotated[float | None, Field(ge=-180, le=180, allow_inf_nan=False)] = None,
        north_m: Annotated[Metres, Field(description="Centre moved north; default: where they are")] = 0.0,
        east_m: Annotated[Metres, Field(description="Centre moved east")] = 0.0,
        spacing_m: Annotated[
            float, Field(gt=0, le=1000, allow_inf_nan=False, description="m between slots")
        ] = 10.0,
        heading_deg: Annotated[
            float | None, Field(ge=0, lt=360, allow_inf_nan=False, description="Facing; default: travel")
        ] = None,
        *,
        notify: Notify | None = None,
    ) -> FleetView:
        """Fly drones into a formation around a point, kept apart; all must join or nothing is sent. The
        point: the centre given, else the drones' own centre (where they are), moved ``north_m`` and
        ``east_m``. Drones on the ground take off first (a first phase, to staggered altitudes as in
        `fleet_takeoff`); then the three phases with barriers of `gateway.fleet.formation.formation`."""
        ids = check_drone_ids(drone_ids)
        _check_centre_args(center_lat_deg, center_lon_deg, north_m, east_m)
        policy = self.safety
        via = caller.policy_via
        deadline = arming_deadline(self.settings)
        grounded = [d for d in ids if self._on_ground(d)]
        if grounded:
            await self._initialised(grounded, notify, deadline)
        low, high = policy.altitude_band(ids)
        climbs = takeoff_altitudes(grounded, alt_m, self._stagger(None), high) if grounded else {}

        contexts: dict[str, VehicleContext] = {}

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = contexts[v.id] = vehicle_context(v)
            self.commands.guard_takeoff(caller, ctx, "formation_goto")
            if v.id in climbs:
                policy.check_takeoff(ctx, climbs[v.id], via)
            else:
                require_airborne(ctx, "formation_goto")
            self._busy(ctx, "formation_goto")
            if ctx.position is None:
                raise VehicleNotReady(f"no position received from {v.id} yet")
            policy.check_actuation(ctx, via)

        vehicles, unable = self._members(caller, ids, check)
        if unable:
            raise refuse_fleet("formation_goto", unable, len(ids))
        starts = [
            DroneStart(d, pos[0], pos[1], climbs.get(d, pos[2]))
            for d in ids
            if (pos := contexts[d].position) is not None
        ]
        center_lat_deg, center_lon_deg = _formation_centre(
            starts, center_lat_deg, center_lon_deg, north_m, east_m
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
        params: JsonObject = {
            "formation": formation,
            "center_lat_deg": center_lat_deg,
            "center_lon_deg": center_lon_deg,
            "alt_m": alt_m,
            "spacing_m": spacing_m,
            "heading_deg": round(plan.heading_deg, 1),
        }
        phases = formation_phases(plan, vehicles, guard="formation_goto")
        if climbs:
            params["took_off_first"] = json_object(climbs)
            first = takeoff_phase({d: vehicles[d] for d in climbs}, climbs, "formation_goto", left(deadline))
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

    @command(tool=Tool("fleet_takeoff", "fleet"))
    async def fleet_takeoff(
        self,
        caller: Caller,
        drone_ids: DroneIds,
        alt_m: FleetAlt,
        stagger_m: Annotated[
            float | None, Field(ge=0, le=100, allow_inf_nan=False, description="m between drones' altitudes")
        ] = None,
        *,
        notify: Notify | None = None,
    ) -> FleetView:
        """Take off drones at once to alt_m, alt_m+stagger, ... (given order). All must be able, or none go.

        Drones still initialising are waited for first (``notify`` hears what each waits
        for); that wait and the drones' arming share one deadline, the wait cap."""
        ids = check_drone_ids(drone_ids)
        policy = self.safety
        _low, high = policy.altitude_band(ids)
        altitudes = takeoff_altitudes(ids, alt_m, self._stagger(stagger_m), high)
        deadline = arming_deadline(self.settings)
        await self._initialised(ids, notify, deadline)

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = vehicle_context(v)
            if ctx.in_air:
                raise InvalidArgument(f"{v.id} is already flying; use formation_goto or go_to_location")
            self._busy(ctx, "fleet_takeoff")
            policy.check_takeoff(ctx, altitudes[v.id], caller.policy_via)

        vehicles, unable = self._members(caller, ids, check)
        if unable:
            raise refuse_fleet("fleet_takeoff", unable, len(ids))
        fop = await self.fleet.start(
            "fleet_takeoff",
            ids,
            [
                takeoff_phase(
                    vehicles,
                    altitudes,
                    "fleet_takeoff",
                    arm_within_s=left(deadline),
                )
            ],
            {"alt_m": alt_m, "altitudes_m": json_object(altitudes)},
            caller.session,
            caller=caller,
            slots={d: {"target_alt_m": a} for d, a in altitudes.items()},
        )
        return self.fleet_view(fop)

    # ------------------------------------------------------------------------------------------------
    # recovery: to every drone that can take it
    # ------------------------------------------------------------------------------------------------

    @command(tool=Tool("fleet_land", "fleet", idempotent=True))
    async def fleet_land(self, caller: Caller, drone_ids: SomeDrones = None) -> FleetView:
        """Land drones in place, all at once; done when disarmed. Those that cannot are listed in not_sent."""

        def check(v: VehicleView) -> None:
            v.require_ready()
            if is_landed_and_disarmed(v):
                raise InvalidArgument(f"{v.id} is already on the ground and disarmed")
            self.safety.check_actuation(vehicle_context(v), caller.policy_via)

        ids, vehicles, unable = self._recovery_members(caller, drone_ids, "fleet_land", check)
        fop = await self.fleet.start(
            "fleet_land",
            list(vehicles),
            [land_phase(vehicles)],
            {"drone_ids": json_list(ids)},
            caller.session,
            caller=caller,
        )
        return self.fleet_view(fop, unable)

    @command(tool=Tool("fleet_return_to_launch", "fleet", idempotent=True))
    async def fleet_return_to_launch(
        self,
        caller: Caller,
        drone_ids: SomeDrones = None,
        rtl_alt_m: Annotated[
            float | None, Field(gt=0, le=10_000, allow_inf_nan=False, description="Lowest return alt, m")
        ] = None,
        stagger_m: Annotated[
            float | None, Field(ge=0, le=100, allow_inf_nan=False, description="m between return altitudes")
        ] = None,
    ) -> FleetView:
        """Fly drones home at separate altitudes and land. Those that cannot are listed in not_sent.

        Each climbs or descends in place to its altitude first."""
        stagger = self._stagger(stagger_m)
        sep = self.settings.min_separation_m
        self.safety.check_stagger(stagger)

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = vehicle_context(v)
            require_airborne(ctx, "fleet_return_to_launch")
            if ctx.position is None:
                raise VehicleNotReady(f"no position received from {v.id} yet")
            self.safety.check_actuation(ctx, caller.policy_via)
            self.safety.check_param_write(
                v.return_altitude_param()[0], via=caller.policy_via, vehicle_id=v.id, governed=v.limit_params
            )

        ids, vehicles, unable = self._recovery_members(caller, drone_ids, "fleet_return_to_launch", check)
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
            {"drone_ids": json_list(ids), "rtl_altitudes_m": json_object(altitudes)},
            caller.session,
            caller=caller,
            slots={d: {"rtl_alt_m": a} for d, a in altitudes.items()},
            notes=notes,
        )
        return self.fleet_view(fop, unable)

    @command(tool=Tool("fleet_hold", "fleet", idempotent=True))
    async def fleet_hold(self, caller: Caller, drone_ids: SomeDrones = None) -> FleetHoldResult:
        """Stop drones where they are (GUIDED hover), ending their actions. Those that cannot: not_sent.

        Ends their operations and any fleet operation they are part of."""

        def check(v: VehicleView) -> None:
            v.require_ready()
            ctx = vehicle_context(v)
            require_airborne(ctx, "fleet_hold")
            self.safety.check_actuation(ctx, caller.policy_via)

        _ids, vehicles, unable = self._recovery_members(caller, drone_ids, "fleet_hold", check)
        superseded = await self.fleet.supersede(vehicles, "fleet_hold")
        failed: list[dict[str, object]] = []

        async def hold(drone_id: str, v: VehicleView) -> None:
            try:
                await self.steps.hold_step(caller, drone_id, "fleet_hold")  # on its owner, in a cluster
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


def _check_centre_args(lat: float | None, lon: float | None, north_m: float, east_m: float) -> None:
    if (lat is None) != (lon is None):
        raise InvalidArgument(
            "give both center_lat_deg and center_lon_deg, or neither (the formation is then centred "
            "where the drones are, moved north_m/east_m)"
        )
    for name, metres in (("north_m", north_m), ("east_m", east_m)):
        geo.check_finite(name, metres)


def _formation_centre(
    starts: Sequence[DroneStart], lat: float | None, lon: float | None, north_m: float, east_m: float
) -> tuple[float, float]:
    """The centre given, else the drones' own centre, moved ``north_m`` and ``east_m``."""
    if lat is None or lon is None:
        lat = sum(s.lat for s in starts) / len(starts)
        lon = sum(s.lon for s in starts) / len(starts)
    if north_m or east_m:
        lat, lon = geo.offset_position(lat, lon, north_m, east_m)
    return lat, lon


def _travel_heading(starts: Sequence[DroneStart], lat: float, lon: float) -> float:
    """Bearing from the drones' centroid to the formation centre (0 when already there)."""
    c_lat = sum(s.lat for s in starts) / len(starts)
    c_lon = sum(s.lon for s in starts) / len(starts)
    if geo.horizontal_distance_m(c_lat, c_lon, lat, lon) < 1.0:
        return 0.0
    return round(geo.bearing_deg(c_lat, c_lon, lat, lon) % 360.0, 1)
