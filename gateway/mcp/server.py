"""The gateway's MCP server: toolsets selected by settings, resources, prompts, session + audit middleware.

Mounting in the one ASGI app (``gateway/app.py``)::

    mcp = build_mcp(gateway)
    app.add_route("/mcp", mcp_http_app(mcp, settings), include_in_schema=False)
    # and inside the FastAPI lifespan, after gateway.start():
    async with mcp_lifespan(mcp): ...
"""

from __future__ import annotations

import asyncio
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
from gateway.mcp.arguments import advertise_policy_limits, install_argument_messages
from gateway.mcp.auth import auth_options
from gateway.mcp.resources import ResourceNotifier, register_prompts, register_resources
from gateway.mcp.session import SessionAudit
from gateway.mcp.toolkit import Toolset, collapse_optional_nulls, register_toolset, strip_schema_titles

log = logging.getLogger(__name__)

SERVER_NAME = "fleet-gateway"
INSTRUCTIONS = (
    "Flies MAVLink drones; drone tools take drone_id, fleet tools drone_ids (list: fleet://drones). "
    "Altitudes are metres above "
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
        try:
            try:  # on a cluster node, each vehicle's operations are picked up by the node taking it over
                if getattr(gateway, "cluster", None) is None:
                    await fa.operations.recover()
            except Exception:  # a store problem must not keep the MCP surface down
                log.exception("could not mark the previous process's operations interrupted")
            async with notifier_box["notifier"].running():
                yield {"fleet": fa}
        finally:  # the gateway is going down: running operations are recorded as interrupted
            await fa.operations.stop()

    server = MCPServer(
        SERVER_NAME,
        version=_version(),
        instructions=INSTRUCTIONS.format(cap=settings.mcp_wait_cap_s),
        lifespan=lifespan,
        subscriptions=bus,
        middleware=[SessionAudit(lambda: fa.store, lambda: fa.operations)],
        **auth_options(settings),
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
        collapse_optional_nulls(tool.parameters)
        advertise_policy_limits(tool, settings)
        install_argument_messages(tool)
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
    """The Streamable HTTP ASGI app serving the path ``/mcp``.

    Add it as the route ``/mcp`` of the FastAPI app (``app.add_route("/mcp", it)``): mounted at "/" it
    would also catch every unknown REST URL (plain-text 404s, and 404 instead of 405).
    """
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


@contextlib.asynccontextmanager
async def mcp_lifespan(server: MCPServer) -> AsyncIterator[None]:
    """Run the Streamable HTTP session manager for the duration of the ASGI app's lifespan.

    Mounted sub-app lifespans never run by themselves, so the app enters this. The session manager holds
    an anyio task group, which must be exited by the task that entered it; lifespans are not always
    entered and exited by one task (pytest fixtures, some servers), so it runs in a task of its own.
    """
    started = asyncio.Event()
    stopping = asyncio.Event()

    async def run() -> None:
        async with server.session_manager.run():
            started.set()
            await stopping.wait()

    task = asyncio.create_task(run(), name="mcp-session-manager")
    waiter = asyncio.create_task(started.wait())
    await asyncio.wait({task, waiter}, return_when=asyncio.FIRST_COMPLETED)
    waiter.cancel()
    if task.done():
        task.result()  # it failed to start: raise its error here
    try:
        yield
    finally:
        stopping.set()
        await task


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("fleet-gateway")
    except Exception:
        return "0"
