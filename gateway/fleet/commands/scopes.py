"""Agent tokens scoped to some vehicles (GATEWAY_AGENT_SCOPES): such an agent sees and commands only those.

A scope is a list of vehicle ids and ``tag:<tag>`` entries, keyed by the agent's principal name
(``agent-<8 hex>``: `principal_of` its token, the name `gateway.mcp.auth` gives agents). A vehicle
outside the scope does not exist for that agent: it is absent from every list and naming it is an
unknown drone. Operators (REST, the console) have no scope.

The Commander's registry is a `ScopedDirectory`: it asks who is acting
(`gateway.fleet.operations.routing.ACTING`,
set by the MCP door for each request and by a cluster node for each call forwarded to it), so the scope
is applied on the node the agent talks to and again on the node that owns the drone.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from gateway.config import Settings
from gateway.errors import UnknownVehicle
from gateway.fleet.operations.routing import ACTING
from gateway.fleet.policy.caller import Caller
from gateway.fleet.vehicles.protocols import FlyingVehicle, VehicleDirectory, VehicleView
from gateway.principals import PRINCIPAL_PREFIX, principal_of, split_tokens

TAG_PREFIX = "tag:"
__all__ = ["PRINCIPAL_PREFIX", "ScopedDirectory", "VehicleScope", "principal_of", "scopes_by_principal"]


@dataclass(frozen=True)
class VehicleScope:
    ids: frozenset[str]
    tags: frozenset[str]

    @classmethod
    def parse(cls, entries: Sequence[str]) -> VehicleScope:
        ids = {e for e in entries if not e.startswith(TAG_PREFIX)}
        tags = {e.removeprefix(TAG_PREFIX) for e in entries if e.startswith(TAG_PREFIX)}
        return cls(frozenset(ids), frozenset(tags))

    def allows(self, vehicle: VehicleView) -> bool:
        return vehicle.id in self.ids or bool(self.tags.intersection(vehicle.spec.tags or []))


class ScopedDirectory:
    """The registry as the caller acting now may see it (all of it, for operators and unscoped agents)."""

    def __init__(self, directory: VehicleDirectory, scopes: Mapping[str, VehicleScope]) -> None:
        self.directory = directory
        self.scopes = dict(scopes)

    def scope_of(self, caller: Caller | None) -> VehicleScope | None:
        if caller is None or caller.is_operator or not self.scopes:
            return None
        return self.scopes.get(caller.principal)

    def all(self) -> Sequence[VehicleView]:
        scope = self.scope_of(ACTING.get())
        every = self.directory.all()
        return every if scope is None else [v for v in every if scope.allows(v)]

    def get(self, vehicle_id: str) -> VehicleView:
        scope = self.scope_of(ACTING.get())
        if scope is None:
            return self.directory.get(vehicle_id)
        allowed = {v.id: v for v in self.all()}
        vehicle = allowed.get(vehicle_id)
        if vehicle is None:
            raise UnknownVehicle(str(vehicle_id)[:64], list(allowed))
        return vehicle

    def flown(self, vehicle_id: str) -> FlyingVehicle:
        self.get(vehicle_id)  # in the caller's scope (UnknownVehicle otherwise)
        return self.directory.flown(vehicle_id)


def scopes_by_principal(settings: Settings) -> dict[str, VehicleScope]:
    """GATEWAY_AGENT_SCOPES as the Commander applies them: every key (an agent's token, or its
    principal name) turned into the agent's principal name. A key is a token when it is one of the
    configured agent tokens, whatever it looks like (a token may start with ``agent-``); Settings has
    already refused a key that is neither."""
    tokens = set(split_tokens(settings.agent_tokens))
    return {
        (principal_of(key) if key in tokens else key): VehicleScope.parse(list(entries))
        for key, entries in settings.agent_scopes.items()
    }
