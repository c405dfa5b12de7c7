"""Waiting on a real vehicle's state with a deadline, failing with what it said."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx
from pymavlink import mavutil

from gateway.fleet.vehicles.vehicle import Vehicle
from tests.helpers.timing import scaled


async def until(what: str, check: Callable[[], object], within_s: float, v: Vehicle) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    while not check():
        if loop.time() > deadline:
            texts = [f"{t.severity}: {t.text}" for t in list(v.telemetry.status_texts)[-8:]]
            raise AssertionError(
                f"{v.id}: {what} not reached within {scaled(within_s):g} s; {v.status()}; {texts}"
            )
        await asyncio.sleep(0.2)


async def closed_flight(http: httpx.AsyncClient, drone_id: str, within_s: float) -> dict[str, Any]:
    """The drone's newest flight once it has ended (landed and disarmed), from REST."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    while True:
        flights = (await http.get("/flights", params={"vehicle_id": drone_id})).json()["items"]
        if flights and flights[0]["ended_at"] is not None:
            return dict(flights[0])
        assert loop.time() < deadline, f"the flight was not closed: {flights}"
        await asyncio.sleep(0.2)  # a cheap REST read; the flight closes as the drone disarms


def tlog_points(path: Path, dialect: str) -> list[tuple[float, float, float]]:
    """(lat, lon, metres above home) of every GLOBAL_POSITION_INT in a .tlog, as pymavlink reads it."""
    log = mavutil.mavlink_connection(str(path), dialect=dialect)
    points = []
    while (msg := log.recv_match(type="GLOBAL_POSITION_INT")) is not None:
        points.append((msg.lat / 1e7, msg.lon / 1e7, msg.relative_alt / 1000))
    return points
