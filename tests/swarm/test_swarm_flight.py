"""Five drones on their own hosts, one gateway, one LLM-side MCP client: a formation flight end to end.

The network is the compose file's, built from Linux network namespaces (`topology.py`): each simulated
drone runs `fleet-gateway sim --count 1 --bind <its address>` inside its own namespace, the gateway
(`fleet-gateway serve`, in the root namespace) reaches each over the bridge at `tcpout://<addr>:5760`, and
the drones are registered with the compose file's one-shot registrar command. Through a real MCP client
over Streamable HTTP the test flies: fleet takeoff, a wedge 150 m away, a circle around the same point,
fleet return to launch (landing). It asserts the final positions against the plans' slots, and that no
two drones came closer than the minimum separation, from the live telemetry sampled every 0.2 s and from
the 1 Hz tracks the gateway recorded. Before it, the namespace network itself: drones reach nothing but
the swarm network, the gateway reaches each. Both tests build the compose file's network, whose fixed
addresses allow one at a time on a machine (topology.py's lock): in one file they run one after the
other on one worker, where in two files one worker could wait for the other's flight.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import secrets
import signal
import socket
import subprocess
import sys
import time
from collections.abc import AsyncIterator
from datetime import datetime
from pathlib import Path
from typing import Any

import httpx
import pytest
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.shared._httpx_utils import create_mcp_http_client
from mcp.types import Implementation

from gateway.fleet import geo
from gateway.util.ports import free_tcp_port
from tests.helpers.procs import tail
from tests.helpers.timing import scaled
from tests.swarm.separation import Sample, closest_approach
from tests.swarm.topology import (
    DRONES,
    GATEWAY_ADDRESS,
    GATEWAY_ENV,
    SwarmNetwork,
    can_create_namespaces,
    drone_address,
    drone_command,
    drone_home,
    drone_id,
    gateway_command,
    register_command,
)

pytestmark = pytest.mark.swarm

_possible, _why = can_create_namespaces()

SPEEDUP = 5.0
MIN_SEPARATION_M = 5.0
SAMPLE_PERIOD_S = 0.2
WAIT_S = scaled(180.0)  # generous: waiting is never an assertion
BIN = Path(sys.executable).parent
OPERATOR_TOKEN = secrets.token_hex(16)  # the compose file requires operator tokens; agents get their own
AGENT_TOKEN = secrets.token_hex(16)
OPERATOR = {"authorization": f"Bearer {OPERATOR_TOKEN}"}


def _program(argv: list[str]) -> list[str]:
    """The topology's command with this environment's `fleet-gateway` executable."""
    return [str(BIN / argv[0]), *argv[1:]]


class Procs:
    """Every process the test starts, stopped (SIGTERM to the group, then SIGKILL) at the end."""

    def __init__(self, logdir: Path) -> None:
        self.logdir = logdir
        self.procs: dict[str, subprocess.Popen] = {}

    def start(self, name: str, argv: list[str], **kw: Any) -> subprocess.Popen:
        log = open(self.logdir / f"{name}.log", "wb")  # the child keeps its own copy
        proc = subprocess.Popen(
            argv, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True, **kw
        )
        log.close()
        self.procs[name] = proc
        return proc

    def log(self, name: str, lines: int = 30) -> str:
        return tail(str(self.logdir / f"{name}.log"), lines)

    def stop_all(self) -> None:
        for proc in self.procs.values():
            if proc.poll() is None:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(proc.pid, signal.SIGTERM)
        deadline = time.monotonic() + scaled(15)
        for proc in self.procs.values():
            try:
                proc.wait(timeout=max(0.1, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(proc.pid, signal.SIGKILL)
                proc.wait(timeout=scaled(5))


def _namespaces(tag: str) -> list[str]:
    listed = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True, check=False).stdout
    return [n for n in listed.split() if n.startswith(f"fgw{tag}")]


def _leftover_sidecars() -> list[int]:
    """mavsdk_server processes still talking to a swarm address (the gateway's sidecars)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            argv = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if argv and b"mavsdk_server" in argv[0] and any(drone_address(0)[:-2].encode() in a for a in argv):
            found.append(int(entry.name))
    return found


async def _wait_for(what: str, check: Any, timeout_s: float = WAIT_S, explain: Any = None) -> Any:
    deadline = time.monotonic() + timeout_s
    while True:
        result = await check()
        if result:
            return result
        if time.monotonic() > deadline:
            raise AssertionError(
                f"{what} not reached within {timeout_s:.0f} s" + (f"\n{explain()}" if explain else "")
            )
        await asyncio.sleep(0.25)


@contextlib.asynccontextmanager
async def swarm(tmp: Path) -> AsyncIterator[str]:
    """The namespaces, five simulators, the gateway and the registrations; all removed on exit."""
    procs = Procs(tmp)
    net = SwarmNetwork(drones=DRONES)
    try:
        net.open()
        for i in range(DRONES):
            procs.start(f"sim-{i}", [*net.exec_prefix(i), *_program(drone_command(i, SPEEDUP))])
        port = free_tcp_port()
        env = {
            **os.environ,
            "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{tmp / 'gateway.db'}",
            "GATEWAY_MIN_SEPARATION_M": str(MIN_SEPARATION_M),
            "GATEWAY_TRACK_FLUSH_S": "0.5",
            "GATEWAY_SIDECAR_BACKOFF_INITIAL_S": "0.2",
            "GATEWAY_SIDECAR_BACKOFF_MAX_S": "1.0",
            "GATEWAY_LOG_LEVEL": "WARNING",
            "GATEWAY_OPERATOR_TOKENS": OPERATOR_TOKEN,
            "GATEWAY_AGENT_TOKENS": AGENT_TOKEN,
            **GATEWAY_ENV,
        }
        procs.start("gateway", _program(gateway_command("127.0.0.1", port)), env=env, cwd=tmp)
        base = f"http://127.0.0.1:{port}"
        async with httpx.AsyncClient(base_url=base, timeout=scaled(10), headers=OPERATOR) as http:

            async def readyz() -> bool:
                if procs.procs["gateway"].poll() is not None:
                    raise AssertionError(f"gateway exited:\n{procs.log('gateway')}")
                with contextlib.suppress(httpx.HTTPError):
                    return (await http.get("/readyz")).status_code == 200
                return False

            await _wait_for("gateway /readyz", readyz, scaled(60))
            # tokens are enforced
            async with httpx.AsyncClient(base_url=base, timeout=scaled(10)) as anonymous:
                assert (await anonymous.get("/api/v1/vehicles")).status_code == 401
                assert (await anonymous.post("/mcp", json={})).status_code == 401
            for i in range(DRONES):
                done = await asyncio.to_thread(  # the registrar finds its token as in compose
                    subprocess.run,
                    _program(register_command(i, base)),
                    capture_output=True,
                    text=True,
                    cwd=tmp,
                    env={**os.environ, "GATEWAY_OPERATOR_TOKENS": OPERATOR_TOKEN},
                )
                assert done.returncode == 0, done.stderr

            async def all_ready() -> bool:
                for name, proc in procs.procs.items():
                    if proc.poll() is not None:
                        raise AssertionError(f"{name} exited:\n{procs.log(name)}")
                items = (await http.get("/api/v1/vehicles")).json()["items"]
                return sorted(v["id"] for v in items if v.get("state") == "ready") == [
                    drone_id(i) for i in range(DRONES)
                ]

            def explain() -> str:
                return "\n".join(f"--- {n}\n{procs.log(n, 10)}" for n in procs.procs)

            await _wait_for("all five drones ready", all_ready, WAIT_S, explain)
        yield base
    finally:
        procs.stop_all()
        net.close()
        assert _namespaces(net.tag) == [], "namespaces left behind"
        for pid in _leftover_sidecars():  # started by our gateway; never left behind
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)


@contextlib.asynccontextmanager
async def _client(base: str, name: str) -> AsyncIterator[Client]:
    """An MCP client over Streamable HTTP with the agent's bearer token (as an agent reaches compose)."""
    http = create_mcp_http_client(headers={"authorization": f"Bearer {AGENT_TOKEN}"})
    async with http, Client(streamable_http_client(f"{base}/mcp", http_client=http),
                            client_info=Implementation(name=name, version="1.0")) as client:  # fmt: skip
        yield client


def _ok(r: Any) -> dict[str, Any]:
    assert not r.is_error, r.content[0].text
    return r.structured_content


async def _finish(c: Client, r: dict[str, Any], figures: dict[str, Any]) -> dict[str, Any]:
    """Keep waiting (monitor_fleet) while a fleet operation answers 'running'."""
    while r["status"] == "running":
        r = _ok(await c.call_tool("monitor_fleet", {"operation_id": r["operation_id"]}))
    figures.setdefault("dispatch_s", {})[r["kind"] + f"#{len(figures['dispatch_s'])}"] = r["dispatch_s"]
    return r


@pytest.mark.skipif(not _possible, reason=f"network namespaces unavailable: {_why}")
def test_gateway_reaches_every_drone_namespace_and_cleanup_is_complete(process_reaper: list) -> None:
    listener = (
        "import socket,sys;s=socket.socket();s.setsockopt(socket.SOL_SOCKET,socket.SO_REUSEADDR,1);"
        "s.bind((sys.argv[1],5760));s.listen();print('up',flush=True);c,a=s.accept();"
        "c.sendall(a[0].encode());c.close()"
    )
    net = SwarmNetwork(drones=2)
    with net:
        names = set(subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.split())
        assert {net.hub, net.drone_namespace(0), net.drone_namespace(1)} <= names
        for index in range(2):
            proc = subprocess.Popen(
                [*net.exec_prefix(index), sys.executable, "-c", listener, drone_address(index)],
                stdout=subprocess.PIPE,
                text=True,
            )
            process_reaper.append(proc)
            assert proc.stdout is not None and proc.stdout.readline().strip() == "up"
            deadline = time.monotonic() + scaled(10)
            while True:
                try:
                    conn = socket.create_connection((drone_address(index), 5760), timeout=scaled(2))
                    break
                except OSError:
                    if time.monotonic() > deadline:
                        raise
                    time.sleep(0.1)
            with conn:
                # the drone sees the gateway's swarm address, as a drone on a real network would
                assert conn.recv(64).decode() == GATEWAY_ADDRESS
        # a drone namespace has no route to anything but its own network
        route = subprocess.run(
            [*net.exec_prefix(0), "ip", "route", "get", "192.0.2.1"], capture_output=True, text=True
        )
        assert route.returncode != 0
    names = set(subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.split())
    assert not any(name.startswith(f"fgw{net.tag}") for name in names)
    links = subprocess.run(["ip", "-o", "link"], capture_output=True, text=True).stdout
    assert f"fgw{net.tag}" not in links


@pytest.mark.skipif(not _possible, reason=f"network namespaces unavailable: {_why}")
@pytest.mark.timeout(scaled(900))
async def test_five_drone_formation_flight_keeps_separation(tmp_path: Path) -> None:
    started = time.monotonic()
    figures: dict[str, Any] = {}
    ids = [drone_id(i) for i in range(DRONES)]
    live: dict[str, list[Sample]] = {d: [] for d in ids}
    stop = asyncio.Event()

    async with swarm(tmp_path) as base:
        figures["setup_s"] = round(time.monotonic() - started, 1)

        async def sample() -> None:
            """Live telemetry of all five drones from one list_drones call, every 0.2 s."""
            async with _client(base, "separation-watch") as watch:
                while not stop.is_set():
                    r = _ok(await watch.call_tool("list_drones", {}))
                    now = time.time()
                    for row in r["drones"]:
                        if row["lat_deg"] is not None and not row["stale"]:
                            live[row["drone_id"]].append((now, row["lat_deg"], row["lon_deg"], row["alt_m"]))
                    with contextlib.suppress(TimeoutError):
                        await asyncio.wait_for(stop.wait(), SAMPLE_PERIOD_S)

        watcher = asyncio.create_task(sample())
        try:
            flight_started = time.monotonic()
            async with _client(base, "swarm-pilot") as c:
                r = await _finish(
                    c, _ok(await c.call_tool("fleet_takeoff", {"drone_ids": ids, "alt_m": 10})), figures
                )
                assert r["status"] == "succeeded", r
                drones = {d["drone_id"]: d for d in r["drones"]}
                assert max(d["sent_after_s"] for d in drones.values()) <= min(
                    d["accepted_after_s"] for d in drones.values()
                ), "every takeoff was sent before the first was accepted"

                # a wedge 150 m north of the fleet's centre
                home_lat, home_lon = (float(x) for x in drone_home(2).split(",")[:2])
                centre = geo.offset_position(home_lat, home_lon, 150.0, 0.0)
                for formation in ("wedge", "circle"):
                    args = {
                        "drone_ids": ids, "formation": formation, "center_lat_deg": centre[0],
                        "center_lon_deg": centre[1], "alt_m": 20, "spacing_m": 15,
                    }  # fmt: skip
                    r = _ok(await c.call_tool("formation_goto", args))
                    r = await _finish(c, r, figures)
                    assert r["status"] == "succeeded", r
                    figures[f"{formation}_planned_clearance_m"] = r["plan"]["min_clearance_m"]
                    now = {
                        row["drone_id"]: row for row in _ok(await c.call_tool("list_drones", {}))["drones"]
                    }
                    for slot in r["drones"]:
                        pos = now[slot["drone_id"]]
                        off = geo.horizontal_distance_m(
                            pos["lat_deg"], pos["lon_deg"], slot["target_lat_deg"], slot["target_lon_deg"]
                        )
                        assert off <= 2.5, (formation, slot, pos)
                        assert abs(pos["alt_m"] - slot["target_alt_m"]) <= 1.5, (formation, slot, pos)

                r = await _finish(
                    c, _ok(await c.call_tool("fleet_return_to_launch", {"drone_ids": ids})), figures
                )
                assert r["status"] == "succeeded", r
                figures["rtl_altitudes_m"] = {d["drone_id"]: d["rtl_alt_m"] for d in r["drones"]}
                now = {row["drone_id"]: row for row in _ok(await c.call_tool("list_drones", {}))["drones"]}
                for i, d in enumerate(ids):
                    lat, lon = (float(x) for x in drone_home(i).split(",")[:2])
                    assert now[d]["armed"] is False and now[d]["in_air"] is False, now[d]
                    assert geo.horizontal_distance_m(now[d]["lat_deg"], now[d]["lon_deg"], lat, lon) <= 3.0, (
                        now[d]
                    )
            figures["flight_s"] = round(time.monotonic() - flight_started, 1)
        finally:
            stop.set()
            await asyncio.wait_for(watcher, scaled(30))

        # the recorded 1 Hz tracks (flight log in the gateway's database, through REST)
        tracks: dict[str, list[Sample]] = {d: [] for d in ids}
        async with httpx.AsyncClient(base_url=base, timeout=scaled(30), headers=OPERATOR) as http:
            for d in ids:
                flights = (await http.get("/api/v1/flights", params={"vehicle_id": d})).json()["items"]
                assert flights, f"no flight recorded for {d}"
                for flight in flights:
                    feature = (await http.get(f"/api/v1/flights/{flight['id']}/track.geojson")).json()
                    coords = feature["geometry"]["coordinates"] if feature["geometry"] else []
                    times, rel = feature["properties"]["times"], feature["properties"]["alt_rel_m"]
                    for (lon, lat, *_amsl), t, alt in zip(coords, times, rel, strict=True):
                        tracks[d].append((datetime.fromisoformat(t).timestamp(), lat, lon, alt or 0.0))
        figures["samples_live"] = sum(len(v) for v in live.values())
        figures["samples_track"] = sum(len(v) for v in tracks.values())
        assert all(len(v) > 50 for v in live.values()), {d: len(v) for d, v in live.items()}
        assert all(len(v) > 10 for v in tracks.values()), {d: len(v) for d, v in tracks.items()}

    closest_live = closest_approach(live)
    closest_track = closest_approach(tracks)
    assert closest_live is not None and closest_track is not None
    figures["closest_live_m"] = (closest_live.a, closest_live.b, round(closest_live.distance_m, 2))
    figures["closest_track_m"] = (closest_track.a, closest_track.b, round(closest_track.distance_m, 2))
    figures["total_s"] = round(time.monotonic() - started, 1)
    print(f"\nswarm figures: {figures}")
    assert closest_live.distance_m >= MIN_SEPARATION_M, closest_live
    assert closest_track.distance_m >= MIN_SEPARATION_M, closest_track
    assert _leftover_sidecars() == []
