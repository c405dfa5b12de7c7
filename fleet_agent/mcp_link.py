"""The host's MCP client side: one Streamable HTTP connection to a gateway's ``/mcp``."""

from __future__ import annotations

from contextlib import AsyncExitStack
from dataclasses import dataclass
from typing import Any

import httpx2
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation

from fleet_agent.records import Arguments, ProgressFn, ToolOutcome

_MAX_PAGES = 50
_CALL_TIMEOUT_S = 300.0


class McpLinkError(RuntimeError):
    """The MCP server could not be reached or answered with a protocol error."""


@dataclass(frozen=True)
class ToolInfo:
    """One MCP tool, reduced to what the host needs."""

    name: str
    description: str
    input_schema: dict[str, Any]


def tool_info_from_mcp(tool: Any) -> ToolInfo:
    return ToolInfo(tool.name, tool.description or tool.name, dict(tool.input_schema or {}))


def outcome_from_result(result: Any) -> ToolOutcome:
    """An ``mcp.types.CallToolResult`` as a ToolOutcome (its text parts joined, its structured content)."""
    texts = [getattr(c, "text", "") for c in result.content or [] if getattr(c, "type", "") == "text"]
    structured = getattr(result, "structured_content", None)
    structured = dict(structured) if isinstance(structured, dict) else None
    return ToolOutcome("\n".join(t for t in texts if t), bool(getattr(result, "is_error", False)), structured)


class McpLink:
    """An open MCP client session: list tools, call them with progress. Use as an async context manager."""

    def __init__(self, url: str, token: str | None = None) -> None:
        self.url = url
        self.token = token
        self._stack: AsyncExitStack | None = None
        self._client: Client | None = None

    async def __aenter__(self) -> McpLink:
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        stack = AsyncExitStack()
        try:
            http = await stack.enter_async_context(
                httpx2.AsyncClient(headers=headers, timeout=httpx2.Timeout(30.0, read=_CALL_TIMEOUT_S))
            )
            client = Client(
                streamable_http_client(self.url, http_client=http),
                client_info=Implementation(name="fleet-agent", version="0.2.0"),
                read_timeout_seconds=_CALL_TIMEOUT_S,
            )
            self._client = await stack.enter_async_context(client)
        except BaseException as exc:
            await stack.aclose()
            if isinstance(exc, Exception):
                raise McpLinkError(f"cannot open an MCP session at {self.url}: {describe(exc)}") from exc
            raise
        self._stack = stack
        return self

    async def __aexit__(self, *exc: object) -> None:
        if self._stack is not None:
            stack, self._stack = self._stack, None
            await stack.aclose()

    @property
    def client(self) -> Client:
        if self._client is None:
            raise RuntimeError("McpLink is not open")
        return self._client

    async def list_tools(self) -> list[ToolInfo]:
        """Every tool the server offers (all pages)."""
        tools: list[ToolInfo] = []
        cursor: str | None = None
        for _ in range(_MAX_PAGES):
            page = await self.client.list_tools(cursor=cursor)
            tools += [tool_info_from_mcp(t) for t in page.tools]
            cursor = page.next_cursor
            if not cursor:
                break
        return tools

    async def call_tool(
        self, name: str, arguments: Arguments, progress: ProgressFn | None = None
    ) -> ToolOutcome:
        """Call a tool; a protocol-level failure becomes an error outcome."""
        try:
            result = await self.client.call_tool(name, arguments, progress_callback=progress)  # type: ignore[arg-type]
        except Exception as exc:  # MCPError, transport errors: reported, not fatal
            return ToolOutcome(text=f"MCP error calling {name}: {describe(exc)}", is_error=True)
        return outcome_from_result(result)


def describe(exc: BaseException) -> str:
    """Readable text for an exception, unwrapping exception groups from task groups."""
    inner = getattr(exc, "exceptions", None)
    if inner:
        return "; ".join(describe(e) for e in inner)
    text = str(exc) or type(exc).__name__
    return f"{type(exc).__name__}: {text}" if text != type(exc).__name__ else text
