"""The store's table of registered vehicles."""

from __future__ import annotations

from typing import Unpack

from sqlalchemy import delete, select
from sqlalchemy.exc import IntegrityError

from gateway.errors import DuplicateVehicle, InvalidArgument, NotFound
from gateway.registry.models import VehicleRow
from gateway.registry.records import (
    VehicleRecord,
    utcnow,
)
from gateway.registry.spec import VehicleChanges, VehicleSpec
from gateway.registry.store_core import StoreCore, rowcount


class VehicleTable(StoreCore):
    """The registered vehicles: add, update, remove, read."""

    async def add_vehicle(self, spec: VehicleSpec, auto_connect: bool = True) -> VehicleRecord:
        spec = VehicleSpec.model_validate(spec.model_dump())
        now = utcnow()
        row = VehicleRow(
            id=spec.id,
            url=spec.url,
            name=spec.name,
            tags=list(spec.tags),
            expected_sysid=spec.expected_sysid,
            node_tag=spec.node_tag,
            gcs_endpoints=list(spec.gcs_endpoints),
            auto_connect=auto_connect,
            created_at=now,
            updated_at=now,
        )
        try:
            async with self._sessions.begin() as session:
                if await session.get(VehicleRow, spec.id) is not None:
                    raise DuplicateVehicle(f"a drone with id '{spec.id}' is already registered", id=spec.id)
                session.add(row)
        except IntegrityError as exc:
            raise DuplicateVehicle(f"a drone with id '{spec.id}' is already registered", id=spec.id) from exc
        return VehicleRecord.model_validate(row)

    _UPDATABLE = frozenset(
        {"name", "tags", "expected_sysid", "node_tag", "url", "gcs_endpoints", "auto_connect"}
    )

    async def update_vehicle(self, vehicle_id: str, **changes: Unpack[VehicleChanges]) -> VehicleRecord:
        unknown = sorted(set(changes) - self._UPDATABLE)
        if unknown:
            raise InvalidArgument(
                f"cannot update field(s) {unknown}; updatable: {sorted(self._UPDATABLE)}", fields=unknown
            )
        async with self._sessions.begin() as session:
            row = await session.get(VehicleRow, vehicle_id)
            if row is None:
                raise NotFound(f"no drone with id '{vehicle_id}' is registered", id=vehicle_id)
            merged = VehicleRecord.model_validate(row).model_dump()
            merged.update(changes)
            if not isinstance(merged["auto_connect"], bool):
                raise InvalidArgument("auto_connect must be true or false", field="auto_connect")
            auto_connect = merged.pop("auto_connect")
            for key in ("created_at", "updated_at"):
                merged.pop(key)
            try:
                spec = VehicleSpec.model_validate(merged)
            except ValueError as exc:
                raise InvalidArgument(f"invalid vehicle update: {exc}", fields=sorted(changes)) from exc
            row.url = spec.url
            row.name = spec.name
            row.tags = list(spec.tags)
            row.expected_sysid = spec.expected_sysid
            row.node_tag = spec.node_tag
            row.gcs_endpoints = list(spec.gcs_endpoints)
            row.auto_connect = auto_connect
            row.updated_at = utcnow()
        return VehicleRecord.model_validate(row)

    async def remove_vehicle(self, vehicle_id: str) -> None:
        async with self._sessions.begin() as session:
            result = await session.execute(delete(VehicleRow).where(VehicleRow.id == vehicle_id))
            if rowcount(result) == 0:
                raise NotFound(f"no drone with id '{vehicle_id}' is registered", id=vehicle_id)

    async def get_vehicle(self, vehicle_id: str) -> VehicleRecord | None:
        async with self._sessions() as session:
            row = await session.get(VehicleRow, vehicle_id)
            return None if row is None else VehicleRecord.model_validate(row)

    async def list_vehicles(self) -> list[VehicleRecord]:
        async with self._sessions() as session:
            rows = (await session.scalars(select(VehicleRow).order_by(VehicleRow.id))).all()
            return [VehicleRecord.model_validate(r) for r in rows]
