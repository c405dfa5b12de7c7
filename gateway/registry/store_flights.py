"""The store's flight history: flights, their tracks and the vehicles' status texts."""

from __future__ import annotations

from collections.abc import Sequence
from datetime import datetime

from pydantic import BaseModel
from sqlalchemy import func, insert, or_, select

from gateway.errors import NotFound
from gateway.registry.models import (
    FlightRow,
    StatusTextRow,
    TrackSampleRow,
)
from gateway.registry.records import (
    FlightRecord,
    StatusTextIn,
    StatusTextRecord,
    TrackSample,
)
from gateway.registry.store_core import StoreCore
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
        row = FlightRow(
            vehicle_id=vehicle_id,
            started_at=started_at,
            home_lat=home_lat,
            home_lon=home_lon,
            home_alt_amsl=home_alt_amsl,
        )
        async with self._sessions.begin() as session:
            session.add(row)
            await session.flush()
            return int(row.id)

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
        async with self._sessions.begin() as session:
            row = await session.get(FlightRow, end.flight_id)
            if row is None:
                raise NotFound(f"no flight with id {end.flight_id}", id=end.flight_id)
            row.ended_at = end.ended_at
            row.duration_s = end.duration_s
            row.distance_m = end.distance_m
            row.max_alt_rel_m = end.max_alt_rel_m
            row.battery_used_pct = end.battery_used_pct
        return FlightRecord.model_validate(row)

    async def list_open_flights(self, vehicle_id: str | None = None) -> list[FlightRecord]:
        query = select(FlightRow).where(FlightRow.ended_at.is_(None))
        if vehicle_id is not None:
            query = query.where(FlightRow.vehicle_id == vehicle_id)
        async with self._sessions() as session:
            rows = (await session.scalars(query.order_by(FlightRow.started_at))).all()
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
        async with self._sessions.begin() as session:
            await session.execute(insert(TrackSampleRow), rows)
        return len(rows)

    async def add_status_texts(self, items: Sequence[StatusTextIn]) -> int:
        if not items:
            return 0
        data: JsonObject = {"rows": [i.model_dump(mode="json") for i in items]}
        kept = await self._kept(f"{len(items)} status texts", "status_texts", data, self._write_status_texts)
        return kept or 0

    async def _write_status_texts(self, data: JsonObject) -> int:
        rows = [StatusTextIn.model_validate(r).model_dump() for r in _rows(data)]
        async with self._sessions.begin() as session:
            await session.execute(insert(StatusTextRow), rows)
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
            conditions.append(FlightRow.vehicle_id == vehicle_id)
        if since is not None:
            conditions.append(or_(FlightRow.ended_at.is_(None), FlightRow.ended_at >= since))
        if until is not None:
            conditions.append(FlightRow.started_at <= until)
        query = select(FlightRow).where(*conditions)
        count = select(func.count()).select_from(FlightRow).where(*conditions)
        async with self._sessions() as session:
            total = int((await session.execute(count)).scalar_one())
            rows = (
                await session.scalars(
                    query.order_by(FlightRow.started_at.desc(), FlightRow.id.desc())
                    .limit(limit)
                    .offset(offset)
                )
            ).all()
            return [FlightRecord.model_validate(r) for r in rows], total

    async def get_flight(self, flight_id: int) -> FlightRecord | None:
        async with self._sessions() as session:
            row = await session.get(FlightRow, flight_id)
            return None if row is None else FlightRecord.model_validate(row)

    async def get_track(self, flight_id: int) -> list[TrackSample]:
        columns = [getattr(TrackSampleRow, name) for name in TrackSample.model_fields]
        query = (
            select(*columns)
            .where(TrackSampleRow.flight_id == flight_id)
            .order_by(TrackSampleRow.t, TrackSampleRow.id)
        )
        async with self._sessions() as session:
            rows = (await session.execute(query)).all()
        # Plain rows, no ORM objects; validated when written, so built without re-validation (long tracks).
        return [TrackSample.model_construct(**row._asdict()) for row in rows]

    async def list_status_texts(
        self, vehicle_id: str, limit: int = 100, since: datetime | None = None
    ) -> list[StatusTextRecord]:
        """The newest ``limit`` status texts of a vehicle, oldest first."""
        query = select(StatusTextRow).where(StatusTextRow.vehicle_id == vehicle_id)
        if since is not None:
            query = query.where(StatusTextRow.t >= since)
        query = query.order_by(StatusTextRow.t.desc(), StatusTextRow.id.desc()).limit(limit)
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [StatusTextRecord.model_validate(r) for r in reversed(rows)]

    async def list_flight_status_texts(self, flight_id: int, limit: int = 500) -> list[StatusTextRecord]:
        """The status texts received during a flight, oldest first (at most ``limit``, the first ones)."""
        query = (
            select(StatusTextRow)
            .where(StatusTextRow.flight_id == flight_id)
            .order_by(StatusTextRow.t, StatusTextRow.id)
            .limit(limit)
        )
        async with self._sessions() as session:
            rows = (await session.scalars(query)).all()
            return [StatusTextRecord.model_validate(r) for r in rows]
