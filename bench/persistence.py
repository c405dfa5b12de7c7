"""Persistence: sustained track-sample write rate with 50 drones, and database size per drone-hour.

Uses the gateway's own ``Store`` (SQLAlchemy async + aiosqlite, WAL) on a fresh SQLite file, writing the
way the flight recorder does: one writer per drone, each sending its batch of ``track_sample_hz *
track_flush_s`` samples (default 1 Hz x 2 s = 2 samples) in one transaction.

1. Real cadence: 50 drones writing at the default rate (50 samples/s in 25 transactions/s) for a
   while: batch write latency p50/p99 and whether the writers keep up.
2. Capacity: the same 50 writers writing back to back: sustained samples/s and transactions/s, i.e.
   the headroom over the real cadence.
3. Size: full flights of one hour at 1 Hz (3,600 samples each, realistic values), WAL checkpointed,
   file size growth divided by drone-hours.
"""

from __future__ import annotations

import asyncio
import math
import random
import time
from datetime import UTC, datetime, timedelta
from pathlib import Path
from typing import Any

import common

DRONES = 50


async def open_store(path: Path) -> Any:
    from gateway.registry.spec import VehicleSpec
    from gateway.registry.store import Store

    store = await Store.open(f"sqlite+aiosqlite:///{path}")
    for i in range(DRONES):
        await store.add_vehicle(VehicleSpec(id=f"d{i + 1}", url=f"tcpout://127.0.0.1:{5760 + 10 * i}"))
    return store


class Track:
    """A plausible 1 Hz track: a random walk at ~8 m/s around a home, climbing to ~40 m."""

    def __init__(self, flight_id: int, seed: int) -> None:
        self.flight_id = flight_id
        self.rng = random.Random(seed)
        self.lat, self.lon, self.alt = 47.397742 + seed * 1e-4, 8.545594, 0.0
        self.heading = self.rng.uniform(0, 360)
        self.battery = 100.0
        self.t = datetime(2026, 1, 1, tzinfo=UTC)

    def next(self) -> Any:
        from gateway.registry.store import TrackSample

        self.heading = (self.heading + self.rng.gauss(0, 10)) % 360
        speed = max(0.0, 8 + self.rng.gauss(0, 1))
        self.lat += speed * math.cos(math.radians(self.heading)) / 111_320
        self.lon += (
            speed * math.sin(math.radians(self.heading)) / (111_320 * math.cos(math.radians(self.lat)))
        )
        self.alt = min(40.0, self.alt + 2.0) + self.rng.gauss(0, 0.2)
        self.battery = max(0.0, self.battery - 0.02)
        self.t += timedelta(seconds=1)
        return TrackSample(
            flight_id=self.flight_id,
            t=self.t,
            lat=self.lat,
            lon=self.lon,
            alt_rel_m=self.alt,
            heading_deg=self.heading,
            ground_speed_mps=speed,
            battery_pct=self.battery,
        )


async def flights(store: Any) -> list[Track]:
    start = datetime(2026, 1, 1, tzinfo=UTC)
    return [
        Track(await store.open_flight(f"d{i + 1}", start, 47.39, 8.54, 488.0), seed=i) for i in range(DRONES)
    ]


async def cadence(store: Any, tracks: list[Track], seconds: float, hz: float, flush_s: float) -> dict:
    """Each drone flushes ``hz * flush_s`` samples every ``flush_s``, phases spread over the period."""
    per_batch = max(1, round(hz * flush_s))
    lat: list[float] = []
    late = 0
    t_end = time.monotonic() + seconds

    async def writer(k: int, track: Track) -> None:
        nonlocal late
        await asyncio.sleep(flush_s * k / len(tracks))
        due = time.monotonic()
        while due < t_end:
            batch = [track.next() for _ in range(per_batch)]
            t0 = time.perf_counter()
            await store.add_track_samples(batch)
            lat.append(time.perf_counter() - t0)
            due += flush_s
            delay = due - time.monotonic()
            if delay < 0:
                late += 1
            await asyncio.sleep(max(0.0, delay))

    await asyncio.gather(*(writer(k, t) for k, t in enumerate(tracks)))
    nominal = len(tracks) * per_batch / flush_s  # what the drones produce; the writers keep up unless late
    return {"lat": lat, "late": late, "rate": nominal, "txn_s": nominal / per_batch, "per_batch": per_batch}


async def capacity(store: Any, tracks: list[Track], seconds: float, per_batch: int) -> dict:
    done = 0
    t_end = time.monotonic() + seconds
    lat: list[float] = []

    async def writer(track: Track) -> None:
        nonlocal done
        while time.monotonic() < t_end:
            batch = [track.next() for _ in range(per_batch)]
            t0 = time.perf_counter()
            await store.add_track_samples(batch)
            lat.append(time.perf_counter() - t0)
            done += 1

    t0 = time.monotonic()
    await asyncio.gather(*(writer(t) for t in tracks))
    elapsed = time.monotonic() - t0
    return {"txn_s": done / elapsed, "rate": done * per_batch / elapsed, "lat": lat}


def db_bytes(path: Path) -> int:
    return sum(p.stat().st_size for p in path.parent.glob(path.name + "*") if p.is_file())


async def checkpoint(store: Any) -> None:
    from sqlalchemy import text

    async with store.engine.begin() as conn:
        await conn.execute(text("PRAGMA wal_checkpoint(TRUNCATE)"))


async def size_per_hour(workdir: Path, drone_hours: int) -> dict:
    path = workdir / "size.db"
    store = await open_store(path)
    try:
        await checkpoint(store)
        base = db_bytes(path)
        start = datetime(2026, 1, 1, tzinfo=UTC)
        for h in range(drone_hours):
            fid = await store.open_flight(
                f"d{h % DRONES + 1}", start + timedelta(hours=h), 47.39, 8.54, 488.0
            )
            track = Track(fid, seed=h)
            for _ in range(3600 // 60):
                await store.add_track_samples([track.next() for _ in range(60)])
            await store.close_flight(fid, start + timedelta(hours=h + 1), 3600.0, 28_000.0, 40.0, 72.0)
        await checkpoint(store)
        grown = db_bytes(path) - base
    finally:
        await store.close()
    return {"drone_hours": drone_hours, "bytes": grown, "per_hour_mb": grown / drone_hours / 1e6}


async def run(full: bool) -> dict[str, Any]:
    from gateway.config import Settings

    settings = Settings(_env_file=None)
    secs = 30.0 if full else 10.0
    with common.workdir("persist") as wd:
        store = await open_store(wd / "rate.db")
        try:
            tracks = await flights(store)
            cad = await cadence(store, tracks, secs, settings.track_sample_hz, settings.track_flush_s)
            cap = await capacity(store, tracks, secs, cad["per_batch"])
            cap60 = await capacity(store, tracks, secs / 2, 60)
        finally:
            await store.close()
        size = await size_per_hour(wd, 50 if full else 5)
    return {
        "cadence": cad,
        "capacity": cap,
        "capacity60": cap60,
        "size": size,
        "hz": settings.track_sample_hz,
        "flush": settings.track_flush_s,
        "secs": secs,
    }


def render(r: dict[str, Any]) -> str:
    cad, cap, cap60, size = r["cadence"], r["capacity"], r["capacity60"], r["size"]
    cl, pl, p60 = common.pcts(cad["lat"]), common.pcts(cap["lat"]), common.pcts(cap60["lat"])
    return "\n".join(
        [
            f"The gateway's `Store` on SQLite (WAL), {DRONES} drones, one writer task per drone as the "
            f"flight recorder does ({r['hz']:g} Hz samples, flushed every {r['flush']:g} s = "
            f"{cad['per_batch']} samples per transaction); {r['secs']:g} s per measurement.",
            "",
            common.table(
                ["load", "samples/s", "transactions/s", "batch write p50 ms", "p99 ms", "late flushes"],
                [
                    [
                        f"real cadence ({DRONES} drones)",
                        f"{cad['rate']:.0f}",
                        f"{cad['txn_s']:.1f}",
                        common.ms(cl["p50"]),
                        common.ms(cl["p99"]),
                        cad["late"],
                    ],
                    [
                        f"capacity, {cad['per_batch']}-sample batches",
                        f"{cap['rate']:.0f}",
                        f"{cap['txn_s']:.0f}",
                        common.ms(pl["p50"]),
                        common.ms(pl["p99"]),
                        "",
                    ],
                    [
                        "capacity, 60-sample batches",
                        f"{cap60['rate']:.0f}",
                        f"{cap60['txn_s']:.0f}",
                        common.ms(p60["p50"]),
                        common.ms(p60["p99"]),
                        "",
                    ],
                ],
            ),
            "",
            f"Headroom: the store sustains {cap['rate'] / max(cad['rate'], 1e-9):.0f}x the track load of "
            f"{DRONES} drones at the recorder's batch size ({cap['rate'] / r['hz']:.0f} drones' worth at "
            f"{r['hz']:g} Hz).",
            "",
            f"Size: {size['drone_hours']} one-hour flights at 1 Hz (3,600 samples each) grew the database "
            f"(after a WAL checkpoint) by {size['bytes'] / 1e6:.2f} MB: **{size['per_hour_mb']:.2f} MB per "
            f"drone-hour** ({size['bytes'] / size['drone_hours'] / 3600:.0f} bytes per sample, indexes "
            "included).",
        ]
    )


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    args = p.parse_args()
    info = common.machine()
    r = asyncio.run(run(args.full))
    text = render(r)
    print(text)
    if args.write:
        common.write_section("persistence", "Persistence: track writes and database size", text, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
