"""FastAPI dependencies shared by the routers: the running gateway, its parts, the caller.

Authentication hooks in at one place: :func:`authorize` runs before every ``/api/v1`` route (it is
the router-level dependency in :mod:`gateway.api`). Today the API is open and every caller is the
anonymous operator; bearer roles replace the body of :func:`authorize` without touching the routers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any, Literal

from fastapi import Depends, Request

from gateway.registry.store import Store
from gateway.runtime import Gateway

Role = Literal["operator", "viewer"]


@dataclass(frozen=True)
class Principal:
    """Who is calling the REST API."""

    name: str
    role: Role

    @property
    def session_key(self) -> str:
        return f"rest:{self.name}"


ANONYMOUS_OPERATOR = Principal(name="anonymous", role="operator")


async def authorize(request: Request) -> Principal:
    """Identify the caller and remember it on the request (read by the audit)."""
    principal = ANONYMOUS_OPERATOR
    request.state.principal = principal
    return principal


def get_gateway(request: Request) -> Gateway:
    return request.app.state.gateway


def get_store(request: Request) -> Store:
    return request.app.state.gateway.require_store()


def get_registry(request: Request) -> Any:
    """The gateway's :class:`gateway.registry.registry.Registry`."""
    return request.app.state.gateway.require_registry()


GatewayDep = Annotated[Gateway, Depends(get_gateway)]
StoreDep = Annotated[Store, Depends(get_store)]
RegistryDep = Annotated[Any, Depends(get_registry)]
PrincipalDep = Annotated[Principal, Depends(authorize)]
