"""Bearer tokens for MCP agents (GATEWAY_AGENT_TOKENS): with tokens configured, /mcp requires one.

The principal of an agent is ``agent-<first 8 hex of the token's SHA-256>``: stable, and never the token
(`gateway.fleet.commands.scopes.principal_of`, beside the agents' vehicle scopes keyed by it).
Sessions of 2026-07-28 clients are keyed by it; the SDK binds 2025-era sessions to it.
"""

from __future__ import annotations

import hmac
from typing import TypedDict

from mcp.server.auth.provider import AccessToken, TokenVerifier
from mcp.server.auth.settings import AuthSettings

from gateway.config import Settings
from gateway.principals import principal_of

__all__ = ["SCOPE", "AgentTokens", "auth_options", "principal_of"]

SCOPE = "fleet"


class AgentTokens(TokenVerifier):
    def __init__(self, tokens: list[str]) -> None:
        self._tokens = [t.encode() for t in tokens]

    async def verify_token(self, token: str) -> AccessToken | None:
        given = token.encode()
        # compare against every token (a list, no early exit): timing says nothing about which matched
        if any([hmac.compare_digest(given, known) for known in self._tokens]):
            return AccessToken(token=token, client_id=principal_of(token), scopes=[SCOPE])
        return None


class AuthOptions(TypedDict, total=False):
    """The keyword arguments of `MCPServer` that enable bearer auth."""

    token_verifier: TokenVerifier
    auth: AuthSettings


def auth_options(settings: Settings) -> AuthOptions:
    """MCPServer keyword arguments enabling bearer auth, or none when no agent token is configured."""
    tokens = [t.strip() for t in settings.agent_tokens.split(",") if t.strip()]
    if not tokens:
        return {}
    base = f"http://{settings.host}:{settings.port}"
    return {
        "token_verifier": AgentTokens(tokens),
        "auth": AuthSettings(issuer_url=base, resource_server_url=f"{base}/mcp", required_scopes=[SCOPE],
                             validate_token_resource=False),
    }  # fmt: skip
