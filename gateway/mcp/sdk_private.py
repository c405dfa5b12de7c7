"""The only place the gateway reaches into the MCP SDK's private attributes, and why.

``mcp`` 2.x has no public way to

- get at a registered tool's ``Tool`` object (its advertised ``parameters`` schema, its ``run``): the
  gateway shortens the advertised schemas (titles, optional nulls, the policy's limits) and validates
  arguments first to answer with one line per bad argument. ``MCPServer.list_tools()`` returns copies
  in wire form, and ``add_tool()`` returns nothing;
- register a handler for ``resources/subscribe`` / ``resources/unsubscribe`` on an ``MCPServer``:
  2025-era clients subscribe that way, and the SDK's ``subscriptions`` bus serves only 2026-07-28
  ``subscriptions/listen`` (see /work/shared/MCP-NOTES.md, resources);
- limit the stateful sessions per caller: the session manager has one limit for all callers together
  (``max_sessions``), so one token that never closes its sessions would hold them all;
- choose per request between a JSON and a streamed answer: the session manager's ``json_response``
  holds for every request (``gateway/mcp/json_answers.py`` answers a request without a progress token
  as JSON, through the SDK's own entry for single-exchange requests and the manager's own settings);
- configure logging without ``rich``: ``MCPServer.__init__`` calls ``configure_logging``, which imports
  rich's console and logging handler whenever rich is installed (1 MiB of a gateway's memory) and then
  calls ``logging.basicConfig``, which changes nothing where logging is configured already (the
  gateway's commands configure it first).

Each use is one function here, so an SDK upgrade that adds a public way changes this file only.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Awaitable, Callable
from typing import Any

from mcp.server._streamable_http_modern import handle_modern_request
from mcp.server.mcpserver.tools import Tool
from mcp.server.streamable_http_manager import StreamableHTTPSessionManager
from starlette.types import Receive, Scope, Send

from gateway.mcp.sdk_types import AnyServer


def _configure_plain_logging(level: str = "INFO") -> None:
    """The SDK's ``configure_logging`` as it is without rich installed: a plain handler on stderr."""
    logging.basicConfig(level=level, format="%(message)s")


def configure_logging_without_rich() -> None:
    """Servers made after this call configure logging without importing rich."""
    import mcp.server.mcpserver.server as sdk_server

    sdk_server.configure_logging = _configure_plain_logging  # type: ignore[attr-defined]


def tools(server: AnyServer) -> list[Tool]:
    """The registered tools, as the server keeps them (mutable)."""
    return list(server._tool_manager.list_tools())


def tool(server: AnyServer, name: str) -> Tool:
    found = server._tool_manager.get_tool(name)
    if found is None:
        raise KeyError(f"no tool named {name!r} is registered")
    return found


def replace_run(tool: Tool, run: Callable[..., Awaitable[Any]]) -> None:  # Any: mcp SDK, Tool.run
    """Put a wrapper in place of a tool's ``run`` (``Tool`` is a pydantic model that refuses new values
    for its methods through ``__setattr__``)."""
    object.__setattr__(tool, "run", run)


def add_request_handler(
    server: AnyServer,
    method: str,
    params_type: type[Any],  # Any: mcp SDK, its request handlers' table
    handler: Callable[..., Awaitable[Any]],  # Any: mcp SDK, its request handlers' table
) -> None:
    """A handler for a request method the ``MCPServer`` layer does not expose."""
    server._lowlevel_server.add_request_handler(method, params_type, handler)


async def answer_single_exchange_as_json(
    manager: StreamableHTTPSessionManager, scope: Scope, receive: Receive, send: Send
) -> None:
    """A 2026-07-28 request answered as the manager answers it in JSON mode."""
    state: Any = manager._lifespan_state  # Any: mcp SDK, its private state, untyped
    await handle_modern_request(manager.app, manager.security_settings, True, state, scope, receive, send)


async def handle_request(
    manager: StreamableHTTPSessionManager, scope: Scope, receive: Receive, send: Send
) -> None:
    """The manager's own dispatch, behind its body limit (which the caller keeps)."""
    await manager._handle_request(scope, receive, send)


def cap_sessions_per_caller(manager: StreamableHTTPSessionManager, cap: int) -> None:
    """Before a new stateful session is admitted: when its caller (the token the manager records as the
    session's owner; None without tokens) already holds ``cap``, the caller's session idle the longest
    is ended (its idle countdown cancelled, so the manager discards it as on an idle timeout). A caller
    whose ``cap`` sessions are all busy is refused as at the manager's own limit."""
    admit = manager._admit_session

    def admit_capped(requestor: Any) -> Any:  # Any: mcp SDK, private _admit_session, untyped
        owners = manager._session_owners
        mine = [
            transport
            for session_id, transport in manager._server_instances.items()
            if owners.get(session_id) == requestor and not transport.is_terminated
        ]
        if len(mine) >= cap:
            idle = [
                (scope.deadline, session_id, scope)
                for session_id, transport in manager._server_instances.items()
                if transport in mine
                and (scope := transport.idle_scope) is not None
                and scope.deadline != math.inf
            ]
            if not idle:
                return None
            _deadline, session_id, scope = min(idle, key=lambda entry: entry[0])
            scope.cancel()  # its server task ends and terminates it, as on an idle timeout
            manager._server_instances.pop(session_id, None)  # forgotten now: its id answers 404
            owners.pop(session_id, None)
        return admit(requestor)

    manager._admit_session = admit_capped  # type: ignore[method-assign]
