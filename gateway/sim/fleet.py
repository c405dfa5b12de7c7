"""Many simulated vehicles in one asyncio loop, driven by one shared clock task."""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import Sequence

from gateway.sim.physics import LocalFrame
from gateway.sim.timeline import Timeline
from gateway.sim.vehicle import SimVehicle
from gateway.util.tasks import cancel_and_wait

log = logging.getLogger(__name__)

DEFAULT_HOME = (-35.363261, 149.165230, 584.0, 353.0)  # ArduPilot SITL's default (CMAC)
HOME_SPACING_M = 5.0


def parse_home(text: str) -> tuple[float, float, float, float]:
    """``LAT,LON,ALT_AMSL,HEADING`` -> tuple; raises ValueError naming the problem."""
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 4:
        raise ValueError(f"home must be LAT,LON,ALT_AMSL,HEADING (4 numbers), got {text!r}")
    try:
        lat, lon, alt, heading = (float(p) for p in parts)
    except ValueError:
        raise ValueError(f"home must be 4 numbers LAT,LON,ALT_AMSL,HEADING, got {text!r}") from None
    if not all(math.isfinite(x) for x in (lat, lon, alt, heading)):
        raise ValueError(f"home values must be finite, got {text!r}")
    if not -90 <= lat <= 90 or not -180 <= lon <= 180:
        raise ValueError(f"home latitude/longitude out of range: {lat}, {lon}")
    return lat, lon, alt, heading % 360


class SimFleet:
    """``count`` vehicles: vehicle i has sysid ``sysid_base + i``, TCP port ``tcp_base_port + 10*i``
    (0 = any free port), optional UDP output to ``udp_base_port + i``, optional second ground station
    port ``gcs_base_port + 10*i`` (0 = any free port); homes 5 m apart eastwards."""

    def __init__(
        self,
        count: int = 1,
        *,
        tcp_base_port: int = 5760,
        udp_base_port: int | None = None,
        gcs_base_port: int | None = None,
        speedup: float = 1.0,
        home: tuple[float, float, float, float] = DEFAULT_HOME,
        bind: str = "127.0.0.1",
        sysid_base: int = 1,
        seed: int | None = None,
        firmware: str = "4.7",
        timeline: Timeline | None = None,
    ) -> None:
        if count < 1:
            raise ValueError(f"count must be at least 1, got {count}")
        if not 1 <= sysid_base or sysid_base + count - 1 > 255:
            raise ValueError(f"system ids {sysid_base}..{sysid_base + count - 1} do not fit in 1..255")
        if tcp_base_port and not 1 <= tcp_base_port + 10 * (count - 1) <= 65535:
            raise ValueError(f"TCP ports from {tcp_base_port} for {count} vehicles exceed 65535")
        if not speedup > 0 or not math.isfinite(speedup):
            raise ValueError(f"speedup must be a positive number, got {speedup}")
        self.speedup = speedup
        lat, lon, alt, heading = home
        frame = LocalFrame(lat, lon, alt)
        self.vehicles: list[SimVehicle] = []
        for i in range(count):
            vlat, vlon = frame.to_latlon(0.0, i * HOME_SPACING_M)
            self.vehicles.append(
                SimVehicle(
                    i,
                    sysid_base + i,
                    (vlat, vlon, alt, heading),
                    speedup=speedup,
                    seed=None if seed is None else seed * 1000 + i,
                    firmware=firmware,
                    bind=bind,
                    tcp_port=tcp_base_port + 10 * i if tcp_base_port else 0,
                    udp_port=udp_base_port + i if udp_base_port else None,
                    gcs_port=_port_of(gcs_base_port, i),
                    timeline=timeline,
                )
            )
        self._task: asyncio.Task | None = None
        self.tick_period = 0.04 if speedup <= 2 else 0.02

    def __getitem__(self, index: int) -> SimVehicle:
        return self.vehicles[index]

    def __len__(self) -> int:
        return len(self.vehicles)

    @property
    def urls(self) -> list[str]:
        return [v.url for v in self.vehicles]

    async def start(self) -> None:
        started: list[SimVehicle] = []
        try:
            for v in self.vehicles:
                await v.start()
                started.append(v)
        except BaseException:
            for v in started:
                await v.stop()
            raise
        self._task = asyncio.create_task(self._run(), name="sim-clock")

    async def stop(self) -> None:
        await cancel_and_wait(self._task)
        self._task = None
        for v in self.vehicles:
            await v.stop()

    async def __aenter__(self) -> SimFleet:
        await self.start()
        return self

    async def __aexit__(self, *exc) -> None:
        await self.stop()

    async def _run(self) -> None:
        loop = asyncio.get_running_loop()
        next_t = loop.time()
        while True:
            for v in self.vehicles:
                try:
                    v.tick()
                except Exception:
                    log.exception("vehicle %d tick failed", v.sysid)
            next_t += self.tick_period
            delay = next_t - loop.time()
            if delay < 0:  # starved of CPU: skip ahead; the next tick integrates the measured time
                next_t = loop.time()
                delay = 0
            await asyncio.sleep(delay)

    def vehicle(self, key: int | str) -> SimVehicle:
        """By index (0..count-1)."""
        try:
            index = int(key)
        except (TypeError, ValueError):
            raise KeyError(f"vehicle index must be an integer, got {key!r}") from None
        if not 0 <= index < len(self.vehicles):
            raise KeyError(f"no vehicle {index}; indices are 0..{len(self.vehicles) - 1}")
        return self.vehicles[index]

    def describe(self) -> list[dict]:
        return [v.state() for v in self.vehicles]


def _port_of(base: int | None, index: int) -> int | None:
    """Vehicle ``index``'s port from a base port (None: no such port; 0: any free one)."""
    if base is None:
        return None
    return base + 10 * index if base else 0


def spread(vehicles: Sequence[SimVehicle]) -> list[str]:
    return [f"vehicle {v.index}: sysid {v.sysid} {v.url}" for v in vehicles]
