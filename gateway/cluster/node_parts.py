"""What the cluster node's parts read of their node (`gateway.cluster.node.ClusterNode`, which passes
itself): the part that every one of them reads, declared once, so no part imports the node."""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from gateway.cluster.bus import Bus
from gateway.cluster.leases import Lease
from gateway.cluster.runtime_view import NodeRuntime
from gateway.config import Settings

if TYPE_CHECKING:
    from gateway.fleet.vehicles.registry import Registry


class NodeCore(Protocol):
    """The node's identity, its registry, the leases it holds and its bus (the stop-only path reads no
    more)."""

    @property
    def node_id(self) -> str: ...

    @property
    def registry(self) -> Registry | None: ...

    @property
    def held(self) -> dict[str, Lease]: ...

    @property
    def bus(self) -> Bus: ...


class NodeWithRuntime(NodeCore, Protocol):
    """The core and the runtime it serves, with its settings."""

    @property
    def gateway(self) -> NodeRuntime: ...

    @property
    def settings(self) -> Settings: ...
