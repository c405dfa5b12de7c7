"""FastAPI dependencies shared by the routers: the running gateway, its parts, the caller.

Authentication hooks in at one place: :func:`authorize` runs before every ``/api/v1`` route (it is
the router-level dependency in :mod:`gateway.api`). With no operator or viewer token configured the
API is open and every caller is the anonymous operator (``fleet-gateway serve`` then binds to loopback
only). With tokens, a ``Authorization: Bearer <token>`` header is required: operator tokens may do
everything, viewer tokens only read. A caller's name is ``operator-``/``viewer-`` plus the first 8 hex
digits of the token's SHA-256 (stable, never the token), as agents are ``agent-...`` on /mcp.
"""

from __future__ import annotations

import hashlib
import hmac
from dataclasses import dataclass, replace
from typing import Annotated, Literal

from fastapi import Depends, HTTPException, Request

from gateway.config import Settings
from gateway.fleet.commands.commander import Commander
from gateway.fleet.vehicles.protocols import VehicleRegistry
from gateway.hosts import foreign_request
from gateway.registry.store import Store
from gateway.runtime import Gateway

Role = Literal["operator", "viewer"]
#: The operator's door: the console marks its requests with this header so the audit and the Commander
#: tell a console click from a script calling REST; both are operators.
Door = Literal["rest", "console"]
DOOR_HEADER = "x-fleet-door"


@dataclass(frozen=True)
class Principal:
    """Who is calling the REST API."""

    name: str
    role: Role
    door: Door = "rest"

    @property
    def session_key(self) -> str:
        return f"{self.door}:{self.name}"


ANONYMOUS_OPERATOR = Principal(name="anonymous", role="operator")


READ_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})

#: Largest row id / offset a request may name: beyond it SQLite (64-bit) and PostgreSQL (BIGINT) overflow.
MAX_ROW = 2**62


def _tokens(text: str) -> list[bytes]:
    return [t.strip().encode() for t in text.split(",") if t.strip()]


def principal_name(role: Role, token: str) -> str:
    return f"{role}-" + hashlib.sha256(token.encode()).hexdigest()[:8]


def _unauthorized(message: str) -> HTTPException:
    return HTTPException(401, detail=message, headers={"WWW-Authenticate": 'Bearer realm="fleet-gateway"'})


def identify(settings: Settings, authorization: str | None) -> Principal:
    """The caller for an Authorization header value; raises 401 when tokens are configured and it fails."""
    operators, viewers = _tokens(settings.operator_tokens), _tokens(settings.viewer_tokens)
    if not operators and not viewers:
        return ANONYMOUS_OPERATOR
    scheme, _, token = (authorization or "").partition(" ")
    if scheme.lower() != "bearer" or not token.strip():
        raise _unauthorized(
            "this API needs an operator or viewer token: send 'Authorization: Bearer <token>'"
        )
    given = token.strip().encode()
    # compare against every token (no early exit) so timing says nothing about which matched
    is_operator = any([hmac.compare_digest(given, t) for t in operators])
    is_viewer = any([hmac.compare_digest(given, t) for t in viewers])
    if is_operator:
        return Principal(principal_name("operator", token.strip()), "operator")
    if is_viewer:
        return Principal(principal_name("viewer", token.strip()), "viewer")
    raise _unauthorized("unknown token: use an operator or viewer token (agent tokens are for /mcp)")


async def authorize(request: Request) -> Principal:
    """Refuse a request from another site (`gateway.hosts`), identify the caller, check its role may use
    this method, and remember it (read by the audit)."""
    settings = request.app.state.gateway.settings
    headers = request.headers
    foreign = foreign_request(
        request.method not in READ_METHODS,
        headers.get("host"),
        headers.get("origin"),
        headers.get("sec-fetch-site"),
        settings,
    )
    if foreign is not None:
        raise HTTPException(foreign[0], detail=foreign[1])
    principal = identify(settings, headers.get("authorization"))
    if request.headers.get(DOOR_HEADER, "").strip().lower() == "console":
        principal = replace(principal, door="console")
    request.state.principal = principal
    if principal.role == "viewer" and request.method not in READ_METHODS:
        raise HTTPException(403, detail="a viewer token can only read; this needs an operator token")
    return principal


def get_gateway(request: Request) -> Gateway:
    gateway: Gateway = request.app.state.gateway
    return gateway


def get_store(request: Request) -> Store:
    return get_gateway(request).require_store()


def get_registry(request: Request) -> VehicleRegistry:
    """The gateway's :class:`gateway.fleet.vehicles.registry.Registry`."""
    return get_gateway(request).require_registry()


def get_commander(request: Request) -> Commander:
    """The one command path (503 while the gateway starts or stops)."""
    return get_gateway(request).commander


GatewayDep = Annotated[Gateway, Depends(get_gateway)]
StoreDep = Annotated[Store, Depends(get_store)]
RegistryDep = Annotated[VehicleRegistry, Depends(get_registry)]
CommanderDep = Annotated[Commander, Depends(get_commander)]
PrincipalDep = Annotated[Principal, Depends(authorize)]


def canonical_vehicle_id(vehicle_id: str, commander: CommanderDep) -> str:
    """The path's vehicle id as registered, ignoring case ('Alpha' is alpha; `gateway.fleet.vehicles.ids`)."""
    return commander.canonical_id(vehicle_id)


#: the ``{vehicle_id}`` of a command route, made canonical before the Commander sees it
CommandVehicleId = Annotated[str, Depends(canonical_vehicle_id)]
