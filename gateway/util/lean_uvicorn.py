"""uvicorn's server and its configuration, without the package's ``__init__``.

``uvicorn/__init__.py`` imports ``uvicorn.main``, its command line: click, the reloader and worker
supervisors and with them multiprocessing (about 2 MiB of a serving gateway's RSS, 27 modules). The
gateway runs uvicorn from its own command (`gateway.server_cli`) and needs only ``uvicorn.config`` and
``uvicorn.server``, so importing this module registers ``uvicorn`` as a bare package
(`gateway.util.bare_package`): ``Config`` is answered from ``uvicorn.config`` (uvicorn's lifespan
modules import it from the package); any other name the package is asked for runs its own ``__init__``
first, so code that uses ``uvicorn.run`` works as before.

sse_starlette (the MCP SDK's and the event stream's server-sent events) imports ``Server`` from
``uvicorn.main`` to wrap its ``handle_exit`` (a stream ends when the server stops). It is imported here,
with ``uvicorn.main`` standing for ``uvicorn.server`` during that import only: it wraps the same class,
and a later ``import uvicorn.main`` loads the real module.

Nothing is done where uvicorn (or sse_starlette) is imported already. `gateway.api` and `gateway.mcp`
import this module before either imports sse_starlette.
"""

from __future__ import annotations

import sys
import types

from gateway.util.bare_package import own_init_when_missed, register_bare_package

PACKAGE = "uvicorn"
CLI_MODULE = "uvicorn.main"
SSE_MODULE = "sse_starlette.sse"
_whole_package = own_init_when_missed(PACKAGE)


def _package_name(package: types.ModuleType, name: str) -> object:
    if name == "Config":
        from uvicorn.config import Config as config_class

        setattr(package, name, config_class)
        return config_class
    return _whole_package(package, name)


def _import_sse_starlette() -> None:
    """sse_starlette, with ``uvicorn.main`` standing for ``uvicorn.server`` while it is imported."""
    if SSE_MODULE in sys.modules or CLI_MODULE in sys.modules:
        return
    import uvicorn.server

    sys.modules[CLI_MODULE] = uvicorn.server
    try:
        import sse_starlette.sse  # noqa: F401
    finally:
        if sys.modules.get(CLI_MODULE) is uvicorn.server:
            del sys.modules[CLI_MODULE]


register_bare_package(PACKAGE, _package_name, "uvicorn")
_import_sse_starlette()

# ruff: noqa: E402 - these come after the bare package is registered
from uvicorn.config import Config
from uvicorn.server import Server

__all__ = ["Config", "Server"]
