"""Shared pieces of the benchmarks: simulator and gateway processes, MCP client, /proc figures,
percentiles, and the writer of ``docs/benchmarks.md``.

Benchmarks are scripts, not tests: they print figures and never assert timings. Each one runs a short
version by default (``--full`` for the long one) and, with ``--write``, replaces its own section of
``docs/benchmarks.md`` (between ``<!-- bench:NAME -->`` markers) together with a description of the machine.

Run directly (``python bench/common.py``) it prints that machine description.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import datetime as dt
import json
import math
import os
import platform
import re
import shutil
import sys
import tempfile
import time
from collections.abc import AsyncIterator, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx

from gateway.util.procs import stop_process_group

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs" / "benchmarks.md"
CLK_TCK = os.sysconf("SC_CLK_TCK")
PAGE_KB = os.sysconf("SC_PAGE_SIZE") // 1024
_VEHICLE_LINE = re.compile(r"^vehicle (\d+) sysid (\d+) (\S+)(?: udp (\S+))?")


# --- command line ------------------------------------------------------------------------------


def parser(description: str) -> argparse.ArgumentParser:
    """The options every benchmark has: --full (long version) and --write (update docs/benchmarks.md)."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--full", action="store_true", help="the long version (more samples / sizes)")
    p.add_argument("--write", action="store_true", help=f"write the figures into {DOCS.relative_to(ROOT)}")
    return p


# --- statistics --------------------------------------------------------------------------------


def percentile(values: Sequence[float], p: float) -> float:
    """The p-th percentile (0..100) with linear interpolation; NaN for no values."""
    if not values:
        return math.nan
    s = sorted(values)
    k = (len(s) - 1) * p / 100.0
    lo, hi = math.floor(k), math.ceil(k)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


def pcts(values: Sequence[float], ps: Iterable[float] = (50, 95, 99)) -> dict[str, float]:
    return {f"p{p:g}": percentile(values, p) for p in ps}


def ms(seconds: float) -> str:
    return "n/a" if math.isnan(seconds) else f"{seconds * 1000:.2f}"


# --- machine -----------------------------------------------------------------------------------


def machine() -> dict[str, str]:
    """nproc, RAM, CPU model, Python, date (UTC) and the load average when the benchmark started."""
    cpu = platform.processor() or "unknown"
    with contextlib.suppress(OSError), open("/proc/cpuinfo") as fh:
        for line in fh:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    ram = "unknown"
    with contextlib.suppress(OSError), open("/proc/meminfo") as fh:
        for line in fh:
            if line.startswith("MemTotal:"):
                ram = f"{int(line.split()[1]) / 1024 / 1024:.1f} GiB"
                break
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    return {
        "nproc": str(os.cpu_count()),
        "RAM": ram,
        "CPU": cpu,
        "Python": platform.python_version(),
        "date": dt.datetime.now(dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "load average (1/5/15 min) at start": load,
    }


def machine_line(info: dict[str, str]) -> str:
    return "Machine: " + "; ".join(f"{k} {v}" for k, v in info.items())


# --- docs/benchmarks.md ------------------------------------------------------------------------

DOC_HEADER = """# Benchmarks

The current figures: for each measured thing its latest figure, the command that prints it, the machine
and the date. Earlier measurements are in this file's git history (`git log -p docs/benchmarks.md`).

## Current figures

| what | figure | target | command | machine, date (load) |
|---|---|---|---|---|
"""


def write_section(name: str, title: str, body: str, info: dict[str, str]) -> None:
    """Replace (or append) the section ``name`` of docs/benchmarks.md."""
    start, end = f"<!-- bench:{name} -->", f"<!-- /bench:{name} -->"
    block = f"{start}\n## {title}\n\n{machine_line(info)}\n\n{body.strip()}\n{end}"
    text = DOCS.read_text() if DOCS.exists() else DOC_HEADER
    pattern = re.compile(re.escape(start) + r".*?" + re.escape(end), re.S)
    if pattern.search(text):
        text = pattern.sub(lambda _m: block, text)
    else:
        text = text.rstrip() + "\n\n" + block + "\n"
    DOCS.write_text(text if text.endswith("\n") else text + "\n")
    print(
        f"wrote section {name!r} of {DOCS.relative_to(ROOT)}; its row in the table of current figures is "
        "changed by hand (the page keeps only the newest figure of each thing)"
    )


def table(headers: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


# --- /proc figures -----------------------------------------------------------------------------


def cpu_seconds(pid: int) -> float:
    """CPU time of one process, in seconds (0 when it is gone).

    The sum of its threads' scheduler run time (``/proc/<pid>/task/*/schedstat``, nanoseconds) where
    the kernel keeps it: ``/proc/<pid>/stat`` counts in clock ticks (10 ms), so the difference of two
    readings around a call of 1-2 ms is 0 or 10 ms, and a sum over a few hundred calls carries about
    20 % of noise from the rounding alone. A thread that ended takes its run time with it, which the
    benchmarks' servers (long-lived thread pools) do not do while measured. Else utime + stime.
    """
    precise = _threads_run_time(pid)
    if precise is not None:
        return precise
    try:
        with open(f"/proc/{pid}/stat") as fh:
            fields = fh.read().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / CLK_TCK  # utime, stime (fields 14, 15)


def _threads_run_time(pid: int) -> float | None:
    total = 0
    try:
        tids = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return None
    for tid in tids:
        try:
            with open(f"/proc/{pid}/task/{tid}/schedstat") as fh:
                total += int(fh.read().split()[0])
        except (OSError, ValueError, IndexError):
            continue  # the thread ended between the listing and the read
    return total / 1e9 if total > 0 else None


def rss_kb(pid: int) -> int:
    """Resident set size of one process, in KiB (0 when it is gone)."""
    try:
        with open(f"/proc/{pid}/statm") as fh:
            return int(fh.read().split()[1]) * PAGE_KB
    except OSError:
        return 0


def smaps_kb(pid: int) -> dict[str, int]:
    """Pss and private (unique) memory of one process, in KiB, from /proc/<pid>/smaps_rollup.

    RSS counts the pages shared between the sidecars (the mavsdk_server binary) once per process; PSS
    splits them fairly and private memory is what one more process really adds."""
    out = {"pss": 0, "private": 0}
    try:
        with open(f"/proc/{pid}/smaps_rollup") as fh:
            for line in fh:
                key, _, rest = line.partition(":")
                if key == "Pss":
                    out["pss"] = int(rest.split()[0])
                elif key in ("Private_Clean", "Private_Dirty"):
                    out["private"] += int(rest.split()[0])
    except OSError:
        pass
    return out


@dataclass
class CpuMeter:
    """CPU use of some processes over an interval, in percent of one core."""

    pids: list[int]
    _t0: float = 0.0
    _c0: float = 0.0

    def start(self) -> None:
        self._t0, self._c0 = time.monotonic(), sum(cpu_seconds(p) for p in self.pids)

    def percent(self) -> float:
        elapsed = time.monotonic() - self._t0
        return 100.0 * (sum(cpu_seconds(p) for p in self.pids) - self._c0) / elapsed if elapsed else math.nan


# --- processes ---------------------------------------------------------------------------------


async def stop_group(proc: asyncio.subprocess.Process, grace_s: float = 10.0) -> None:
    """SIGTERM the process group, wait, then SIGKILL; never raises."""
    await stop_process_group(proc, grace_s)


def _log_fd(path: Path) -> int:
    """A file descriptor for a child's log (the child keeps its own copy)."""
    return os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)


def _tail(path: Path, n: int = 30) -> str:
    try:
        return "".join(path.read_text(errors="replace").splitlines(keepends=True)[-n:])
    except OSError:
        return ""


@dataclass
class Sim:
    """A running ``fleet-gateway sim`` process."""

    proc: asyncio.subprocess.Process
    urls: list[str]
    sysids: list[int]
    udp_urls: list[str | None]
    control_url: str
    log: Path

    @property
    def pid(self) -> int:
        return self.proc.pid


@contextlib.asynccontextmanager
async def sim(
    count: int, *, speedup: float = 1.0, udp_base_port: int | None = None, workdir: Path
) -> AsyncIterator[Sim]:
    """Simulated drones on OS-chosen loopback TCP ports (and optional UDP outputs); always stopped."""
    log = workdir / "sim.log"
    args = [
        sys.executable, "-m", "gateway.cli", "sim", "--count", str(count), "--tcp-base-port", "0",
        "--control-port", "0", "--speedup", str(speedup), "--seed", "1",
    ]  # fmt: skip
    if udp_base_port is not None:
        args += ["--udp-base-port", str(udp_base_port)]
    err = _log_fd(log)
    try:
        proc = await asyncio.create_subprocess_exec(
            *args,
            stdout=asyncio.subprocess.PIPE,
            stderr=err,
            stdin=asyncio.subprocess.DEVNULL,
            start_new_session=True,
            env={**os.environ, "PYTHONUNBUFFERED": "1"},
        )
    finally:
        os.close(err)
    try:
        urls: list[str] = []
        sysids: list[int] = []
        udp: list[str | None] = []
        control = ""
        assert proc.stdout is not None
        deadline = time.monotonic() + 60
        while True:
            raw = await asyncio.wait_for(proc.stdout.readline(), max(1.0, deadline - time.monotonic()))
            if not raw:
                raise RuntimeError(f"simulator exited before it was ready:\n{_tail(log)}")
            line = raw.decode().strip()
            if m := _VEHICLE_LINE.match(line):
                sysids.append(int(m.group(2)))
                urls.append(m.group(3))
                udp.append(m.group(4))
            elif line.startswith("control "):
                control = line.split(" ", 1)[1]
            elif line == "ready":
                break
        yield Sim(proc, urls, sysids, udp, control, log)
    finally:
        await stop_group(proc)


@dataclass
class Gateway:
    """A running ``fleet-gateway serve`` process (REST + /mcp) with its own SQLite file."""

    proc: asyncio.subprocess.Process
    base_url: str
    db_path: Path
    log: Path
    drone_ids: list[str]
    http: httpx.AsyncClient = field(repr=False)

    @property
    def pid(self) -> int:
        return self.proc.pid

    @property
    def mcp_url(self) -> str:
        return f"{self.base_url}/mcp"

    async def vehicles(self) -> list[dict[str, Any]]:
        r = await self.http.get("/api/v1/vehicles")
        r.raise_for_status()
        return r.json()["items"]

    async def sidecar_pids(self) -> list[int]:
        pids = []
        for v in await self.vehicles():
            pid = ((v.get("status") or {}).get("sidecar") or {}).get("pid")
            if pid:
                pids.append(int(pid))
        return pids

    def log_tail(self, n: int = 30) -> str:
        return _tail(self.log, n)


async def register(db_url: str, drones: Sequence[tuple[str, str, int]]) -> None:
    """Register (id, url, sysid) drones in the database before the gateway starts (it restores them)."""
    from gateway.registry.spec import VehicleSpec
    from gateway.registry.store import Store

    store = await Store.open(db_url)
    try:
        for vid, url, sysid in drones:
            await store.add_vehicle(VehicleSpec(id=vid, url=url, expected_sysid=sysid))
    finally:
        await store.close()


@contextlib.asynccontextmanager
async def gateway(
    sim_: Sim,
    *,
    workdir: Path,
    count: int | None = None,
    env: dict[str, str] | None = None,
    start_s: float | None = None,
) -> AsyncIterator[Gateway]:
    """A gateway over the first ``count`` drones of ``sim_`` (ids d1..dN); stopped (with every sidecar)
    on exit. ``start_s``: how long it may take to answer ``/healthz`` (default: 60 s and 0.5 s a drone)."""
    from gateway.util.ports import free_tcp_port

    count = len(sim_.urls) if count is None else count
    ids = [f"d{i + 1}" for i in range(count)]
    db = workdir / "gateway.db"
    db_url = f"sqlite+aiosqlite:///{db}"
    await register(db_url, list(zip(ids, sim_.urls[:count], sim_.sysids[:count], strict=True)))
    port = free_tcp_port()
    log = workdir / "gateway.log"
    full_env = {
        **os.environ,
        "GATEWAY_DATABASE_URL": db_url,
        "GATEWAY_HOST": "127.0.0.1",
        "GATEWAY_PORT": str(port),
        "GATEWAY_LOG_LEVEL": "WARNING",
        "PYTHONUNBUFFERED": "1",
        **(env or {}),
    }
    out = _log_fd(log)
    try:
        proc = await asyncio.create_subprocess_exec(
            sys.executable, "-m", "gateway.cli", "serve",
            stdout=out, stderr=out, stdin=asyncio.subprocess.DEVNULL, start_new_session=True,
            env=full_env, cwd=workdir,
        )  # fmt: skip
    finally:
        os.close(out)
    base = f"http://127.0.0.1:{port}"
    http = httpx.AsyncClient(base_url=base, timeout=30)
    try:
        # every sidecar is started with its gateway: hundreds of them keep the machine busy before a gateway
        # (this one, or another started beside it, as bench/scale.py's gateway with no drone) answers
        deadline = time.monotonic() + (60 + 0.5 * len(sim_.urls) if start_s is None else start_s)
        while True:
            if proc.returncode is not None:
                raise RuntimeError(f"gateway exited:\n{_tail(log)}")
            with contextlib.suppress(httpx.HTTPError):
                if (await http.get("/healthz")).status_code == 200:
                    break
            if time.monotonic() > deadline:
                raise RuntimeError(f"gateway did not answer /healthz:\n{_tail(log)}")
            await asyncio.sleep(0.2)
        yield Gateway(proc, base, db, log, ids, http)
    finally:
        await http.aclose()
        await stop_group(proc, grace_s=20)


async def wait_states(
    gw: Gateway, want: str = "ready", timeout_s: float = 120.0
) -> tuple[float, dict[str, str]]:
    """Wait until every drone is in state ``want`` (or the timeout); return (seconds waited, states)."""
    t0 = time.monotonic()
    states: dict[str, str] = {}
    while time.monotonic() - t0 < timeout_s:
        with contextlib.suppress(httpx.HTTPError):
            states = {v["id"]: str(v.get("state")) for v in await gw.vehicles()}
            if states and all(s == want for s in states.values()):
                break
        await asyncio.sleep(0.5)
    return time.monotonic() - t0, states


@contextlib.contextmanager
def workdir(prefix: str) -> Any:
    path = Path(tempfile.mkdtemp(prefix=f"bench-{prefix}-"))
    try:
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


# --- MCP ---------------------------------------------------------------------------------------


def mcp_client(url: str, name: str = "bench") -> Any:
    """An MCP client over Streamable HTTP (use as ``async with``)."""
    from mcp import Client
    from mcp.types import Implementation

    return Client(url, client_info=Implementation(name=name, version="1"))


def structured(result: Any) -> dict[str, Any]:
    """The structured result of a tool call; raises with the tool's error text when it failed."""
    if result.is_error:
        text = result.content[0].text if result.content else repr(result)
        raise RuntimeError(f"tool error: {text}")
    return result.structured_content or {}


async def timed(coro: Any) -> tuple[float, Any]:
    t0 = time.perf_counter()
    value = await coro
    return time.perf_counter() - t0, value


def dumps(obj: Any) -> str:
    return json.dumps(obj, separators=(",", ":"), ensure_ascii=False)


if __name__ == "__main__":
    print(machine_line(machine()))
