"""The running gateway: every long-lived part, built here and only here, with one start/stop.

The HTTP app (:mod:`gateway.app`) and ``mcp-stdio`` create one :class:`Gateway` and start it. Starting
opens the store, restores the operator locks and the takeover locks (`gateway.fleet.policy.takeover`), builds
the safety policy (which reads them through a read-only view), the operation managers and the
`Commander` every door sends its commands through (the operations tell it of takeovers), then restores
and connects the vehicles. Stopping ends running operations (recorded as interrupted),
every sidecar, then the store.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import TYPE_CHECKING

from gateway.config import Settings
from gateway.errors import GatewayError
from gateway.fleet.commands.commander import Commander
from gateway.fleet.commands.scopes import ScopedDirectory, scopes_by_principal
from gateway.fleet.operations.fleet_operation import FleetOperation
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.policy.operator_locks import LockBook
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.vehicles.protocols import VehicleRegistry
from gateway.registry.store import Store

if TYPE_CHECKING:
    from gateway.cluster.node import ClusterNode

log = logging.getLogger(__name__)

RegistryFactory = Callable[[Settings, Store], VehicleRegistry]


class GatewayNotRunning(GatewayError, code="not_ready", http_status=503):
    """The gateway is starting or stopping; retry shortly."""


def _default_registry(settings: Settings, store: Store) -> VehicleRegistry:
    from gateway.fleet.vehicles.registry import Registry

    return Registry(settings, store)


class Gateway:
    """Owns the store, the registry, the policy, the operations and the Commander for the life of the
    process. Before `start` (and after `stop`) the parts that need the store are absent: their
    accessors raise GatewayNotRunning."""

    def __init__(self, settings: Settings, registry_factory: RegistryFactory | None = None) -> None:
        self.settings = settings
        self.store: Store | None = None
        self.registry: VehicleRegistry | None = None
        # Operator locks: set through REST, persisted, restored on start. Agents get only a read-only
        # view (through ``safety``). One book for the life of the gateway, so views stay valid.
        self.locks = LockBook()
        self.safety: SafetyPolicy | None = None
        self.operations: OperationManager | None = None
        self.fleet_operations: FleetOperations | None = None
        self._commander: Commander | None = None
        self._registry_factory = registry_factory or _default_registry
        self._registry_started = False
        # This process as a node of a cluster, when GATEWAY_CLUSTER_NATS_URL is set.
        self.cluster: ClusterNode | None = None

    @property
    def ready(self) -> bool:
        """True once the store is open and the registry has started (and until stop)."""
        return self.store is not None and self.store.is_open and self._registry_started

    def require_store(self) -> Store:
        if self.store is None or not self.store.is_open:
            raise GatewayNotRunning("the gateway's database is not open (starting or stopping)")
        return self.store

    def require_registry(self) -> VehicleRegistry:
        if self.registry is None or not self._registry_started:
            raise GatewayNotRunning("the vehicle registry is not running (starting or stopping)")
        return self.registry

    def require_safety(self) -> SafetyPolicy:
        if self.safety is None:
            raise GatewayNotRunning("the safety policy is not loaded yet (starting)")
        return self.safety

    @property
    def commander(self) -> Commander:
        """The one command path (`gateway.fleet.commands.commander`); GatewayNotRunning before start."""
        if self._commander is None or not self._registry_started:
            raise GatewayNotRunning("the gateway is not running (starting or stopping); retry shortly")
        return self._commander

    async def start(self) -> None:
        """Open (and migrate) the database, build the policy, operations and Commander, then restore
        and connect the registered vehicles."""
        if self.settings.clustered:
            from gateway.cluster.node import check_settings

            check_settings(self.settings)
        log.info("opening database %s", _redact(self.settings.database_url))
        self.store = await Store.open(self.settings.database_url)
        try:
            spool_file = self.settings.spool_file
            if spool_file is not None:  # writes a killed run kept go first, before anything new
                await self.store.keep_spool_in(spool_file)
            for lock in await self.store.list_locks():
                self.locks.lock(lock.scope, lock.reason, lock.by, at=lock.locked_at)
            for lock in await self.store.list_takeovers():
                self.locks.take_over(lock.scope, lock.reason, at=lock.locked_at, by=lock.by)
            self.safety = SafetyPolicy.from_settings(self.settings, self.locks.view())
            self.operations = OperationManager(self.settings, self.store)
            if self.settings.clustered:
                # other nodes are running theirs: each vehicle's operations are picked up by the node
                # that takes the vehicle over (gateway.cluster.takeover), never all at once here
                self.registry = self._cluster_registry(self.store)
            else:
                interrupted = await self.operations.recover()
                if interrupted:
                    log.info("%d operation(s) of the previous process recorded as interrupted", interrupted)
                self.registry = self._registry_factory(self.settings, self.store)
            router = None if self.cluster is None else self.cluster.router
            store = self.store

            async def fleet_ended(fop: FleetOperation) -> None:
                # calls that returned while it ran (wait:false, a capped wait) end with its outcome
                await store.finish_audit_of(fop.id, fop.status, fop.message)

            self.fleet_operations = FleetOperations(
                self.operations, alive=lambda: self._registry_started, router=router, on_ended=fleet_ended
            )
            self._commander = Commander(
                self.settings,
                ScopedDirectory(self.registry, scopes_by_principal(self.settings)),
                self.store,
                self.operations,
                self.fleet_operations,
                self.safety,
                self.locks,
                router=router,
                registrations=self.registry,
            )
            self.operations.on_takeover = self._commander.taken_over
            self.operations.taken_over = self.locks.takeover_for
            await self.registry.start()
            self._registry_started = True
            if not self.settings.clustered:  # a drone found flying keeps its mode watch (a cluster
                # node arms it only for the running operations it resumes: gateway.cluster.takeover)
                self.operations.watch_found_flying(
                    vehicle for v in self.registry.all() if (vehicle := v.flown_here()) is not None
                )
            if self.cluster is not None:
                await self.cluster.start()
        except BaseException:
            await self.stop()
            raise
        log.info("gateway started")

    async def stop(self) -> None:
        """End running operations (recorded as interrupted), stop every sidecar, then close the
        database. Safe to call twice."""
        self._registry_started = False
        self._commander = None
        fleet_operations, self.fleet_operations = self.fleet_operations, None
        operations, self.operations = self.operations, None
        cluster, self.cluster = self.cluster, None
        registry, self.registry = self.registry, None
        try:
            if fleet_operations is not None:
                await fleet_operations.stop()
            if operations is not None:
                await operations.stop()
            if cluster is not None:  # after its operations are recorded, before its sidecars stop:
                try:  # hand the vehicles over
                    await cluster.stop()
                except Exception:
                    log.exception("leaving the cluster failed")
            if registry is not None:
                await registry.stop()
        finally:
            store, self.store = self.store, None
            if store is not None:
                await store.close()
        log.info("gateway stopped")

    def _cluster_registry(self, store: Store) -> VehicleRegistry:
        """A registry whose vehicles start as views of other nodes' vehicles; this node's lease keeper
        adopts the ones it wins. The Commander's verbs for the others go to their owners."""
        from gateway.cluster.node import ClusterNode, remote_factory
        from gateway.fleet.vehicles.registry import Registry

        node = self.cluster = ClusterNode(self)
        registry = node.registry = Registry(
            self.settings, store, remote_factory=remote_factory(self.settings)
        )
        registry.on_registrations_changed(node.registrations_changed)
        return registry

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
