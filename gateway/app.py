"""The one ASGI app of the gateway: REST under /api/v1, /healthz, /readyz, /metrics, /docs, /console, /mcp.

``create_app(settings)`` builds the app and its :class:`~gateway.runtime.Gateway` (``app.state.gateway``),
which the lifespan starts (database migrated and opened, vehicles restored) and stops (every sidecar
ended, database closed).
"""

# ruff: noqa: E402 - FastAPI is imported after its OpenAPI models are (below)
from __future__ import annotations

from gateway.util.deferred_models import import_with_models_deferred

# before FastAPI imports them (`fastapi.params` does): validators built when /openapi.json first is
import_with_models_deferred("fastapi.openapi.models")

import logging
from collections.abc import AsyncIterator, Callable
from contextlib import AbstractAsyncContextManager, AsyncExitStack, asynccontextmanager

from fastapi import FastAPI
from starlette.types import ASGIApp, Receive, Scope, Send

from gateway import package_version
from gateway.api import build_api_router, health, metrics
from gateway.api.docs import install_docs
from gateway.api.errors import install_error_handlers
from gateway.api.limits import BodyLimitMiddleware, McpBodyLimit, McpHostGuard
from gateway.api.openapi import install_openapi, operation_id
from gateway.config import Settings, get_settings
from gateway.console import install_console
from gateway.console import router as console_router
from gateway.mcp.server import build_mcp, mcp_http_app
from gateway.runtime import Gateway, RegistryFactory
from gateway.util.heap import release_free_memory

log = logging.getLogger(__name__)


LifespanHook = Callable[[], AbstractAsyncContextManager[object]]


def create_app(settings: Settings | None = None, registry_factory: RegistryFactory | None = None) -> FastAPI:
    """Build the gateway's ASGI app. ``registry_factory`` replaces the vehicle registry (unit tests)."""
    settings = settings or get_settings()
    gateway = Gateway(settings, registry_factory=registry_factory)
    hooks: list[LifespanHook] = []

    @asynccontextmanager
    async def lifespan(_app: FastAPI) -> AsyncIterator[None]:
        await gateway.start()
        try:
            async with AsyncExitStack() as stack:
                for hook in hooks:  # started after the gateway, stopped before it
                    await stack.enter_async_context(hook())
                release_free_memory()  # what importing and building the app left free
                yield
        finally:
            await gateway.stop()

    app = GatewayApp(
        title="fleet-gateway",
        version=package_version(),
        description="Operator REST API of the MCP gateway for a fleet of MAVLink drones.",
        lifespan=lifespan,
        docs_url=None,  # served by install_docs from local assets
        redoc_url=None,  # ReDoc exists only as a CDN script
        generate_unique_id_function=operation_id,
    )
    app.state.gateway = gateway
    app.state.lifespan_hooks = hooks
    install_error_handlers(app)
    install_docs(app)
    app.add_middleware(BodyLimitMiddleware, max_bytes=settings.max_request_body_bytes)
    metrics.install_metrics(app, gateway)
    app.include_router(health.router)
    app.include_router(metrics.router)
    app.include_router(build_api_router(console_router))
    install_console(app)
    mount_mcp(app, gateway, hooks)
    install_openapi(app)
    return app


class GatewayApp(FastAPI):
    """The FastAPI app, with the MCP endpoint served in front of the REST API's middleware stack.

    A tool call needs none of that stack (REST error handlers, request metrics, routing) and paid for
    every layer twice, on the way in and on each message sent back: about a tenth of a small call's
    CPU. It keeps the request body limit, with its JSON-RPC 413.
    """

    mcp_door: ASGIApp | None = None

    def build_middleware_stack(self) -> ASGIApp:
        stack = super().build_middleware_stack()
        return stack if self.mcp_door is None else McpFirst(stack, self.mcp_door)


class McpFirst:
    """ASGI: the MCP path to ``mcp``, everything else (and the lifespan) to ``app``."""

    def __init__(self, app: ASGIApp, mcp: ASGIApp) -> None:
        self.app, self.mcp = app, mcp

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and scope["path"] == MCP_PATH:
            await self.mcp(scope, receive, send)
        else:
            await self.app(scope, receive, send)


def mount_mcp(app: GatewayApp, gateway: Gateway, hooks: list[LifespanHook]) -> None:
    """Serve the MCP server's Streamable HTTP app at /mcp, in front of the REST API (`GatewayApp`).

    The session manager must run in this app's lifespan (mounted sub-app lifespans never run); it
    enters the MCP server's own lifespan, after the gateway has started. Only the path /mcp reaches
    the MCP app, so every other path keeps the API's JSON errors.
    """
    mcp = build_mcp(gateway)
    mcp_app = mcp_http_app(mcp, gateway.settings)  # creates the session manager
    hooks.append(mcp.session_manager.run)
    app.state.mcp = mcp
    app.mcp_door = McpHostGuard(
        McpBodyLimit(mcp_app, gateway.settings.max_request_body_bytes), gateway.settings
    )


MCP_PATH = "/mcp"
