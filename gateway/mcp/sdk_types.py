"""The MCP SDK's generic types as this layer uses them. The SDK's `Context`, `MCPServer` and
`ServerRequestContext` are generic over the server's lifespan state and the transport's request type,
which it leaves untyped itself (`mcp.server.context.CallNext`, `MCPServer.middleware`): the untyped
parameters here are the SDK's, named once."""

from __future__ import annotations

from typing import Any

from mcp.server.context import CallNext as CallNext
from mcp.server.context import HandlerResult as HandlerResult
from mcp.server.context import ServerRequestContext
from mcp.server.mcpserver import Context, MCPServer

# Any: mcp SDK, a tool's (or resolver's) request context, generic over session and lifespan
ToolContext = Context[Any, Any]
# Any: mcp SDK, an inbound message's context as middleware sees it, generic over lifespan and request
RequestContext = ServerRequestContext[Any, Any]
# Any: mcp SDK, an MCP server whatever its lifespan state
AnyServer = MCPServer[Any]
# Any: mcp SDK, a tool's JSON schema (or a part of one) as it holds it (``Tool.parameters``)
SdkSchema = dict[str, Any]
# Any: mcp SDK, a tool call's JSON arguments as it passes them (``Tool.run``)
SdkArguments = dict[str, Any]

__all__ = [
    "AnyServer",
    "CallNext",
    "HandlerResult",
    "RequestContext",
    "SdkArguments",
    "SdkSchema",
    "ToolContext",
]
