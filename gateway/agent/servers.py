"""More MCP servers beside the gateway: their tools offered to the model with the gateway's.

As the source paper did with a maps server, the host can attach other MCP servers (``--server``, repeatable):
a URL (Streamable HTTP) or a command that speaks MCP over stdio. "Fly bravo to the water tower" then works
when a places server knows the tower: the model asks it for the coordinates and flies there with the
gateway's tools. Every call goes to the server that offers the tool; a tool whose name the gateway (or an
earlier server) already offers is left out, so a second server can never stand in for a gateway tool. The
gateway's profile (``--profile small``) selects among the gateway's tools only: an attached server's tools
are always offered, as that server describes them.
"""

from __future__ import annotations

import shlex
from collections.abc import Sequence
from contextlib import AsyncExitStack

from mcp import Client, StdioServerParameters
from mcp.types import Implementation

from gateway.agent.mcp_link import McpLink, McpLinkError, ProgressFn, _describe
from gateway.agent.toolbox import Arguments, ToolInfo, ToolOutcome, outcome_from_result, tool_info_from_mcp


class StdioLink:
    """An MCP server started as a command, spoken to over its stdin/stdout (closed with the link)."""

    def __init__(self, command: Sequence[str], *, call_timeout_s: float = 300.0) -> None:
        if not command:
            raise McpLinkError("an MCP server command is empty")
        self.command = list(command)
        self.call_timeout_s = call_timeout_s
        self._stack: AsyncExitStack | None = None
        self._client: Client | None = None

    async def __aenter__(self) -> StdioLink:
        stack = AsyncExitStack()
        params = StdioServerParameters(command=self.command[0], args=self.command[1:])
        try:
            client = Client(
                params,
                client_info=Implementation(name="fleet-gateway-agent", version="0.1.0"),
                read_timeout_seconds=self.call_timeout_s,
            )
            self._client = await stack.enter_async_context(client)
        except BaseException as exc:
            await stack.aclose()
            if isinstance(exc, Exception):
                raise McpLinkError(
                    f"cannot start MCP server {shlex.join(self.command)}: {_describe(exc)}"
                ) from exc
            raise
        self._stack = stack
        return self

    async def __aexit__(self, *exc: object) -> None:
        if self._stack is not None:
            stack, self._stack = self._stack, None
            await stack.aclose()

    async def list_tools(self) -> list[ToolInfo]:
        assert self._client is not None, "StdioLink is not open"
        return [tool_info_from_mcp(t) for t in (await self._client.list_tools()).tools]

    async def call_tool(
        self, name: str, arguments: Arguments, progress: ProgressFn | None = None
    ) -> ToolOutcome:
        assert self._client is not None, "StdioLink is not open"
        try:
            result = await self._client.call_tool(name, arguments, progress_callback=progress)  # type: ignore[arg-type]
        except Exception as exc:
            return ToolOutcome(text=f"MCP error calling {name}: {_describe(exc)}", is_error=True)
        return outcome_from_result(result)


Link = McpLink | StdioLink


def link_for(spec: str) -> Link:
    """``http(s)://...`` -> a Streamable HTTP link; anything else -> a command run over stdio."""
    spec = spec.strip()
    if spec.startswith(("http://", "https://")):
        return McpLink(spec)
    return StdioLink(shlex.split(spec))


class ToolRouter:
    """The gateway's link plus attached servers, as one tool caller: each call goes to its tool's server."""

    def __init__(self, gateway: McpLink) -> None:
        self.gateway = gateway
        self._extra: list[Link] = []
        self._owner: dict[str, Link] = {}
        self.extra_tools: list[ToolInfo] = []
        self.left_out: list[str] = []  # "name (server)": tools a server offers under a name already taken

    async def attach(self, link: Link, taken: set[str]) -> None:
        """Add an opened server's tools; names already ``taken`` are left out (and recorded)."""
        self._extra.append(link)
        for tool in await link.list_tools():
            if tool.name in taken:
                self.left_out.append(tool.name)
                continue
            taken.add(tool.name)
            self._owner[tool.name] = link
            self.extra_tools.append(tool)

    async def list_tools(self) -> list[ToolInfo]:
        return list(await self.gateway.list_tools()) + list(self.extra_tools)

    async def call_tool(
        self, name: str, arguments: Arguments, progress: ProgressFn | None = None
    ) -> ToolOutcome:
        link = self._owner.get(name)
        if link is None:
            return await self.gateway.call_tool(name, arguments, progress)
        return await link.call_tool(name, arguments, progress)
