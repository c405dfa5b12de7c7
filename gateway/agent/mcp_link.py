"""The host's MCP client side: one Streamable HTTP connection to a gateway's ``/mcp``."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from contextlib import AsyncExitStack

import httpx2
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation

from gateway.agent.toolbox import Arguments, ToolInfo, ToolOutcome, outcome_from_result, tool_info_from_mcp

ProgressFn = Callable[[float, float | None, str | None], Awaitable[None]]

_MAX_PAGES = 50


class McpLinkError(RuntimeError):
    """The MCP server could not be reached or answered with a protocol error."""


class McpLink:
    """An open MCP client session: list tools, call them with progress. Use as an async context manager."""

    def __init__(
        self,
        url: str,
        token: str | None = None,
        *,
        call_timeout_s: float = 300.0,
        mode: str = "auto",
        include_structured: bool = False,
    ) -> None:
        self.url = url
        self.token = token
        self.call_timeout_s = call_timeout_s
        self.mode = mode
        self.include_structured = include_structured
        self._stack: AsyncExitStack | None = None
        self._client: Client | None = None

    async def __aenter__(self) -> McpLink:
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        stack = AsyncExitStack()
        try:
            http = await stack.enter_async_context(
                httpx2.AsyncClient(headers=headers, timeout=httpx2.Timeout(30.0, read=self.call_timeout_s))
            )
            client = Client(
                streamable_http_client(self.url, http_client=http),
                mode=self.mode,
                client_info=Implementation(name="fleet-gateway-agent", version="0.1.0"),
                read_timeout_seconds=self.call_timeout_s,
            )
            self._client = await stack.enter_async_context(client)
        except BaseException as exc:
            await stack.aclose()
            if isinstance(exc, Exception):
                raise McpLinkError(f"cannot open an MCP session at {self.url}: {_describe(exc)}") from exc
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
        """Call a tool; a protocol-level failure becomes an error outcome (the model sees it verbatim)."""
        try:
            result = await self.client.call_tool(name, arguments, progress_callback=progress)  # type: ignore[arg-type]
        except Exception as exc:  # MCPError, transport errors: reported to the model, not fatal
            return ToolOutcome(text=f"MCP error calling {name}: {_describe(exc)}", is_error=True)
        return outcome_from_result(result, include_structured=self.include_structured)


def _describe(exc: BaseException) -> str:
    """Readable text for an exception, unwrapping exception groups from task groups."""
    inner = getattr(exc, "exceptions", None)
    if inner:
        return "; ".join(_describe(e) for e in inner)
    text = str(exc) or type(exc).__name__
    return f"{type(exc).__name__}: {text}" if text != type(exc).__name__ else text
