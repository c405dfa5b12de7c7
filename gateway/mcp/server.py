"""The gateway's MCP server: toolsets selected by settings, resources, prompts, session + audit middleware.

Mounting in the one ASGI app (``gateway/app.py``)::

    mcp = build_mcp(gateway)
    app.mcp_door = McpBodyLimit(mcp_http_app(mcp, settings), limit)  # ahead of the REST API (GatewayApp)
    # and inside the FastAPI lifespan, after gateway.start():
    async with mcp.session_manager.run(): ...

The server's lifespan (entered once, by the session manager or by ``run_stdio_async``, after the
gateway has started) yields a `FleetState`: tools, the kill confirmation and the audit middleware
reach the Commander through ``ctx.request_context.lifespan_context``. Resources cannot take a context
(the SDK's static resources have none), so they and their change notifier read the gateway they were
built over.
"""

from __future__ import annotations

import contextlib
import importlib
import logging
from collections.abc import AsyncIterator, Sequence

from mcp.server.mcpserver import Context, MCPServer
from mcp.server.subscriptions import InMemorySubscriptionBus
from mcp.server.transport_security import TransportSecuritySettings
from mcp.shared.exceptions import MCPError
from mcp.types import INVALID_PARAMS, GetPromptResult
from starlette.applications import Starlette

from gateway import package_version
from gateway.config import Settings
from gateway.mcp import sdk_private
from gateway.mcp.access import FleetState
from gateway.mcp.arguments import advertise_policy_limits, install_argument_messages
from gateway.mcp.auth import auth_options
from gateway.mcp.declared import complete, declared
from gateway.mcp.json_answers import answer_silent_requests_as_json
from gateway.mcp.resources import ResourceNotifier, register_prompts, register_resources
from gateway.mcp.sdk_crypto import deferred_request_state_security
from gateway.mcp.sdk_types import AnyServer
from gateway.mcp.session import SessionAudit
from gateway.mcp.toolkit import (
    Toolset,
    collapse_optional_nulls,
    nullable_type_lists,
    register_toolset,
    strip_schema_titles,
)
from gateway.runtime import Gateway

log = logging.getLogger(__name__)

SERVER_NAME = "fleet-gateway"
INSTRUCTIONS = (
    "Flies MAVLink drones; drone tools take drone_id, fleet tools drone_ids (list: fleet://drones). "
    "Altitudes are metres above "
    "home unless alt_frame='amsl'. Long actions (takeoff, goto, land, missions) wait until done, up to "
    "{cap:g} s (wait=false: answer at once); status 'running' means still in progress: call "
    "monitor_flight before the next move."
)


def load_toolset(name: str) -> Toolset | None:
    """The toolset ``name``: the module ``gateway.mcp.tools.<name>`` (a module-level ``toolset``, its
    hand-written tools) completed with the tools the verbs declare for it (`gateway.mcp.declared`);
    None when there is neither."""
    try:
        module = importlib.import_module(f"gateway.mcp.tools.{name}")
    except ModuleNotFoundError as exc:
        if exc.name != f"gateway.mcp.tools.{name}":
            raise
        if not declared(name):
            log.info("MCP toolset %r is not available in this build", name)
            return None
        return complete(Toolset(name))
    toolset: Toolset = module.toolset
    return complete(toolset)


def tool_names(toolsets: Sequence[str]) -> list[str]:
    """The names of the tools a server with these toolsets lists, in its order: the hand-written tools
    of each toolset's module and the tools the verbs declare for it. Derived from the declarations, so
    what counts tools (tests, docs) needs no number changed when a command is added."""
    names: list[str] = []
    for name in toolsets:
        toolset = load_toolset(name)
        if toolset is not None:
            names.extend(spec.name for spec in toolset.tools)
    return names


class GatewayMCPServer(MCPServer[FleetState]):
    """The SDK's server, with one answer it gets wrong: a prompt that does not exist, or asked for
    without its arguments, is the client's bad parameters (JSON-RPC -32602, naming the prompts there
    are), not an error with code 0 (the SDK turns the ValueError it raises into that)."""

    async def get_prompt(
        self,
        name: str,
        arguments: dict[str, object] | None = None,
        context: Context[FleetState, object] | None = None,
    ) -> GetPromptResult:
        known = sorted(p.name for p in await self.list_prompts())
        if name not in known:
            raise MCPError(INVALID_PARAMS, f"unknown prompt {name!r}; the prompts: {', '.join(known)}")
        try:
            result = await super().get_prompt(name, arguments, context)
        except MCPError:
            raise
        except ValueError as exc:  # the SDK's words for missing or bad arguments
            raise MCPError(INVALID_PARAMS, f"prompt {name!r}: {exc}") from None
        assert isinstance(result, GetPromptResult)
        return result


def build_mcp(gateway: Gateway) -> MCPServer[FleetState]:
    """The MCP server over a runtime ``Gateway`` (which need not be started yet: its Commander is taken
    when the server's lifespan starts)."""
    settings = gateway.settings
    bus = InMemorySubscriptionBus()
    notifier = ResourceNotifier(gateway, bus, formation="fleet" in settings.toolsets)

    @contextlib.asynccontextmanager
    async def lifespan(_server: MCPServer[FleetState]) -> AsyncIterator[FleetState]:
        async with notifier.running():
            yield FleetState(gateway)

    sdk_private.configure_logging_without_rich()
    server: MCPServer[FleetState] = GatewayMCPServer(
        SERVER_NAME,
        version=package_version(),
        instructions=INSTRUCTIONS.format(cap=settings.mcp_wait_cap_s),
        lifespan=lifespan,
        subscriptions=bus,
        middleware=[SessionAudit()],
        request_state_security=deferred_request_state_security(),
        **auth_options(settings),
    )
    for name in settings.toolsets:
        toolset = load_toolset(name)
        if toolset is not None:
            register_toolset(server, toolset)
    for tool in sdk_private.tools(server):
        strip_schema_titles(tool.parameters)
        collapse_optional_nulls(tool.parameters)
        advertise_policy_limits(tool, settings)
        install_argument_messages(tool)
        if tool.output_schema is not None:
            strip_schema_titles(tool.output_schema)
            compact = nullable_type_lists(tool.output_schema)
            assert isinstance(compact, dict)  # a dict stays a dict
            tool.output_schema.clear()
            tool.output_schema.update(compact)
    notifier.install(server)
    register_resources(server, gateway, formation="fleet" in settings.toolsets)
    register_prompts(server)
    return server


def mcp_http_app(server: AnyServer, settings: Settings) -> Starlette:
    """The Streamable HTTP ASGI app serving the path ``/mcp``.

    `gateway.app.GatewayApp` serves it for the path ``/mcp`` only: mounted at "/" it would also catch
    every unknown REST URL (plain-text 404s, and 404 instead of 405).
    """
    app = server.streamable_http_app(
        streamable_http_path="/mcp",
        json_response=False,  # SSE: progress notifications need it
        stateless_http=False,  # 2025-era clients get sessions (subscriptions, elicitation)
        session_idle_timeout=settings.mcp_session_idle_s,
        # Host and Origin: checked in front of /mcp by the REST API's rule (gateway.api.limits.McpHostGuard)
        transport_security=TransportSecuritySettings(enable_dns_rebinding_protection=False),
    )
    sdk_private.cap_sessions_per_caller(server.session_manager, settings.mcp_sessions_per_caller)
    answer_silent_requests_as_json(server.session_manager)  # a request without a progress token
    return app
