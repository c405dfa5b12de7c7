"""What wakes at rest: per thread, the context switches and CPU of the gateway, its sidecars and simulator.

One simulator process with N drones at real time, one gateway over them; once every drone is ready and
the start has settled, every thread of the three is read from /proc twice, ``--window`` seconds apart:
its voluntary and involuntary context switches (``/proc/<pid>/task/<tid>/status``) and its run time
(``schedstat``). Threads are grouped by name (``comm``, numbers dropped), summed over the sidecars, and
printed per drone and per second: each voluntary switch is one time a thread slept and was woken, which
at rest is most of a process's CPU. No call is made in the window.

``--env NAME=VALUE[;NAME=VALUE]`` adds a second simulator and gateway with that environment (its
sidecars inherit it), measured over the same window as the first (as is): an A/B comparison under the
same load of a shared machine. Several ``--env`` add several.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import re
import time
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import common

WINDOW_S = 30.0
SETTLE_S = 10.0


@dataclass
class ThreadSample:
    name: str
    voluntary: int
    involuntary: int
    run_ns: int


def _name_group(name: str) -> str:
    """Thread names without their numbers (gRPC numbers its pool's threads: ``default-executo`` etc)."""
    return re.sub(r"[-_ ]?\d+$", "", name) or name


def threads(pid: int) -> dict[int, ThreadSample]:
    out: dict[int, ThreadSample] = {}
    with contextlib.suppress(OSError):
        for tid in os.listdir(f"/proc/{pid}/task"):
            base = f"/proc/{pid}/task/{tid}"
            try:
                status = Path(f"{base}/status").read_text()
                run_ns = int(Path(f"{base}/schedstat").read_text().split()[0])
            except (OSError, ValueError, IndexError):
                continue
            fields = dict(line.split(":\t", 1) for line in status.splitlines() if ":\t" in line)
            out[int(tid)] = ThreadSample(
                fields.get("Name", "?").strip(),
                int(fields.get("voluntary_ctxt_switches", "0")),
                int(fields.get("nonvoluntary_ctxt_switches", "0")),
                run_ns,
            )
    return out


def delta(
    before: dict[int, ThreadSample], after: dict[int, ThreadSample]
) -> dict[str, tuple[int, float, float, float]]:
    """Per thread name: (threads, voluntary, involuntary, CPU seconds) over the interval (threads that
    lived through it only)."""
    grouped: dict[str, list[float]] = defaultdict(lambda: [0, 0.0, 0.0, 0.0])
    for tid, b in after.items():
        a = before.get(tid)
        if a is None:
            continue
        g = grouped[_name_group(b.name)]
        g[0] += 1
        g[1] += b.voluntary - a.voluntary
        g[2] += b.involuntary - a.involuntary
        g[3] += (b.run_ns - a.run_ns) / 1e9
    return {k: (int(v[0]), v[1], v[2], v[3]) for k, v in grouped.items()}


def render(title: str, d: dict[str, tuple[int, float, float, float]], seconds: float, per: int) -> str:
    rows = sorted(d.items(), key=lambda kv: -(kv[1][1] + kv[1][2]))
    total_w = sum(v[1] + v[2] for v in d.values())
    total_cpu = sum(v[3] for v in d.values())
    lines = [
        f"{title}: {sum(v[0] for v in d.values())} threads; per drone {total_w / seconds / per:.1f} "
        f"wake-ups/s, {100 * total_cpu / seconds / per:.3f} % of a core",
        common.table(
            ["thread", "threads", "voluntary/s per drone", "involuntary/s per drone", "CPU % per drone"],
            [
                (
                    name,
                    n,
                    f"{vol / seconds / per:.2f}",
                    f"{inv / seconds / per:.2f}",
                    f"{100 * cpu / seconds / per:.4f}",
                )
                for name, (n, vol, inv, cpu) in rows
            ],
        ),
    ]
    return "\n".join(lines)


async def stack_pids(
    stack: contextlib.AsyncExitStack, n: int, wd: Path, env: dict[str, str]
) -> tuple[common.Gateway, dict[str, list[int]]]:
    """One simulator and one gateway over its ``n`` drones, ready; their processes by kind."""
    sim_ = await stack.enter_async_context(common.sim(n, speedup=1.0, workdir=wd))
    gw = await stack.enter_async_context(common.gateway(sim_, workdir=wd, env=env))
    t_ready, states = await common.wait_states(gw, "ready", 120.0 + 2.0 * n)
    ready = sum(1 for s in states.values() if s == "ready")
    print(f"{ready}/{n} ready in {t_ready:.1f} s ({' '.join(f'{k}={v}' for k, v in env.items()) or 'as is'})")
    return gw, {"gateway": [gw.pid], "sidecars": await gw.sidecar_pids(), "simulator": [sim_.pid]}


def summed(
    pids: list[int], before: dict[int, dict[int, ThreadSample]], after: dict[int, dict[int, ThreadSample]]
) -> dict[str, tuple[int, float, float, float]]:
    merged: dict[str, list[float]] = defaultdict(lambda: [0, 0.0, 0.0, 0.0])
    for p in pids:
        for name, vals in delta(before[p], after[p]).items():
            for i, v in enumerate(vals):
                merged[name][i] += v
    return {k: (int(v[0]), v[1], v[2], v[3]) for k, v in merged.items()}


async def run(n: int, window_s: float, envs: list[dict[str, str]]) -> None:
    """Each environment its own simulator and gateway, all at once, measured over the same window (so
    under the same load: an A/B comparison on a shared machine)."""
    async with contextlib.AsyncExitStack() as stack:
        stacks = []
        for i, env in enumerate(envs):
            wd = stack.enter_context(common.workdir(f"wakeups{i}"))
            stacks.append(await stack_pids(stack, n, wd, env))
        print(f"settling {SETTLE_S:g} s")
        await asyncio.sleep(SETTLE_S)
        every = [p for _, kinds in stacks for pids in kinds.values() for p in pids]
        before = {p: threads(p) for p in every}
        t0 = time.monotonic()
        load0 = os.getloadavg()[0]
        await asyncio.sleep(window_s)
        seconds = time.monotonic() - t0
        after = {p: threads(p) for p in every}
        print(f"window {seconds:.1f} s; load average (1 min) {load0:.2f} -> {os.getloadavg()[0]:.2f}\n")
        for env, (_, kinds) in zip(envs, stacks, strict=True):
            print(f"## {' '.join(f'{k}={v}' for k, v in env.items()) or 'as is'}\n")
            for kind in ("gateway", "sidecars", "simulator"):
                d = summed(kinds[kind], before, after)
                print(render(kind, d, seconds, n) + "\n")


def main() -> int:
    p = common.parser(__doc__ or "")
    p.add_argument("--drones", type=int, default=10)
    p.add_argument("--window", type=float, default=WINDOW_S)
    p.add_argument(
        "--env",
        action="append",
        default=[],
        help="NAME=VALUE[;NAME=VALUE] for a gateway's environment (its sidecars inherit it); each --env "
        "adds a simulator and gateway measured beside the first, which runs as is",
    )
    args = p.parse_args()
    print(common.machine_line(common.machine()))
    envs: list[dict[str, str]] = [{}]
    envs += [dict(pair.split("=", 1) for pair in e.split(";")) for e in args.env]
    asyncio.run(run(args.drones, args.window, envs))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
