"""/api/v1/vehicles/{id}/params/{name}: an operator reads and writes one autopilot parameter.

Both are the Commander's parameter verbs (the ones get_parameter and set_parameter call) with the
operator's caller (``via="rest"``): a write takes the same command path and the policy's rules for an
operator, and is audited; a read is not (reads change nothing). The name is the autopilot's
(ArduPilot's renamed parameters are found under either spelling).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Annotated

from fastapi import APIRouter, Path
from pydantic import BaseModel, ConfigDict, Field

from gateway.api.audit import AuditedRoute
from gateway.api.control import operator
from gateway.api.deps import CommanderDep, CommandVehicleId, PrincipalDep
from gateway.errors import CommandFailed, NotFound
from gateway.fleet.operations.views import ParamValue

router = APIRouter(tags=["operator control"], route_class=AuditedRoute)

ParamName = Annotated[
    str,
    Path(
        pattern=r"^[A-Za-z0-9_]{1,16}$",
        description="The parameter's name: 1-16 of A-Z, 0-9, '_' (any case).",
        examples=["WPNAV_SPEED"],
    ),
]


class ParamIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    value: float = Field(
        allow_inf_nan=False, description="The new value (an integer for an integer parameter)."
    )


class ParamOut(BaseModel):
    vehicle_id: str
    name: str = Field(description="The name the autopilot knows it by.")
    value: float
    type: str = Field(description="int or float: the parameter's type on the autopilot.")

    @classmethod
    def of(cls, found: ParamValue) -> ParamOut:
        return cls(vehicle_id=found.drone_id, name=found.name, value=found.value, type=found.type)


@contextmanager
def _unknown_is_not_found() -> Iterator[None]:
    """A name the autopilot does not list is the request's resource missing (404), not the autopilot
    failing (502): the message, the autopilot's words, stays as it is."""
    try:
        yield
    except CommandFailed as exc:
        if exc.details.get("result") != "UNKNOWN_PARAMETER":
            raise
        raise NotFound(exc.message, **exc.details) from None


@router.get(
    "/vehicles/{vehicle_id}/params/{name}", response_model=ParamOut, summary="Read one autopilot parameter"
)
async def read_param(
    vehicle_id: CommandVehicleId, name: ParamName, commander: CommanderDep, who: PrincipalDep
) -> ParamOut:
    with _unknown_is_not_found():
        return ParamOut.of(await commander.get_param(operator(who), vehicle_id, name))


@router.put(
    "/vehicles/{vehicle_id}/params/{name}",
    response_model=ParamOut,
    summary="Write one autopilot parameter (operator); the value stored is read back",
)
async def write_param(
    vehicle_id: CommandVehicleId, name: ParamName, body: ParamIn, commander: CommanderDep, who: PrincipalDep
) -> ParamOut:
    with _unknown_is_not_found():
        return ParamOut.of(await commander.set_param(operator(who), vehicle_id, name, body.value))
