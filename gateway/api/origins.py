"""A vehicle's origin over REST: where its distance limit and geofence checks count from
(`gateway.fleet.policy.origin`). The first home the vehicle reported sets it; the autopilot's later
homes (ArduPilot sets one at every arming) do not move it; an operator moves it here (audited): the verb
`move_origin` (`gateway.fleet.commands.registry_verbs`)."""

from __future__ import annotations

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.control import operator
from gateway.api.deps import CommanderDep, CommandVehicleId, PrincipalDep, RegistryDep, StoreDep
from gateway.fleet.policy.origin import OriginView, origin_view
from gateway.fleet.vehicles.readings import home

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)


class OriginIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, strict=True, description="Latitude, degrees.")
    lon: float = Field(ge=-180, le=180, allow_inf_nan=False, strict=True, description="Longitude, degrees.")
    alt_amsl_m: float = Field(
        ge=-500, le=9000, allow_inf_nan=False, strict=True, description="Altitude above mean sea level, m."
    )


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


@router.put(
    "/vehicles/{vehicle_id}/origin", response_model=OriginView, summary="Move a drone's origin (operator)"
)
async def put_origin(
    vehicle_id: CommandVehicleId, body: OriginIn, commander: CommanderDep, who: PrincipalDep
) -> OriginView:
    return await commander.move_origin(operator(who), vehicle_id, body.lat, body.lon, body.alt_amsl_m)
