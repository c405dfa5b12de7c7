"""The gateway's MCP server: toolsets selected by settings, resources, prompts, session + audit middleware.

Mounting in the one ASGI app (``gateway/app.py``)::

    mcp = build_mcp(gateway)
    app.mount("/", mcp_http_app(mcp, settings))     # after the REST routes; endpoint is /mcp
    # and inside the FastAPI lifespan, after gateway.start():
    async with mcp_lifespan(mcp): ...
"""

from __future__ import annotations

import contextlib
import importlib
import logging
from collections.abc import AsyncIterator
from typing import Any

from mcp.server.mcpserver import MCPServer
from mcp.server.subscriptions import InMemorySubscriptionBus
from mcp.server.transport_security import TransportSecuritySettings
from starlette.applications import Starlette

from gateway.mcp.access import FleetAccess
from gateway.mcp.resources import ResourceNotifier, register_prompts, register_resources
from gateway.mcp.session import SessionAudit
from gateway.mcp.toolkit import Toolset, register_toolset, strip_schema_titles

log = logging.getLogger(__name__)

SERVER_NAME = "fleet-gateway"
INSTRUCTIONS = (
    "Flies MAVLink drones; every tool takes drone_id (list: fleet://drones). Altitudes are metres above "
    "home unless alt_frame='amsl'. Long actions (takeoff, goto, land, missions) wait until done, up to "
    "{cap:g} s; status 'running' means still in progress: call monitor_flight before the next move."
)


def load_toolset(name: str) -> Toolset | None:
    """The toolset module ``gateway.mcp.tools.<name>`` (a module-level ``toolset``), if it exists."""
    try:
        module = importlib.import_module(f"gateway.mcp.tools.{name}")
    except ModuleNotFoundError as exc:
        if exc.name == f"gateway.mcp.tools.{name}":
            log.info("MCP toolset %r is not available in this build", name)
            return None
        raise
    return module.toolset


def build_mcp(gateway: Any) -> MCPServer:
    """The MCP server over a runtime ``Gateway`` (settings, registry, store, operations, safety)."""
    settings = gateway.settings
    fa = FleetAccess(gateway)
    bus = InMemorySubscriptionBus()
    notifier_box: dict[str, ResourceNotifier] = {}

    @contextlib.asynccontextmanager
    async def lifespan(server: MCPServer) -> AsyncIterator[dict[str, Any]]:
        async with notifier_box["notifier"].running():
            yield {"fleet": fa}

    server = MCPServer(
        SERVER_NAME,
        version=_version(),
        instructions=INSTRUCTIONS.format(cap=settings.mcp_wait_cap_s),
        lifespan=lifespan,
        subscriptions=bus,
        middleware=[SessionAudit(lambda: fa.store)],
    )
    server.fleet_access = fa  # type: ignore[attr-defined]  # resolvers reach the gateway through it
    for name in settings.toolsets:
        toolset = load_toolset(name)
        if toolset is not None:
            register_toolset(server, toolset, fa)
            if hasattr(toolset, "register_resources"):  # a toolset may bring resources (fleet://formation)
                toolset.register_resources(server, fa)
    for tool in server._tool_manager.list_tools():
        strip_schema_titles(tool.parameters)
        if tool.output_schema is not None:
            strip_schema_titles(tool.output_schema)
    notifier = ResourceNotifier(server, fa)
    notifier.install()
    notifier_box["notifier"] = notifier
    server.resource_notifier = notifier  # type: ignore[attr-defined]
    register_resources(server, fa)
    register_prompts(server)
    return server


def mcp_http_app(server: MCPServer, settings: Any) -> Starlette:
    """The Streamable HTTP ASGI app serving ``/mcp`` (mount it at "/" after the REST routes)."""
    hosts = ["127.0.0.1:*", "localhost:*", "[::1]:*"]
    origins = ["http://127.0.0.1:*", "http://localhost:*", "http://[::1]:*"]
    extra = [h.strip() for h in getattr(settings, "mcp_allowed_hosts", "").split(",") if h.strip()]
    for host in extra:
        hosts += [host, f"{host}:*"]
        origins += [f"http://{host}", f"https://{host}", f"http://{host}:*", f"https://{host}:*"]
    return server.streamable_http_app(
        streamable_http_path="/mcp",
        json_response=False,  # SSE: progress notifications need it
        stateless_http=False,  # 2025-era clients get sessions (subscriptions, elicitation)
        transport_security=TransportSecuritySettings(
            enable_dns_rebinding_protection=True, allowed_hosts=hosts, allowed_origins=origins
        ),
    )


streamable_http_app = mcp_http_app
"""The name gateway/app.py imports."""


def mcp_lifespan(server: MCPServer) -> contextlib.AbstractAsyncContextManager[None]:
    """Run this inside the ASGI app's lifespan: mounted sub-app lifespans never run by themselves."""
    return server.session_manager.run()


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("fleet-gateway")
    except Exception:
        return "0"
