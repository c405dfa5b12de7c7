"""The MCP SDK's generic types as this layer uses them. The SDK's `Context`, `MCPServer` and
`ServerRequestContext` are generic over the server's lifespan state and the transport's request type,
which it types as ``Any`` itself (`mcp.server.context.CallNext`, `MCPServer.middleware`): the ``Any``
here is the SDK's, named once."""

from __future__ import annotations

from typing import Any

from mcp.server.context import CallNext as CallNext
from mcp.server.context import HandlerResult as HandlerResult
from mcp.server.context import ServerRequestContext
from mcp.server.mcpserver import Context, MCPServer

#: a tool's (or resolver's) request context (mcp SDK: generic over session and lifespan)
ToolContext = Context[Any, Any]
#: an inbound message's context as middleware sees it (mcp SDK: generic over lifespan and request)
RequestContext = ServerRequestContext[Any, Any]
#: an MCP server whatever its lifespan state (mcp SDK)
AnyServer = MCPServer[Any]
#: a tool's JSON schema (or a part of one) as the SDK holds it (mcp SDK: ``Tool.parameters``)
SdkSchema = dict[str, Any]
#: a tool call's JSON arguments as the SDK passes them (mcp SDK: ``Tool.run``)
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
