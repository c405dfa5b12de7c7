"""The store's kept ``.plan`` extras: per vehicle, the rally points and geofence circles of its last
``.plan`` (`gateway.fleet.missions.plan_extras`), kept across restarts and seen by every node."""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime

from sqlalchemy import insert, update

from gateway.registry.models import vehicle_plan_extras
from gateway.registry.records import utcnow
from gateway.registry.store_core import StoreCore, row_by_key

Point = tuple[float, float, float]


@dataclass(frozen=True)
class KeptPlanExtras:
    """Rally points ([lat, lon, alt above home]) and circles ({zone name: (lat, lon, radius m)})."""

    rally: list[Point] = field(default_factory=list)
    circles: dict[str, Point] = field(default_factory=dict)
    set_by: str = ""
    set_at: datetime | None = None


def _point(values: list[float]) -> Point:
    return float(values[0]), float(values[1]), float(values[2])


class PlanExtrasTable(StoreCore):
    """One row of .plan extras per vehicle (gone with the vehicle)."""

    async def get_plan_extras(self, vehicle_id: str) -> KeptPlanExtras | None:
        async with self.engine.connect() as conn:
            row = await row_by_key(conn, vehicle_plan_extras, vehicle_id)
        if row is None:
            return None
        return KeptPlanExtras(
            [_point(p) for p in row["rally"]],
            {name: _point(c) for name, c in row["circles"].items()},
            row["set_by"],
            row["set_at"],
        )

    async def save_plan_extras(self, vehicle_id: str, extras: KeptPlanExtras, set_by: str) -> None:
        values = {
            "rally": [list(p) for p in extras.rally],
            "circles": {name: list(c) for name, c in extras.circles.items()},
            "set_by": set_by[:200],
            "set_at": utcnow(),
        }
        async with self.engine.begin() as conn:
            if await row_by_key(conn, vehicle_plan_extras, vehicle_id) is None:
                await conn.execute(insert(vehicle_plan_extras).values(vehicle_id=vehicle_id, **values))
            else:
                where = vehicle_plan_extras.c.vehicle_id == vehicle_id
                await conn.execute(update(vehicle_plan_extras).where(where).values(values))
