"""Measure the emergency stop (POST /api/v1/fleet/stop) on a 10-drone fleet in the air.

Not a test (durations are never asserted): run ``.venv/bin/python -m tests.load.estop_timing``. It
starts 10 simulated drones and a gateway with real sidecars on loopback, takes all off, then times the
stop request (response received) for hold (three times, unlocking in between) and once for land.
"""

from __future__ import annotations

import asyncio
import statistics
import sys
import tempfile
import time
from pathlib import Path

import httpx

from tests.helpers.timing import scaled
from tests.mcp.conftest import gateway_stack, structured

DRONES = 10


async def main() -> int:
    with tempfile.TemporaryDirectory() as tmp:
        async with gateway_stack(Path(tmp), count=DRONES, speedup=5.0) as stack:
            ids = stack.drone_ids
            async with stack.client("auto", name="estop") as c:
                r = structured(await c.call_tool("fleet_takeoff", {"drone_ids": ids, "alt_m": 10}))
                while r["status"] == "running":
                    r = structured(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
                if r["status"] != "succeeded":
                    print("takeoff failed:", r["message"])
                    return 1
            timings: dict[str, list[float]] = {"hold": [], "land": []}
            async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
                for action in ("hold", "hold", "hold", "land"):
                    await http.delete("/api/v1/fleet/lock")
                    start = time.perf_counter()
                    resp = await http.post("/api/v1/fleet/stop", json={"action": action})
                    elapsed = time.perf_counter() - start
                    body = resp.json()
                    sent = sum(1 for x in body["results"] if x["outcome"] == "sent")
                    timings[action].append(elapsed)
                    print(
                        f"stop {action}: HTTP {resp.status_code} in {elapsed * 1000:.0f} ms, {sent}/{DRONES} "
                        f"sent, fleet lock: {bool(body['fleet_lock'])}"
                    )
                    await asyncio.sleep(2.0)
            hold = timings["hold"]
            print(
                f"hold: median {statistics.median(hold) * 1000:.0f} ms, max {max(hold) * 1000:.0f} ms; "
                f"land: {timings['land'][0] * 1000:.0f} ms ({DRONES} drones)"
            )
    return 0


if __name__ == "__main__":
    sys.exit(asyncio.run(main()))
