"""Fleet dispatch: time from a ``formation_goto`` call to the last drone's command acknowledged.

For each fleet size the drones take off together (``fleet_takeoff``), then ``formation_goto`` is called
with ``wait=false`` several times (a ``fleet_hold`` between calls ends the previous formation). With
``wait=false`` the tool returns once its first phase's commands have been sent to every drone and
accepted (COMMAND_ACK), so the client-side call time is the figure; the server's own
``dispatch_s[0]`` (first command sent -> all accepted) is shown beside it. For comparison the same
drones also get one ``go_to_location(wait=false)`` each, all sent concurrently by the client
(labelled "per-drone gotos, concurrent"), which is what a client without fleet tools would do.

Default: 3 drones; ``--full``: 3, 10 and 25 (heavy: run rarely on a shared machine).
"""

from __future__ import annotations

import asyncio
import time
from typing import Any

import common

SPEEDUP = 4.0
ALT_M = 20.0
PHASE_LABELS = ("1 transit alt", "2 fly", "3 formation alt")


async def measure_size(n: int, repeats: int) -> dict[str, Any]:
    from gateway.fleet import geo

    with common.workdir(f"fleet{n}") as wd:
        async with (
            common.sim(n, speedup=SPEEDUP, workdir=wd) as sim_,
            common.gateway(sim_, workdir=wd) as gw,
        ):
            _t, states = await common.wait_states(gw, "ready", 90.0 + 3.0 * n)
            if any(s != "ready" for s in states.values()):
                raise RuntimeError(f"drones not ready: {states}\n{gw.log_tail()}")
            ids = gw.drone_ids
            async with common.mcp_client(gw.mcp_url) as mcp:
                tools = {t.name for t in (await mcp.list_tools()).tools}
                if "formation_goto" not in tools:
                    raise RuntimeError("this build has no formation_goto (fleet toolset)")
                took = common.structured(
                    await mcp.call_tool(
                        "fleet_takeoff", {"drone_ids": ids, "alt_m": ALT_M, "stagger_m": 2.0, "wait": True}
                    )
                )
                for _ in range(20):
                    if took["status"] != "running":
                        break
                    took = common.structured(await mcp.call_tool("monitor_fleet", {}))
                if took["status"] != "succeeded":
                    raise RuntimeError(f"fleet_takeoff: {took['status']}: {took['message']}")
                first = common.structured(await mcp.call_tool("get_position", {"drone_id": ids[0]}))
                last = common.structured(await mcp.call_tool("get_position", {"drone_id": ids[-1]}))
                lat0, lon0 = (
                    (first["lat_deg"] + last["lat_deg"]) / 2,
                    (first["lon_deg"] + last["lon_deg"]) / 2,
                )
                formation: list[dict[str, float]] = []
                for k in range(repeats):
                    lat, lon = geo.offset_position(lat0, lon0, 25.0 if k % 2 == 0 else -25.0, 0.0)
                    t0 = time.perf_counter()
                    r = await mcp.call_tool(
                        "formation_goto",
                        {
                            "drone_ids": ids,
                            "formation": "grid",
                            "center_lat_deg": lat,
                            "center_lon_deg": lon,
                            "alt_m": ALT_M + 10.0,
                            "spacing_m": 8.0,
                            "wait": False,
                        },
                    )
                    call_s = time.perf_counter() - t0
                    out = common.structured(r)
                    phase1 = sum(1 for m in out["drones"] if m.get("accepted_after_s") is not None)
                    final = out
                    for _ in range(10):  # monitor_fleet waits (capped) until the formation is done
                        final = common.structured(
                            await mcp.call_tool("monitor_fleet", {"operation_id": out["operation_id"]})
                        )
                        if final["status"] != "running":
                            break
                    formation.append(
                        {
                            "call_s": call_s,
                            "phase1": phase1,
                            "dispatch_s": final.get("dispatch_s") or [],
                            "phases": final.get("phases") or [],
                            "status": final["status"],
                            "commanded": sum(
                                1 for m in final["drones"] if m.get("accepted_after_s") is not None
                            ),
                        }
                    )
                    if final["status"] == "running":
                        common.structured(await mcp.call_tool("fleet_hold", {"drone_ids": ids}))
                gotos: list[float] = []
                for k in range(repeats):
                    here = [
                        common.structured(await mcp.call_tool("get_position", {"drone_id": d})) for d in ids
                    ]
                    north = 6.0 if k % 2 == 0 else -6.0
                    targets = [geo.offset_position(p["lat_deg"], p["lon_deg"], north, 0.0) for p in here]

                    async def goto(d: str, tgt: tuple[float, float], alt: float) -> None:
                        common.structured(
                            await mcp.call_tool(
                                "go_to_location",
                                {
                                    "drone_id": d,
                                    "lat_deg": tgt[0],
                                    "lon_deg": tgt[1],
                                    "alt_m": alt,
                                    "wait": False,
                                },
                            )
                        )

                    t0 = time.perf_counter()
                    await asyncio.gather(
                        *(goto(d, t, p["alt_m"]) for d, t, p in zip(ids, targets, here, strict=True))
                    )
                    gotos.append(time.perf_counter() - t0)
                    await asyncio.sleep(1.0)
                    common.structured(await mcp.call_tool("fleet_hold", {"drone_ids": ids}))
                common.structured(await mcp.call_tool("fleet_land", {"drone_ids": ids, "wait": False}))
    return {"n": n, "formation": formation, "gotos": gotos}


def render(results: list[dict[str, Any]]) -> str:
    rows: list[list[Any]] = []
    for r in results:
        if "error" in r:
            rows.append([r["n"], 0, f"failed: {r['error']}", "", "", "", ""])
            continue
        f = r["formation"]
        call = common.pcts([x["call_s"] for x in f], (50, 100))
        by_phase: dict[str, list[float]] = {}
        for x in f:
            for i, d in enumerate(x["dispatch_s"]):
                name = PHASE_LABELS[i] if i < len(PHASE_LABELS) else f"phase {i + 1}"
                by_phase.setdefault(name, []).append(d)
        phases = "; ".join(
            f"{name} {common.ms(common.percentile(v, 50))} / {common.ms(max(v))}"
            for name, v in by_phase.items()
        )
        g = common.pcts(r["gotos"], (50, 100))
        rows.append(
            [
                r["n"],
                len(f),
                f"{common.ms(call['p50'])} / {common.ms(call['p100'])}",
                ",".join(str(c) for c in sorted({x["phase1"] for x in f})),
                phases or "n/a",
                ",".join(sorted({x["status"] for x in f})),
                f"{common.ms(g['p50'])} / {common.ms(g['p100'])}",
            ]
        )
    return "\n".join(
        [
            f"Simulator at speed-up {SPEEDUP:g}x; drones airborne (fleet_takeoff) before measuring; "
            f"`formation_goto` (grid, {ALT_M + 10:g} m, 8 m spacing, centre 25 m away) with `wait=false`, "
            "then `monitor_fleet` until it finished. Times in ms, median / worst over the repeats. The call "
            "returns once its first phase (climb to transit altitudes) is sent and acknowledged, which "
            "commands only the drones that must change altitude; the server's `dispatch_s` per phase "
            "(first command sent -> all accepted) shows each burst, the fly phase commanding every drone.",
            "",
            common.table(
                [
                    "drones",
                    "repeats",
                    "formation_goto call, wait=false",
                    "drones commanded in phase 1",
                    "server dispatch per phase",
                    "outcome",
                    "per-drone gotos, concurrent (to last ACK)",
                ],
                rows,
            ),
        ]
    )


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--sizes", default=None, help="comma-separated fleet sizes (default 3; --full 3,10,25)")
    p.add_argument("--repeats", type=int, default=None, help="formation_goto calls per size")
    args = p.parse_args()
    sizes = [int(x) for x in (args.sizes or ("3,10,25" if args.full else "3")).split(",")]
    repeats = args.repeats or (5 if args.full else 3)
    info = common.machine()
    results = []
    for n in sizes:
        print(f"-- {n} drones", flush=True)
        try:
            results.append(asyncio.run(measure_size(n, repeats)))
        except Exception as exc:  # one size failing must not lose the others' figures
            results.append({"n": n, "error": f"{type(exc).__name__}: {exc}"[:300]})
        print(render(results[-1:]).splitlines()[-1], flush=True)
    text = render(results)
    print(text)
    if args.write:
        common.write_section("fleet", "Fleet dispatch: formation_goto to the last ACK", text, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
