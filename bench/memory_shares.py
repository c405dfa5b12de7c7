"""Memory shares of a gateway: what its start keeps beyond the libraries a running gateway needs, and
where each further drone's memory goes.

1. ``serve`` with no drone, its RSS once it answers ``/healthz``, and which of the modules a start keeps
   out it has loaded: on a new database (the first start
   runs Alembic's upgrade), again on that database (current: Alembic is not imported), and again with
   ``rich`` kept out of the process (the MCP SDK's ``MCPServer`` imports it for its logging handler
   whenever it is installed). Each start is a process of its own.
2. A gateway at rest with 1 and with ``1 + --more`` drones of the simulator, tracemalloc started in the
   gateway at its start (a ``sitecustomize`` on its PYTHONPATH) and a snapshot taken at rest: the Python
   objects each further drone adds, in all and by file and line. What a drone adds to the RSS beyond
   them (``bench/memory.py`` prints the RSS growth) is outside Python's allocator.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path
from typing import Any

import common

#: how long a gateway tracing its allocations from its first import may take to answer /healthz: the
#: tracing makes its start several times slower, more so on a busy machine
START_S = 300.0

# The child of part 1: serve in the main thread; a watcher thread waits until it answers, writes its RSS
# and what it imported, and stops it.
START_CHILD = r"""
import json, os, signal, sys, threading, time, urllib.error, urllib.request

port, out = sys.argv[1], sys.argv[2]
for name in filter(None, os.environ.get("SHARES_BLOCK", "").split(",")):
    sys.modules[name] = None  # an import of it fails as if it were not installed

def rss_mib():
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmRSS"):
                return int(line.split()[1]) / 1024

def watch():
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/healthz", timeout=2)
            break
        except urllib.error.HTTPError:
            break
        except OSError:
            time.sleep(0.1)
    kept_out = ("alembic", "mako", "pygments", "rich", "cryptography", "httpx2", "mcp.client")
    loaded = [name for name in kept_out if sys.modules.get(name)]
    with open(out, "w") as fh:
        json.dump({"rss_mib": rss_mib(), "modules": len(sys.modules), "loaded": loaded}, fh)
    os.kill(os.getpid(), signal.SIGINT)

threading.Thread(target=watch, daemon=True).start()
from gateway.cli import main
sys.exit(main(["serve", "--port", port]))
"""

# Put on the gateway's PYTHONPATH in part 2: tracemalloc from the start, a snapshot on SIGUSR1.
SITECUSTOMIZE = r"""
import os, signal
if os.environ.get("SHARES_SNAPSHOT"):
    import gc, tracemalloc
    tracemalloc.start(1)
    def _snapshot(*_):
        gc.collect()
        tracemalloc.take_snapshot().dump(os.environ["SHARES_SNAPSHOT"])
    signal.signal(signal.SIGUSR1, _snapshot)
"""


def start_once(workdir: Path, block: str = "") -> dict[str, Any]:
    from gateway.util.ports import free_tcp_port

    out = workdir / "start.json"
    out.unlink(missing_ok=True)
    child = workdir / "start_child.py"
    child.write_text(START_CHILD)
    env = {
        **os.environ,
        "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{workdir / 'gateway.db'}",
        "GATEWAY_HOST": "127.0.0.1",
        "GATEWAY_LOG_LEVEL": "WARNING",
        "SHARES_BLOCK": block,
    }
    subprocess.run(
        [sys.executable, str(child), str(free_tcp_port()), str(out)],
        cwd=workdir, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=180, check=False,
    )  # fmt: skip
    if not out.exists():
        raise RuntimeError("the gateway did not answer /healthz")
    result: dict[str, Any] = json.loads(out.read_text())
    return result


def starts() -> None:
    with common.workdir("shares-start") as wd:
        rows = [
            ("new database (first start)", start_once(wd)),
            ("the same database (current)", start_once(wd)),
            ("the same, rich kept out", start_once(wd, block="rich")),
        ]
    print(
        "| `serve`, no drone | RSS MiB | modules "
        "| of Alembic, Mako, Pygments, rich, cryptography, httpx2, the MCP client loaded |"
    )
    print("|---|---|---|---|")
    for what, r in rows:
        print(f"| {what} | {r['rss_mib']:.1f} | {r['modules']} | {', '.join(r['loaded']) or 'none'} |")


async def snapshot(n: int, hooks: Path, out: Path) -> tuple[float, int]:
    env = {"PYTHONPATH": os.pathsep.join(filter(None, [str(hooks), os.environ.get("PYTHONPATH", "")]))}
    env["SHARES_SNAPSHOT"] = str(out)
    with common.workdir(f"shares{n}") as wd:
        async with (
            common.sim(n, speedup=1.0, workdir=wd) as sim_,
            common.gateway(sim_, workdir=wd, env=env, start_s=START_S) as gw,
        ):
            _t, states = await common.wait_states(gw, "ready", 90.0 + 3.0 * n)
            await asyncio.sleep(10.0)  # at rest
            os.kill(gw.pid, signal.SIGUSR1)
            await asyncio.to_thread(wait_for_file, out, 60.0)
            return common.rss_kb(gw.pid) / 1024, sum(1 for s in states.values() if s == "ready")


def wait_for_file(path: Path, within_s: float) -> None:
    """Until ``path`` exists and its size has stopped growing (the dump is written whole)."""
    deadline = time.monotonic() + within_s
    size = -1
    while time.monotonic() < deadline:
        now = path.stat().st_size if path.exists() else -1
        if now > 0 and now == size:
            return
        size = now
        time.sleep(0.5)
    raise RuntimeError(f"no tracemalloc snapshot in {path} after {within_s:g} s")


def short(filename: str) -> str:
    for marker in ("site-packages/", "/python3.11/", str(common.ROOT) + "/"):
        if marker in filename:
            return filename.split(marker, 1)[1]
    return filename


async def per_drone(more: int, top: int) -> None:
    with tempfile.TemporaryDirectory(prefix="bench-shares-") as tmp:
        hooks = Path(tmp)
        (hooks / "sitecustomize.py").write_text(SITECUSTOMIZE)
        small, large = hooks / "small.snap", hooks / "large.snap"
        _rss1, ready1 = await snapshot(1, hooks, small)
        _rss2, ready2 = await snapshot(1 + more, hooks, large)
        a, b = tracemalloc.Snapshot.load(str(small)), tracemalloc.Snapshot.load(str(large))
    total_a = sum(s.size for s in a.statistics("filename"))
    total_b = sum(s.size for s in b.statistics("filename"))
    print(
        f"\nPython objects, gateway at rest: {total_a / 2**20:.2f} MiB with 1 drone ({ready1} ready), "
        f"{total_b / 2**20:.2f} MiB with {1 + more} ({ready2} ready): "
        f"{(total_b - total_a) / more / 1024:.0f} KiB each further drone (tracemalloc)."
    )
    print("\n| where (file:line) | KiB a drone | blocks a drone |")
    print("|---|---|---|")
    for st in b.compare_to(a, "lineno")[:top]:
        frame = st.traceback[0]
        kib, blocks = st.size_diff / more / 1024, st.count_diff / more
        print(f"| {short(frame.filename)}:{frame.lineno} | {kib:.1f} | {blocks:.0f} |")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--more", type=int, default=10, help="drones added to the one of part 2 (default 10)")
    p.add_argument("--top", type=int, default=12, help="lines listed of what a drone adds (default 12)")
    p.add_argument("--no-drones", action="store_true", help="part 1 only")
    args = p.parse_args()
    print(common.machine_line(common.machine()))
    starts()
    if not args.no_drones:
        asyncio.run(per_drone(args.more, args.top))


if __name__ == "__main__":
    main()
