"""Fake drones for *unit* tests of the fleet tools (in-process MCP client, no sidecars): the MCP area's
fake vehicles, spread out on a line, with hooks to hold a command until every drone has sent its own
(proof that dispatch is concurrent) and to make one drone's command fail."""

from __future__ import annotations

import asyncio
import time
from typing import Any

from gateway.config import Settings
from gateway.errors import CommandFailed
from gateway.fleet import geo
from gateway.fleet.safety import LockBook
from tests.mcp.fakes import HOME, FakeGateway, FakeRegistry, FakeVehicle, _pos


class SpreadVehicle(FakeVehicle):
    """A fake drone with its own home, ``east_m`` east of the shared one; optional command latency,
    a barrier every command waits at, and per-command failures."""

    def __init__(self, vid: str, east_m: float, speed: float = 150.0) -> None:
        super().__init__(vid, speed=speed)
        lat, lon = geo.offset_position(HOME[0], HOME[1], 0.0, east_m)
        self.home_ll = (lat, lon)
        self._set(position=_pos(lat, lon, 0.0), home=_pos(lat, lon, 0.0))
        self.latency_s = 0.0
        self.barrier: asyncio.Barrier | None = None
        self.fail: dict[str, str] = {}  # command name -> failure text
        self.log: list[tuple[float, str, tuple]] = []  # (monotonic time, command, args)

    async def _gate(self, name: str, *args: Any) -> None:
        self.log.append((time.monotonic(), name, args))
        if self.barrier is not None:
            await asyncio.wait_for(self.barrier.wait(), 5.0)
        if self.latency_s:
            await asyncio.sleep(self.latency_s)
        if name in self.fail:
            raise CommandFailed(f"{name} on drone '{self.id}' failed: {self.fail[name]}", vehicle_id=self.id)

    async def takeoff(self, alt: float) -> None:
        await self._gate("takeoff", alt)
        await super().takeoff(alt)

    async def goto(self, lat: float, lon: float, alt: float, yaw: float | None = None) -> None:
        await self._gate("goto", lat, lon, alt)
        await super().goto(lat, lon, alt, yaw)

    async def land(self) -> None:
        await self._gate("land")
        await super().land()

    async def hold(self) -> None:
        await self._gate("hold")
        await super().hold()

    async def return_to_launch(self) -> None:
        await self._gate("rtl")
        self.sent.append(("rtl",))
        self._fly(self.home_ll[0], self.home_ll[1], 0.0, then=self._landed)

    async def set_param(self, name: str, value: float) -> tuple[float, str]:
        await self._gate("param", name, value)
        return await super().set_param(name, value)


class SpreadGateway(FakeGateway):
    """``n`` spread drones (``spacing_m`` apart eastwards) and an operator lock book."""

    def __init__(self, settings: Settings, n: int = 5, spacing_m: float = 10.0) -> None:
        super().__init__(settings, n=0)
        self.registry = FakeRegistry([SpreadVehicle(f"d{i + 1}", i * spacing_m) for i in range(n)])
        self.lockbook = LockBook()
        self.locks = self.lockbook

    def vehicles(self) -> list[SpreadVehicle]:
        return self.registry.all()  # type: ignore[return-value]
