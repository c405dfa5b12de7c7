"""The MCP SDK's package without its ``__init__``, and its httpx2 when first used.

``mcp/__init__.py`` imports the SDK's client (``Client``, ``ClientSession``, ``ClientSessionGroup``,
its stdio, SSE and Streamable HTTP transports) for its top-level names; a server never uses them. And
``mcp.server.mcpserver.resources.types`` imports httpx2 (with httpcore2, h11, certifi, idna) for one
method, ``HttpResource.read``, which fetches a resource the server registered by URL: the gateway
registers none. Both cost 2.4 MiB of a serving gateway's RSS (52 modules; `bench/memory.py`).

- ``install_bare_package()`` registers ``mcp`` as its directory only (as ``gateway/link/mavsdk_system.py``
  does for mavsdk_grpc), so importing ``mcp.server...`` runs no client code. The first name asked of the
  package that it does not have (``from mcp import ClientSession``, ``mcp.Client``) runs the real
  ``__init__`` in the package, so such code works as before, with the client loaded.
- ``httpx2_when_used()`` puts a stand-in for ``httpx2`` in ``sys.modules`` while the SDK is imported; the
  SDK module keeps the stand-in, whose first attribute asked imports the real httpx2 and answers from it.
  Every later import of httpx2 gets the real package.

Nothing is done where ``mcp`` (or httpx2) is imported already: a program that imports the SDK before the
gateway gets it whole.
"""

from __future__ import annotations

import contextlib
import importlib
import sys
import types
from collections.abc import Iterator

from gateway.util.bare_package import own_init_when_missed, register_bare_package

SDK_PACKAGE = "mcp"
DEFERRED_MODULE = "httpx2"


def install_bare_package() -> bool:
    """``mcp`` as a bare package (its ``__init__`` runs when a name of it is first missed); False when
    ``mcp`` is imported already and nothing was done."""
    missed = own_init_when_missed(SDK_PACKAGE)
    return register_bare_package(SDK_PACKAGE, missed, "the MCP SDK (the mcp package)") is not None


@contextlib.contextmanager
def httpx2_when_used() -> Iterator[None]:
    """Within: ``import httpx2`` binds a stand-in that imports the real package at its first use."""
    if DEFERRED_MODULE in sys.modules:
        yield
        return
    stand_in = types.ModuleType(DEFERRED_MODULE)

    def real_name(name: str) -> object:
        if sys.modules.get(DEFERRED_MODULE) is stand_in:
            del sys.modules[DEFERRED_MODULE]
        return getattr(importlib.import_module(DEFERRED_MODULE), name)

    stand_in.__getattr__ = real_name  # type: ignore[method-assign]
    sys.modules[DEFERRED_MODULE] = stand_in
    try:
        yield
    finally:
        if sys.modules.get(DEFERRED_MODULE) is stand_in:
            del sys.modules[DEFERRED_MODULE]
