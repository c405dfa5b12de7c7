"""A vehicle's origin over REST: where its distance limit and geofence checks count from
(`gateway.fleet.policy.origin`). The first home the vehicle reported sets it; the autopilot's later
homes (ArduPilot sets one at every arming) do not move it; an operator moves it (audited) with
``PUT /vehicles/{vehicle_id}/origin``, the route the verb `move_origin` declares
(`gateway.fleet.commands.registry_verbs`, made by `gateway.api.declared`)."""

from __future__ import annotations

from fastapi import APIRouter

from gateway.api.audit import AuditedRoute
from gateway.api.deps import CommandVehicleId, RegistryDep, StoreDep
from gateway.fleet.policy.origin import OriginView, origin_view
from gateway.fleet.vehicles.readings import home

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)


@router.get(
    "/vehicles/{vehicle_id}/origin", response_model=OriginView, summary="Where a drone's limits count from"
)
async def get_origin(vehicle_id: CommandVehicleId, registry: RegistryDep, store: StoreDep) -> OriginView:
    view = registry.get(vehicle_id)
    stored = await store.get_origin(vehicle_id)
    in_force = view.origin
    if stored is not None and (in_force is None or stored.point == in_force):
        return origin_view(vehicle_id, stored, home(view))
    return origin_view(vehicle_id, in_force, home(view))
