"""Scale: one gateway with N simulated drones, each with its own mavsdk_server sidecar.

For each size: time until every drone is ``ready``; the cost of each drone at rest (no calls: gateway and
sidecar CPU per drone, telemetry updates per drone per second by stream); then, over a measuring window
on the ground, the
gateway's CPU (percent of one core) and RSS, the RSS of each sidecar and their CPU (from /proc), the
simulator's CPU, the whole machine's CPU use, telemetry freshness (``age_s`` of the cached position
that ``get_position`` returns, sampled round robin over the drones at a fixed call rate, p50/p99, and how
many answers were flagged stale) and the latency of listing the fleet (``list_drones`` when the fleet
toolset exists, else a read of the ``fleet://drones`` resource). Then what could run out (the gateway's
open files against its limit, the gateway's and the sidecars' threads, the sidecars' private memory, the
machine's available memory) and, unless ``--no-estop``, the emergency stop: every drone takes off, then
one ``POST /api/v1/fleet/stop`` (action land); how long until it answers and until every autopilot is in
LAND, as the simulator (a process of its own) says.

The simulator runs at real time (speed-up 1), so stream rates are what a real vehicle sends, in processes
of its own (more than one above ``SIM_PER_PROCESS`` drones: MAVLink system ids end at 255). Default: 10
drones; ``--full``: 10, 25 and 50; ``--sizes`` picks others. This is the heavy benchmark: on a shared
machine run the large sizes rarely.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import time
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import common

WINDOW_S = 20.0
FULL_WINDOW_S = 30.0
READ_RATE_HZ = 10.0
IDLE_WINDOW_S = 15.0
LIST_EVERY_S = 0.5
LIST_BURST = 30
# Thresholds of the "signs of overload" column: a 5 Hz position stream is at most ~0.2 s old when the
# gateway keeps up; a read tool answering from the cache should take milliseconds.
AGE_LIMIT_S = 1.0
GW_CPU_LIMIT = 80.0
MACHINE_CPU_LIMIT = 90.0
READ_LIMIT_S = 0.25
#: the emergency stop: every drone takes off to this height first, then the fleet stop (action land)
ESTOP_ALT_M = 5.0
ESTOP_LIMIT_S = 3.0
ESTOP_POLL_S = 0.05
#: drones per simulator process (MAVLink system ids end at 255)
SIM_PER_PROCESS = 250


def machine_cpu() -> tuple[float, float]:
    """(busy, total) jiffies of the whole machine, from /proc/stat."""
    with open("/proc/stat") as fh:
        parts = [int(x) for x in fh.readline().split()[1:]]
    idle = parts[3] + parts[4]
    return sum(parts) - idle, sum(parts)


async def list_fleet(mcp: Any, have_tool: bool) -> None:
    if have_tool:
        common.structured(await mcp.call_tool("list_drones", {}))
    else:
        await mcp.read_resource("fleet://drones")


async def message_counts(gw: common.Gateway) -> dict[str, float]:
    """Telemetry updates the gateway received so far, per stream, summed over the drones (/metrics)."""
    r = await gw.http.get("/metrics")
    r.raise_for_status()
    out: dict[str, float] = {}
    for line in r.text.splitlines():
        if line.startswith("fleet_gateway_telemetry_messages_total{"):
            labels, _, value = line.rpartition(" ")
            stream = labels.split('stream="', 1)[1].split('"', 1)[0]
            out[stream] = out.get(stream, 0.0) + float(value)
    return out


async def idle_ingest(
    gw: common.Gateway, empty: common.Gateway, sidecars: list[int], n: int
) -> dict[str, Any]:
    """With no call at all: the gateway's and the sidecars' CPU per drone (percent of one core) and the
    telemetry updates per drone per second, by stream: what each drone costs at rest.

    ``empty`` is a gateway with no drone, measured over the same window (so under the same load): what
    a gateway costs by itself (its event loop, the HTTP server, the database's writer). The gateway's CPU
    per drone is given both ways: all of it shared by the drones, and what the drones add to that.
    """
    gw_cpu, sc_cpu, empty_cpu = (
        common.CpuMeter([gw.pid]),
        common.CpuMeter(sidecars),
        common.CpuMeter([empty.pid]),
    )
    c0 = await message_counts(gw)
    for meter in (gw_cpu, sc_cpu, empty_cpu):
        meter.start()
    t0 = time.monotonic()
    await asyncio.sleep(IDLE_WINDOW_S)
    gw_pct, sc_pct, empty_pct = gw_cpu.percent(), sc_cpu.percent(), empty_cpu.percent()
    c1 = await message_counts(gw)
    elapsed = time.monotonic() - t0
    rates = {k: (v - c0.get(k, 0.0)) / elapsed / max(1, n) for k, v in c1.items()}
    return {
        "idle_gw_pct_per_drone": gw_pct / max(1, n),
        "idle_empty_gw_pct": empty_pct,
        "idle_gw_added_pct_per_drone": (gw_pct - empty_pct) / max(1, n),
        "idle_sc_pct_per_drone": sc_pct / max(1, len(sidecars)),
        "idle_msgs_per_drone": sum(rates.values()),
        "idle_rates": {k: round(v, 2) for k, v in sorted(rates.items()) if v > 0},
    }


async def listing_cost(gw: common.Gateway, mcp: Any, have_list: bool, idle_pct: float) -> dict[str, Any]:
    """``LIST_BURST`` fleet listings back to back, nothing else calling: the gateway's CPU per listing
    (its /proc counters less its idle rate, so the figure holds on a busy machine) and their latency."""
    lat: list[float] = []
    c0, t0, own0 = common.cpu_seconds(gw.pid), time.monotonic(), time.process_time()
    for _ in range(LIST_BURST):
        t = time.perf_counter()
        await list_fleet(mcp, have_list)
        lat.append(time.perf_counter() - t)
    cpu = common.cpu_seconds(gw.pid) - c0 - idle_pct / 100.0 * (time.monotonic() - t0)
    client = time.process_time() - own0  # the MCP client: the request, the result and its validation
    return {
        "list_cpu_ms": 1000.0 * cpu / LIST_BURST,
        "list_client_cpu_ms": 1000.0 * client / LIST_BURST,
        "list_burst_lat": lat,
    }


@contextlib.asynccontextmanager
async def simulators(n: int, wd: Path) -> AsyncIterator[list[common.Sim]]:
    """``n`` simulated drones in as few simulator processes as MAVLink allows: system ids end at 255, so
    a process holds at most ``SIM_PER_PROCESS`` drones, each process numbering its own from 1 (every
    drone has a link of its own, as a fleet of more than 255 real drones would)."""
    parts = -(-n // SIM_PER_PROCESS)
    counts = [n // parts + (1 if i < n % parts else 0) for i in range(parts)]
    async with contextlib.AsyncExitStack() as stack:
        sims = []
        for i, count in enumerate(counts):
            folder = wd / f"sim{i}"
            folder.mkdir(exist_ok=True)
            sims.append(await stack.enter_async_context(common.sim(count, speedup=1.0, workdir=folder)))
        yield sims


def together(sims: list[common.Sim]) -> common.Sim:
    """The drones of several simulator processes as one list (for the gateway's registration)."""
    first = sims[0]
    return common.Sim(
        proc=first.proc,
        urls=[u for s in sims for u in s.urls],
        sysids=[i for s in sims for i in s.sysids],
        udp_urls=[u for s in sims for u in s.udp_urls],
        control_url=first.control_url,
        log=first.log,
    )


async def sim_vehicles(http: Any, sims: list[common.Sim]) -> list[dict[str, Any]]:
    """Every simulated vehicle's true state, from each simulator's control API."""
    vehicles: list[dict[str, Any]] = []
    for sim_ in sims:
        r = await http.get(f"{sim_.control_url}/vehicles")
        r.raise_for_status()
        vehicles += r.json()
    return vehicles


async def emergency_stop(gw: common.Gateway, sims: list[common.Sim], mcp: Any, n: int) -> dict[str, Any]:
    """Every drone takes off (REST, one takeoff each, all at once) to ``ESTOP_ALT_M``; once the gateway
    sees every one of them in the air, the fleet stop (``POST /api/v1/fleet/stop``, action land, the
    fleet locked first): the time until it answers and, read from the simulator itself (its control
    API, polled every ``ESTOP_POLL_S``), until every autopilot is in LAND."""
    import httpx

    out: dict[str, Any] = {"estop_airborne": 0, "estop_answer_s": None, "estop_all_s": None}
    sem = asyncio.Semaphore(25)

    refusals: dict[str, int] = {}

    async def take_off(drone: str) -> bool:
        async with sem:
            r = await gw.http.post(f"/api/v1/vehicles/{drone}/takeoff", json={"alt_rel_m": ESTOP_ALT_M})
            if r.status_code != 200:  # why, without the drone's name: the same refusal counted once
                try:
                    why = str(r.json()["error"]["message"])
                except (ValueError, KeyError, TypeError):
                    why = r.text
                key = f"{r.status_code} {why.replace(drone, '<drone>')[:160]}"
                refusals[key] = refusals.get(key, 0) + 1
            return r.status_code == 200

    accepted = await asyncio.gather(*(take_off(d) for d in gw.drone_ids))
    out["estop_takeoffs_accepted"] = sum(accepted)
    out["estop_refusals"] = refusals
    async with httpx.AsyncClient(timeout=30) as sim_http:
        deadline = time.monotonic() + 60.0 + 0.5 * n
        while time.monotonic() < deadline:
            up = [v for v in await sim_vehicles(sim_http, sims) if v["rel_alt_m"] > 1.0]
            out["estop_airborne"] = len(up)
            if len(up) == n:
                break
            await asyncio.sleep(1.0)
        # the gateway skips a drone it reads as on the ground: wait until it sees them all in the air
        while time.monotonic() < deadline:
            rows = common.structured(await mcp.call_tool("list_drones", {})).get("drones", [])
            if sum(1 for row in rows if row.get("in_air")) >= out["estop_airborne"]:
                break
            await asyncio.sleep(0.5)
        t0 = time.perf_counter()
        r = await gw.http.post("/api/v1/fleet/stop", json={"action": "land"}, timeout=120)
        out["estop_answer_s"] = time.perf_counter() - t0
        body = r.json() if r.status_code == 200 else {"results": []}
        outcomes: dict[str, int] = {}
        for item in body.get("results", []):
            outcomes[item["outcome"]] = outcomes.get(item["outcome"], 0) + 1
        out["estop_outcomes"] = outcomes
        landing = 0
        while time.perf_counter() - t0 < 30.0:
            modes = [v["mode"] for v in await sim_vehicles(sim_http, sims)]
            landing = sum(1 for m in modes if m == "LAND")
            if landing >= out["estop_airborne"]:
                out["estop_all_s"] = time.perf_counter() - t0
                break
            await asyncio.sleep(ESTOP_POLL_S)
        out["estop_landing"] = landing
    return out


def resources(gw_pid: int, sidecars: list[int]) -> dict[str, Any]:
    """What the size uses of what can run out: the gateway's file descriptors (and its limit), threads
    (the gateway's, all sidecars'), the sidecars' private memory and the machine's available memory."""

    def count(path: str) -> int:
        try:
            return len(os.listdir(path))
        except OSError:
            return 0

    def fd_limit(pid: int) -> str:
        with contextlib.suppress(OSError):
            for line in Path(f"/proc/{pid}/limits").read_text().splitlines():
                if line.startswith("Max open files"):
                    return line.split()[3]
        return "?"

    mem_available = 0
    with contextlib.suppress(OSError, IndexError, ValueError):
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemAvailable:"):
                mem_available = int(line.split()[1]) // 1024
    return {
        "gw_fds": count(f"/proc/{gw_pid}/fd"),
        "gw_fd_limit": fd_limit(gw_pid),
        "gw_threads": count(f"/proc/{gw_pid}/task"),
        "sc_threads": sum(count(f"/proc/{p}/task") for p in sidecars),
        "mem_available_mib": mem_available,
    }


async def measure_size(
    n: int, window_s: float, ready_timeout_s: float, with_estop: bool = True
) -> dict[str, Any]:
    with common.workdir(f"scale{n}") as wd, common.workdir(f"scale{n}-empty") as wd_empty:
        async with (
            simulators(n, wd) as sims,
            common.gateway(together(sims), workdir=wd) as gw,
            common.gateway(together(sims), workdir=wd_empty, count=0) as empty,
        ):
            t_ready, states = await common.wait_states(gw, "ready", ready_timeout_s)
            ready = sum(1 for s in states.values() if s == "ready")
            sidecars = await gw.sidecar_pids()
            async with common.mcp_client(gw.mcp_url) as mcp:
                tools = {t.name for t in (await mcp.list_tools()).tools}
                have_list = "list_drones" in tools
                await asyncio.sleep(3.0)  # let start-up work settle
                idle = await idle_ingest(gw, empty, sidecars, n)
                gw_cpu, sc_cpu, sim_cpu = (
                    common.CpuMeter([gw.pid]),
                    common.CpuMeter(sidecars),
                    common.CpuMeter([s.pid for s in sims]),
                )
                for m in (gw_cpu, sc_cpu, sim_cpu):
                    m.start()
                busy0, total0 = machine_cpu()
                ages: list[float] = []
                stale = errors = 0
                list_lat: list[float] = []
                read_lat: list[float] = []
                t_end = time.monotonic() + window_s

                async def reader() -> None:
                    nonlocal stale, errors
                    i = 0
                    while time.monotonic() < t_end:
                        drone = gw.drone_ids[i % n]
                        i += 1
                        t0 = time.perf_counter()
                        r = await mcp.call_tool("get_position", {"drone_id": drone})
                        read_lat.append(time.perf_counter() - t0)
                        if r.is_error or not r.structured_content:
                            errors += 1
                        else:
                            ages.append(float(r.structured_content["age_s"]))
                            stale += bool(r.structured_content.get("stale"))
                        await asyncio.sleep(max(0.0, 1 / READ_RATE_HZ - (time.perf_counter() - t0)))

                async def lister() -> None:
                    while time.monotonic() < t_end:
                        t0 = time.perf_counter()
                        await list_fleet(mcp, have_list)
                        list_lat.append(time.perf_counter() - t0)
                        await asyncio.sleep(LIST_EVERY_S)

                await asyncio.gather(reader(), lister())
                busy1, total1 = machine_cpu()
                listing = await listing_cost(gw, mcp, have_list, idle["idle_gw_pct_per_drone"] * n)
                stop: dict[str, Any] = {}
                if with_estop and have_list:
                    try:  # the figures above are kept when the stop's phase breaks
                        stop = await emergency_stop(gw, sims, mcp, n)
                    except Exception as exc:
                        stop = {"estop_error": f"{type(exc).__name__}: {str(exc)[:200]}"}
                sc_rss = [common.rss_kb(p) for p in sidecars]
                used = resources(gw.pid, sidecars)
                sc_mem = [common.smaps_kb(p) for p in sidecars]
                result = {
                    "n": n,
                    "ready": ready,
                    "t_ready": t_ready,
                    "states": states,
                    "gw_cpu": gw_cpu.percent(),
                    "gw_rss_mb": common.rss_kb(gw.pid) / 1024,
                    "sc_rss_mb": (sum(sc_rss) / len(sc_rss) / 1024) if sc_rss else float("nan"),
                    "sc_rss_total_mb": sum(sc_rss) / 1024,
                    "sc_pss_mb": (sum(m["pss"] for m in sc_mem) / len(sc_mem) / 1024)
                    if sc_mem
                    else float("nan"),
                    "sc_private_mb": (
                        (sum(m["private"] for m in sc_mem) / len(sc_mem) / 1024) if sc_mem else float("nan")
                    ),
                    "sc_cpu": sc_cpu.percent(),
                    "sim_cpu": sim_cpu.percent(),
                    "machine_cpu": 100.0 * (busy1 - busy0) / max(1, total1 - total0),
                    "ages": ages,
                    "stale": stale,
                    "errors": errors,
                    "list_lat": list_lat,
                    "read_lat": read_lat,
                    "list_kind": "list_drones" if have_list else "fleet://drones resource",
                    **idle,
                    **listing,
                    **used,
                    **stop,
                    "load": _load(),
                }
    return result


def _load() -> str:
    with open("/proc/loadavg") as fh:
        return " ".join(fh.read().split()[:3])


def overload_signs(r: dict[str, Any]) -> list[str]:
    """What in this measurement says the gateway (or the machine) no longer keeps up."""
    signs = []
    if r["ready"] < r["n"]:
        signs.append(f"{r['n'] - r['ready']} drones never ready")
    age99 = common.percentile(r["ages"], 99)
    if age99 > AGE_LIMIT_S:
        signs.append(f"position p99 age {age99:.1f} s (> {AGE_LIMIT_S:g} s)")
    if r["stale"] or r["errors"]:
        signs.append(f"{r['stale']} stale / {r['errors']} failed reads")
    if r["gw_cpu"] > GW_CPU_LIMIT:
        signs.append(f"gateway at {r['gw_cpu']:.0f}% of a core")
    if r["machine_cpu"] > MACHINE_CPU_LIMIT:
        signs.append(f"machine CPU {r['machine_cpu']:.0f}%")
    if "estop_error" in r:
        signs.append(f"the emergency stop's phase failed: {r['estop_error']}")
    elif r.get("estop_all_s") is None and "estop_airborne" in r:
        signs.append("the emergency stop did not reach every drone within 30 s")
    elif r.get("estop_all_s", 0.0) > ESTOP_LIMIT_S:
        signs.append(f"emergency stop {r['estop_all_s']:.1f} s (> {ESTOP_LIMIT_S:g} s)")
    if common.percentile(r["read_lat"], 99) > READ_LIMIT_S:
        signs.append(f"get_position p99 {common.ms(common.percentile(r['read_lat'], 99))} ms")
    return signs


def render(results: list[dict[str, Any]], window_s: float) -> str:
    rows = []
    for r in results:
        age, lat, rd = common.pcts(r["ages"]), common.pcts(r["list_lat"]), common.pcts(r["read_lat"])
        rows.append(
            [
                r["n"],
                f"{r['ready']}/{r['n']} in {r['t_ready']:.0f} s",
                f"{r['gw_cpu']:.0f}",
                f"{r['gw_rss_mb']:.0f}",
                f"{r['sc_rss_mb']:.1f} / {r['sc_pss_mb']:.1f} / {r['sc_private_mb']:.1f}",
                f"{r['sc_cpu']:.0f}",
                f"{r['sim_cpu']:.0f}",
                f"{r['machine_cpu']:.0f}",
                f"{age['p50']:.2f} / {age['p99']:.2f}",
                f"{r['stale']}/{len(r['ages']) + r['errors']}",
                f"{common.ms(rd['p50'])} / {common.ms(rd['p99'])}",
                f"{common.ms(lat['p50'])} / {common.ms(lat['p99'])}",
                "; ".join(overload_signs(r)) or "none",
            ]
        )
    idle_rows = [
        [
            r["n"],
            f"{r['idle_gw_pct_per_drone']:.3f}",
            f"{r['idle_empty_gw_pct']:.2f}",
            f"{r['idle_gw_added_pct_per_drone']:.3f}",
            f"{r['idle_sc_pct_per_drone']:.3f}",
            f"{r['idle_msgs_per_drone']:.1f}",
            ", ".join(f"{k} {v:g}" for k, v in r["idle_rates"].items()),
        ]
        for r in results
    ]
    list_rows = [
        [
            r["n"],
            f"{r['list_cpu_ms']:.1f}",
            f"{r['list_client_cpu_ms']:.1f}",
            f"{common.ms(common.percentile(r['list_burst_lat'], 50))} / "
            f"{common.ms(common.percentile(r['list_burst_lat'], 99))}",
            r["load"],
        ]
        for r in results
    ]
    used_rows = [
        [
            r["n"],
            f"{r['gw_fds']} / {r['gw_fd_limit']}",
            r["gw_threads"],
            r["sc_threads"],
            f"{r['sc_private_mb'] * r['n']:.0f}",
            r["mem_available_mib"],
        ]
        for r in results
        if "gw_fds" in r
    ]
    stop_rows = [
        [
            r["n"],
            f"{r['estop_airborne']}/{r['n']} ({r['estop_takeoffs_accepted']} takeoffs accepted"
            + "".join(f"; {k} x{v}" for k, v in sorted(r.get("estop_refusals", {}).items()))
            + ")",
            "-" if r["estop_answer_s"] is None else f"{r['estop_answer_s']:.2f}",
            "-" if r["estop_all_s"] is None else f"{r['estop_all_s']:.2f}",
            f"{r['estop_landing']}/{r['estop_airborne']}",
            ", ".join(f"{k} {v}" for k, v in sorted(r["estop_outcomes"].items())) or "-",
        ]
        for r in results
        if "estop_airborne" in r
    ]
    kinds = {r["list_kind"] for r in results}
    lines = [
        f"Simulator at real time; measured on the ground over a {window_s:g} s window after all drones "
        f"were ready; `get_position` called round robin at {READ_RATE_HZ:g} calls/s; fleet listing every "
        f"{LIST_EVERY_S:g} s via {', '.join(sorted(kinds))}. CPU in percent of one core (the machine has "
        f"{common.machine()['nproc']}); machine CPU in percent of all cores.",
        "",
        common.table(
            [
                "drones",
                "ready",
                "gateway CPU %",
                "gateway RSS MiB",
                "per sidecar RSS / PSS / private MiB",
                "all sidecars CPU %",
                "sim CPU %",
                "machine CPU %",
                "position age p50 / p99 s",
                "stale / reads",
                "get_position p50 / p99 ms",
                "list p50 / p99 ms",
                "signs of overload",
            ],
            rows,
        ),
        "",
        f"At rest (no call at all, {IDLE_WINDOW_S:g} s before the window above): what each drone costs, "
        "CPU in percent of one core, and the telemetry updates the gateway receives from its sidecar. A "
        "gateway with no drone runs beside it over the same window (same load): what each drone adds is "
        "the difference, shared by the drones.",
        "",
        common.table(
            [
                "drones",
                "gateway CPU per drone % (all of it / drones)",
                "a gateway with no drone, CPU %",
                "gateway CPU each drone adds %",
                "CPU per sidecar %",
                "updates per drone per s",
                "streams",
            ],
            idle_rows,
        ),
        "",
        f"The fleet listing alone: {LIST_BURST} listings back to back after the window, nothing else "
        "calling; "
        "the gateway's CPU per listing (its /proc counters less its idle rate: holds on a busy machine) and "
        "the listing's latency at the client (which validates the result against the output schema).",
        "",
        common.table(
            [
                "drones",
                "gateway CPU per listing, ms",
                "client CPU per listing, ms",
                "latency p50 / p99 ms",
                "load average 1/5/15 min",
            ],
            list_rows,
        ),
    ]
    if used_rows:
        lines += [
            "",
            "What can run out, after the window: the gateway's open files and their limit, its threads, the "
            "sidecars' threads and private memory, and the machine's available memory.",
            "",
            common.table(
                [
                    "drones",
                    "gateway open files / limit",
                    "gateway threads",
                    "all sidecars' threads",
                    "all sidecars' private memory MiB",
                    "machine memory available MiB",
                ],
                used_rows,
            ),
        ]
    if stop_rows:
        lines += [
            "",
            f"The emergency stop: every drone takes off to {ESTOP_ALT_M:g} m (one REST takeoff each, all at "
            "once); once the gateway reads every one in the air, `POST /api/v1/fleet/stop` with action land "
            "(the fleet is locked first). The time until the call answers, and until every autopilot is in "
            f"LAND as the simulator itself says (its control API polled every {ESTOP_POLL_S * 1000:.0f} ms; "
            f"target: all within {ESTOP_LIMIT_S:g} s).",
            "",
            common.table(
                [
                    "drones",
                    "airborne before the stop",
                    "fleet stop answered, s",
                    "every autopilot in LAND, s",
                    "in LAND / airborne",
                    "outcomes of the stop",
                ],
                stop_rows,
            ),
        ]
    return "\n".join(lines)


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("--sizes", default=None, help="comma-separated fleet sizes (default 10; --full 10,25,50)")
    p.add_argument("--window", type=float, default=None, help="measuring window per size, s")
    p.add_argument(
        "--no-estop", action="store_true", help="leave out the emergency stop (the drones stay on the ground)"
    )
    args = p.parse_args()
    sizes = [int(x) for x in (args.sizes or ("10,25,50" if args.full else "10")).split(",")]
    window = args.window or (FULL_WINDOW_S if args.full else WINDOW_S)
    info = common.machine()
    results: list[dict[str, Any]] = []
    failed: list[str] = []
    for n in sizes:
        print(f"-- {n} drones", flush=True)
        try:
            r = asyncio.run(
                measure_size(n, window, ready_timeout_s=90.0 + 3.0 * n, with_estop=not args.no_estop)
            )
        except Exception as exc:  # a size that breaks the setup is a result too
            print(f"{n} drones: failed: {type(exc).__name__}: {exc}", flush=True)
            failed.append(f"{n} drones: {type(exc).__name__}: {str(exc)[:300]}")
            continue
        results.append(r)
        with contextlib.suppress(Exception):
            print(render([r], window).splitlines()[-1], flush=True)
    text = render(results, window)
    if failed:
        text += "\n\nSizes whose setup failed: " + "; ".join(failed)
    print(text)
    if args.write:
        common.write_section("scale", "Scale: drones per gateway", text, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
