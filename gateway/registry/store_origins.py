"""The store's vehicle origins: the first home each vehicle reported,
or where an operator moved it; kept across restarts."""

from __future__ import annotations

from sqlalchemy import RowMapping, insert, select, update

from gateway.registry.models import vehicle_origins
from gateway.registry.records import ORIGIN_SOURCES, Origin, OriginSource
from gateway.registry.store_core import StoreCore, row_by_key


def _origin(row: RowMapping) -> Origin:
    return Origin(
        vehicle_id=row["vehicle_id"],
        lat=row["lat"],
        lon=row["lon"],
        alt_amsl_m=row["alt_amsl_m"],
        source=_source(row["source"]),
        set_by=row["set_by"],
        set_at=row["set_at"],
    )


def _source(stored: str) -> OriginSource:
    """A row's source as the model names it; ValueError for one no version of the gateway writes."""
    for source in ORIGIN_SOURCES:
        if stored == source:
            return source
    raise ValueError(f"vehicle_origins.source: {stored!r} is not one of {', '.join(ORIGIN_SOURCES)}")


class OriginTable(StoreCore):
    """One origin per vehicle."""

    async def get_origin(self, vehicle_id: str) -> Origin | None:
        async with self.engine.connect() as conn:
            row = await row_by_key(conn, vehicle_origins, vehicle_id)
        return None if row is None else _origin(row)

    async def list_origins(self) -> list[Origin]:
        async with self.engine.connect() as conn:
            query = select(vehicle_origins).order_by(vehicle_origins.c.vehicle_id)
            rows = (await conn.execute(query)).mappings().all()
        return [_origin(r) for r in rows]

    async def save_origin(self, origin: Origin, *, only_if_absent: bool = False) -> Origin:
        """Store ``origin``; with ``only_if_absent`` an origin already stored is kept and returned (the
        first home is recorded once, whichever gateway node saw it first)."""
        values = {
            "lat": origin.lat,
            "lon": origin.lon,
            "alt_amsl_m": origin.alt_amsl_m,
            "source": origin.source,
            "set_by": origin.set_by[:200],
            "set_at": origin.set_at,
        }
        async with self.engine.begin() as conn:
            row = await row_by_key(conn, vehicle_origins, origin.vehicle_id)
            if row is not None and only_if_absent:
                return _origin(row)
            if row is None:
                await conn.execute(insert(vehicle_origins).values(vehicle_id=origin.vehicle_id, **values))
            else:
                where = vehicle_origins.c.vehicle_id == origin.vehicle_id
                await conn.execute(update(vehicle_origins).where(where).values(values))
            return origin
