"""A drone's last .plan extras in the store: its rally points and the circles its geofence was drawn as,
kept across a restart (a new store over the same database) and gone with the drone. On a real SQLite
file and on PostgreSQL."""

from __future__ import annotations

from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from gateway.registry.store_plans import KeptPlanExtras

RALLY = [(-35.362261, 149.166230, 30.0), (-35.364261, 149.165230, 25.0)]
CIRCLES = {"d1-plan-circle-1": (-35.364761, 149.165230, 40.0)}


async def test_rally_points_and_circles_outlive_a_restart_and_go_with_the_drone(db_url: str) -> None:
    store = await Store.open(db_url)
    try:
        await store.add_vehicle(VehicleSpec(id="d1", url="udpin://127.0.0.1:14540"))
        assert await store.get_plan_extras("d1") is None
        await store.save_plan_extras("d1", KeptPlanExtras(RALLY, CIRCLES), "operator-1")
    finally:
        await store.close()

    again = await Store.open(db_url)  # a restart
    try:
        kept = await again.get_plan_extras("d1")
        assert kept is not None
        assert kept.rally == RALLY and kept.circles == CIRCLES and kept.set_by == "operator-1"
        await again.save_plan_extras("d1", KeptPlanExtras(RALLY[:1], {}), "operator-2")  # replaced whole
        kept = await again.get_plan_extras("d1")
        assert kept is not None and kept.rally == RALLY[:1] and kept.circles == {}
        await again.remove_vehicle("d1")
        assert await again.get_plan_extras("d1") is None
    finally:
        await again.close()
