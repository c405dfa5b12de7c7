"""Operator flight commands over REST: take off, fly to a position, kill the motors.

The safety policy checks them with ``via="rest"``: the limits (altitude, distance, geofences,
battery) apply to operators as to agents; operator locks and the simulators-only switch do not, and
an operator may kill motors anywhere. Each command supersedes the drone's current MCP operation.
"""

from __future__ import annotations

import math
from typing import Any

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.control import ActionOut
from gateway.api.deps import GatewayDep, RegistryDep
from gateway.fleet.safety import Target, VehicleContext

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)


class TakeoffIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    alt_rel_m: float = Field(gt=0, le=10_000, allow_inf_nan=False, description="Metres above home.")


class GotoIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, description="Latitude, degrees.")
    lon: float = Field(ge=-180, le=180, allow_inf_nan=False, description="Longitude, degrees.")
    alt_rel_m: float = Field(ge=0, le=10_000, allow_inf_nan=False, description="Metres above home.")
    yaw_deg: float | None = Field(None, allow_inf_nan=False, description="Heading on arrival; None keeps it.")


def vehicle_context(vehicle: Any) -> VehicleContext:
    """What the policy needs, from the vehicle's fresh telemetry (stale or missing values are None)."""
    fresh = vehicle.telemetry.fresh
    battery, home, pos = fresh("battery"), fresh("home"), fresh("position")
    return VehicleContext(
        vehicle_id=vehicle.id,
        is_simulator=bool(vehicle.status().get("is_simulator")),
        armed=bool(fresh("armed")),
        in_air=bool(fresh("in_air")),
        battery_pct=None if battery is None else battery.remaining_pct,
        home=None if home is None else (home.lat_deg, home.lon_deg, home.abs_alt_m),
        position=None if pos is None else (pos.lat_deg, pos.lon_deg, pos.rel_alt_m),
    )


async def _supersede(gateway: Any, vehicle_id: str, action: str) -> str | None:
    if gateway.operations is None:
        return None
    op = await gateway.operations.supersede(vehicle_id, by=f"operator {action}")
    return getattr(op, "id", None)


@router.post("/vehicles/{vehicle_id}/takeoff", response_model=ActionOut, summary="Take off (operator)")
async def takeoff_vehicle(
    vehicle_id: str, body: TakeoffIn, gateway: GatewayDep, registry: RegistryDep
) -> ActionOut:
    vehicle = registry.get(vehicle_id)
    gateway.safety.check_takeoff(vehicle_context(vehicle), body.alt_rel_m, via="rest")
    await vehicle.takeoff(body.alt_rel_m)
    superseded = await _supersede(gateway, vehicle_id, "takeoff")
    return ActionOut(vehicle_id=vehicle_id, action="takeoff", outcome="sent", superseded_operation=superseded)


@router.post("/vehicles/{vehicle_id}/goto", response_model=ActionOut, summary="Fly to a position (operator)")
async def goto_vehicle(
    vehicle_id: str, body: GotoIn, gateway: GatewayDep, registry: RegistryDep
) -> ActionOut:
    vehicle = registry.get(vehicle_id)
    target = Target(body.lat, body.lon, body.alt_rel_m)
    gateway.safety.check_motion(vehicle_context(vehicle), target, via="rest")
    yaw = None if body.yaw_deg is None else math.fmod(body.yaw_deg, 360.0)
    await vehicle.goto(body.lat, body.lon, body.alt_rel_m, yaw)
    superseded = await _supersede(gateway, vehicle_id, "goto")
    return ActionOut(vehicle_id=vehicle_id, action="goto", outcome="sent", superseded_operation=superseded)


@router.post(
    "/vehicles/{vehicle_id}/kill", response_model=ActionOut, summary="Stop the motors at once (operator)"
)
async def kill_vehicle(vehicle_id: str, gateway: GatewayDep, registry: RegistryDep) -> ActionOut:
    vehicle = registry.get(vehicle_id)
    gateway.safety.check_kill(vehicle_context(vehicle), via="rest")
    await vehicle.kill()
    superseded = await _supersede(gateway, vehicle_id, "kill")
    return ActionOut(vehicle_id=vehicle_id, action="kill", outcome="sent", superseded_operation=superseded)
