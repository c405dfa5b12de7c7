"""The store's kept ``.plan`` extras: per vehicle, the rally points and geofence circles of its last
``.plan`` (`gateway.fleet.missions.plan_extras`), kept across restarts and seen by every node."""

from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime

from gateway.registry.models import PlanExtrasRow
from gateway.registry.records import utcnow
from gateway.registry.store_core import StoreCore

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
        async with self._sessions() as session:
            row = await session.get(PlanExtrasRow, vehicle_id)
            if row is None:
                return None
            return KeptPlanExtras(
                [_point(p) for p in row.rally],
                {name: _point(c) for name, c in row.circles.items()},
                row.set_by,
                row.set_at,
            )

    async def save_plan_extras(self, vehicle_id: str, extras: KeptPlanExtras, set_by: str) -> None:
        async with self._sessions.begin() as session:
            row = await session.get(PlanExtrasRow, vehicle_id)
            if row is None:
                row = PlanExtrasRow(vehicle_id=vehicle_id)
                session.add(row)
            row.rally = [list(p) for p in extras.rally]
            row.circles = {name: list(c) for name, c in extras.circles.items()}
            row.set_by, row.set_at = set_by[:200], utcnow()
