"""Where the gateway's CPU goes per MCP call: CPU time per call from the process's own counters, and
(with ``--profile``) a py-spy profile of each kind of call.

One simulated drone, one gateway process (``fleet-gateway serve``: REST + /mcp, SQLite audit), one MCP
client (the SDK's Streamable HTTP client, 2026-07-28 stateless mode, over loopback). Three kinds of call,
each run ``n`` times back to back:

- a cached read: ``get_position`` (answered from the telemetry cache);
- a call failing validation: ``go_to_location`` with ``lat_deg=500`` (refused by the argument schema,
  audited as an error);
- an actuating call: ``set_max_speed`` (a command to the autopilot, COMMAND_ACK awaited, under the
  drone's command lock, audited).

CPU per call is the gateway process's user + system time over the run (``/proc/<pid>/stat``) minus its
idle rate (telemetry ingest of the drone, measured over a quiet window just before) times the run's
length, divided by the number of calls: meaningful on a busy machine, where wall-clock latency is not.
With ``--profile`` each kind is run a second time under ``py-spy record --gil`` (samples of the thread
holding the GIL: Python CPU, not waiting), after the unprofiled run the CPU figure comes from. It needs
``py-spy`` on PATH (``pip install py-spy``; it attaches to the gateway with ptrace).
"""

from __future__ import annotations

import asyncio
import collections
import contextlib
import os
import shutil
import subprocess
import time
from collections.abc import Awaitable, Callable
from pathlib import Path
from typing import Any

import common

SPEEDUP = 4.0
ALT_M = 10.0
IDLE_S = 5.0

CALLS: dict[str, tuple[str, dict[str, Any], bool]] = {
    # label: (tool, arguments, error expected)
    "cached read (get_position)": ("get_position", {"drone_id": "d1"}, False),
    "failing validation (go_to_location lat_deg=500)": (
        "go_to_location",
        {"drone_id": "d1", "lat_deg": 500.0, "lon_deg": 0.0, "alt_m": 10.0},
        True,
    ),
    "actuating (set_max_speed)": ("set_max_speed", {"drone_id": "d1", "speed_mps": 5.0}, False),
}


async def idle_rate(pid: int, seconds: float) -> float:
    """CPU seconds per second of the process while nothing calls it."""
    c0, t0 = common.cpu_seconds(pid), time.monotonic()
    await asyncio.sleep(seconds)
    return (common.cpu_seconds(pid) - c0) / (time.monotonic() - t0)


async def per_call(
    pid: int, n: int, op: Callable[[int], Awaitable[None]], idle: float
) -> tuple[float, list[float]]:
    """(net gateway CPU seconds per call, latencies)."""
    latencies = []
    c0, t0 = common.cpu_seconds(pid), time.monotonic()
    for i in range(n):
        s = time.perf_counter()
        await op(i)
        latencies.append(time.perf_counter() - s)
    elapsed = time.monotonic() - t0
    used = common.cpu_seconds(pid) - c0
    return max(0.0, used - idle * elapsed) / n, latencies


def call_op(mcp: Any, tool: str, args: dict[str, Any], error: bool) -> Callable[[int], Awaitable[None]]:
    async def op(i: int) -> None:
        a = dict(args)
        if "speed_mps" in a:
            a["speed_mps"] = 5.0 + i % 2
        result = await mcp.call_tool(tool, a)
        if bool(result.is_error) != error:
            raise RuntimeError(f"{tool}: unexpected result {result}")

    return op


def start_pyspy(pid: int, out: Path, rate: int) -> subprocess.Popen[bytes]:
    return subprocess.Popen(
        ["py-spy", "record", "--pid", str(pid), "--rate", str(rate), "--format", "raw", "--gil",
         "-o", str(out)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip


def stop_pyspy(proc: subprocess.Popen[bytes]) -> None:
    proc.send_signal(2)  # SIGINT: py-spy writes its output and exits
    try:
        proc.wait(30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


INGEST = "telemetry ingest (gRPC streams)"
# what a frame belongs to, first match wins (module path fragments of py-spy's "func (file:line)")
BUCKETS = [
    ("audit + session rows (SQLAlchemy / aiosqlite)", ("sqlalchemy", "aiosqlite", "registry/store.py")),
    ("argument validation (pydantic)", ("pydantic", "func_metadata")),
    ("JSON encode / decode", ("json/", "orjson")),
    ("MCP SDK (session, routing, SSE)", ("mcp/server", "mcp/shared", "sse_starlette", "mcp/types")),
    ("HTTP server (uvicorn, starlette, h11)", ("uvicorn", "starlette", "h11", "httptools")),
    (INGEST, ("grpc", "mavsdk_grpc", "link/telemetry")),
    ("gateway code", ("gateway/",)),
    ("asyncio / anyio event loop", ("asyncio", "anyio")),
]


def summarize(raw: Path, top: int = 12) -> dict[str, Any]:
    """Inclusive share per bucket (a stack counts once for the innermost bucket it touches, from the
    leaf up) and the hottest functions (self time)."""
    buckets: collections.Counter[str] = collections.Counter()
    leaf: collections.Counter[str] = collections.Counter()
    inclusive: collections.Counter[str] = collections.Counter()
    total = 0
    for line in raw.read_text(errors="replace").splitlines():
        stack, _, count_s = line.rpartition(" ")
        if not stack or not count_s.isdigit():
            continue
        count = int(count_s)
        frames = stack.split(";")
        total += count
        leaf[_short(frames[-1])] += count
        for f in set(frames):
            inclusive[_short(f)] += count
        owner = "other"
        for f in reversed(frames):
            owner = next((name for name, keys in BUCKETS if any(k in f for k in keys)), "")
            if owner:
                break
        buckets[owner or "other"] += count
    return {"total": total, "buckets": buckets, "leaf": leaf.most_common(top), "inclusive": inclusive}


def _short(frame: str) -> str:
    func, _, where = frame.partition(" (")
    where = where.rstrip(")")
    for marker in ("site-packages/", "lib/python3", "issue-28/", "/gateway/"):
        if marker in where:
            where = where.split(marker, 1)[1]
    return f"{func} ({where.rsplit(':', 1)[0]})"


async def run(n: int, profile: bool, rate: int, workdir: Path) -> dict[str, Any]:
    results: dict[str, Any] = {}
    async with (
        common.sim(1, speedup=SPEEDUP, workdir=workdir) as sim_,
        common.gateway(sim_, workdir=workdir) as gw,
    ):
        waited, states = await common.wait_states(gw, "ready", 120)
        if any(s != "ready" for s in states.values()):
            raise RuntimeError(f"drone not ready after {waited:.0f} s: {states}\n{gw.log_tail()}")
        async with common.mcp_client(gw.mcp_url) as mcp:
            take = common.structured(await mcp.call_tool("takeoff", {"drone_id": "d1", "alt_m": ALT_M}))
            if take.get("status") != "succeeded":
                raise RuntimeError(f"takeoff did not finish: {take}")
            for label, (tool, args, error) in CALLS.items():
                op = call_op(mcp, tool, args, error)
                for i in range(10):  # warm-up
                    await op(i)
                idle = await idle_rate(gw.pid, IDLE_S)
                cpu, lat = await per_call(gw.pid, n, op, idle)
                if profile:  # a second run of the same calls, sampled (the first one is not disturbed)
                    spy = start_pyspy(gw.pid, workdir / f"{tool}.txt", rate)
                    try:
                        await asyncio.sleep(1.0)  # py-spy attaches
                        await per_call(gw.pid, n, op, idle)
                    finally:
                        stop_pyspy(spy)
                results[label] = {
                    "cpu_ms": cpu * 1000,
                    "idle_pct": idle * 100,
                    "lat": common.pcts(lat),
                    "profile": summarize(workdir / f"{tool}.txt") if profile else None,
                }
            with contextlib.suppress(Exception):
                await mcp.call_tool("land", {"drone_id": "d1", "wait": False})
        results["rss_mib"] = common.rss_kb(gw.pid) / 1024
    return results


def render(r: dict[str, Any], n: int, profile: bool) -> str:
    rows = []
    for label in CALLS:
        x = r[label]
        rows.append(
            [label, n, f"{x['cpu_ms']:.2f}", common.ms(x["lat"]["p50"]), common.ms(x["lat"]["p99"]),
             f"{x['idle_pct']:.1f}"]
        )  # fmt: skip
    lines = [
        f"One simulated drone (speed-up {SPEEDUP:g}x, hovering at {ALT_M:g} m), one gateway process with "
        "SQLite audit, one MCP client (Streamable HTTP, 2026-07-28 stateless mode, loopback). CPU per "
        "call is the gateway process's own CPU time (/proc) over the run, less its idle rate.",
        "",
        common.table(
            ["call", "n", "gateway CPU per call, ms", "p50 ms", "p99 ms", "idle gateway CPU, % of a core"],
            rows,
        ),
        "",
        f"Gateway RSS after the run: {r['rss_mib']:.0f} MiB.",
    ]
    if profile:
        for label in CALLS:
            p = r[label]["profile"]
            total = max(1, p["total"])
            # the telemetry ingest goes on whether calls come or not: the call's milliseconds are shared
            # out over the other samples
            calls = max(1, total - p["buckets"].get(INGEST, 0))
            cpu_ms = r[label]["cpu_ms"]
            lines += [
                "",
                f"Profile of {label} (py-spy, {total} samples on the gateway's threads; share of samples, "
                "each stack counted once for the innermost part it is in; ms per call: the call's CPU "
                f"({cpu_ms:.2f} ms) shared out over the samples that are not the telemetry ingest, which "
                "goes on without calls):",
                "",
                common.table(
                    ["where", "share", "ms per call"],
                    [
                        [k, f"{v / total:.0%}", "-" if k == INGEST else f"{cpu_ms * v / calls:.2f}"]
                        for k, v in p["buckets"].most_common()
                    ],
                ),
                "",
                "Hottest functions (self time): "
                + "; ".join(f"`{f}` {c / total:.0%}" for f, c in p["leaf"][:8]),
            ]
    return "\n".join(lines)


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--profile", action="store_true", help="also record a py-spy profile of each kind")
    p.add_argument("-n", type=int, default=None, help="calls per kind (default 300, --full 1000)")
    p.add_argument("--rate", type=int, default=250, help="py-spy samples per second")
    p.add_argument("--keep", type=Path, default=None, help="copy the raw py-spy files into this folder")
    args = p.parse_args()
    if args.profile and shutil.which("py-spy") is None:
        print("--profile needs py-spy on PATH: pip install py-spy")
        return 2
    n = args.n or (1000 if args.full else 300)
    info = common.machine()
    with common.workdir("callcpu") as wd:
        r = asyncio.run(run(n, args.profile, args.rate, wd))
        if args.keep is not None:
            args.keep.mkdir(parents=True, exist_ok=True)
            for f in wd.glob("*.txt"):
                shutil.copy(f, args.keep / f.name)
    text = render(r, n, args.profile)
    print(text)
    if args.write:
        common.write_section("call_cpu", "Gateway CPU per MCP call, and where it goes", text, info)
    print(f"(load average at the end: {' '.join(f'{x:.2f}' for x in os.getloadavg())})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
