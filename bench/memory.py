"""Memory: the gateway and its sidecars with 1, 10 (and with ``--full`` 25) simulated drones.

For each size: one gateway with SQLite, every drone ready, then the same MCP calls a client makes in
bench/peers.py (cached position and battery reads, a call failing validation, the fleet listing), then
the gateway's RSS and PSS and each sidecar's RSS / PSS / private memory (from /proc). Printed: one drone's
cost (gateway + its sidecar, RSS as bench/peers.py counts it) and what each further drone adds (the
gateway's growth per drone between the smallest and the largest size, and one sidecar's private memory,
which is what one more mavsdk_server process really adds: the rest of its RSS is the binary, shared).
The libraries the gateway has not loaded (imported when first used) are listed from its /proc maps.
"""

from __future__ import annotations

import asyncio
from typing import Any

import common

CALLS = 30
#: shared objects of libraries the gateway imports only when they are used (looked for in /proc maps)
LAZY_LIBRARIES = {
    "numpy": "numpy/",
    "shapely": "shapely/",
    "scipy": "scipy/",
    "pymavlink": "pymavlink/",
}


def loaded_libraries(pid: int) -> list[str]:
    try:
        with open(f"/proc/{pid}/maps") as fh:
            maps = fh.read()
    except OSError:
        return []
    return sorted(name for name, fragment in LAZY_LIBRARIES.items() if fragment in maps)


async def measure(n: int) -> dict[str, Any]:
    with common.workdir(f"memory{n}") as wd:
        async with common.sim(n, speedup=1.0, workdir=wd) as sim_, common.gateway(sim_, workdir=wd) as gw:
            t_ready, states = await common.wait_states(gw, "ready", 90.0 + 3.0 * n)
            ready = sum(1 for s in states.values() if s == "ready")
            async with common.mcp_client(gw.mcp_url) as mcp:
                drone = gw.drone_ids[0]
                for i in range(CALLS):
                    await mcp.call_tool("get_position", {"drone_id": gw.drone_ids[i % n]})
                    await mcp.call_tool("get_battery", {"drone_id": drone})
                    await mcp.call_tool(
                        "go_to_location", {"drone_id": drone, "lat_deg": 500, "lon_deg": 0, "alt_m": 10}
                    )
                await mcp.call_tool("list_drones", {})
            await asyncio.sleep(2.0)
            sidecars = await gw.sidecar_pids()
            sc_rss = [common.rss_kb(p) / 1024 for p in sidecars]
            sc_mem = [common.smaps_kb(p) for p in sidecars]
            gw_mem = common.smaps_kb(gw.pid)
            return {
                "n": n,
                "ready": ready,
                "t_ready": t_ready,
                "gw_rss": common.rss_kb(gw.pid) / 1024,
                "gw_pss": gw_mem["pss"] / 1024,
                "sc_rss": sum(sc_rss) / max(1, len(sc_rss)),
                "sc_pss": sum(m["pss"] for m in sc_mem) / 1024 / max(1, len(sc_mem)),
                "sc_private": sum(m["private"] for m in sc_mem) / 1024 / max(1, len(sc_mem)),
                "lazy_loaded": loaded_libraries(gw.pid),
            }


def render(results: list[dict[str, Any]], load: tuple[str, str]) -> str:
    rows = [
        [
            r["n"],
            f"{r['ready']}/{r['n']}",
            f"{r['gw_rss']:.0f}",
            f"{r['gw_pss']:.0f}",
            f"{r['sc_rss']:.1f} / {r['sc_pss']:.1f} / {r['sc_private']:.1f}",
            f"{r['gw_rss'] + r['n'] * r['sc_rss']:.0f}",
            ", ".join(r["lazy_loaded"]) or "none",
        ]
        for r in results
    ]
    lines = [
        f"After every drone is ready and {CALLS} rounds of MCP calls (position and battery reads, a call "
        f"failing validation, one fleet listing); load average (1 min) {load[0]} at the start, {load[1]} at "
        "the end. MiB.",
        "",
        common.table(
            [
                "drones",
                "ready",
                "gateway RSS",
                "gateway PSS",
                "per sidecar RSS / PSS / private",
                "gateway + sidecars RSS",
                "lazily imported libraries loaded",
            ],
            rows,
        ),
    ]
    one = next((r for r in results if r["n"] == 1), None)
    if one is not None:
        lines += [
            "",
            f"One drone, gateway plus its sidecar (RSS, as bench/peers.py counts a server): "
            f"**{one['gw_rss'] + one['sc_rss']:.0f} MiB**.",
        ]
    if len(results) >= 2:
        a, b = results[0], results[-1]
        growth = (b["gw_rss"] - a["gw_rss"]) / max(1, b["n"] - a["n"])
        lines.append(
            f"Each further drone: the gateway grows by {growth:.2f} MiB (RSS, {a['n']} -> {b['n']} drones) "
            f"and its sidecar adds {b['sc_private']:.1f} MiB of private memory ({b['sc_rss']:.1f} MiB RSS, "
            "most of it the shared mavsdk_server binary)."
        )
    return "\n".join(lines)


def load1() -> str:
    with open("/proc/loadavg") as fh:
        return fh.read().split()[0]


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--sizes", default=None, help="comma-separated fleet sizes (default 1,10; --full 1,10,25)")
    args = p.parse_args()
    sizes = [int(x) for x in (args.sizes or ("1,10,25" if args.full else "1,10")).split(",")]
    info = common.machine()
    start = load1()
    results = []
    for n in sizes:
        r = asyncio.run(measure(n))
        print(
            f"{n} drones: gateway RSS {r['gw_rss']:.0f} MiB, sidecar RSS {r['sc_rss']:.1f} MiB "
            f"(private {r['sc_private']:.1f}), load {load1()}",
            flush=True,
        )
        results.append(r)
    text = render(results, (start, load1()))
    print(text)
    if args.write:
        common.write_section("memory", "Memory per drone", text, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
