"""Persistence and REST figures: track-sample insert rates by batch size, audit inserts, and REST latency
for flight listing and a one-hour track as GeoJSON (in-process ASGI, SQLite in WAL mode on a temp file).

Usage: python bench/store_rest.py
"""

from __future__ import annotations

import asyncio
import logging
import statistics
import sys
import tempfile
import time
from datetime import UTC, datetime, timedelta
from pathlib import Path

import httpx

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from gateway.app import create_app  # noqa: E402
from gateway.config import Settings  # noqa: E402
from gateway.registry.store import AuditEntry, Store, TrackSample  # noqa: E402

T0 = datetime(2026, 1, 1, tzinfo=UTC)


def samples(flight_id: int, n: int, start: datetime) -> list[TrackSample]:
    return [
        TrackSample(
            flight_id=flight_id,
            t=start + timedelta(seconds=i),
            lat=47.0 + i * 1e-6,
            lon=8.0,
            alt_rel_m=10.0,
            heading_deg=90.0,
            ground_speed_mps=5.0,
            battery_pct=100 - i / 100,
        )
        for i in range(n)
    ]


async def store_figures(url: str) -> None:
    store = await Store.open(url)
    try:
        flight = await store.open_flight("bench", T0)
        for batch in (1, 5, 50, 500):
            n = 500 if batch == 1 else 5000
            rows = samples(flight, n, T0)
            started = time.perf_counter()
            for i in range(0, n, batch):
                await store.add_track_samples(rows[i : i + batch])
            elapsed = time.perf_counter() - started
            per_batch_ms = elapsed / (n / batch) * 1000
            print(
                f"track samples, batch {batch:4d}: {n / elapsed:8.0f} samples/s ({per_batch_ms:.2f} ms/batch)"
            )
        n = 500
        started = time.perf_counter()
        for i in range(n):
            await store.add_audit(
                AuditEntry(source="mcp", action="go_to_location", arguments={"i": i}, outcome="ok")
            )
        print(f"audit rows, one transaction each: {n / (time.perf_counter() - started):8.0f} rows/s")
    finally:
        await store.close()


async def rest_figures(url: str) -> None:
    store = await Store.open(url)
    hour_flight = await store.open_flight("alpha", T0)
    await store.add_track_samples(samples(hour_flight, 3600, T0))
    await store.close_flight(hour_flight, T0 + timedelta(hours=1), 3600, 1000, 10, 20)
    for i in range(1000):
        fid = await store.open_flight("bravo" if i % 2 else "charlie", T0 + timedelta(hours=i + 2))
        await store.close_flight(fid, T0 + timedelta(hours=i + 2, minutes=5), 300, 100, 10, 2)
    await store.close()

    app = create_app(Settings(database_url=url, log_level="WARNING"))
    async with app.router.lifespan_context(app):
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as client:
            paths = [
                "/api/v1/flights?vehicle_id=bravo&limit=50",
                f"/api/v1/flights/{hour_flight}/track.geojson",  # 3600 points
                "/api/v1/audit?limit=100",
            ]
            for path in paths:
                times = []
                for _ in range(30):
                    started = time.perf_counter()
                    response = await client.get(path)
                    times.append((time.perf_counter() - started) * 1000)
                    response.raise_for_status()
                times.sort()
                p95 = times[int(len(times) * 0.95) - 1]
                print(f"GET {path}: p50 {statistics.median(times):.1f} ms, p95 {p95:.1f} ms")


async def main() -> None:
    logging.disable(logging.INFO)  # request logs would drown the figures
    with tempfile.TemporaryDirectory() as tmp:
        await store_figures(f"sqlite+aiosqlite:///{tmp}/store.db")
        await rest_figures(f"sqlite+aiosqlite:///{tmp}/rest.db")


if __name__ == "__main__":
    asyncio.run(main())
