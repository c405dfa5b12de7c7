"""The store's table of registered vehicles."""

from __future__ import annotations

from typing import Unpack

from sqlalchemy import delete, insert, select, update
from sqlalchemy.exc import IntegrityError

from gateway.errors import DuplicateVehicle, InvalidArgument, NotFound
from gateway.registry.models import vehicles
from gateway.registry.records import (
    VehicleRecord,
    utcnow,
)
from gateway.registry.spec import VehicleChanges, VehicleSpec
from gateway.registry.store_core import StoreCore, row_by_key, rowcount


def _spec_values(spec: VehicleSpec) -> dict[str, object]:
    """The registration's fields (all but its id) as its row's values."""
    return {
        "url": spec.url,
        "name": spec.name,
        "node_tag": spec.node_tag,
        "tags": list(spec.tags),
        "gcs_endpoints": list(spec.gcs_endpoints),
        "expected_sysid": spec.expected_sysid,
    }


class VehicleTable(StoreCore):
    """The registered vehicles: add, update, remove, read."""

    async def add_vehicle(self, spec: VehicleSpec, auto_connect: bool = True) -> VehicleRecord:
        spec = VehicleSpec.model_validate(spec.model_dump())
        now = utcnow()
        values = {"id": spec.id, **_spec_values(spec), "auto_connect": auto_connect}
        values.update(created_at=now, updated_at=now)
        try:
            async with self.engine.begin() as conn:
                if await row_by_key(conn, vehicles, spec.id) is not None:
                    raise DuplicateVehicle(f"a drone with id '{spec.id}' is already registered", id=spec.id)
                await conn.execute(insert(vehicles).values(values))
        except IntegrityError as exc:
            raise DuplicateVehicle(f"a drone with id '{spec.id}' is already registered", id=spec.id) from exc
        return VehicleRecord.model_validate(values)

    _UPDATABLE = frozenset(
        {"name", "tags", "expected_sysid", "node_tag", "url", "gcs_endpoints", "auto_connect"}
    )

    async def update_vehicle(self, vehicle_id: str, **changes: Unpack[VehicleChanges]) -> VehicleRecord:
        unknown = sorted(set(changes) - self._UPDATABLE)
        if unknown:
            raise InvalidArgument(
                f"cannot update field(s) {unknown}; updatable: {sorted(self._UPDATABLE)}", fields=unknown
            )
        async with self.engine.begin() as conn:
            row = await row_by_key(conn, vehicles, vehicle_id)
            if row is None:
                raise NotFound(f"no drone with id '{vehicle_id}' is registered", id=vehicle_id)
            record = VehicleRecord.model_validate(row)
            merged = record.model_dump()
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
            values = {**_spec_values(spec), "auto_connect": auto_connect, "updated_at": utcnow()}
            await conn.execute(update(vehicles).where(vehicles.c.id == vehicle_id).values(values))
        return VehicleRecord.model_validate({**record.model_dump(), **values})

    async def remove_vehicle(self, vehicle_id: str) -> None:
        async with self.engine.begin() as conn:
            result = await conn.execute(delete(vehicles).where(vehicles.c.id == vehicle_id))
            if rowcount(result) == 0:
                raise NotFound(f"no drone with id '{vehicle_id}' is registered", id=vehicle_id)

    async def get_vehicle(self, vehicle_id: str) -> VehicleRecord | None:
        async with self.engine.connect() as conn:
            row = await row_by_key(conn, vehicles, vehicle_id)
        return None if row is None else VehicleRecord.model_validate(row)

    async def list_vehicles(self) -> list[VehicleRecord]:
        async with self.engine.connect() as conn:
            rows = (await conn.execute(select(vehicles).order_by(vehicles.c.id))).mappings().all()
        return [VehicleRecord.model_validate(r) for r in rows]
