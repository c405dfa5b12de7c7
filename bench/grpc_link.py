"""The gateway's link to mavsdk_server, weighed: grpcio with mavsdk_grpc's plugin wrappers against grpclib.

One real ArduCopter SITL (real time, ``eval "$(../shared/sitl/install)"``) and one mavsdk_server, as a
gateway's sidecar starts it (``--sysid 245 --compid 190``, gRPC on a loopback TCP port). The telemetry
rates are asked for as the gateway asks for them at rest (``STREAM_RATES_HZ`` less the ArduPilot
dialect's skipped streams, MAV_CMD_SET_MESSAGE_INTERVAL through mavlink_direct), by a child process that
ends before anything is measured. Then each client runs in a fresh child process of its own, one after
the other, against the same sidecar:

* ``baseline``: asyncio and ``gateway.util.bare_package``, no link: what every other figure stands on;
* ``grpcio-wrappers``: the gateway's former path (grpcio's asyncio channel and mavsdk_grpc's 9 plugin
  wrappers, their ``*_pb2`` and ``*_pb2_grpc`` modules);
* ``grpcio-pb2``: grpcio's asyncio channel with the 9 plugins' ``*_pb2`` messages, no wrappers;
* ``grpclib-pb2``: grpclib (pure-Python asyncio gRPC over h2) with the same ``*_pb2`` messages, no
  wrappers and no grpcio: ``Channel.request`` with the method's path and its message classes (the
  gateway's path now is this, through ``gateway.link.mavsdk_system.System``).

Each opens the streams ``gateway/link/telemetry_feed.py`` subscribes on ArduPilot (``STREAMS``) and
makes one unary call (``UNARY``), waits for the first position and settles, then counts what arrives
over the window at rest; ``--session`` adds the streams the gateway's MAVSDK session opens besides
(``SESSION_STREAMS``: HEARTBEAT, COMMAND_ACK and EKF_STATUS_REPORT through mavlink_direct, the
connection state), ``--channels K`` opens K channels with all their streams per client (K drones'
links in one process, each to a loopback address of its own: ``channel_host``).

Printed for each client: RSS after the subscriptions and RSS / PSS at the window's end
(``/proc/<pid>/statm``, ``smaps_rollup``; that RSS split into anonymous and file pages, ``status``),
stream items a second, CPU seconds per 1,000 items (the sum of its threads' run time,
``/proc/<pid>/task/*/schedstat``; in brackets the same from ``/proc/<pid>/stat``'s clock ticks) and the
sidecar's CPU over the same window. An item is counted and dropped: the gateway's
own conversion into its cache would come on top in either link.

Without the SITL the benchmark says so and skips.
"""

from __future__ import annotations

# Only the standard library at the top: each client runs this file as a fresh child process
# (``--child``), whose memory is the figure, so a child imports nothing but what its client needs;
# bench/common.py (httpx) and the test helpers are imported by the parent, in ``main``.
import argparse
import asyncio
import contextlib
import functools
import importlib
import importlib.util
import json
import os
import sys
import tempfile
import time
import types
from collections.abc import AsyncIterator, Awaitable, Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

#: The streams ``gateway.link.telemetry_feed.TelemetryFeed.start`` subscribes on ArduPilot, as (plugin,
#: the wrapper's method, its argument): all but ``flight_mode``, which the feed never subscribes where
#: the link names the mode from the HEARTBEAT itself (ArduPilot's dialect does)
Stream = tuple[str, str, str | None]
STREAMS: tuple[Stream, ...] = (
    ("telemetry", "position", None),
    ("telemetry", "home", None),
    ("telemetry", "attitude_euler", None),
    ("telemetry", "velocity_ned", None),
    ("telemetry", "battery", None),
    ("telemetry", "gps_info", None),
    ("telemetry", "landed_state", None),
    ("telemetry", "health", None),
    ("telemetry", "rc_status", None),
    ("telemetry", "imu", None),
    ("telemetry", "raw_imu", None),
    ("telemetry", "odometry", None),
    ("telemetry", "status_text", None),
    ("mission_raw", "mission_progress", None),
)
#: With ``--session``, the streams ``gateway.link.mavsdk_session.MavsdkSession.start`` adds on ArduPilot
#: (its events loop waits for an autopilot that speaks the events protocol, and SIMSTATE ends at the first)
SESSION_STREAMS: tuple[Stream, ...] = (
    ("mavlink_direct", "message", "HEARTBEAT"),
    ("mavlink_direct", "message", "COMMAND_ACK"),
    ("mavlink_direct", "message", "EKF_STATUS_REPORT"),
    ("core", "connection_state", None),
)
#: the one unary call each client makes (mavsdk_server answers it)
UNARY = ("action", "get_takeoff_altitude")
#: the plugins the gateway uses (``gateway.link.mavsdk_system.PLUGINS``): a link without the wrappers
#: still loads their ``*_pb2`` modules
PLUGINS = (
    "action",
    "core",
    "events",
    "info",
    "mavlink_direct",
    "mission",
    "mission_raw",
    "param",
    "telemetry",
)
#: the grpcio client as the gateway ran it (without gRPC's EventEngine client)
CLIENT_EXPERIMENTS = "-event_engine_client,-event_engine_for_all_other_endpoints,-event_engine_callback_cq"
KINDS = {
    "baseline": "asyncio only, no link",
    "grpcio-wrappers": "grpcio + mavsdk_grpc's wrappers (the gateway's former path)",
    "grpcio-pb2": "grpcio + the *_pb2 messages, no wrappers",
    "grpclib-pb2": "grpclib + the *_pb2 messages, no grpcio",
}
GCS_SYSID, GCS_COMPID = 245, 190  # the gateway's defaults (Settings.gcs_sysid; gateway.link.sidecar)
FIRST_POSITION_S = 60.0  # a child's deadline for its first position
SETTLE_S = 6.0  # then every stream asked for at 0.2 Hz has had its first item
MAV_CMD_SET_MESSAGE_INTERVAL = 511


def camel(name: str) -> str:
    """MAVSDK's snake_case name as its proto spells it: ``gps_info`` -> ``GpsInfo``."""
    return "".join(part[:1].upper() + part[1:] for part in name.split("_"))


def label(stream: Stream) -> str:
    """A stream's name in the figures: its argument (a MAVLink message's name) or its method's."""
    return stream[2] or stream[1]


def stream_rpc(name: str) -> str:
    """The RPC behind a wrapper's stream: ``position`` -> ``SubscribePosition``."""
    return "Subscribe" + camel(name)


def resolve(module: types.ModuleType, plugin: str, rpc: str) -> tuple[str, Any, Any, bool]:
    """The method ``rpc`` of ``plugin``'s service in its ``*_pb2`` module: its path, request and reply
    classes and whether it streams. Any: protobuf's generated classes, untyped."""
    service = module.DESCRIPTOR.services_by_name[camel(plugin) + "Service"]
    method = service.methods_by_name[rpc]
    request = getattr(module, method.input_type.name)
    reply = getattr(module, method.output_type.name)
    return f"/{service.full_name}/{rpc}", request, reply, bool(method.server_streaming)


# --- the child: one client --------------------------------------------------------------------------

Counter = Callable[[str], None]
Streams = tuple[Stream, ...]
Tasks = set[asyncio.Task[None]]
Opened = tuple[Callable[[], Awaitable[None]], object]  # how to close it, and the unary call's answer


def _load_pb2() -> dict[str, types.ModuleType]:
    """The 9 plugins' ``*_pb2`` modules, loaded as the gateway loads mavsdk_grpc: without its package
    ``__init__`` (which imports all 40 plugins)."""
    from gateway.util.bare_package import register_bare_package

    def no_name(_package: types.ModuleType, name: str) -> object:
        raise AttributeError(f"module 'mavsdk_grpc' has no attribute {name!r}")

    register_bare_package("mavsdk_grpc", no_name, "the mavsdk_grpc package (mavsdk-grpc)")
    return {plugin: importlib.import_module(f"mavsdk_grpc.{plugin}_pb2") for plugin in PLUGINS}


def channel_host(index: int) -> str:
    """The address of a client's channel ``index``: one loopback address each (mavsdk_server listens on
    all of them), so that grpcio, which shares one connection between channels to the same address,
    opens one per channel, as it does for drones, each with a sidecar of its own."""
    return f"127.0.0.{index + 1}"


def request_of(request: Any, argument: str | None) -> Any:
    """A stream's request message: empty, or its one field set to ``argument`` (mavlink_direct's
    message name). Any: protobuf's generated classes, untyped."""
    if argument is None:
        return request()
    (field,) = request.DESCRIPTOR.fields
    return request(**{field.name: argument})


async def _pump(items: Callable[[], AsyncIterator[object]], name: str, count: Counter) -> None:
    async for _item in items():
        count(name)


async def open_baseline(
    _port: int, _channels: int, _streams: Streams, _count: Counter, _tasks: Tasks
) -> Opened:
    import gateway.util.bare_package  # noqa: F401 - every other client loads it

    async def close() -> None:
        return None

    return close, None


async def open_wrappers(port: int, channels: int, streams: Streams, count: Counter, tasks: Tasks) -> Opened:
    """mavsdk_grpc's wrappers of the 9 plugins on grpcio's channel, as the gateway's link was before it
    moved to grpclib (``gateway.link.mavsdk_system`` then)."""
    os.environ.setdefault("GRPC_EXPERIMENTS", CLIENT_EXPERIMENTS)
    _load_pb2()  # the bare package: the wrappers asked for, not the package's 40
    from mavsdk_grpc.async_plugin_manager import AsyncPluginManager

    wrappers = {p: getattr(importlib.import_module(f"mavsdk_grpc.{p}"), camel(p)) for p in PLUGINS}
    managers = []
    answer: object = None
    for index in range(channels):
        manager = await AsyncPluginManager.create(host=channel_host(index), port=port)
        managers.append(manager)
        plugins = {name: make(manager) for name, make in wrappers.items()}
        answer = await asyncio.wait_for(getattr(plugins[UNARY[0]], UNARY[1])(), 10.0)
        for stream in streams:
            plugin, method, argument = stream
            subscribe = getattr(plugins[plugin], method)
            items = functools.partial(subscribe, argument) if argument is not None else subscribe
            tasks.add(asyncio.create_task(_pump(items, label(stream), count)))

    async def close() -> None:
        for manager in managers:
            await manager.channel.close(grace=None)

    return close, answer


async def open_grpcio_pb2(port: int, channels: int, streams: Streams, count: Counter, tasks: Tasks) -> Opened:
    os.environ.setdefault("GRPC_EXPERIMENTS", CLIENT_EXPERIMENTS)
    modules = _load_pb2()
    from grpc import aio

    opened = []
    answer: object = None
    for index in range(channels):
        channel = aio.insecure_channel(f"{channel_host(index)}:{port}")
        await channel.channel_ready()
        opened.append(channel)
        path, request, reply, _ = resolve(modules[UNARY[0]], UNARY[0], camel(UNARY[1]))
        unary = channel.unary_unary(path, request_serializer=request.SerializeToString,
                                    response_deserializer=reply.FromString)  # fmt: skip
        answer = (await unary(request(), timeout=10.0)).altitude
        for stream in streams:
            plugin, method, argument = stream
            path, request, reply, _ = resolve(modules[plugin], plugin, stream_rpc(method))
            call = channel.unary_stream(path, request_serializer=request.SerializeToString,
                                        response_deserializer=reply.FromString)  # fmt: skip
            items = functools.partial(call, request_of(request, argument))
            tasks.add(asyncio.create_task(_pump(items, label(stream), count)))

    async def close() -> None:
        for channel in opened:
            await channel.close(grace=None)

    return close, answer


async def open_grpclib_pb2(
    port: int, channels: int, streams: Streams, count: Counter, tasks: Tasks
) -> Opened:
    modules = _load_pb2()
    from grpclib.client import Channel
    from grpclib.const import Cardinality

    async def items(channel: Channel, path: str, message: Any, reply: Any) -> AsyncIterator[object]:
        async with channel.request(path, Cardinality.UNARY_STREAM, type(message), reply) as call:
            await call.send_message(message, end=True)
            while (item := await call.recv_message()) is not None:
                yield item

    opened = []
    answer: object = None
    for index in range(channels):
        channel = Channel(channel_host(index), port)
        opened.append(channel)
        path, request, reply, _ = resolve(modules[UNARY[0]], UNARY[0], camel(UNARY[1]))
        async with channel.request(path, Cardinality.UNARY_UNARY, request, reply, timeout=10.0) as call:
            await call.send_message(request(), end=True)
            answer = (await call.recv_message()).altitude
        for stream in streams:
            plugin, method, argument = stream
            path, request, reply, _ = resolve(modules[plugin], plugin, stream_rpc(method))
            subscribe = functools.partial(items, channel, path, request_of(request, argument), reply)
            tasks.add(asyncio.create_task(_pump(subscribe, label(stream), count)))

    async def close() -> None:
        for channel in opened:
            channel.close()

    return close, answer


OPENERS = {
    "baseline": open_baseline,
    "grpcio-wrappers": open_wrappers,
    "grpcio-pb2": open_grpcio_pb2,
    "grpclib-pb2": open_grpclib_pb2,
}


def _say(event: str, **fields: object) -> None:
    print(json.dumps({"event": event, **fields}), flush=True)


async def _first_position(counts: dict[str, int], kind: str) -> None:
    deadline = time.monotonic() + FIRST_POSITION_S
    while kind != "baseline" and counts["position"] == 0:
        if time.monotonic() > deadline:
            raise SystemExit(f"{kind}: no position within {FIRST_POSITION_S:g} s")
        await asyncio.sleep(0.1)
    await asyncio.sleep(SETTLE_S)


async def child(kind: str, port: int, channels: int, streams: Streams) -> None:
    """One client: open it, say ``subscribed``; then ``start`` zeroes the counts, ``stop`` reports them,
    the end of standard input closes the client."""
    counts = {label(stream): 0 for stream in streams}

    def count(name: str) -> None:
        counts[name] += 1

    tasks: set[asyncio.Task[None]] = set()
    close, answer = await OPENERS[kind](port, channels, streams, count, tasks)
    await _first_position(counts, kind)
    _say("subscribed", unary=answer, modules=len(sys.modules))
    reader = asyncio.StreamReader()
    loop = asyncio.get_running_loop()
    await loop.connect_read_pipe(lambda: asyncio.StreamReaderProtocol(reader), sys.stdin)
    while line := (await reader.readline()).decode().strip():
        if line == "start":
            counts.update(dict.fromkeys(counts, 0))
            _say("started")
        elif line == "stop":
            _say("counts", counts=counts)
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    await close()


async def set_rates(port: int) -> None:
    """Ask for the gateway's rest rates, as its session does (a child of its own, ended before anything
    is measured): prints each stream's MAV_RESULT."""
    from gateway.fleet.dialects.ardupilot import ArduPilot
    from gateway.link.mavsdk_system import System
    from gateway.link.rawlink import MAV_RESULT, CommandChannel, NoAck
    from gateway.link.telemetry_feed import MESSAGE_IDS, STREAM_RATES_HZ

    system = System("127.0.0.1", port)
    await system.connect()
    channel = CommandChannel(GCS_SYSID)
    pump = asyncio.create_task(channel.pump(system))
    results: dict[str, str] = {}
    for name, hz in STREAM_RATES_HZ.items():
        if name in ArduPilot.skipped_streams:
            continue
        params = (MESSAGE_IDS[name], 1e6 / hz)
        try:
            result = await channel.send(system, lambda aw: asyncio.wait_for(aw, 5.0), 1,
                                        MAV_CMD_SET_MESSAGE_INTERVAL, params)  # fmt: skip
        except NoAck:
            results[name] = "no answer"
            continue
        results[name] = MAV_RESULT.get(result, str(result))
    pump.cancel()
    await asyncio.gather(pump, return_exceptions=True)
    await system.close()
    _say("rates", results=results)


def child_main(argv: list[str]) -> int:
    """``--child KIND PORT CHANNELS [session]``, as the parent runs it."""
    kind, port, channels = argv[0], int(argv[1]), int(argv[2])
    if kind == "rates":
        asyncio.run(set_rates(port))
    else:
        streams = STREAMS + SESSION_STREAMS if argv[3:4] == ["session"] else STREAMS
        asyncio.run(child(kind, port, channels, streams))
    return 0


# --- the parent: the SITL, the sidecar, the clients one after the other ---------------------------------


def _installed(name: str) -> bool:
    return importlib.util.find_spec(name) is not None


def missing_pieces(
    ardupilot_missing: Callable[[], str | None], installed: Callable[[str], bool] = _installed
) -> str | None:
    """Why the benchmark cannot run here (None when it can)."""
    if not installed("grpclib"):
        return "grpclib is not installed (a dependency of the gateway since its link speaks it): make install"
    return ardupilot_missing()


def _autopilots() -> types.ModuleType:
    """tests/helpers/autopilots.py without the helpers' package ``__init__``, which imports mavsdk_grpc
    (and so grpcio): the parent loads no gRPC, so that no page of it is shared with a child's (PSS)."""
    from gateway.util.bare_package import own_init_when_missed, register_bare_package

    register_bare_package("tests.helpers", own_init_when_missed("tests.helpers"), "the tests' helpers")
    return importlib.import_module("tests.helpers.autopilots")


def _mavsdk_server_binary() -> Path:
    spec = importlib.util.find_spec("mavsdk_grpc")  # found without running its __init__
    assert spec is not None and spec.submodule_search_locations is not None
    return Path(next(iter(spec.submodule_search_locations))) / "bin" / "mavsdk_server"


async def _port_open(port: int) -> bool:
    try:
        _reader, writer = await asyncio.open_connection("127.0.0.1", port)
    except OSError:
        return False
    writer.close()
    with contextlib.suppress(OSError):
        await writer.wait_closed()
    return True


@contextlib.asynccontextmanager
async def mavsdk_server(url: str, folder: Path) -> AsyncIterator[tuple[asyncio.subprocess.Process, int]]:
    """mavsdk_server as the gateway's sidecar runs it, serving once it has found the vehicle."""
    import common

    from gateway.util.ports import free_tcp_port

    port = free_tcp_port()
    log = os.open(folder / "mavsdk_server.log", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    argv = [str(_mavsdk_server_binary()), "-p", str(port), "--sysid", str(GCS_SYSID), "--compid",
            str(GCS_COMPID), url]  # fmt: skip
    proc = await asyncio.create_subprocess_exec(
        *argv, stdout=log, stderr=log, stdin=asyncio.subprocess.DEVNULL, start_new_session=True
    )
    os.close(log)  # the child keeps its own copy
    try:
        deadline = time.monotonic() + 120.0
        while not await _port_open(port):
            if proc.returncode is not None or time.monotonic() > deadline:
                text = (folder / "mavsdk_server.log").read_text(errors="replace")[-2000:]
                raise SystemExit(f"mavsdk_server did not serve within 120 s:\n{text}")
            await asyncio.sleep(0.2)
        yield proc, port
    finally:
        await common.stop_group(proc)


async def _event(proc: asyncio.subprocess.Process, name: str, timeout_s: float) -> dict[str, Any]:
    assert proc.stdout is not None
    while True:
        raw = await asyncio.wait_for(proc.stdout.readline(), timeout_s)
        if not raw:
            raise RuntimeError(f"the child ended before {name!r}")
        with contextlib.suppress(ValueError):
            message = json.loads(raw)
            if isinstance(message, dict) and message.get("event") == name:
                return message


@dataclass(frozen=True)
class Plan:
    """What one run measures: the clients in order, the window, channels per client, the streams."""

    kinds: tuple[str, ...]
    seconds: float
    channels: int = 1
    session: bool = False

    @property
    def streams(self) -> Streams:
        return STREAMS + SESSION_STREAMS if self.session else STREAMS


async def _spawn(kind: str, port: int, plan: Plan, log: Path) -> asyncio.subprocess.Process:
    err = os.open(log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    argv = ["--child", kind, str(port), str(plan.channels), *(["session"] if plan.session else [])]
    try:
        return await asyncio.create_subprocess_exec(
            sys.executable, __file__, *argv,
            stdin=asyncio.subprocess.PIPE, stdout=asyncio.subprocess.PIPE, stderr=err,
        )  # fmt: skip
    finally:
        os.close(err)


def stat_cpu_seconds(pid: int) -> float:
    """utime + stime from ``/proc/<pid>/stat`` (clock ticks; threads that ended included)."""
    import common

    try:
        with open(f"/proc/{pid}/stat") as fh:
            fields = fh.read().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / common.CLK_TCK


def rss_split_kb(pid: int) -> tuple[int, int]:
    """RssAnon and RssFile from ``/proc/<pid>/status``, KiB: the heap, and the pages of files mapped
    (shared objects: how much of them is resident follows the page cache, docs/benchmarks.md)."""
    fields = {"RssAnon:": 0, "RssFile:": 0}
    with contextlib.suppress(OSError), open(f"/proc/{pid}/status") as fh:
        for line in fh:
            key, *rest = line.split()
            if key in fields and rest:
                fields[key] = int(rest[0])
    return fields["RssAnon:"], fields["RssFile:"]


def _cpu(pid: int, server_pid: int) -> tuple[float, float, float]:
    """The client's CPU seconds (threads' run time, and /proc/<pid>/stat's ticks), the sidecar's."""
    import common

    return common.cpu_seconds(pid), stat_cpu_seconds(pid), common.cpu_seconds(server_pid)


async def measure(kind: str, port: int, server_pid: int, plan: Plan, folder: Path) -> dict[str, Any]:
    """One client in its own process: memory after its subscriptions and after the window, what it
    received and its CPU over the window."""
    import common

    log = folder / f"{kind}.log"
    proc = await _spawn(kind, port, plan, log)
    assert proc.stdin is not None
    try:
        try:
            subscribed = await _event(proc, "subscribed", FIRST_POSITION_S + SETTLE_S + 60.0)
        except (RuntimeError, TimeoutError):
            raise SystemExit(
                f"{kind}: no subscriptions:\n{log.read_text(errors='replace')[-3000:]}"
            ) from None
        rss_subscribed = common.rss_kb(proc.pid)
        proc.stdin.write(b"start\n")
        await _event(proc, "started", 30.0)
        before, t0 = _cpu(proc.pid, server_pid), time.monotonic()
        await asyncio.sleep(plan.seconds)
        after, elapsed = _cpu(proc.pid, server_pid), time.monotonic() - t0
        proc.stdin.write(b"stop\n")
        counts = (await _event(proc, "counts", 30.0))["counts"]
        rss_end, smaps, (anon, files) = (
            common.rss_kb(proc.pid),
            common.smaps_kb(proc.pid),
            rss_split_kb(proc.pid),
        )
        proc.stdin.close()
        await asyncio.wait_for(proc.wait(), 30.0)
    finally:
        if proc.returncode is None:
            proc.kill()
            await proc.wait()
    cpu, stat_cpu, sidecar_cpu = (b - a for a, b in zip(before, after, strict=True))
    return {
        "kind": kind,
        "unary": subscribed.get("unary"),
        "modules": subscribed.get("modules"),
        "rss_subscribed": rss_subscribed / 1024,
        "rss": rss_end / 1024,
        "pss": smaps["pss"] / 1024,
        "anon": anon / 1024,
        "file": files / 1024,
        "elapsed": elapsed,
        "items": sum(counts.values()),
        "rates": {name: n / elapsed for name, n in counts.items()},
        "cpu": cpu,
        "stat_cpu": stat_cpu,
        "sidecar_cpu": sidecar_cpu,
    }


async def set_rest_rates(port: int, folder: Path) -> dict[str, str]:
    proc = await _spawn("rates", port, Plan((), 0.0), folder / "rates.log")
    try:
        return (await _event(proc, "rates", 120.0))["results"]
    except (RuntimeError, TimeoutError):
        text = (folder / "rates.log").read_text(errors="replace")[-3000:]
        raise SystemExit(f"the rates were not set:\n{text}") from None
    finally:
        if proc.returncode is None:
            await asyncio.wait_for(proc.wait(), 30.0)


async def run(plan: Plan) -> tuple[dict[str, str], list[dict[str, Any]]]:
    autopilots = _autopilots()
    with tempfile.TemporaryDirectory(prefix="grpc-link-") as tmp:
        folder = Path(tmp)
        with autopilots.arducopter(folder, speedup=1.0, sysid=1, taken=set()) as pilot:
            async with mavsdk_server(pilot.url, folder) as (server, port):
                rates = await set_rest_rates(port, folder)
                results = [await measure(kind, port, server.pid, plan, folder) for kind in plan.kinds]
    return rates, results


def _row(r: dict[str, Any]) -> list[object]:
    items, elapsed = r["items"], r["elapsed"]
    per_k = f"{1000 * r['cpu'] / items:.3f} ({1000 * r['stat_cpu'] / items:.2f})" if items else "-"
    return [
        r["kind"], f"{r['rss_subscribed']:.1f}", f"{r['rss']:.1f} / {r['pss']:.1f}",
        f"{r['anon']:.1f} / {r['file']:.1f}", f"{items / elapsed:.2f}",
        per_k, f"{100 * r['cpu'] / elapsed:.2f}", f"{100 * r['sidecar_cpu'] / elapsed:.2f}", r["modules"],
        "-" if r["unary"] is None else f"{r['unary']:g} m",
    ]  # fmt: skip


HEADERS = [
    "client", "RSS subscribed, MiB", "RSS / PSS at the end, MiB", "RSS anon / file", "items/s",
    "CPU s per 1,000 items (stat)", "CPU % of a core", "sidecar CPU %", "modules", "unary answer",
]  # fmt: skip


def render(rates: dict[str, str], results: list[dict[str, Any]], plan: Plan, loads: tuple[str, str]) -> str:
    import common

    flowing = [r for r in results if r["items"]]
    stream_rows = [
        [label(stream), *(f"{r['rates'][label(stream)]:.2f}" for r in flowing)] for stream in plan.streams
    ]
    lines = [
        f"One ArduCopter SITL (real time) at rest, one mavsdk_server; {plan.channels} channel(s) per "
        f"client, {len(plan.streams)} streams each; a {plan.seconds:g} s window; load average (1 min) "
        f"{loads[0]} at the start, {loads[1]} at the end.",
        "Rates asked for: " + ", ".join(f"{k} {v}" for k, v in rates.items()) + ".",
        "",
        common.table(HEADERS, [_row(r) for r in results]),
        "",
        common.table(["stream, items/s", *(r["kind"] for r in flowing)], stream_rows),
    ]
    by_kind = {r["kind"]: r for r in results}
    old, new = by_kind.get("grpcio-wrappers"), by_kind.get("grpclib-pb2")
    if old and new and old["items"] and new["items"]:
        lines += [
            "",
            f"grpclib-pb2 against grpcio-wrappers: RSS {new['rss'] - old['rss']:+.1f} MiB, PSS "
            f"{new['pss'] - old['pss']:+.1f} MiB; CPU per 1,000 items "
            f"{(new['cpu'] / new['items']) / (old['cpu'] / old['items']):.2f}x.",
        ]
    return "\n".join(lines)


def parse(argv: list[str]) -> Plan:
    """The command line as a Plan; a bad value exits with one line naming it."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--full", action="store_true", help="a 180 s window instead of 60 s")
    p.add_argument("--seconds", type=float, help="the window at rest, s (default 60; 180 with --full)")
    p.add_argument("--channels", type=int, default=1, help="channels per client, each with every stream")
    p.add_argument("--clients", default=",".join(KINDS), help=f"which, in order (of {', '.join(KINDS)})")
    p.add_argument("--session", action="store_true", help="the session's streams too (SESSION_STREAMS)")
    args = p.parse_args(argv)
    seconds = args.seconds if args.seconds is not None else 180.0 if args.full else 60.0
    if not 0 < seconds < float("inf"):
        p.error(f"--seconds: {seconds:g} is not a window (accepted: a number of seconds above 0)")
    if not 1 <= args.channels <= 254:
        p.error(f"--channels: {args.channels} is not a number of channels (accepted: 1 to 254)")
    kinds = tuple(args.clients.split(","))
    unknown = [k for k in kinds if k not in KINDS]
    if unknown:
        p.error(
            f"--clients: {', '.join(unknown)} unknown (accepted: a comma-separated list of "
            f"{', '.join(KINDS)})"
        )
    return Plan(kinds, seconds, args.channels, args.session)


def main(argv: list[str]) -> int:
    import common

    plan = parse(argv)
    sys.path.insert(0, str(common.ROOT))
    why = missing_pieces(lambda: _autopilots().ardupilot_missing())
    if why:
        print(f"SKIPPED: {why}")
        return 0
    info = common.machine()
    print(common.machine_line(info), flush=True)
    rates, results = asyncio.run(run(plan))
    loads = (
        info["load average (1/5/15 min) at start"].split()[0],
        Path("/proc/loadavg").read_text().split()[0],
    )
    print(render(rates, results, plan, loads))
    return 0


if __name__ == "__main__":
    if sys.argv[1:2] == ["--child"]:
        raise SystemExit(child_main(sys.argv[2:]))
    raise SystemExit(main(sys.argv[1:]))
