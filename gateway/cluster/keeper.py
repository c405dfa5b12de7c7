"""Which vehicles this node should own: the lease plan (pure) and the loop that carries it out.

Every ``ttl/3`` seconds a node says it is alive, renews its leases (a lease it could not renew is lost:
its sidecar stops at once), and takes free leases up to its fair share: each vehicle counts
``1/k`` for each of the ``k`` live nodes allowed to own it (all nodes, or those carrying its
``node_tag``). A node holding more than its share (it started first) hands over vehicles that are on
the ground and idle; a flying drone is never handed over for balance, only when its node is lost.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field

from gateway.cluster.leases import Lease, NodeRecord


@dataclass(frozen=True)
class Wanted:
    """A registration as the plan sees it."""

    vehicle_id: str
    node_tag: str | None = None
    auto_connect: bool = True


@dataclass
class LeasePlan:
    #: free vehicles this node may take, in the order to try; take at most ``room`` of them
    candidates: list[str] = field(default_factory=list)
    room: int = 0
    #: held vehicles to give up now
    release: list[str] = field(default_factory=list)
    share: float = 0.0


def eligible(vehicle: Wanted, tags: Iterable[str]) -> bool:
    return vehicle.node_tag is None or vehicle.node_tag in set(tags)


def plan(
    node_id: str,
    node_tags: Sequence[str],
    vehicles: Sequence[Wanted],
    leases: Mapping[str, Lease],
    nodes: Sequence[NodeRecord],
    held: set[str],
    idle: set[str],
) -> LeasePlan:
    """What this node should take and give up, from what the database says now.

    ``held``: the vehicles this node owns; ``idle``: those of them on the ground with nothing running.
    """
    alive = {n.node_id: list(n.tags) for n in nodes if n.alive}
    alive[node_id] = list(node_tags)
    wanted = {v.vehicle_id: v for v in vehicles if v.auto_connect}
    mine = [v for v in wanted.values() if eligible(v, node_tags)]
    share = 0.0
    for v in mine:
        k = sum(1 for tags in alive.values() if eligible(v, tags))
        share += 1.0 / max(k, 1)
    target = math.ceil(share - 1e-9)
    out = LeasePlan(share=share)
    # no longer ours to run: removed, disconnected by an operator, or pinned elsewhere
    out.release = sorted(vid for vid in held if vid not in wanted or not eligible(wanted[vid], node_tags))
    keep = len(held) - len(out.release)
    if keep > target:
        spare = sorted(vid for vid in idle if vid in held and vid not in out.release)
        give = spare[: keep - target]
        out.release += give
        keep -= len(give)
    out.room = max(0, target - keep)
    for v in sorted(mine, key=lambda w: w.vehicle_id):
        if v.vehicle_id in held:
            continue
        lease = leases.get(v.vehicle_id)
        if lease is None or not lease.live:
            out.candidates.append(v.vehicle_id)
    return out
