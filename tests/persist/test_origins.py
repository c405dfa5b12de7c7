"""A vehicle's origin in the registry and its keeper: the first home it reported, kept across restarts,
never moved by the homes the autopilot sets later (ArduPilot sets one at every arming), moved by an
operator. On a real SQLite file and on PostgreSQL."""

from __future__ import annotations

import asyncio

import pytest

from gateway.errors import InvalidArgument
from gateway.fleet.vehicles.origin_keeper import OriginKeeper
from gateway.link.telemetry import PositionValue, TelemetryCache
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.helpers.timing import scaled

FIRST = (-35.363261, 149.165230, 584.0)
FAR = (-35.354712, 149.165230, 590.0)  # about 950 m north


def _home(cache: TelemetryCache, point: tuple[float, float, float]) -> None:
    cache.put("home", PositionValue(point[0], point[1], point[2], 0.0))


async def _stored(store: Store, vehicle_id: str) -> None:
    deadline = asyncio.get_running_loop().time() + scaled(10)
    while await store.get_origin(vehicle_id) is None:
        assert asyncio.get_running_loop().time() < deadline, "the origin was not stored"
        await asyncio.sleep(0.05)


async def test_the_first_home_is_the_origin_and_later_homes_do_not_move_it(db_url: str) -> None:
    store = await Store.open(db_url)
    try:
        await store.add_vehicle(VehicleSpec(id="d1", url="udpin://127.0.0.1:14540"))
        cache = TelemetryCache()
        keeper = OriginKeeper("d1", cache, store)
        await keeper.start()
        assert keeper.current() is None  # no home yet: no origin
        _home(cache, FIRST)
        await _stored(store, "d1")
        _home(cache, FAR)  # the autopilot set home again at arming, 950 m out
        origin = keeper.current()
        assert origin is not None and origin.point == FIRST and origin.source == "first_home"
        await keeper.stop()

        # a restart: the stored origin holds, whatever home the autopilot reports now
        again = OriginKeeper("d1", cache, store)
        await again.start()
        assert again.current() is not None and again.current().point == FIRST  # type: ignore[union-attr]
        moved = await again.move(FAR[0], FAR[1], FAR[2], "operator-1")
        assert moved.source == "operator" and moved.set_by == "operator-1"
        stored = await store.get_origin("d1")
        assert stored is not None and stored.point == FAR and stored.source == "operator"
        with pytest.raises(InvalidArgument, match="origin lat must be a number; got '10'"):
            await again.move("10", 0, 0, "operator-1")
        with pytest.raises(InvalidArgument, match=r"alt_amsl_m must be -500\.\.9000 m"):
            await again.move(0.0, 0.0, 1e6, "operator-1")
        assert (await store.get_origin("d1")).point == FAR  # type: ignore[union-attr]
        await again.stop()
        # the first home is stored once: a second keeper's own first home does not replace it
        kept = await store.save_origin(
            stored.__class__("d1", *FIRST, "first_home", "x", stored.set_at), only_if_absent=True
        )
        assert kept.point == FAR
        await store.remove_vehicle("d1")
        assert await store.get_origin("d1") is None  # removed with the vehicle
    finally:
        await store.close()
