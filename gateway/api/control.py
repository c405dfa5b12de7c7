"""Operator take-over: locks (per drone and fleet-wide), hold / land / RTL, and the fleet stop.

A lock refuses agents' (MCP) actuating commands on the drone; it is persisted and survives restarts.
The actions here are the operator's own commands, each one Commander call with ``via="rest"``: land
and RTL are tracked operations, hold ends the drone's current operation, and the fleet stop ends every
running fleet operation before it tells the drones anything.
"""

from __future__ import annotations

from typing import Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field, StrictBool

from gateway.api.audit import AuditedRoute
from gateway.api.deps import CommanderDep, CommandVehicleId, GatewayDep, Principal, PrincipalDep
from gateway.fleet.commands.operator_verbs import STOP_LOCK_REASON
from gateway.fleet.operations.views import LockResult, OperationView, StopOutcome, StopReport, UnlockResult
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.geofence import FLEET
from gateway.fleet.policy.operator_locks import MAX_REASON_CHARS

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)

Action = Literal["hold", "land", "rtl"]


def operator(who: Principal) -> Caller:
    """The Commander's caller for a REST request."""
    return Caller(via=who.door, principal=who.name, session=who.session_key)


class LockIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    reason: str = Field(
        min_length=1, max_length=MAX_REASON_CHARS, description="Why; agents and operators are shown it."
    )


class LockList(BaseModel):
    items: list[LockResult]


class CommandOut(StopReport):
    """What an operator command did to one drone (`StopOutcome`, with the REST API's ``vehicle_id``)."""

    vehicle_id: str

    @classmethod
    def of_operation(cls, op: OperationView, action: str) -> CommandOut:
        return cls(vehicle_id=op.drone_id, action=action, outcome="sent", operation_id=op.operation_id)

    @classmethod
    def of_outcome(cls, r: StopOutcome) -> CommandOut:
        return cls(vehicle_id=r.drone_id, **r.model_dump(exclude={"drone_id"}))


class StopIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    action: Literal["hold", "land", "rtl"] = Field(
        "hold",
        description="What every airborne drone is told to do: hold (GUIDED), land, or rtl.",
    )
    lock: StrictBool = Field(
        True,
        description="Lock the fleet (before stopping) so agents cannot resume; false: locks unchanged.",
    )
    lock_reason: str | None = Field(
        None,
        min_length=1,
        max_length=MAX_REASON_CHARS,
        description=f"Reason of the fleet lock (default: '{STOP_LOCK_REASON}').",
    )


class StopOut(BaseModel):
    action: str
    fleet_lock: LockResult | None
    superseded_fleet_operations: list[str] = Field(
        default_factory=list, description="Fleet operations (formations...) ended before the stop."
    )
    results: list[CommandOut]


# --- locks ---------------------------------------------------------------------------------------


@router.get("/locks", response_model=LockList, summary="Operator locks in force")
async def list_locks(gateway: GatewayDep) -> LockList:
    return LockList(items=[LockResult.of(lk) for lk in gateway.locks.all()])


@router.post("/vehicles/{vehicle_id}/lock", response_model=LockResult, summary="Lock a drone against agents")
async def lock_vehicle(
    vehicle_id: CommandVehicleId, body: LockIn, commander: CommanderDep, who: PrincipalDep
) -> LockResult:
    return await commander.lock(operator(who), vehicle_id, body.reason)


@router.delete("/vehicles/{vehicle_id}/lock", response_model=UnlockResult, summary="Unlock a drone")
async def unlock_vehicle(
    vehicle_id: CommandVehicleId, commander: CommanderDep, who: PrincipalDep
) -> UnlockResult:
    return await commander.unlock(operator(who), vehicle_id)


@router.post("/fleet/lock", response_model=LockResult, summary="Lock the whole fleet against agents")
async def lock_fleet(body: LockIn, commander: CommanderDep, who: PrincipalDep) -> LockResult:
    return await commander.lock(operator(who), FLEET, body.reason)


@router.delete("/fleet/lock", response_model=UnlockResult, summary="Remove the fleet lock")
async def unlock_fleet(commander: CommanderDep, who: PrincipalDep) -> UnlockResult:
    return await commander.unlock(operator(who), FLEET)


# --- takeover locks (a pilot, another ground station or a failsafe took the drone) ----------------


@router.get("/takeovers", response_model=LockList, summary="Drones taken over by a pilot or ground station")
async def list_takeovers(gateway: GatewayDep) -> LockList:
    """Drones whose mode a pilot, another ground station or a failsafe changed while the gateway flew
    them: agents are refused until an operator releases them (docs/safety.md)."""
    return LockList(items=[LockResult.of(lk) for lk in gateway.locks.takeovers()])


@router.delete(
    "/vehicles/{vehicle_id}/takeover",
    response_model=UnlockResult,
    summary="Release a drone taken over by a pilot or ground station",
)
async def release_takeover(
    vehicle_id: CommandVehicleId, commander: CommanderDep, who: PrincipalDep
) -> UnlockResult:
    """Agents may command the drone again (the pilot or ground station is done with it)."""
    return await commander.release(operator(who), vehicle_id)


# --- actions -------------------------------------------------------------------------------------


def _action_route(action: Action) -> None:
    """Hold (ends the drone's current operation), land or RTL (tracked operations superseding it): the
    Commander's stop of one drone, as the fleet stop sends it to each."""

    async def endpoint(
        vehicle_id: CommandVehicleId, commander: CommanderDep, who: PrincipalDep
    ) -> CommandOut:
        return CommandOut.of_outcome(await commander.stop_one(operator(who), vehicle_id, action))

    endpoint.__name__ = f"{action}_vehicle"
    router.add_api_route(
        f"/vehicles/{{vehicle_id}}/{action}",
        endpoint,
        methods=["POST"],
        response_model=CommandOut,
        summary={"hold": "Hold position", "land": "Land", "rtl": "Return to launch"}[action] + " (operator)",
    )


_action_route("hold")
_action_route("land")
_action_route("rtl")


@router.post(
    "/fleet/stop",
    response_model=StopOut,
    summary="Emergency stop: lock the fleet, then every airborne drone holds, lands or returns",
)
async def fleet_stop(commander: CommanderDep, who: PrincipalDep, body: StopIn | None = None) -> StopOut:
    body = body or StopIn()
    result = await commander.stop_all(operator(who), body.action, body.lock, body.lock_reason)
    return StopOut(
        action=result.action,
        fleet_lock=result.fleet_lock,
        superseded_fleet_operations=result.superseded_fleet_operations,
        results=[CommandOut.of_outcome(r) for r in result.results],
    )
