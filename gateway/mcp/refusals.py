"""A refused or invalid tool call as data: the text a model reads, and beside it, as structured content,
the same ``code``, ``message``, ``rule`` and ``details`` that REST returns (gateway/errors.py), so that
any MCP client can act on the rule instead of the wording."""

from __future__ import annotations

from mcp.types import CallToolResult, TextContent

from gateway.errors import GatewayError, SafetyRefusal


def refusal_result(
    text: str, code: str, message: str, *, rule: str | None = None, details: dict[str, object] | None = None
) -> CallToolResult:
    """An error result whose structured content is ``{code, message, rule, details}``."""
    structured = {"code": code, "message": message, "rule": rule, "details": _plain(details or {})}
    return CallToolResult(
        content=[TextContent(type="text", text=text)], structured_content=structured, is_error=True
    )


def gateway_error_result(exc: GatewayError) -> CallToolResult:
    """A gateway error as a tool error: a safety refusal's text starts with ``Refused:``."""
    details = {k: v for k, v in exc.details.items() if k != "rule"}
    if isinstance(exc, SafetyRefusal):
        return refusal_result(
            f"Refused: {exc.message}", exc.code, exc.message, rule=exc.rule, details=details
        )
    return refusal_result(exc.message, exc.code, exc.message, details=details)


def _plain(value: object) -> object:
    """Details as JSON values (a detail that is not one is given as its text)."""
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, list | tuple | set | frozenset):
        return [_plain(v) for v in value]
    return str(value)
