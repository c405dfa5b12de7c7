"""Operator flight commands over REST: take off, fly to a position, kill the motors.

Each is one Commander call with ``via="rest"`` (`gateway.fleet.commands.commander`): the limits (altitude,
distance, geofences, battery) apply to operators as to agents; operator locks and the simulators-only
switch do not, an operator may kill motors anywhere and may interrupt a takeoff. Takeoff and goto are
tracked operations (``operation_id``; see ``GET /api/v1/operations``), which an agent's motion command
cannot cut short mid-climb.
"""

from __future__ import annotations

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.control import CommandOut, operator
from gateway.api.deps import CommanderDep, CommandVehicleId, PrincipalDep

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)


class TakeoffIn(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)  # JSON numbers only: no "10", no true

    alt_rel_m: float = Field(gt=0, le=10_000, allow_inf_nan=False, description="Metres above home.")


class GotoIn(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)  # JSON numbers only: no "10", no true

    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, description="Latitude, degrees.")
    lon: float = Field(ge=-180, le=180, allow_inf_nan=False, description="Longitude, degrees.")
    alt_rel_m: float = Field(ge=0, le=10_000, allow_inf_nan=False, description="Metres above home.")
    yaw_deg: float | None = Field(None, allow_inf_nan=False, description="Heading on arrival; None keeps it.")


@router.post("/vehicles/{vehicle_id}/takeoff", response_model=CommandOut, summary="Take off (operator)")
async def takeoff_vehicle(
    vehicle_id: CommandVehicleId, body: TakeoffIn, commander: CommanderDep, who: PrincipalDep
) -> CommandOut:
    op = await commander.takeoff(operator(who), vehicle_id, body.alt_rel_m)
    return CommandOut.of_operation(op, "takeoff")


@router.post("/vehicles/{vehicle_id}/goto", response_model=CommandOut, summary="Fly to a position (operator)")
async def goto_vehicle(
    vehicle_id: CommandVehicleId, body: GotoIn, commander: CommanderDep, who: PrincipalDep
) -> CommandOut:
    op = await commander.goto(
        operator(who), vehicle_id, body.lat, body.lon, body.alt_rel_m, "home", body.yaw_deg, "operator goto"
    )
    return CommandOut.of_operation(op, "goto")


@router.post(
    "/vehicles/{vehicle_id}/kill", response_model=CommandOut, summary="Stop the motors at once (operator)"
)
async def kill_vehicle(
    vehicle_id: CommandVehicleId, commander: CommanderDep, who: PrincipalDep
) -> CommandOut:
    result = await commander.kill(operator(who), vehicle_id, confirmed=True)
    return CommandOut(
        vehicle_id=vehicle_id, action="kill", outcome="sent", superseded_operation=result.superseded_operation
    )
