"""The running gateway: settings, store and registry with one start/stop.

The HTTP app (:mod:`gateway.app`) creates one :class:`Gateway` and starts it in its lifespan. It holds
the operator locks (restored from the database) and the safety policy that reads them; the MCP area
adds its ``operations``.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from gateway.config import Settings
from gateway.errors import GatewayError
from gateway.fleet.safety import LockBook, SafetyPolicy
from gateway.registry.store import Store

log = logging.getLogger(__name__)

RegistryFactory = Callable[[Settings, Store], Any]


class GatewayNotRunning(GatewayError):
    """The gateway is starting or stopping; retry shortly."""

    code = "not_ready"
    http_status = 503


def _default_registry(settings: Settings, store: Store) -> Any:
    from gateway.fleet.registry import Registry

    return Registry(settings, store)


class Gateway:
    """Owns the store and the vehicle registry for the life of the process."""

    def __init__(self, settings: Settings, registry_factory: RegistryFactory | None = None) -> None:
        self.settings = settings
        self.store: Store | None = None
        self.registry: Any = None
        # Operator locks: set through REST, persisted, restored on start. Agents get only a read-only
        # view (through ``safety``). One book for the life of the gateway, so views stay valid.
        self.locks = LockBook()
        self.safety: SafetyPolicy | None = None
        # The MCP area's OperationManager (it creates one when the gateway has none).
        self.operations: Any = None
        self._registry_factory = registry_factory or _default_registry
        self._registry_started = False

    @property
    def ready(self) -> bool:
        """True once the store is open and the registry has started (and until stop)."""
        return self.store is not None and self.store.is_open and self._registry_started

    def require_store(self) -> Store:
        if self.store is None or not self.store.is_open:
            raise GatewayNotRunning("the gateway's database is not open (starting or stopping)")
        return self.store

    def require_registry(self) -> Any:
        if self.registry is None or not self._registry_started:
            raise GatewayNotRunning("the vehicle registry is not running (starting or stopping)")
        return self.registry

    async def start(self) -> None:
        """Open (and migrate) the database, then restore and connect the registered vehicles."""
        log.info("opening database %s", _redact(self.settings.database_url))
        self.store = await Store.open(self.settings.database_url)
        try:
            for lock in await self.store.list_locks():
                self.locks.lock(lock.scope, lock.reason, lock.by, at=lock.locked_at)
            self.safety = SafetyPolicy.from_settings(self.settings, self.locks.view())
            self.registry = self._registry_factory(self.settings, self.store)
            await self.registry.start()
            self._registry_started = True
        except BaseException:
            await self.stop()
            raise
        log.info("gateway started")

    async def stop(self) -> None:
        """Stop every sidecar, then close the database. Safe to call twice."""
        self._registry_started = False
        registry, self.registry = self.registry, None
        try:
            if registry is not None:
                await registry.stop()
        finally:
            store, self.store = self.store, None
            if store is not None:
                await store.close()
        log.info("gateway stopped")

    async def __aenter__(self) -> Gateway:
        await self.start()
        return self

    async def __aexit__(self, *exc: object) -> None:
        await self.stop()


def _redact(url: str) -> str:
    """Hide a password in a database URL for logs."""
    from sqlalchemy.engine import make_url

    try:
        return make_url(url).render_as_string(hide_password=True)
    except Exception:
        return "<unparsable url>"
