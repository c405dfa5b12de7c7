"""The runtime as a cluster node sees it.

The runtime (`gateway.runtime.Gateway`) builds its node only when clustering is configured and hands it
itself; the node and its parts depend on `NodeRuntime`, what they read of it, and never import the
runtime module.
"""

from __future__ import annotations

from typing import Protocol

from gateway.config import Settings
from gateway.fleet.commands.commander import Commander
from gateway.fleet.operations.fleet_ops import FleetOperations
from gateway.fleet.operations.operations import OperationManager
from gateway.fleet.policy.operator_locks import LockBook
from gateway.registry.store import Store


class NodeRuntime(Protocol):
    """What a cluster node reads of the runtime it serves."""

    @property
    def settings(self) -> Settings: ...

    @property
    def ready(self) -> bool:
        """The store is open and the registry has started."""
        ...

    @property
    def store(self) -> Store | None: ...

    def require_store(self) -> Store:
        """The open store; GatewayNotRunning while starting or stopping."""
        ...

    @property
    def locks(self) -> LockBook: ...

    @property
    def operations(self) -> OperationManager | None: ...

    @property
    def fleet_operations(self) -> FleetOperations | None: ...

    @property
    def commander(self) -> Commander:
        """The one command path; GatewayNotRunning before start."""
        ...
