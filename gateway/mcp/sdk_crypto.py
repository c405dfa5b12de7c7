"""The MCP SDK's request-state cryptography, loaded when a request state is first sealed or opened.

``mcp.server.request_state`` imports ``cryptography`` (AES-GCM, HKDF-SHA256, ``InvalidTag``) at the top
of the module, and ``MCPServer.__init__`` derives an ephemeral AES key with it, whatever the server
serves. ``cryptography``'s Rust extension is 8 MiB of a gateway's resident memory, and the request state
it protects is used by one exchange only: a multi-round-trip call of the 2026-07-28 protocol (the
gateway's elicited confirmations). So:

- ``defer_sdk_cryptography()`` (run by ``gateway/mcp/__init__.py``, before any MCP SDK module) imports
  ``mcp.server.request_state`` with stand-ins for the four names it takes from ``cryptography``, and
  takes the stand-ins out of ``sys.modules`` again: any other import of ``cryptography`` gets the real
  package. The stand-ins of ``AESGCM``, ``HKDF`` and ``SHA256`` are callables; the first call imports the
  real package and puts the real four names into the SDK module, before anything of them runs. The
  stand-in of ``InvalidTag`` is an exception class nothing raises: only a real ``AESGCM`` raises the real
  one, and there is none before the names are replaced.
- ``deferred_request_state_security()`` is the SDK's own ephemeral policy (a process-local 32-byte key,
  AES-256-GCM under HKDF-SHA256, the SDK's codec, TTL, audience and principal binding) whose codec is
  made at the first seal or unseal instead of in ``MCPServer.__init__``.

The SDK's code runs unchanged; only when its cryptography is imported moves.
"""

from __future__ import annotations

import importlib
import os
import sys
import threading
import types
from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mcp.server.request_state import AESGCMRequestStateCodec, RequestStateSecurity

#: the names ``mcp.server.request_state`` imports from cryptography, by module
SDK_CRYPTOGRAPHY = {
    "cryptography.exceptions": "InvalidTag",
    "cryptography.hazmat.primitives.ciphers.aead": "AESGCM",
    "cryptography.hazmat.primitives.hashes": "SHA256",
    "cryptography.hazmat.primitives.kdf.hkdf": "HKDF",
}
SDK_MODULE = "mcp.server.request_state"

_load_lock = threading.Lock()


class _InvalidTagNotLoaded(Exception):
    """Stands for ``cryptography.exceptions.InvalidTag`` until cryptography is loaded (never raised)."""


def load_sdk_cryptography() -> None:
    """Import cryptography's four names and put them into the SDK's request-state module."""
    with _load_lock:
        sdk = sys.modules[SDK_MODULE]
        for module_name, name in SDK_CRYPTOGRAPHY.items():
            setattr(sdk, name, getattr(importlib.import_module(module_name), name))


def _loading(name: str) -> Callable[..., object]:
    def stand_in(*args: object, **kwargs: object) -> object:
        load_sdk_cryptography()
        real: Callable[..., object] = getattr(sys.modules[SDK_MODULE], name)
        return real(*args, **kwargs)

    stand_in.__name__ = stand_in.__qualname__ = name
    return stand_in


def defer_sdk_cryptography() -> bool:
    """Import the SDK's request-state module without cryptography; False when that is too late (it, or
    cryptography, is imported already) and nothing was done."""
    if SDK_MODULE in sys.modules or any(name in sys.modules for name in SDK_CRYPTOGRAPHY):
        return False
    stand_ins = {}
    for module_name, name in SDK_CRYPTOGRAPHY.items():
        module = types.ModuleType(module_name)
        setattr(module, name, _InvalidTagNotLoaded if name == "InvalidTag" else _loading(name))
        stand_ins[module_name] = module
    sys.modules.update(stand_ins)
    try:
        importlib.import_module(SDK_MODULE)
    finally:
        for module_name, module in stand_ins.items():
            if sys.modules.get(module_name) is module:
                del sys.modules[module_name]
    return True


class DeferredCodec:
    """The SDK's ``AESGCMRequestStateCodec`` under a key made now, built at its first use."""

    def __init__(self) -> None:
        self._key = os.urandom(32)
        self._codec: AESGCMRequestStateCodec | None = None

    def _real(self) -> AESGCMRequestStateCodec:
        if self._codec is None:
            from mcp.server.request_state import AESGCMRequestStateCodec

            self._codec = AESGCMRequestStateCodec([self._key])
        return self._codec

    def seal(self, payload: bytes) -> str:
        return self._real().seal(payload)

    def unseal(self, token: str) -> bytes:
        return self._real().unseal(token)


def deferred_request_state_security() -> RequestStateSecurity:
    """``RequestStateSecurity.ephemeral()`` with its codec built at the first seal or unseal."""
    from mcp.server.request_state import RequestStateSecurity

    return RequestStateSecurity(codec=DeferredCodec())
