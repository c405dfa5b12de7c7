"""Small fleets started again and again, to catch a drone that never becomes ready and say what it waits for.

Each round starts one simulator with ``--drones`` drones and one gateway over them (as bench/wakeups.py
does), and waits up to ``--within`` seconds for every drone to be ready. For each drone that is not, it
prints what the gateway says it waits for (``initialising``, the state, the last error), what the relay
carried between the drone and its sidecar (bytes each way), the stream rates the simulator holds for
that link (MAVLink message id: interval in seconds) with the bytes it sent and received, and the gateway's
log lines of that drone (its sidecar's output among them). A round whose drones are all ready prints one
line. The gateway logs at INFO (``--log-level``); a round's directory is kept when a drone was stuck.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import shutil
import tempfile
import time
from pathlib import Path
from typing import Any

import common
import httpx


async def _sim_state(control_url: str, index: int) -> dict[str, Any]:
    async with httpx.AsyncClient(base_url=control_url, timeout=10) as http:
        r = await http.get(f"/vehicles/{index}")
        r.raise_for_status()
        data: dict[str, Any] = r.json()
        return data


def _report(vid: str, vehicle: dict[str, Any], sim_state: dict[str, Any], log_lines: list[str]) -> str:
    status = vehicle.get("status") or {}
    links = sim_state.get("links") or []
    lines = [
        f"  {vid}: state {vehicle.get('state')}, initialising {status.get('initialising')!r}, "
        f"last error {status.get('last_error')!r}, sidecar {status.get('sidecar')}",
        f"    relay: {status.get('relay')}",
    ]
    for link in links:
        lines.append(
            f"    sim link {link.get('name')}: connected {link.get('connected')}, clients "
            f"{link.get('clients_served')}, bytes in {link.get('bytes_in')} out {link.get('bytes_out')}, "
            f"streams {link.get('streams')}"
        )
        lines.append(f"      rate requests (id, us): {link.get('rate_requests')}")
    lines.append(f"    sim: t_boot {sim_state.get('t_boot_s')} s, boots {sim_state.get('boots')}")
    lines += [f"    | {line}" for line in log_lines[-40:]]
    return "\n".join(lines)


async def one_round(n: int, speedup: float, within_s: float, level: str, keep: Path) -> int:
    """One fleet; returns how many drones were not ready."""
    wd = Path(tempfile.mkdtemp(prefix="bench-stuck-"))
    stuck = 0
    try:
        async with common.sim(n, speedup=speedup, workdir=wd) as sim_:
            env = {"GATEWAY_LOG_LEVEL": level}
            async with common.gateway(sim_, workdir=wd, env=env) as gw:
                waited, states = await common.wait_states(gw, "ready", within_s)
                not_ready = [vid for vid in gw.drone_ids if states.get(vid) != "ready"]
                stuck = len(not_ready) if states else n
                print(f"{n - stuck}/{n} ready after {waited:.1f} s", flush=True)
                if not_ready:
                    log_text = gw.log.read_text(errors="replace").splitlines()
                    by_id = {v["id"]: v for v in await gw.vehicles()}
                    for vid in not_ready:
                        index = int(vid[1:]) - 1
                        mine = [line for line in log_text if f"{vid}:" in line or f"[{vid}]" in line]
                        state = await _sim_state(sim_.control_url, index)
                        print(_report(vid, by_id.get(vid, {}), state, mine), flush=True)
    finally:
        if stuck:
            target = keep / wd.name
            shutil.copytree(wd, target, dirs_exist_ok=True)
            print(f"  kept {target}", flush=True)
        shutil.rmtree(wd, ignore_errors=True)
    return stuck


async def run(n: int, rounds: int, speedup: float, within_s: float, level: str, keep: Path) -> None:
    failed = 0
    t0 = time.monotonic()
    for i in range(rounds):
        print(f"round {i + 1}/{rounds} (load {os.getloadavg()[0]:.1f}):", end=" ", flush=True)
        with contextlib.suppress(RuntimeError):
            if await one_round(n, speedup, within_s, level, keep):
                failed += 1
    print(f"{failed} of {rounds} rounds had a drone not ready ({time.monotonic() - t0:.0f} s)")


def main() -> int:
    p = common.parser(__doc__ or "")
    p.add_argument("--drones", type=int, default=8)
    p.add_argument("--rounds", type=int, default=10)
    p.add_argument("--speedup", type=float, default=1.0)
    p.add_argument("--within", type=float, default=60.0, help="seconds each round waits for every drone")
    p.add_argument("--log-level", default="INFO")
    p.add_argument("--keep", type=Path, default=Path(tempfile.gettempdir()) / "bench-stuck-kept")
    args = p.parse_args()
    args.keep.mkdir(parents=True, exist_ok=True)
    asyncio.run(run(args.drones, args.rounds, args.speedup, args.within, args.log_level, args.keep))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
