"""An agent's principal name, derived from its bearer token: the name audit rows, scopes and sessions use,
so that the token itself is never stored or shown."""

from __future__ import annotations

import hashlib

PRINCIPAL_PREFIX = "agent-"


def principal_of(token: str) -> str:
    """``agent-<first 8 hex of the token's SHA-256>``: stable, and never the token itself."""
    return PRINCIPAL_PREFIX + hashlib.sha256(token.encode()).hexdigest()[:8]


def split_tokens(text: str) -> list[str]:
    """A comma-separated token list as configured (GATEWAY_AGENT_TOKENS and the like)."""
    return [t.strip() for t in text.split(",") if t.strip()]
