"""GATEWAY_AGENT_SCOPES as the Commander applies them (`gateway.fleet.scopes`): every key (an agent's
token, or its principal name) turned into the agent's principal name."""

from __future__ import annotations

from gateway.config import Settings
from gateway.fleet.scopes import VehicleScope
from gateway.mcp.auth import principal_of


def scopes_by_principal(settings: Settings) -> dict[str, VehicleScope]:
    return {
        (key if key.startswith("agent-") else principal_of(key)): VehicleScope.parse(list(entries))
        for key, entries in settings.agent_scopes.items()
    }
