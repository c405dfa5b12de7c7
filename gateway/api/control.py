"""Operator take-over: locks (per drone and fleet-wide), hold / land / RTL, and the fleet stop.

A lock refuses agents' (MCP) actuating commands on the drone; it is persisted and survives restarts.
The actions here are the operator's own commands: they supersede the drone's current MCP operation.
"""

from __future__ import annotations

import asyncio
import logging
from datetime import UTC, datetime
from typing import Any, Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.deps import GatewayDep, PrincipalDep, RegistryDep, StoreDep
from gateway.errors import GatewayError, UnknownVehicle
from gateway.fleet.geofence import FLEET
from gateway.fleet.safety import MAX_REASON_CHARS, Lock

log = logging.getLogger(__name__)

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)

Action = Literal["hold", "land", "rtl"]
STOP_LOCK_REASON = "emergency stop"
_ACTIONS: dict[str, str] = {"hold": "hold", "land": "land", "rtl": "return_to_launch"}


class LockIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    reason: str = Field(
        min_length=1, max_length=MAX_REASON_CHARS, description="Why; agents and operators are shown it."
    )


class LockOut(BaseModel):
    scope: str = Field(description='A vehicle id, or "*" for the whole fleet.')
    reason: str
    by: str
    locked_at: datetime

    @classmethod
    def of(cls, lock: Lock) -> LockOut:
        return cls(scope=lock.scope, reason=lock.reason, by=lock.by, locked_at=lock.locked_at)


class UnlockOut(BaseModel):
    scope: str
    was_locked: bool


class LockList(BaseModel):
    items: list[LockOut]


class ActionOut(BaseModel):
    vehicle_id: str
    action: str
    outcome: Literal["sent", "skipped", "failed"]
    message: str | None = None
    superseded_operation: str | None = None


class StopIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    action: Literal["hold", "land", "rtl"] = Field(
        "hold",
        description="What every airborne drone is told to do: hold (GUIDED), land, or rtl.",
    )
    lock: bool = Field(
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
    fleet_lock: LockOut | None
    results: list[ActionOut]


# --- locks ---------------------------------------------------------------------------------------


async def _lock(gateway: Any, store: Any, scope: str, reason: str, by: str) -> LockOut:
    lock = gateway.locks.lock(scope, reason, by, at=datetime.now(UTC))
    await store.save_lock(lock.scope, lock.reason, lock.by, lock.locked_at)
    if getattr(gateway, "cluster", None) is not None:  # every node refuses agents from now on
        await gateway.cluster.announce(
            "lock",
            {"scope": lock.scope, "reason": lock.reason, "by": lock.by, "at": lock.locked_at.isoformat()},
        )
    log.warning("operator %s locked %s: %s", by, "the fleet" if scope == FLEET else scope, lock.reason)
    return LockOut.of(lock)


async def _unlock(gateway: Any, store: Any, scope: str, by: str) -> UnlockOut:
    removed = gateway.locks.unlock(scope)
    stored = await store.delete_lock(scope)
    if getattr(gateway, "cluster", None) is not None:
        await gateway.cluster.announce("unlock", {"scope": scope})
    if removed or stored:
        log.warning("operator %s unlocked %s", by, "the fleet" if scope == FLEET else scope)
    return UnlockOut(scope=scope, was_locked=removed is not None or stored)


@router.get("/locks", response_model=LockList, summary="Operator locks in force")
async def list_locks(gateway: GatewayDep) -> LockList:
    return LockList(items=[LockOut.of(lk) for lk in gateway.locks.all()])


@router.post("/vehicles/{vehicle_id}/lock", response_model=LockOut, summary="Lock a drone against agents")
async def lock_vehicle(
    vehicle_id: str,
    body: LockIn,
    gateway: GatewayDep,
    store: StoreDep,
    registry: RegistryDep,
    who: PrincipalDep,
) -> LockOut:
    registry.get(vehicle_id)  # UnknownVehicle names the known ids
    return await _lock(gateway, store, vehicle_id, body.reason, who.name)


@router.delete("/vehicles/{vehicle_id}/lock", response_model=UnlockOut, summary="Unlock a drone")
async def unlock_vehicle(
    vehicle_id: str, gateway: GatewayDep, store: StoreDep, who: PrincipalDep
) -> UnlockOut:
    return await _unlock(gateway, store, vehicle_id, who.name)


@router.post("/fleet/lock", response_model=LockOut, summary="Lock the whole fleet against agents")
async def lock_fleet(body: LockIn, gateway: GatewayDep, store: StoreDep, who: PrincipalDep) -> LockOut:
    return await _lock(gateway, store, FLEET, body.reason, who.name)


@router.delete("/fleet/lock", response_model=UnlockOut, summary="Remove the fleet lock")
async def unlock_fleet(gateway: GatewayDep, store: StoreDep, who: PrincipalDep) -> UnlockOut:
    return await _unlock(gateway, store, FLEET, who.name)


# --- actions -------------------------------------------------------------------------------------


async def _act(gateway: Any, vehicle: Any, action: str) -> ActionOut:
    """Send hold/land/rtl; the drone's running MCP operation (if any) is marked superseded. A drone
    owned by another cluster node gets it from its owner."""
    if getattr(vehicle, "remote", False):
        done = await vehicle.call("operator_action", {"action": action})
        return ActionOut.model_validate({k: v for k, v in done.items() if k in ActionOut.model_fields})
    await getattr(vehicle, _ACTIONS[action])()
    superseded = None
    if gateway.operations is not None:
        op = await gateway.operations.supersede(vehicle.id, by=f"operator {action}")
        superseded = getattr(op, "id", None)
    return ActionOut(vehicle_id=vehicle.id, action=action, outcome="sent", superseded_operation=superseded)


def _action_route(action: Action) -> None:
    async def endpoint(vehicle_id: str, gateway: GatewayDep, registry: RegistryDep) -> ActionOut:
        return await _act(gateway, registry.get(vehicle_id), action)

    endpoint.__name__ = f"{action}_vehicle"
    router.add_api_route(
        f"/vehicles/{{vehicle_id}}/{action}",
        endpoint,
        methods=["POST"],
        response_model=ActionOut,
        summary={"hold": "Hold position", "land": "Land", "rtl": "Return to launch"}[action] + " (operator)",
    )


for _action in ("hold", "land", "rtl"):
    _action_route(_action)  # type: ignore[arg-type]


def _in_air(vehicle: Any) -> bool | None:
    return vehicle.telemetry.fresh("in_air")


@router.post(
    "/fleet/stop",
    response_model=StopOut,
    summary="Emergency stop: lock the fleet, then every airborne drone holds, lands or returns",
)
async def fleet_stop(
    gateway: GatewayDep, store: StoreDep, registry: RegistryDep, who: PrincipalDep, body: StopIn | None = None
) -> StopOut:
    body = body or StopIn()
    fleet_lock = None
    if body.lock or body.lock_reason:
        reason = body.lock_reason or STOP_LOCK_REASON
        fleet_lock = await _lock(gateway, store, FLEET, reason, who.name)

    async def one(vehicle: Any) -> ActionOut:
        state = str(getattr(vehicle.state, "value", vehicle.state))
        if state in ("registered", "failed"):
            message = f"not connected ({state})"
            return ActionOut(vehicle_id=vehicle.id, action=body.action, outcome="skipped", message=message)
        if _in_air(vehicle) is False:
            return ActionOut(
                vehicle_id=vehicle.id, action=body.action, outcome="skipped", message="on the ground"
            )
        try:
            return await _act(gateway, vehicle, body.action)
        except (GatewayError, UnknownVehicle) as exc:
            return ActionOut(vehicle_id=vehicle.id, action=body.action, outcome="failed", message=exc.message)
        except Exception as exc:  # one drone's failure must not stop the others
            log.exception("fleet stop: %s failed on %s", body.action, vehicle.id)
            return ActionOut(vehicle_id=vehicle.id, action=body.action, outcome="failed", message=repr(exc))

    results = await asyncio.gather(*(one(v) for v in registry.all()))
    return StopOut(action=body.action, fleet_lock=fleet_lock, results=list(results))
