"""/api/v1/cluster: this node, the live nodes and which vehicles each owns (404 on a gateway alone)."""

from __future__ import annotations

from fastapi import APIRouter

from gateway.api.deps import GatewayDep
from gateway.errors import NotFound

router = APIRouter(prefix="/cluster", tags=["cluster"])


@router.get(
    "",
    summary="Cluster nodes and the vehicles each one owns",
    responses={404: {"description": "This gateway is not a cluster node (GATEWAY_CLUSTER_NATS_URL unset)."}},
)
async def cluster_view(gateway: GatewayDep) -> dict[str, object]:
    node = gateway.cluster
    if node is None:
        raise NotFound("this gateway is not a cluster node (GATEWAY_CLUSTER_NATS_URL is not set)")
    return node.describe()
