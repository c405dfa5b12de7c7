"""The operator console's live stream (GET /api/v1/events) with N simulated drones on the ground.

For each size: the gateway's CPU (percent of one core) with no console open, then with ``--consoles``
streams open (the cost of the hub that builds the fleet snapshot once for all of them); the size of one
``fleet`` event; its age when it reaches the client (server timestamp to receipt, same clock) and the gap
between two of them; and how long an operator's REST call takes to come back as an ``audit`` event on an
open stream. The simulator runs in real time. Default: 10 drones; ``--full``: 10 and 50.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import time
from datetime import datetime
from typing import Any

import common
import httpx

WINDOW_S = 10.0
AUDIT_CALLS = 10


class StreamWatch:
    """One open /api/v1/events stream: sizes and timings of the fleet events, audit arrivals."""

    def __init__(self, base_url: str) -> None:
        self.base_url = base_url
        self.sizes: list[int] = []
        self.ages: list[float] = []
        self.gaps: list[float] = []
        self.audit_seen: dict[str, float] = {}  # lock reason -> monotonic arrival
        self.audit_arrived = asyncio.Event()
        self._last: float | None = None

    async def run(self) -> None:
        async with (
            httpx.AsyncClient(base_url=self.base_url, timeout=None) as http,
            http.stream("GET", "/api/v1/events") as response,
        ):
            event = ""
            async for line in response.aiter_lines():
                if line.startswith("event:"):
                    event = line[6:].strip()
                elif line.startswith("data:"):
                    self._data(event, line[5:].strip())

    def _data(self, event: str, text: str) -> None:
        now = time.monotonic()
        if event == "fleet":
            body = json.loads(text)
            self.sizes.append(len(text.encode()))
            sent = datetime.fromisoformat(body["t"]).timestamp()
            self.ages.append(time.time() - sent)
            if self._last is not None:
                self.gaps.append(now - self._last)
            self._last = now
        elif event == "audit":
            for row in json.loads(text)["items"]:
                reason = ((row.get("arguments") or {}).get("body") or {}).get("reason")
                if reason:
                    self.audit_seen.setdefault(reason, now)
                    self.audit_arrived.set()


async def measure(n: int, consoles: int) -> dict[str, Any]:
    with common.workdir(f"console{n}") as wd:
        async with common.sim(n, speedup=1.0, workdir=wd) as sim_, common.gateway(sim_, workdir=wd) as gw:
            _, states = await common.wait_states(gw, "ready", 120.0 + 3 * n)
            await asyncio.sleep(3.0)
            idle = common.CpuMeter([gw.pid])
            idle.start()
            await asyncio.sleep(WINDOW_S)
            cpu_idle = idle.percent()

            watches = [StreamWatch(gw.base_url) for _ in range(consoles)]
            tasks = [asyncio.create_task(w.run()) for w in watches]
            try:
                await asyncio.sleep(2.0)  # connected, backlog received
                busy = common.CpuMeter([gw.pid])
                busy.start()
                audit_latency = []
                for i in range(AUDIT_CALLS):
                    reason = f"bench {i}"
                    t0 = time.monotonic()
                    r = await gw.http.post("/api/v1/vehicles/d1/lock", json={"reason": reason})
                    r.raise_for_status()
                    while reason not in watches[0].audit_seen:
                        watches[0].audit_arrived.clear()
                        await asyncio.wait_for(watches[0].audit_arrived.wait(), 10)
                    audit_latency.append(watches[0].audit_seen.get(reason, float("nan")) - t0)
                    await asyncio.sleep(WINDOW_S / AUDIT_CALLS)
                cpu_busy = busy.percent()
                await gw.http.delete("/api/v1/vehicles/d1/lock")
            finally:
                for task in tasks:
                    task.cancel()
                for task in tasks:
                    with contextlib.suppress(asyncio.CancelledError, httpx.HTTPError):
                        await task
    sizes = [s for w in watches for s in w.sizes]
    ages = [a for w in watches for a in w.ages]
    gaps = [g for w in watches for g in w.gaps]
    return {
        "drones": n,
        "ready": sum(1 for s in states.values() if s == "ready"),
        "cpu_idle": cpu_idle,
        "cpu_streaming": cpu_busy,
        "event_kb": sum(sizes) / len(sizes) / 1024 if sizes else float("nan"),
        "ages": common.pcts(ages, (50, 99)),
        "gaps": common.pcts(gaps, (50, 99)),
        "audit": common.pcts(audit_latency, (50, 99)),
    }


def main() -> None:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--consoles", type=int, default=3, help="event streams open at once")
    args = p.parse_args()
    sizes = (10, 50) if args.full else (10,)
    results = [asyncio.run(measure(n, args.consoles)) for n in sizes]
    rows = [
        (
            f"{r['drones']} ({r['ready']} ready)",
            f"{r['cpu_idle']:.1f} %",
            f"{r['cpu_streaming']:.1f} %",
            f"{r['event_kb']:.1f} KB",
            f"{common.ms(r['ages']['p50'])} / {common.ms(r['ages']['p99'])}",
            f"{common.ms(r['gaps']['p50'])} / {common.ms(r['gaps']['p99'])}",
            f"{common.ms(r['audit']['p50'])} / {common.ms(r['audit']['p99'])}",
        )
        for r in results
    ]
    body = (
        f"{args.consoles} consoles streaming at once, drones on the ground, simulator in real time. CPU is "
        "the gateway process in percent of one core (sidecars not included).\n\n"
        + common.table(
            [
                "drones",
                "gateway CPU, no console",
                f"with {args.consoles} consoles",
                "fleet event",
                "event age p50 / p99 (ms)",
                "gap p50 / p99 (ms)",
                "REST call to audit event p50 / p99 (ms)",
            ],
            rows,
        )
    )
    info = common.machine()
    print(common.machine_line(info))
    print(body)
    if args.write:
        common.write_section("console", "Operator console stream", body, info)


if __name__ == "__main__":
    main()
