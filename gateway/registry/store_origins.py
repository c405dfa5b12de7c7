"""The store's vehicle origins: the first home each vehicle reported,
or where an operator moved it; kept across restarts."""

from __future__ import annotations

from sqlalchemy import select

from gateway.registry.models import OriginRow
from gateway.registry.records import ORIGIN_SOURCES, Origin, OriginSource
from gateway.registry.store_core import StoreCore


def _origin(row: OriginRow) -> Origin:
    return Origin(
        vehicle_id=row.vehicle_id,
        lat=row.lat,
        lon=row.lon,
        alt_amsl_m=row.alt_amsl_m,
        source=_source(row.source),
        set_by=row.set_by,
        set_at=row.set_at,
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
        async with self._sessions() as session:
            row = await session.get(OriginRow, vehicle_id)
            return None if row is None else _origin(row)

    async def list_origins(self) -> list[Origin]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(OriginRow).order_by(OriginRow.vehicle_id))).all()
            return [_origin(r) for r in rows]

    async def save_origin(self, origin: Origin, *, only_if_absent: bool = False) -> Origin:
        """Store ``origin``; with ``only_if_absent`` an origin already stored is kept and returned (the
        first home is recorded once, whichever gateway node saw it first)."""
        async with self._sessions.begin() as session:
            row = await session.get(OriginRow, origin.vehicle_id)
            if row is not None and only_if_absent:
                return _origin(row)
            if row is None:
                row = OriginRow(vehicle_id=origin.vehicle_id)
                session.add(row)
            row.lat, row.lon, row.alt_amsl_m = origin.lat, origin.lon, origin.alt_amsl_m
            row.source, row.set_by, row.set_at = origin.source, origin.set_by[:200], origin.set_at
            return origin
