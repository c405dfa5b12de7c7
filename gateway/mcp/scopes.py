"""Agent tokens scoped to some vehicles (GATEWAY_AGENT_SCOPES): such an agent sees and commands only those.

A scope is a list of vehicle ids and ``tag:<tag>`` entries, keyed by the agent's token or by its principal
name (``agent-<8 hex>``, see :mod:`gateway.mcp.auth`). A vehicle outside the scope does not exist for that
agent: it is absent from every list and naming it is an unknown drone. Every node of a cluster reads the
same settings, so the scope holds whichever node the agent talks to.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from mcp.server.auth.middleware.auth_context import get_access_token

from gateway.errors import UnknownVehicle
from gateway.mcp.auth import principal_of

TAG_PREFIX = "tag:"


@dataclass(frozen=True)
class VehicleScope:
    ids: frozenset[str]
    tags: frozenset[str]

    @classmethod
    def parse(cls, entries: list[str]) -> VehicleScope:
        ids = {e for e in entries if not e.startswith(TAG_PREFIX)}
        tags = {e.removeprefix(TAG_PREFIX) for e in entries if e.startswith(TAG_PREFIX)}
        return cls(frozenset(ids), frozenset(tags))

    def allows(self, vehicle: Any) -> bool:
        if vehicle.id in self.ids:
            return True
        tags = getattr(vehicle.spec, "tags", None) or []
        return bool(self.tags.intersection(tags))


def scopes_by_principal(settings: Any) -> dict[str, VehicleScope]:
    """GATEWAY_AGENT_SCOPES with every key turned into the agent's principal name."""
    raw: dict[str, list[str]] = getattr(settings, "agent_scopes", None) or {}
    return {
        (key if key.startswith("agent-") else principal_of(key)): VehicleScope.parse(list(entries))
        for key, entries in raw.items()
    }


def current_scope(scopes: dict[str, VehicleScope]) -> VehicleScope | None:
    """The scope of the agent making the current MCP request; None: every vehicle."""
    if not scopes:
        return None
    token = get_access_token()
    if token is None:
        return None
    return scopes.get(token.client_id)


class ScopedRegistry:
    """The registry as one agent may see it; everything but ``get`` and ``all`` passes through."""

    def __init__(self, registry: Any, scope: VehicleScope) -> None:
        self._registry = registry
        self._scope = scope

    def all(self) -> list[Any]:
        return [v for v in self._registry.all() if self._scope.allows(v)]

    def get(self, vehicle_id: str) -> Any:
        vehicle = self._registry.get(vehicle_id) if vehicle_id in {v.id for v in self.all()} else None
        if vehicle is None:
            raise UnknownVehicle(str(vehicle_id)[:64], [v.id for v in self.all()])
        return vehicle

    def __getattr__(self, name: str) -> Any:
        return getattr(self._registry, name)
