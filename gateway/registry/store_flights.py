"""The store's flight history: flights, their tracks and the vehicles' status texts."""

from __future__ import annotations

from collections.abc import Sequence
from datetime import datetime

from pydantic import BaseModel
from sqlalchemy import func, insert, or_, select, update

from gateway.errors import NotFound
from gateway.registry.models import flights, status_texts, track_samples
from gateway.registry.records import (
    FlightRecord,
    StatusTextIn,
    StatusTextRecord,
    TrackSample,
)
from gateway.registry.store_core import StoreCore, row_by_key, rowcount
from gateway.util.json_types import JsonObject, JsonValue


class FlightEnd(BaseModel):
    """The end of a flight as a kept write holds it (JSON, read again after a restart)."""

    flight_id: int
    ended_at: datetime
    duration_s: float | None = None
    distance_m: float | None = None
    max_alt_rel_m: float | None = None
    battery_used_pct: float | None = None


def _rows(data: JsonObject) -> list[JsonValue]:
    """The rows of a kept batch (``{"rows": [...]}``); ValueError when it holds none."""
    rows = data.get("rows")
    if not isinstance(rows, list):
        raise ValueError(f"a kept batch holds its rows as a list under 'rows'; got {str(rows)[:80]!r}")
    return rows


class FlightTables(StoreCore):
    """Flights, their track samples and the status texts the vehicles sent."""

    async def open_flight(
        self,
        vehicle_id: str,
        started_at: datetime,
        home_lat: float | None = None,
        home_lon: float | None = None,
        home_alt_amsl: float | None = None,
    ) -> int:
        values = {
            "vehicle_id": vehicle_id,
            "started_at": started_at,
            "home_lat": home_lat,
            "home_lon": home_lon,
            "home_alt_amsl": home_alt_amsl,
        }
        async with self.engine.begin() as conn:
            result = await conn.execute(insert(flights).values(values).returning(flights.c.id))
            return int(result.scalar_one())

    async def close_flight(
        self,
        flight_id: int,
        ended_at: datetime,
        duration_s: float | None = None,
        distance_m: float | None = None,
        max_alt_rel_m: float | None = None,
        battery_used_pct: float | None = None,
    ) -> FlightRecord | None:
        """End a flight; None when the database is unreachable (the end is written when it is back)."""
        data = FlightEnd(
            flight_id=flight_id, ended_at=ended_at, duration_s=duration_s, distance_m=distance_m,
            max_alt_rel_m=max_alt_rel_m, battery_used_pct=battery_used_pct,
        ).model_dump(mode="json")  # fmt: skip
        return await self._kept(f"the end of flight {flight_id}", "flight_end", data, self._write_flight_end)

    async def _write_flight_end(self, data: JsonObject) -> FlightRecord:
        end = FlightEnd.model_validate(data)
        changes = end.model_dump(exclude={"flight_id"})
        async with self.engine.begin() as conn:
            result = await conn.execute(update(flights).where(flights.c.id == end.flight_id).values(changes))
            if not rowcount(result):
                raise NotFound(f"no flight with id {end.flight_id}", id=end.flight_id)
            row = await row_by_key(conn, flights, end.flight_id)
        return FlightRecord.model_validate(row)

    async def list_open_flights(self, vehicle_id: str | None = None) -> list[FlightRecord]:
        query = select(flights).where(flights.c.ended_at.is_(None))
        if vehicle_id is not None:
            query = query.where(flights.c.vehicle_id == vehicle_id)
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query.order_by(flights.c.started_at))).mappings().all()
        return [FlightRecord.model_validate(r) for r in rows]

    async def add_track_samples(self, samples: Sequence[TrackSample]) -> int:
        """Insert a batch of track samples in one transaction; returns how many were written (0: kept
        until the database is back)."""
        if not samples:
            return 0
        data: JsonObject = {"rows": [s.model_dump(mode="json") for s in samples]}
        kept = await self._kept(
            f"{len(samples)} track samples", "track_samples", data, self._write_track_samples
        )
        return kept or 0

    async def _write_track_samples(self, data: JsonObject) -> int:
        rows = [TrackSample.model_validate(r).model_dump() for r in _rows(data)]
        async with self.engine.begin() as conn:
            await conn.execute(insert(track_samples), rows)
        return len(rows)

    async def add_status_texts(self, items: Sequence[StatusTextIn]) -> int:
        if not items:
            return 0
        data: JsonObject = {"rows": [i.model_dump(mode="json") for i in items]}
        kept = await self._kept(f"{len(items)} status texts", "status_texts", data, self._write_status_texts)
        return kept or 0

    async def _write_status_texts(self, data: JsonObject) -> int:
        rows = [StatusTextIn.model_validate(r).model_dump() for r in _rows(data)]
        async with self.engine.begin() as conn:
            await conn.execute(insert(status_texts), rows)
        return len(rows)

    async def list_flights(
        self,
        vehicle_id: str | None = None,
        since: datetime | None = None,
        until: datetime | None = None,
        limit: int = 50,
        offset: int = 0,
    ) -> tuple[list[FlightRecord], int]:
        """Flights overlapping [since, until], newest first, with the total count for paging."""
        conditions = []
        if vehicle_id is not None:
            conditions.append(flights.c.vehicle_id == vehicle_id)
        if since is not None:
            conditions.append(or_(flights.c.ended_at.is_(None), flights.c.ended_at >= since))
        if until is not None:
            conditions.append(flights.c.started_at <= until)
        query = select(flights).where(*conditions)
        count = select(func.count()).select_from(flights).where(*conditions)
        newest_first = query.order_by(flights.c.started_at.desc(), flights.c.id.desc())
        async with self.engine.connect() as conn:
            total = int((await conn.execute(count)).scalar_one())
            rows = (await conn.execute(newest_first.limit(limit).offset(offset))).mappings().all()
        return [FlightRecord.model_validate(r) for r in rows], total

    async def get_flight(self, flight_id: int) -> FlightRecord | None:
        async with self.engine.connect() as conn:
            row = await row_by_key(conn, flights, flight_id)
        return None if row is None else FlightRecord.model_validate(row)

    async def get_track(self, flight_id: int) -> list[TrackSample]:
        columns = [track_samples.c[name] for name in TrackSample.model_fields]
        query = (
            select(*columns)
            .where(track_samples.c.flight_id == flight_id)
            .order_by(track_samples.c.t, track_samples.c.id)
        )
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query)).mappings().all()
        # validated when written, so built without re-validation (long tracks)
        return [TrackSample.model_construct(**row) for row in rows]

    async def list_status_texts(
        self, vehicle_id: str, limit: int = 100, since: datetime | None = None
    ) -> list[StatusTextRecord]:
        """The newest ``limit`` status texts of a vehicle, oldest first."""
        query = select(status_texts).where(status_texts.c.vehicle_id == vehicle_id)
        if since is not None:
            query = query.where(status_texts.c.t >= since)
        query = query.order_by(status_texts.c.t.desc(), status_texts.c.id.desc()).limit(limit)
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query)).mappings().all()
        return [StatusTextRecord.model_validate(r) for r in reversed(rows)]

    async def list_flight_status_texts(self, flight_id: int, limit: int = 500) -> list[StatusTextRecord]:
        """The status texts received during a flight, oldest first (at most ``limit``, the first ones)."""
        query = (
            select(status_texts)
            .where(status_texts.c.flight_id == flight_id)
            .order_by(status_texts.c.t, status_texts.c.id)
            .limit(limit)
        )
        async with self.engine.connect() as conn:
            rows = (await conn.execute(query)).mappings().all()
        return [StatusTextRecord.model_validate(r) for r in rows]
