"""The one ASGI app of the gateway: REST under /api/v1, /healthz, /readyz, /metrics, /docs, /console, /mcp.

``create_app(settings)`` builds the app and its :class:`~gateway.runtime.Gateway` (``app.state.gateway``),
which the lifespan starts (database migrated and opened, vehicles restored) and stops (every sidecar
ended, database closed).
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import logging
from collections.abc import AsyncIterator, Callable
from contextlib import AbstractAsyncContextManager, AsyncExitStack, asynccontextmanager
from typing import Any

from fastapi import FastAPI
from starlette.routing import Route

from gateway.api import build_api_router, health, metrics
from gateway.api.docs import install_docs
from gateway.api.errors import install_error_handlers
from gateway.api.limits import BodyLimitMiddleware
from gateway.config import Settings, get_settings
from gateway.console import install_console
from gateway.runtime import Gateway, RegistryFactory

log = logging.getLogger(__name__)


def _version() -> str:
    try:
        return importlib.metadata.version("fleet-gateway")
    except importlib.metadata.PackageNotFoundError:
        return "0+unknown"


LifespanHook = Callable[[], AbstractAsyncContextManager[Any]]


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
                yield
        finally:
            await gateway.stop()

    app = FastAPI(
        title="fleet-gateway",
        version=_version(),
        description="Operator REST API of the MCP gateway for a fleet of MAVLink drones.",
        lifespan=lifespan,
        docs_url=None,  # served by install_docs from local assets
        redoc_url=None,  # ReDoc exists only as a CDN script
    )
    app.state.gateway = gateway
    app.state.lifespan_hooks = hooks
    install_error_handlers(app)
    install_docs(app)
    app.add_middleware(BodyLimitMiddleware, max_bytes=settings.max_request_body_bytes)
    metrics.install_metrics(app, gateway)
    app.include_router(health.router)
    app.include_router(metrics.router)
    app.include_router(build_api_router())
    install_console(app)
    mount_mcp(app, gateway, hooks)  # last: after the REST routes
    return app


def mount_mcp(app: FastAPI, gateway: Gateway, hooks: list[LifespanHook]) -> bool:
    """Serve the MCP area's Streamable HTTP app at /mcp, when that area is installed.

    ``gateway.mcp.server`` provides ``build_mcp(gateway)`` (an ``MCPServer``) and
    ``streamable_http_app(mcp, settings)`` (its Starlette app, serving the path ``/mcp``). The session
    manager must run in this app's lifespan: mounted sub-app lifespans never run.

    Rather than mounting the MCP app at "/" (which would answer every unknown path with its own
    plain-text 404), each path it serves is routed to it, so other paths keep the API's JSON errors.
    """
    if importlib.util.find_spec("gateway.mcp.server") is None:
        log.info("MCP server module not present: /mcp is not served")
        return False
    from gateway.mcp import server as mcp_server

    mcp = mcp_server.build_mcp(gateway)
    mcp_app = mcp_server.streamable_http_app(mcp, gateway.settings)
    hooks.append(lambda: mcp.session_manager.run())
    app.state.mcp = mcp
    for route in getattr(mcp_app, "routes", []):
        path = getattr(route, "path", None)
        if path:
            app.router.routes.append(Route(path, endpoint=mcp_app, include_in_schema=False))
    return True
