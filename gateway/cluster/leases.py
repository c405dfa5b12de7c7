"""Ownership of vehicles by cluster nodes: leases and node liveness in PostgreSQL.

Every time is the database's clock (``now()``), never a node's, so nodes with skewed clocks still agree on
whether a lease has expired. Each statement is one atomic ``INSERT ... ON CONFLICT DO UPDATE ... WHERE``
or ``UPDATE ... WHERE``: PostgreSQL locks the row and re-checks the condition on its latest version, so
two nodes racing for one expired lease cannot both win, and a renewal that comes after a takeover fails.

Each statement runs on its own, committed as it ends (no ``BEGIN`` and ``COMMIT`` around it): the rows it
changes are locked only while it runs, never until a ``COMMIT`` sent by a node whose event loop is slow
to send it. The renewal thread (`gateway.cluster.renewal`) and the keeper's tick renew the same rows, and
a renewal that waited on a tick's open transaction waited on the starved loop it was made to escape; one
statement is also one round trip instead of three.

``epoch`` grows at every change of owner (a fencing number): a message stamped with an older epoch comes
from a previous owner.
"""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator, Sequence
from dataclasses import dataclass
from datetime import datetime
from typing import Any

from sqlalchemy import text
from sqlalchemy.exc import IntegrityError

from gateway.registry.sql_async import AsyncConnection, AsyncEngine


@dataclass(frozen=True)
class Lease:
    vehicle_id: str
    node_id: str
    epoch: int
    expires_at: datetime
    #: seconds until expiry by the database's clock when read (negative: expired)
    remaining_s: float

    @property
    def live(self) -> bool:
        return self.remaining_s > 0


@dataclass(frozen=True)
class NodeRecord:
    node_id: str
    tags: list[str]
    api_url: str | None
    started_at: datetime
    last_seen: datetime
    remaining_s: float

    @property
    def alive(self) -> bool:
        return self.remaining_s > 0


_LEASE_COLUMNS = (
    "vehicle_id, node_id, epoch, expires_at, EXTRACT(EPOCH FROM (expires_at - now()))::float8 AS remaining_s"
)

_ACQUIRE = text(
    f"""
    INSERT INTO vehicle_leases AS l (vehicle_id, node_id, epoch, acquired_at, renewed_at, expires_at)
    SELECT CAST(:vid AS varchar), CAST(:node AS varchar), 1, now(), now(),
           now() + make_interval(secs => CAST(:ttl AS float8))
    WHERE EXISTS (SELECT 1 FROM vehicles WHERE id = CAST(:vid AS varchar))
    ON CONFLICT (vehicle_id) DO UPDATE
       SET node_id = EXCLUDED.node_id, epoch = l.epoch + 1, acquired_at = now(), renewed_at = now(),
           expires_at = EXCLUDED.expires_at
     WHERE l.expires_at <= now()
    RETURNING {_LEASE_COLUMNS}
    """
)

_RENEW = text(
    f"""
    UPDATE vehicle_leases
       SET renewed_at = now(), expires_at = now() + make_interval(secs => CAST(:ttl AS float8))
     WHERE node_id = CAST(:node AS varchar) AND vehicle_id = ANY(CAST(:ids AS varchar[]))
       AND expires_at > now()
    RETURNING {_LEASE_COLUMNS}
    """
)

# A released lease is expired, not deleted: its epoch keeps growing across owners.
_RELEASE = text(
    """
    UPDATE vehicle_leases SET expires_at = now()
     WHERE node_id = CAST(:node AS varchar) AND vehicle_id = ANY(CAST(:ids AS varchar[]))
       AND expires_at > now()
    RETURNING vehicle_id
    """
)

_LIST = text(f"SELECT {_LEASE_COLUMNS} FROM vehicle_leases ORDER BY vehicle_id")

_HEARTBEAT = text(
    """
    INSERT INTO cluster_nodes AS n (node_id, tags, api_url, started_at, last_seen, expires_at)
    VALUES (CAST(:node AS varchar), CAST(:tags AS json), CAST(:api AS varchar), now(), now(),
            now() + make_interval(secs => CAST(:ttl AS float8)))
    ON CONFLICT (node_id) DO UPDATE
       SET tags = EXCLUDED.tags, api_url = EXCLUDED.api_url, last_seen = now(),
           expires_at = EXCLUDED.expires_at
    """
)

_NODES = text(
    """
    SELECT node_id, tags, api_url, started_at, last_seen,
           EXTRACT(EPOCH FROM (expires_at - now()))::float8 AS remaining_s
      FROM cluster_nodes ORDER BY node_id
    """
)

_LEAVE = text("UPDATE cluster_nodes SET expires_at = now() WHERE node_id = CAST(:node AS varchar)")


def _lease(row: Any) -> Lease:  # Any: SQLAlchemy, a text() query's untyped Row
    return Lease(row.vehicle_id, row.node_id, int(row.epoch), row.expires_at, float(row.remaining_s))


class LeaseStore:
    """The lease and node-liveness statements of one node (PostgreSQL only)."""

    def __init__(self, engine: AsyncEngine, node_id: str, ttl_s: float) -> None:
        if engine.dialect.name != "postgresql":
            raise ValueError(
                f"cluster leases need PostgreSQL; the database is {engine.dialect.name} "
                "(set GATEWAY_DATABASE_URL=postgresql+asyncpg://...)"
            )
        self.engine = engine
        self.node_id = node_id
        self.ttl_s = float(ttl_s)

    @contextlib.asynccontextmanager
    async def _statement(self) -> AsyncIterator[AsyncConnection]:
        """A connection whose each statement commits as it ends (autocommit)."""
        async with self.engine.connect() as conn:
            yield await conn.execution_options(isolation_level="AUTOCOMMIT")

    async def acquire(self, vehicle_id: str) -> Lease | None:
        """Take the vehicle's lease if nobody holds a live one; None when another node does (or the
        vehicle is not registered)."""
        try:
            async with self._statement() as conn:
                row = (
                    await conn.execute(_ACQUIRE, {"vid": vehicle_id, "node": self.node_id, "ttl": self.ttl_s})
                ).first()
        except IntegrityError:  # the vehicle was removed between the check and the insert
            return None
        return None if row is None else _lease(row)

    async def renew(self, vehicle_ids: Sequence[str]) -> dict[str, Lease]:
        """Extend this node's live leases on ``vehicle_ids``; the ones returned are still held."""
        if not vehicle_ids:
            return {}
        async with self._statement() as conn:
            rows = (
                await conn.execute(
                    _RENEW, {"ids": list(vehicle_ids), "node": self.node_id, "ttl": self.ttl_s}
                )
            ).all()
        return {r.vehicle_id: _lease(r) for r in rows}

    async def release(self, vehicle_ids: Sequence[str]) -> list[str]:
        """Give up this node's leases at once (clean stop, rebalancing); returns those released."""
        if not vehicle_ids:
            return []
        async with self._statement() as conn:
            rows = (await conn.execute(_RELEASE, {"ids": list(vehicle_ids), "node": self.node_id})).all()
        return [r.vehicle_id for r in rows]

    async def leases(self) -> dict[str, Lease]:
        """Every lease, live or expired, by vehicle id."""
        async with self.engine.connect() as conn:
            rows = (await conn.execute(_LIST)).all()
        return {r.vehicle_id: _lease(r) for r in rows}

    async def heartbeat(self, tags: Sequence[str], api_url: str | None) -> None:
        """Say this node is alive for another ``ttl_s`` (and what its tags are)."""
        import json

        params = {"node": self.node_id, "tags": json.dumps(list(tags)), "api": api_url, "ttl": self.ttl_s}
        async with self._statement() as conn:
            await conn.execute(_HEARTBEAT, params)

    async def nodes(self) -> list[NodeRecord]:
        async with self.engine.connect() as conn:
            rows = (await conn.execute(_NODES)).all()
        return [
            NodeRecord(
                r.node_id, list(r.tags or []), r.api_url, r.started_at, r.last_seen, float(r.remaining_s)
            )
            for r in rows
        ]

    async def leave(self) -> None:
        """A clean stop: this node is no longer counted as alive (its leases are released separately)."""
        async with self._statement() as conn:
            await conn.execute(_LEAVE, {"node": self.node_id})
