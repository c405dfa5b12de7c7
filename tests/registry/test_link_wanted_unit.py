"""A link asked to connect reads connecting at once, not registered, until its sidecar runs: a cluster node
that adopts a drone reads the stored origin first, and a fleet stop in that window skipped the drone as
"not connected (registered)" instead of sending its stop once the drone was heard."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from gateway.config import Settings
from gateway.fleet.vehicles.vehicle import Vehicle
from gateway.link.contract import ConnectionState
from gateway.link.session import Link, LinkHooks
from gateway.registry.spec import VehicleSpec

SPEC = VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760")


def _link() -> Link:
    return Link(SPEC, Settings(_env_file=None), LinkHooks(rules_for=lambda _autopilot: None))


def test_wanted_reads_connecting_and_unwanted_registered_again() -> None:
    lk = _link()
    assert lk.state == ConnectionState.REGISTERED
    lk.want()
    assert lk.state == ConnectionState.CONNECTING
    lk.unwant()
    assert lk.state == ConnectionState.REGISTERED


async def test_a_connect_that_fails_before_its_sidecar_leaves_it_registered(monkeypatch: Any) -> None:
    lk = _link()

    async def broken() -> None:
        raise OSError("the drone's device is gone")

    monkeypatch.setattr(lk, "_start_sidecar", broken)
    with pytest.raises(OSError):
        await lk.connect()
    assert lk.state == ConnectionState.REGISTERED


async def test_a_disconnect_leaves_it_registered() -> None:
    lk = _link()
    lk.want()
    await lk.disconnect()
    assert lk.state == ConnectionState.REGISTERED


async def test_a_vehicle_reads_connecting_while_its_stored_origin_is_read(monkeypatch: Any) -> None:
    vehicle = Vehicle(SPEC, Settings(_env_file=None))
    reading = asyncio.Event()

    async def slow_origin() -> None:
        reading.set()
        await asyncio.Event().wait()  # a database that does not answer

    monkeypatch.setattr(vehicle.origins, "start", slow_origin)
    connecting = asyncio.create_task(vehicle.connect())
    await asyncio.wait_for(reading.wait(), 10)
    assert vehicle.state == ConnectionState.CONNECTING
    connecting.cancel()
    with pytest.raises(asyncio.CancelledError):
        await connecting
    assert vehicle.state == ConnectionState.REGISTERED
