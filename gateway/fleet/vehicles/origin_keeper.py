"""Keeps a vehicle's origin (`gateway.fleet.policy.origin`): loads it from the registry when the vehicle
connects, records the first home the vehicle reports when it has none, and moves it when an operator
says so. The autopilot's later homes (ArduPilot sets one at every arming) never move it."""

from __future__ import annotations

import asyncio
import logging

from gateway.fleet.policy.origin import Origin, checked_point
from gateway.link.telemetry import TelemetryCache
from gateway.registry.records import utcnow
from gateway.registry.store import Store
from gateway.util.tasks import cancel_and_wait

log = logging.getLogger(__name__)

WATCH_PERIOD_S = 0.5


class OriginKeeper:
    """The origin of one vehicle, in memory and in the registry."""

    def __init__(self, vehicle_id: str, telemetry: TelemetryCache, store: Store | None) -> None:
        self.vehicle_id = vehicle_id
        self.telemetry = telemetry
        self.store = store
        self.origin: Origin | None = None
        self._loaded = store is None
        self._stored = store is None
        self._task: asyncio.Task[None] | None = None

    async def start(self) -> None:
        """Load the stored origin (once), then watch for the first home while there is none."""
        await self._load()
        if self._task is None or self._task.done():
            self._task = asyncio.create_task(self._watch(), name=f"origin-{self.vehicle_id}")

    async def stop(self) -> None:
        await cancel_and_wait(self._task)
        self._task = None

    def current(self) -> Origin | None:
        """The origin; the vehicle's first fresh home becomes it when it has none yet (recorded in the
        registry by the watch)."""
        if self.origin is None and self._loaded:
            home = self.telemetry.fresh("home")
            if home is not None:
                self.origin = Origin(
                    self.vehicle_id,
                    float(home.lat_deg),
                    float(home.lon_deg),
                    float(home.abs_alt_m),
                    "first_home",
                    "autopilot",
                    utcnow(),
                )
                log.info(
                    "%s: origin set to its first home %.7f, %.7f",
                    self.vehicle_id,
                    self.origin.lat,
                    self.origin.lon,
                )
        return self.origin

    async def move(self, lat: object, lon: object, alt_amsl_m: object, by: str) -> Origin:
        """An operator's new origin (checked: InvalidArgument naming the argument), stored at once."""
        point = checked_point(lat, lon, alt_amsl_m)
        origin = Origin(self.vehicle_id, *point, "operator", by, utcnow())
        if self.store is not None:
            origin = await self.store.save_origin(origin)
            self._stored = True
        self.origin = origin
        self._loaded = True
        return origin

    async def _load(self) -> None:
        if self._loaded or self.store is None:
            return
        try:
            stored = await self.store.get_origin(self.vehicle_id)
        except Exception:
            log.exception("%s: the stored origin could not be read; trying again", self.vehicle_id)
            return
        self._loaded = True
        if stored is not None:
            self.origin, self._stored = stored, True

    async def _watch(self) -> None:
        while not self._stored:
            await self._load()
            origin = self.current()
            if origin is not None and self.store is not None:
                try:
                    kept = await self.store.save_origin(origin, only_if_absent=True)
                except Exception:
                    log.exception("%s: the origin could not be stored; trying again", self.vehicle_id)
                else:
                    self.origin, self._stored = kept, True
                    return
            await asyncio.sleep(WATCH_PERIOD_S)
