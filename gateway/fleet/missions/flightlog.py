"""Flight log: an arm -> disarm period is a flight, with a 1 Hz track and the status texts received.

Everything is read from the vehicle's telemetry cache (no extra subscriptions) and written through the
Store in batches every ``track_flush_s``. A flight left open by a gateway that died is closed at the
next start from its recorded track. While the vehicle's link is relayed, the frames it sends during a
flight are written as received to the flight's raw log (`gateway.fleet.missions.raw_tlog`).
"""

from __future__ import annotations

import asyncio
import itertools
import logging
from collections.abc import Callable
from datetime import UTC, datetime

from gateway.config import Settings
from gateway.fleet import geo
from gateway.fleet.missions.raw_tlog import RawTlog, tlog_folder
from gateway.link.session import Link
from gateway.link.telemetry import StatusTextValue
from gateway.registry.store import StatusTextIn, Store, TrackSample
from gateway.util import ticks
from gateway.util.tasks import cancel_and_wait

log = logging.getLogger("gateway.flightlog")


def _utc(epoch_s: float | None = None) -> datetime:
    return datetime.now(UTC) if epoch_s is None else datetime.fromtimestamp(epoch_s, UTC)


class _Flight:
    def __init__(self, flight_id: int, started_at: datetime, battery_start: float | None) -> None:
        self.id = flight_id
        self.started_at = started_at
        self.battery_start = battery_start
        self.battery_last = battery_start
        self.distance_m = 0.0
        self.max_alt_rel_m: float | None = None
        self.last_fix: tuple[float, float] | None = None

    def add(self, lat: float, lon: float, alt_rel_m: float, battery: float | None) -> None:
        if self.last_fix is not None:
            self.distance_m += geo.horizontal_distance_m(self.last_fix[0], self.last_fix[1], lat, lon)
        self.last_fix = (lat, lon)
        self.max_alt_rel_m = alt_rel_m if self.max_alt_rel_m is None else max(self.max_alt_rel_m, alt_rel_m)
        if battery is not None:
            self.battery_last = battery
            if self.battery_start is None:
                self.battery_start = battery

    @property
    def battery_used(self) -> float | None:
        if self.battery_start is None or self.battery_last is None:
            return None
        return max(0.0, self.battery_start - self.battery_last)


#: MAVSDK's GpsInfo.FixType names -> MAVLink GPS_FIX_TYPE (what GPS_RAW_INT carries)
GPS_FIX_TYPES = {
    "NO_GPS": 0,
    "NO_FIX": 1,
    "FIX_2D": 2,
    "FIX_3D": 3,
    "FIX_DGPS": 4,
    "RTK_FLOAT": 5,
    "RTK_FIXED": 6,
}


class FlightRecorder:
    """Records the flights of one vehicle while it is connected."""

    def __init__(
        self,
        link: Link,
        heartbeat_state: Callable[[], tuple[int, int] | None],
        store: Store,
        settings: Settings,
    ) -> None:
        """``link``: the vehicle's (its id, its telemetry cache, the bytes it relays);
        ``heartbeat_state``: (MAV_TYPE, custom mode) of the autopilot's last HEARTBEAT, None while there
        is none fresh."""
        self.link = link
        self._heartbeat_state = heartbeat_state
        self.store = store
        self.settings = settings
        self.flight: _Flight | None = None
        self._track: list[TrackSample] = []
        self._texts: list[StatusTextIn] = []
        self._due = asyncio.Event()  # set by the shared ticks when a recorder between flights has work
        self._next_flush = 0.0  # event loop time
        self._task: asyncio.Task[None] | None = None
        folder = tlog_folder(settings, store.url)
        self.raw: RawTlog | None = None
        if folder is not None:
            self.raw = RawTlog(folder, link.id, settings.flight_tlog_max_mib * 1024 * 1024)

    async def start(self) -> None:
        await self._close_leftovers()
        self.link.telemetry.on_status_text(self._on_status_text)
        if self.raw is not None:
            self.link.vehicle_bytes = self.raw.received
        self._task = asyncio.create_task(self._run(), name=f"flightlog-{self.link.id}")

    async def stop(self) -> None:
        """Stop recording: close a flight in progress (the gateway no longer watches it) and flush."""
        self.link.telemetry.remove_status_listener(self._on_status_text)
        if self.raw is not None and self.link.vehicle_bytes == self.raw.received:
            self.link.vehicle_bytes = None
        await cancel_and_wait(self._task)
        self._task = None
        if self.flight is not None:
            await self._close(_utc(), "recording stopped")
        await self.flush()

    def _on_status_text(self, item: StatusTextValue) -> None:
        if self._task is None:
            return
        self._texts.append(
            StatusTextIn(
                vehicle_id=self.link.id,
                flight_id=self.flight.id if self.flight else None,
                t=_utc(item.t),
                severity=item.severity,
                text=item.text,
            )
        )

    async def _close_leftovers(self) -> None:
        """Flights a previous gateway left open: end them at their last track sample."""
        for flight in await self.store.list_open_flights(self.link.id):
            track = await self.store.get_track(flight.id)
            ended = track[-1].t if track else flight.started_at
            distance = 0.0
            for a, b in itertools.pairwise(track):
                distance += geo.horizontal_distance_m(a.lat, a.lon, b.lat, b.lon)
            alts = [s.alt_rel_m for s in track if s.alt_rel_m is not None]
            batteries = [s.battery_pct for s in track if s.battery_pct is not None]
            used = max(0.0, batteries[0] - batteries[-1]) if batteries else None
            await self.store.close_flight(
                flight.id,
                ended_at=ended,
                duration_s=max(0.0, (_aware(ended) - _aware(flight.started_at)).total_seconds()),
                distance_m=distance,
                max_alt_rel_m=max(alts) if alts else None,
                battery_used_pct=used,
            )
            log.info("%s: closed flight %d left open by a previous run", self.link.id, flight.id)

    async def _run(self) -> None:
        """A step every ``track_sample_hz`` while a flight is open; between flights the recorder waits,
        and the ticks every recorder of the event loop shares (`gateway.util.ticks`) wake it when there
        is something to do (``_due_at_rest``): one timer for the fleet at rest, not one per drone."""
        period = 1.0 / self.settings.track_sample_hz
        loop = asyncio.get_running_loop()
        self._next_flush = loop.time() + self.settings.track_flush_s
        tick = ticks.every(period, self._due_at_rest)
        try:
            while True:
                try:
                    await self._tick()
                    if loop.time() >= self._next_flush:
                        self._next_flush = loop.time() + self.settings.track_flush_s
                        await self.flush()
                except asyncio.CancelledError:
                    raise
                except Exception:  # a database hiccup must not end flight recording
                    log.exception("%s: flight log step failed", self.link.id)
                if self.flight is None:
                    self._due.clear()
                    await self._due.wait()
                else:
                    await asyncio.sleep(period)
        finally:
            tick.cancel()

    def _due_at_rest(self) -> None:
        """At each shared tick: wake the recorder waiting between flights when the drone is armed (a
        flight opens) or status texts wait to be written."""
        if self.flight is not None:
            return  # the recorder steps by itself in flight
        texts_due = bool(self._texts) and asyncio.get_running_loop().time() >= self._next_flush
        if texts_due or self.link.telemetry.fresh("armed") is True:
            self._due.set()

    async def _tick(self) -> None:
        cache = self.link.telemetry
        armed = cache.fresh("armed")
        battery = cache.fresh("battery")
        battery_pct = battery.remaining_pct if battery is not None else None
        if armed is True and self.flight is None:
            home = cache.fresh("home", max_age_s=3600.0)
            started = _utc()
            flight_id = await self.store.open_flight(
                self.link.id,
                started,
                home.lat_deg if home else None,
                home.lon_deg if home else None,
                home.abs_alt_m if home else None,
            )
            self.flight = _Flight(flight_id, started, battery_pct)
            if self.raw is not None:
                try:
                    self.raw.open(flight_id)
                except OSError as exc:
                    log.error("%s: the raw MAVLink log cannot be written: %s", self.link.id, exc)
            log.info("%s: armed, flight %d started", self.link.id, flight_id)
        elif armed is False and self.flight is not None:
            await self._close(_utc(), "disarmed")
            return
        if self.flight is None or armed is not True:
            return
        pos = cache.fresh("position")
        if pos is None:
            return
        velocity = cache.fresh("velocity_ned")
        heading = cache.fresh("heading_deg")
        heartbeat = self._heartbeat_state()
        gps = cache.fresh("gps_info")
        self.flight.add(pos.lat_deg, pos.lon_deg, pos.rel_alt_m, battery_pct)
        self._track.append(
            TrackSample(
                flight_id=self.flight.id,
                t=_utc(),
                lat=pos.lat_deg,
                lon=pos.lon_deg,
                alt_rel_m=pos.rel_alt_m,
                heading_deg=heading,
                ground_speed_mps=velocity.ground_speed_mps if velocity is not None else None,
                battery_pct=battery_pct,
                mav_type=heartbeat[0] if heartbeat is not None else None,
                custom_mode=heartbeat[1] if heartbeat is not None else None,
                gps_fix_type=GPS_FIX_TYPES.get(gps.fix_type) if gps is not None else None,
                satellites=min(255, max(0, gps.num_satellites)) if gps is not None else None,
            )
        )

    async def _close(self, ended: datetime, why: str) -> None:
        flight, self.flight = self.flight, None
        if flight is None:
            return
        if self.raw is not None:
            self.raw.close()
        await self.flush()
        await self.store.close_flight(
            flight.id,
            ended_at=ended,
            duration_s=(ended - flight.started_at).total_seconds(),
            distance_m=round(flight.distance_m, 2),
            max_alt_rel_m=flight.max_alt_rel_m,
            battery_used_pct=flight.battery_used,
        )
        log.info(
            "%s: flight %d ended (%s): %.0f m flown, max %.1f m above home",
            self.link.id,
            flight.id,
            why,
            flight.distance_m,
            flight.max_alt_rel_m or 0.0,
        )

    async def flush(self) -> None:
        """Write the pending track samples and status texts, one transaction each."""
        if self.raw is not None:
            self.raw.flush()
        track, self._track = self._track, []
        texts, self._texts = self._texts, []
        if track:
            await self.store.add_track_samples(track)
        if texts:
            await self.store.add_status_texts(texts)


def _aware(value: datetime) -> datetime:
    return value if value.tzinfo is not None else value.replace(tzinfo=UTC)
