"""Operator take-over of the fleet: the locks and takeovers in force and the fleet stop, and the answer
of an operator's command on one drone (`CommandOut`).

A lock refuses agents' (MCP) actuating commands on the drone; it is persisted and survives restarts.
The routes that lock, unlock or release (a drone or the fleet) and those on one drone (hold / land /
RTL, takeoff, goto, kill, the mission's start, pause and resume, the origin) are declared by their
verbs (``@command(route=Route(...))``) and made by `gateway.api.declared`. The fleet stop ends every
running fleet operation before it tells the drones anything.
"""

from __future__ import annotations

from typing import Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field, StrictBool

from gateway.api.audit import AuditedRoute
from gateway.api.deps import CommanderDep, GatewayDep, Principal, PrincipalDep
from gateway.fleet.commands.operator_verbs import STOP_LOCK_REASON
from gateway.fleet.operations.views import LockResult, OperationView, StopOutcome, StopReport
from gateway.fleet.policy.caller import Caller
from gateway.fleet.policy.operator_locks import MAX_REASON_CHARS

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)


def operator(who: Principal) -> Caller:
    """The Commander's caller for a REST request."""
    return Caller(via=who.door, principal=who.name, session=who.session_key)


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


# --- takeover locks (a pilot, another ground station or a failsafe took the drone) ----------------


@router.get("/takeovers", response_model=LockList, summary="Drones taken over by a pilot or ground station")
async def list_takeovers(gateway: GatewayDep) -> LockList:
    """Drones whose mode a pilot, another ground station or a failsafe changed while the gateway flew
    them: agents are refused until an operator releases them (docs/safety.md)."""
    return LockList(items=[LockResult.of(lk) for lk in gateway.locks.takeovers()])


# --- the fleet stop ------------------------------------------------------------------------------


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
