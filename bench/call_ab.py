"""Two gateways side by side, this checkout and another one, with their calls interleaved: what a change
does to the CPU of an MCP call, under the same load for both.

One simulator, two gateway processes (``fleet-gateway serve``, SQLite audit), each on its own simulated
drone with its own sidecar: one runs this checkout, the other the checkout given with ``--other`` (a
git worktree of another commit: ``git worktree add /tmp/base <commit>``; its ``gateway`` package is put
first on that process's PYTHONPATH, everything else is this environment's). Calls alternate between the
two, and the order within each pair alternates too. CPU per call is each process's CPU time over the
call (its threads' scheduler run time, see ``common.cpu_seconds``), summed over its calls.

Which gateway starts first, and which one of a pair is called first, is not neutral (the same code in
both slots measured 5-10 % apart): ``--swap`` runs the other checkout in the first slot. Run it both
ways and read the two results together.
"""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import common

CALLS: dict[str, tuple[str, dict[str, Any]]] = {
    "cached read (get_position)": ("get_position", {"drone_id": "d1"}),
    "failing validation (go_to_location lat_deg='north')": (
        "go_to_location",
        {"drone_id": "d1", "lat_deg": "north", "lon_deg": 0.0, "alt_m": 10.0},
    ),
}
WARM_UP = 30


async def measure(other: Path, n: int, swap: bool) -> list[list[str]]:
    here_env: dict[str, str] | None = None
    other_env = {"PYTHONPATH": str(other)}
    first, second = (
        (("other", other_env), ("this", here_env)) if swap else (("this", here_env), ("other", other_env))
    )
    with common.workdir("ab-1") as w1, common.workdir("ab-2") as w2:
        async with common.sim(1, speedup=4.0, workdir=w1) as sim_:
            async with (
                common.gateway(sim_, workdir=w1, env=first[1]) as g1,
                common.gateway(sim_, workdir=w2, env=second[1]) as g2,
            ):
                for gw in (g1, g2):
                    await common.wait_states(gw, "ready", 120)
                async with common.mcp_client(g1.mcp_url) as m1, common.mcp_client(g2.mcp_url) as m2:
                    slots = [(first[0], m1, g1.pid), (second[0], m2, g2.pid)]
                    cpu: dict[tuple[str, str], float] = {}
                    for label, (tool, args) in CALLS.items():
                        for _ in range(WARM_UP):
                            for _, mcp, _ in slots:
                                await mcp.call_tool(tool, args)
                        for i in range(n):
                            for name, mcp, pid in slots if i % 2 == 0 else slots[::-1]:
                                c0 = common.cpu_seconds(pid)
                                await mcp.call_tool(tool, args)
                                cpu[(label, name)] = (
                                    cpu.get((label, name), 0.0) + common.cpu_seconds(pid) - c0
                                )
    rows = []
    for label in CALLS:
        this, that = cpu[(label, "this")] / n * 1000, cpu[(label, "other")] / n * 1000
        rows.append([label, f"{this:.3f}", f"{that:.3f}", f"{this / that:.2f}x"])
    return rows


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--other", type=Path, required=True, help="the other checkout (a git worktree)")
    p.add_argument("-n", type=int, default=600, help="calls of each kind to each gateway (default 600)")
    p.add_argument("--swap", action="store_true", help="the other checkout in the first slot")
    args = p.parse_args()
    if not (args.other / "gateway" / "__init__.py").is_file():
        p.error(f"--other: {args.other} holds no gateway package; give a checkout of this repository")
    load0 = common.machine()["load average (1/5/15 min) at start"]
    rows = asyncio.run(measure(args.other.resolve(), args.n, args.swap))
    slot = "the other checkout first" if args.swap else "this checkout first"
    print(f"{args.n} calls of each kind to each gateway, interleaved ({slot}); load average {load0}")
    print(common.table(["call", "this checkout, CPU ms per call", "the other, ms", "ratio"], rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
