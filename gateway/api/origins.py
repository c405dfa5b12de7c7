"""A vehicle's origin over REST: where its distance limit and geofence checks count from
(`gateway.fleet.policy.origin`). The first home the vehicle reported sets it; the autopilot's later
homes (ArduPilot sets one at every arming) do not move it; an operator moves it here (audited)."""

from __future__ import annotations

from datetime import datetime
from typing import Literal

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.deps import CommandVehicleId, PrincipalDep, RegistryDep, StoreDep
from gateway.fleet import geo
from gateway.fleet.policy.origin import Origin
from gateway.fleet.vehicles.readings import home

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)


class OriginIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, strict=True, description="Latitude, degrees.")
    lon: float = Field(ge=-180, le=180, allow_inf_nan=False, strict=True, description="Longitude, degrees.")
    alt_amsl_m: float = Field(
        ge=-500, le=9000, allow_inf_nan=False, strict=True, description="Altitude above mean sea level, m."
    )


class OriginOut(BaseModel):
    vehicle_id: str
    origin: dict[str, float] | None = Field(description="lat, lon, alt_amsl_m; null until a home came.")
    source: Literal["first_home", "operator"] | None = None
    set_by: str | None = None
    set_at: datetime | None = None
    home: dict[str, float] | None = Field(None, description="The autopilot's current home.")
    home_from_origin_m: float | None = Field(None, description="How far the autopilot's home is from it.")


def _point(lat: float, lon: float, alt: float) -> dict[str, float]:
    return {"lat": lat, "lon": lon, "alt_amsl_m": alt}


def _out(vehicle_id: str, origin: Origin | tuple[float, float, float] | None, now_home: object) -> OriginOut:
    current = home_point = None
    if isinstance(now_home, tuple):
        home_point = now_home
    out = OriginOut(vehicle_id=vehicle_id, origin=None)
    if isinstance(origin, Origin):
        current = origin.point
        out.source, out.set_by, out.set_at = origin.source, origin.set_by, origin.set_at
    elif origin is not None:
        current = origin
    if current is not None:
        out.origin = _point(*current)
    if home_point is not None:
        out.home = _point(*home_point)
        if current is not None:
            out.home_from_origin_m = round(
                geo.horizontal_distance_m(current[0], current[1], home_point[0], home_point[1]), 2
            )
    return out


@router.get(
    "/vehicles/{vehicle_id}/origin", response_model=OriginOut, summary="Where a drone's limits count from"
)
async def get_origin(vehicle_id: CommandVehicleId, registry: RegistryDep, store: StoreDep) -> OriginOut:
    view = registry.get(vehicle_id)
    stored = await store.get_origin(vehicle_id)
    in_force = view.origin
    if stored is not None and (in_force is None or stored.point == in_force):
        return _out(vehicle_id, stored, home(view))
    return _out(vehicle_id, in_force, home(view))


@router.put(
    "/vehicles/{vehicle_id}/origin", response_model=OriginOut, summary="Move a drone's origin (operator)"
)
async def put_origin(
    vehicle_id: CommandVehicleId, body: OriginIn, registry: RegistryDep, who: PrincipalDep
) -> OriginOut:
    moved = await registry.move_origin(vehicle_id, body.lat, body.lon, body.alt_amsl_m, who.name)
    return _out(vehicle_id, moved, home(registry.get(vehicle_id)))
