"""The simulator against real ArduCopter SITL: the same steps, through the gateway, at the same speed-up.

Each autopilot is booted fresh and flown by the gateway's vehicle layer (registry, mavsdk_server
sidecar): boot to "ready" and to the first accepted arm, takeoff to 10 m (lift-off at 0.2 m, 9.5 m),
a 100 m reposition at 10 m, LAND to disarmed, then a second flight to 15 m, 85 m away, and RTL to
disarmed. Times are simulated seconds read from the vehicle's own clock (ATTITUDE.time_boot_ms), so a
busy machine does not change them. The boot milestones come from ``bench/readiness.py`` (a bare MAVLink
ground station that tries to arm in GUIDED every 0.25 s), several runs each.

    .venv/bin/python bench/sim_vs_real.py                 # simulator and real SITL, speed-up 5
    .venv/bin/python bench/sim_vs_real.py --speedup 1 --write

``--write`` replaces the comparison section of docs/simulator.md and bench/sim_vs_real.json (the real
figures, which ``tests/sim/test_sim_vs_real.py`` holds the simulator to). The real half needs
``eval "$(../shared/sitl/install)"``; without it only the simulator is flown.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import datetime as dt
import json
import math
import re
import sys
import tempfile
import textwrap
import time
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import readiness  # noqa: E402

from gateway.fleet import geo  # noqa: E402
from gateway.fleet.vehicles.registry import Registry  # noqa: E402
from gateway.fleet.vehicles.vehicle import ConnectionState, Vehicle  # noqa: E402
from gateway.registry.spec import VehicleSpec  # noqa: E402
from gateway.registry.store import Store  # noqa: E402
from tests.helpers import autopilots, sim_process  # noqa: E402
from tests.registry.conftest import fast_settings  # noqa: E402

DOC = ROOT / "docs" / "simulator.md"
FIGURES = ROOT / "bench" / "sim_vs_real.json"
MARK_START, MARK_END = "<!-- sim-vs-real -->", "<!-- /sim-vs-real -->"

#: step key -> label, in flight order
STEPS = {
    "boot_ready": "boot -> gateway says ready",
    "boot_armed": "boot -> first arm accepted (gateway's arm)",
    "liftoff": "takeoff command -> lift-off (0.2 m)",
    "climb": "takeoff command -> 9.5 m",
    "reposition": "100 m reposition at 10 m -> within 1 m",
    "land": "LAND from 10 m -> disarmed",
    "rtl": "RTL from 85 m at 15 m (stopped) -> disarmed",
}
#: readiness milestone key -> label (bench/readiness.py)
MILESTONES = {**readiness.LABELS, "origin_to_arm": "EKF origin -> first GUIDED arm"}
#: how far the simulator may be from the real autopilot before it needs correcting (s): the larger of
#: an absolute and a relative tolerance
TOLERANCE_S, TOLERANCE_REL = 1.0, 0.10


def tolerance(real_s: float) -> float:
    return max(TOLERANCE_S, TOLERANCE_REL * real_s)


class VehicleClock:
    """The vehicle's boot clock (simulated seconds), from ATTITUDE.time_boot_ms, extrapolated between
    messages with the speed-up."""

    def __init__(self, v: Vehicle, speedup: float) -> None:
        self.speedup = speedup
        self._boot_s: float | None = None
        self._at = 0.0
        self._task = asyncio.create_task(self._follow(v))

    async def _follow(self, v: Vehicle) -> None:
        while True:
            with contextlib.suppress(Exception):
                async for msg in v.system.mavlink_direct.message("ATTITUDE"):
                    self._boot_s = json.loads(msg.fields_json)["time_boot_ms"] / 1000.0
                    self._at = time.monotonic()
            await asyncio.sleep(0.2)

    def now(self) -> float | None:
        if self._boot_s is None:
            return None
        return self._boot_s + (time.monotonic() - self._at) * self.speedup

    async def close(self) -> None:
        self._task.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            await self._task


async def _until(what: str, check: Callable[[], bool], within_s: float, v: Vehicle) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while not check():
        if loop.time() > deadline:
            raise RuntimeError(f"{v.id}: {what} not reached within {within_s:g} s (wall); {v.status()}")
        await asyncio.sleep(0.01)


def _rel_alt(v: Vehicle) -> float:
    pos = v.telemetry.fresh("position")
    return -1.0 if pos is None else pos.rel_alt_m


def _speed(v: Vehicle) -> float:
    vel = v.telemetry.fresh("velocity_ned")
    return math.inf if vel is None else math.hypot(vel.north_mps, vel.east_mps)


def _distance_to(v: Vehicle, lat: float, lon: float) -> float:
    pos = v.telemetry.fresh("position")
    return math.inf if pos is None else geo.horizontal_distance_m(pos.lat_deg, pos.lon_deg, lat, lon)


async def fly(v: Vehicle, speedup: float) -> dict[str, float]:
    """The steps of the module doc on a vehicle just registered; simulated seconds per step."""
    wall = 300.0 / speedup + 60.0  # generous bound of each wait (wall seconds)
    got: dict[str, float] = {}
    clock = VehicleClock(v, speedup)
    try:

        def now() -> float:
            t = clock.now()
            if t is None:
                raise RuntimeError(f"{v.id}: no ATTITUDE (vehicle clock) yet")
            return t

        await _until("ready", lambda: v.state == ConnectionState.READY and clock.now() is not None, wall, v)
        got["boot_ready"] = now()
        await v.arm()
        got["boot_armed"] = now()

        t0 = now()
        await v.takeoff(10)
        await _until("lift-off", lambda: _rel_alt(v) >= 0.2, wall, v)
        got["liftoff"] = now() - t0
        await _until("9.5 m", lambda: _rel_alt(v) >= 9.5, wall, v)
        got["climb"] = now() - t0
        await _until("10 m", lambda: _rel_alt(v) >= 9.9, wall, v)

        home = v.telemetry.home
        assert home is not None
        lat, lon = geo.offset_position(home.value.lat_deg, home.value.lon_deg, 100.0, 0.0)
        t0 = now()
        await v.goto(lat, lon, 10)
        await _until("100 m away", lambda: _distance_to(v, lat, lon) < 1.0, wall, v)
        got["reposition"] = now() - t0

        t0 = now()
        await v.land()
        await _until("landed and disarmed", lambda: v.telemetry.fresh("armed") is False, wall, v)
        got["land"] = now() - t0
        await _until("on the ground", lambda: v.telemetry.fresh("in_air") is False, wall, v)

        # second flight: 85 m from home at 15 m, then RTL (RTL altitude 15 m on both)
        await v.takeoff(15)
        await _until("15 m", lambda: _rel_alt(v) >= 14.5, wall, v)
        lat, lon = geo.offset_position(home.value.lat_deg, home.value.lon_deg, 0.0, 85.0)
        await v.goto(lat, lon, 15)
        await _until("85 m from home", lambda: _distance_to(v, lat, lon) < 1.0, wall, v)
        await _until("stopped", lambda: _speed(v) < 0.3, wall, v)
        t0 = now()
        await v.return_to_launch()
        await _until("home and disarmed", lambda: v.telemetry.fresh("armed") is False, wall, v)
        got["rtl"] = now() - t0
    finally:
        await clock.close()
    return got


@contextlib.asynccontextmanager
async def registry() -> AsyncIterator[Registry]:
    with tempfile.TemporaryDirectory(prefix="sim-vs-real-") as folder:
        store = await Store.open(f"sqlite+aiosqlite:///{folder}/gateway.db")
        reg = Registry(fast_settings(link_lost_after_s=3.0), store)
        await reg.start()
        try:
            yield reg
        finally:
            await reg.stop()
            await store.close()


async def fly_sim(speedup: float) -> dict[str, float]:
    async with sim_process(1, speedup=speedup) as sim, registry() as reg:
        return await fly(await reg.add(VehicleSpec(id="sim", url=sim.urls[0])), speedup)


async def fly_real(speedup: float) -> dict[str, float]:
    with tempfile.TemporaryDirectory(prefix="sim-vs-real-") as folder:
        with autopilots.arducopter(Path(folder), speedup=speedup) as ap:
            async with registry() as reg:
                return await fly(await reg.add(VehicleSpec(id="sitl", url=ap.url)), speedup)


def milestones(runs: list[readiness.Readiness]) -> dict[str, list[float]]:
    """Milestone key -> its value in each run that reached it."""
    out: dict[str, list[float]] = {}
    for r in runs:
        for key, value in [*r.at.items(), ("origin_to_arm", r.origin_to_arm())]:
            if value is not None:
                out.setdefault(key, []).append(round(value, 2))
    return out


@dataclass
class Side:
    """One autopilot's figures: flight steps (one list entry per flight) and readiness milestones."""

    flights: dict[str, list[float]]
    ready: dict[str, list[float]]


async def measure(
    real: bool, speedup: float, flights: int, readiness_runs: int, *, progress: Callable[[str], None] = print
) -> Side:
    fly_one = fly_real if real else fly_sim
    probe_one = readiness.run_real if real else readiness.run_sim
    name = "ArduCopter SITL" if real else "simulator"
    steps: dict[str, list[float]] = {}
    for k in range(flights):
        progress(f"{name}: flight {k + 1}/{flights} at speed-up {speedup:g}")
        for key, value in (await fly_one(speedup)).items():
            steps.setdefault(key, []).append(round(value, 2))
    runs = []
    for k in range(readiness_runs):
        progress(f"{name}: readiness run {k + 1}/{readiness_runs}")
        runs.append(await probe_one(speedup))
    return Side(steps, milestones(runs))


def spread(values: list[float] | None) -> str:
    return readiness.spread(values or [])


def differences(sim: Side, real: Side) -> list[str]:
    """Steps where the simulator is outside the tolerance of every real run."""
    out = []
    for group_sim, group_real, labels in (
        (sim.flights, real.flights, STEPS),
        (sim.ready, real.ready, MILESTONES),
    ):
        for key, label in labels.items():
            s, r = group_sim.get(key), group_real.get(key)
            if not s or not r:
                continue
            lo, hi = min(r) - tolerance(min(r)), max(r) + tolerance(max(r))
            if not all(lo <= x <= hi for x in s):
                out.append(f"{label}: simulator {spread(s)} s, real {spread(r)} s")
    return out


def section(sim: Side, real: Side, speedup: float, date: str, real_date: str | None = None) -> str:
    rows = []
    for group, labels in (("flight", STEPS), ("ready", MILESTONES)):
        for key, label in labels.items():
            s = getattr(sim, "flights" if group == "flight" else "ready").get(key)
            r = getattr(real, "flights" if group == "flight" else "ready").get(key)
            rows.append(f"| {label} | {spread(s)} | {spread(r)} |")
    n_flights = len(next(iter(real.flights.values()), []))
    n_ready = len(next(iter(real.ready.values()), []))
    when = f"{date}" + (f" (real figures of {real_date})" if real_date and real_date != date else "")
    intro = (
        f"Measured {when} by `bench/sim_vs_real.py --speedup {speedup:g}`: both flown through the gateway's "
        f"vehicle layer and mavsdk_server; real: ArduCopter 4.7-dev SITL, {n_flights} flight(s) and "
        f"{n_ready} readiness runs. Simulated seconds from the vehicle's clock; a range is the spread "
        "over runs."
    )
    return "\n".join(
        [
            MARK_START,
            *textwrap.wrap(intro, 105),
            "",
            "| step (simulated s) | simulator | real ArduCopter SITL |",
            "|---|---|---|",
            *rows,
            MARK_END,
        ]
    )


def recorded() -> tuple[Side, float, str]:
    """The real figures last written by ``--write``, their speed-up and date."""
    data = json.loads(FIGURES.read_text())
    return Side(data["flights"], data["ready"]), float(data["speedup"]), str(data["date"])


def write(sim: Side, real: Side, speedup: float, real_date: str | None = None) -> None:
    date = dt.datetime.now(dt.UTC).strftime("%Y-%m-%d")
    block = section(sim, real, speedup, date, real_date)
    text = DOC.read_text()
    pattern = re.compile(re.escape(MARK_START) + r".*?" + re.escape(MARK_END), re.S)
    if not pattern.search(text):
        raise SystemExit(f"{DOC}: no {MARK_START} ... {MARK_END} section to replace")
    DOC.write_text(pattern.sub(lambda _m: block, text))
    if real_date is None:  # newly measured real figures
        figures: dict[str, Any] = {"date": date, "speedup": speedup}
        figures |= {"flights": real.flights, "ready": real.ready}
        FIGURES.write_text(json.dumps(figures, indent=1, sort_keys=True) + "\n")
        print(f"wrote {FIGURES.relative_to(ROOT)}")
    print(f"wrote {DOC.relative_to(ROOT)}")


async def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--speedup", type=float, default=5.0, help="speed-up of both (default 5)")
    p.add_argument("--flights", type=int, default=1, help="flights per autopilot (default 1)")
    p.add_argument("--readiness-runs", type=int, default=3, help="boot probes per autopilot (default 3)")
    p.add_argument("--write", action="store_true", help="update docs/simulator.md and bench/sim_vs_real.json")
    p.add_argument(
        "--sim-only", action="store_true", help="fly the simulator only; compare with the recorded real ones"
    )
    args = p.parse_args()
    sim = await measure(False, args.speedup, args.flights, args.readiness_runs)
    why = "--sim-only" if args.sim_only else autopilots.ardupilot_missing()
    if why:
        real, speedup, real_date = recorded()
        print(f"simulator only ({why}); real figures recorded {real_date} at speed-up {speedup:g}")
        print(section(sim, real, args.speedup, dt.date.today().isoformat(), real_date))
        diffs = differences(sim, real)
        print("beyond tolerance:" if diffs else "all steps within tolerance", *diffs, sep="\n  ")
        if args.write and speedup == args.speedup:
            write(sim, real, args.speedup, real_date)
        return
    real = await measure(True, args.speedup, args.flights, args.readiness_runs)
    print(section(sim, real, args.speedup, dt.date.today().isoformat()))
    diffs = differences(sim, real)
    print("beyond tolerance:" if diffs else "all steps within tolerance", *diffs, sep="\n  ")
    if args.write:
        write(sim, real, args.speedup)


if __name__ == "__main__":
    asyncio.run(main())
