"""/api/v1/vehicles: register, list, inspect, change, remove, connect and disconnect drones.

Each change is one call of its verb with the operator's caller (`gateway.fleet.commands.registry_verbs`:
`register_drone`, `update_drone`, `remove_drone`, `connect_drone`, `disconnect_drone`); the answer is
the stored registration with the live vehicle's state."""

from __future__ import annotations

from typing import Annotated

from fastapi import APIRouter, Query, Response
from fastapi.encoders import jsonable_encoder

from gateway.api.audit import AuditedRoute
from gateway.api.control import operator
from gateway.api.deps import CommanderDep, GatewayDep, PrincipalDep, RegistryDep, StoreDep
from gateway.api.schemas import (
    IsoTime,
    StatusTextList,
    VehicleCreate,
    VehicleList,
    VehicleOut,
    VehicleUpdate,
    as_utc,
)
from gateway.errors import UnknownVehicle
from gateway.fleet.policy.operator_locks import LockView
from gateway.fleet.vehicles.protocols import VehicleRegistry, VehicleView
from gateway.registry.store import Store, VehicleRecord

router = APIRouter(prefix="/vehicles", tags=["vehicles"], route_class=AuditedRoute)


def _live(registry: VehicleRegistry, vehicle_id: str) -> VehicleView | None:
    """The registry's Vehicle, or None when the registry does not hold it."""
    try:
        return registry.get(vehicle_id)
    except UnknownVehicle:
        return None


def vehicle_view(
    record: VehicleRecord,
    vehicle: VehicleView | None,
    with_telemetry: bool = False,
    locks: LockView | None = None,
) -> VehicleOut:
    data: dict[str, object] = record.model_dump()
    if locks is not None:
        data["locked"] = locks.reason_for(record.id)
        taken = locks.takeover_for(record.id)
        if taken is not None:
            data["taken_over"] = {
                "reason": taken.reason,
                "by": taken.by,
                "locked_at": taken.locked_at.isoformat(),
            }
    if vehicle is not None:
        status = jsonable_encoder(vehicle.status())
        data["status"] = status
        state = status.get("state", vehicle.state) if isinstance(status, dict) else vehicle.state
        data["state"] = str(getattr(state, "value", state))
        if with_telemetry:
            data["telemetry"] = jsonable_encoder(vehicle.telemetry.snapshot())
    return VehicleOut.model_validate(data)


async def _record(store: Store, registry: VehicleRegistry, vehicle_id: str) -> VehicleRecord:
    record = await store.get_vehicle(vehicle_id)
    if record is None:
        raise UnknownVehicle(vehicle_id[:64], [v.id for v in await store.list_vehicles()])
    return record


@router.get("", response_model=VehicleList, summary="List registered vehicles with their state")
async def list_vehicles(store: StoreDep, registry: RegistryDep, gateway: GatewayDep) -> VehicleList:
    records = await store.list_vehicles()
    items = [vehicle_view(r, _live(registry, r.id), locks=gateway.locks) for r in records]
    return VehicleList(items=items, total=len(items))


@router.post("", status_code=201, response_model=VehicleOut, summary="Register a vehicle")
async def register_vehicle(
    body: VehicleCreate,
    registry: RegistryDep,
    commander: CommanderDep,
    who: PrincipalDep,
    gateway: GatewayDep,
) -> VehicleOut:
    record = await commander.register_drone(operator(who), body.to_spec(), body.connect)
    return vehicle_view(record, _live(registry, record.id), locks=gateway.locks)


@router.get("/{vehicle_id}", response_model=VehicleOut, summary="A vehicle with state and latest telemetry")
async def get_vehicle(
    vehicle_id: str, store: StoreDep, registry: RegistryDep, gateway: GatewayDep
) -> VehicleOut:
    record = await _record(store, registry, vehicle_id)
    return vehicle_view(record, _live(registry, vehicle_id), with_telemetry=True, locks=gateway.locks)


@router.patch("/{vehicle_id}", response_model=VehicleOut, summary="Change a vehicle's registration")
async def update_vehicle(
    vehicle_id: str,
    body: VehicleUpdate,
    registry: RegistryDep,
    commander: CommanderDep,
    who: PrincipalDep,
    gateway: GatewayDep,
) -> VehicleOut:
    record = await commander.update_drone(operator(who), vehicle_id, body.changes())
    return vehicle_view(record, _live(registry, vehicle_id), locks=gateway.locks)


@router.delete("/{vehicle_id}", status_code=204, summary="Remove a vehicle (stops its sidecar)")
async def remove_vehicle(vehicle_id: str, commander: CommanderDep, who: PrincipalDep) -> Response:
    await commander.remove_drone(operator(who), vehicle_id)
    return Response(status_code=204)


def _sidecar_route(action: str, summary: str) -> None:
    """POST /vehicles/{vehicle_id}/connect or /disconnect: its verb with the operator's caller; the
    registration after it."""

    async def endpoint(
        vehicle_id: str,
        registry: RegistryDep,
        commander: CommanderDep,
        who: PrincipalDep,
        gateway: GatewayDep,
    ) -> VehicleOut:
        verb = commander.connect_drone if action == "connect" else commander.disconnect_drone
        record = await verb(operator(who), vehicle_id)
        return vehicle_view(record, _live(registry, vehicle_id), locks=gateway.locks)

    endpoint.__name__ = f"{action}_vehicle"
    router.add_api_route(
        f"/{{vehicle_id}}/{action}", endpoint, methods=["POST"], response_model=VehicleOut, summary=summary
    )


_sidecar_route("connect", "Start the vehicle's sidecar")
_sidecar_route("disconnect", "Stop the vehicle's sidecar")


@router.get("/{vehicle_id}/statustexts", response_model=StatusTextList, summary="Recent STATUSTEXT messages")
async def status_texts(
    vehicle_id: str,
    store: StoreDep,
    registry: RegistryDep,
    limit: Annotated[
        int, Query(ge=1, le=1000, description="Newest messages to return (oldest first).")
    ] = 100,
    since: Annotated[
        IsoTime | None, Query(description="Only messages at or after this time (ISO 8601).")
    ] = None,
) -> StatusTextList:
    await _record(store, registry, vehicle_id)
    items = await store.list_status_texts(vehicle_id, limit=limit, since=as_utc(since))
    return StatusTextList(vehicle_id=vehicle_id, items=items)
