"""How a verb on one drone is offered as an operator's REST route: its `Route` declaration
(``@command(route=Route(...))``, `gateway.fleet.commands.command_core`), which `gateway.api.declared` turns
into the route (fleet/ never imports the API layer), and the request bodies whose field names the REST
API published before the verbs named their parameters (``alt_rel_m`` for ``alt_m``, ``lat`` for
``lat_deg``).

A route is ``{method} /api/v1/vehicles/{vehicle_id}/{path}``, run with the operator's caller: the path's
vehicle id (made canonical) fills the verb's parameter ``drone`` (a route with ``drone=None`` is
``/api/v1/{path}``, on no one drone: the fleet's lock), ``fills`` fixes others, and the JSON
body gives the rest: ``body``'s fields (named as ``renames`` maps them to the verb's parameters), or,
without ``body``, a strict model of the verb's own parameters (their ``Annotated`` bounds and
descriptions; ``label`` and ``omit`` keep their defaults; none left: no body)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from gateway.fleet.policy.operator_locks import MAX_REASON_CHARS

RouteMethod = Literal["POST", "PUT", "DELETE"]


@dataclass(frozen=True)
class Route:
    """One REST route of a verb (see the module's docstring). The answer is the REST API's
    ``CommandOut`` for a verb returning an operation, an instant command's result or a stop outcome
    (its ``action`` the verb's name, or the stop's), else the verb's own result model."""

    path: str
    summary: str
    method: RouteMethod = "POST"
    #: the route function's name, the OpenAPI operation id (default: ``<verb>_vehicle``)
    name: str = ""
    #: the OpenAPI description (default: none)
    description: str | None = None
    #: the verb's parameter the path's vehicle id fills; None: the path names no drone
    drone: str | None = "drone_id"
    #: the request body; None: the verb's own parameters (see the module's docstring)
    body: type[BaseModel] | None = None
    #: body field -> the verb's parameter it fills (a field not named here fills its namesake)
    renames: Mapping[str, str] = dataclasses.field(default_factory=dict)
    #: the verb's parameters this route fixes
    fills: Mapping[str, object] = dataclasses.field(default_factory=dict)
    #: the verb's parameters the route does not offer (they keep their defaults)
    omit: tuple[str, ...] = ()
    #: the verb the route calls (filled by `command`)
    verb: str = ""

    @property
    def url(self) -> str:
        """The route's path under /api/v1: ``/vehicles/{vehicle_id}/takeoff``, ``/fleet/lock``."""
        return f"/vehicles/{{vehicle_id}}/{self.path}" if self.drone else f"/{self.path}"

    @property
    def key(self) -> str:
        """``POST /vehicles/{vehicle_id}/takeoff``: one route per method and path."""
        return f"{self.method} {self.url}"


#: every route a verb declares, by `Route.key` (filled by `command`)
ROUTES: dict[str, Route] = {}


def declare_routes(verb: str, routes: tuple[Route, ...]) -> None:
    """Register ``verb``'s routes; a method and path declared by two verbs is refused."""
    for route in routes:
        other = ROUTES.get(route.key)
        if other is not None and other.verb != verb:
            raise ValueError(f"route {route.key} is declared by both {other.verb} and {verb}")
        ROUTES[route.key] = dataclasses.replace(route, verb=verb)


# --- request bodies the REST API published with its own field names -------------------------------


class TakeoffIn(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)  # JSON numbers only: no "10", no true

    alt_rel_m: float = Field(gt=0, le=10_000, allow_inf_nan=False, description="Metres above home.")


class GotoIn(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)  # JSON numbers only: no "10", no true

    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, description="Latitude, degrees.")
    lon: float = Field(ge=-180, le=180, allow_inf_nan=False, description="Longitude, degrees.")
    alt_rel_m: float = Field(ge=0, le=10_000, allow_inf_nan=False, description="Metres above home.")
    yaw_deg: float | None = Field(None, allow_inf_nan=False, description="Heading on arrival; None keeps it.")


class LockIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    reason: str = Field(
        min_length=1, max_length=MAX_REASON_CHARS, description="Why; agents and operators are shown it."
    )


class OriginIn(BaseModel):
    model_config = ConfigDict(extra="forbid")

    lat: float = Field(ge=-90, le=90, allow_inf_nan=False, strict=True, description="Latitude, degrees.")
    lon: float = Field(ge=-180, le=180, allow_inf_nan=False, strict=True, description="Longitude, degrees.")
    alt_amsl_m: float = Field(
        ge=-500, le=9000, allow_inf_nan=False, strict=True, description="Altitude above mean sea level, m."
    )


__all__ = ["ROUTES", "GotoIn", "LockIn", "OriginIn", "Route", "TakeoffIn", "declare_routes"]
