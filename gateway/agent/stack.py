"""A local sim + gateway for the agent benchmark and end-to-end tests, and ways to read the true state.

``LocalStack`` starts ``fleet-gateway sim`` and ``fleet-gateway serve`` as subprocesses on free loopback
ports (own process groups, always stopped), registers one drone per simulated vehicle through the REST
API and waits until every drone is ready. ``SimTruth`` reads the simulator's true state (the judge of
the benchmark); ``GatewayTruth`` falls back to the gateway's own telemetry tools for an external gateway.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import re
import secrets
import signal
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Protocol

import httpx

from gateway.agent.mcp_link import McpLink
from gateway.agent.missions import DroneTruth
from gateway.util.ports import free_tcp_port

_VEHICLE_LINE = re.compile(r"^vehicle (\d+) sysid (\d+) (\S+)")


class StackError(RuntimeError):
    """The local sim or gateway did not come up; the message holds the tail of its log."""


class Truth(Protocol):
    source: str

    async def snapshot(self, drone_ids: Sequence[str]) -> dict[str, DroneTruth]: ...

    async def homes(self, drone_ids: Sequence[str]) -> dict[str, tuple[float, float, float]]: ...


class SimTruth:
    """True state from the simulator's control API (vehicle index per drone id)."""

    source = "the simulator (true state)"

    def __init__(self, control_url: str, index_of: dict[str, int]) -> None:
        self.index_of = dict(index_of)
        self._http = httpx.AsyncClient(base_url=control_url.rstrip("/"), timeout=10.0)

    async def aclose(self) -> None:
        await self._http.aclose()

    async def state(self, drone_id: str) -> dict[str, Any]:
        response = await self._http.get(f"/vehicles/{self.index_of[drone_id]}")
        response.raise_for_status()
        return response.json()

    async def snapshot(self, drone_ids: Sequence[str]) -> dict[str, DroneTruth]:
        out = {}
        for d in drone_ids:
            s = await self.state(d)
            out[d] = DroneTruth(
                float(s["lat"]),
                float(s["lon"]),
                float(s["rel_alt_m"]),
                bool(s["armed"]),
                s.get("battery_pct"),
            )
        return out

    async def homes(self, drone_ids: Sequence[str]) -> dict[str, tuple[float, float, float]]:
        """Where each drone stands now (it arms there, so that becomes its home for the mission)."""
        out = {}
        for d in drone_ids:
            s = await self.state(d)
            out[d] = (float(s["lat"]), float(s["lon"]), float(s["alt_amsl_m"]) - float(s["rel_alt_m"]))
        return out

    async def recharge(self, drone_id: str, pct: float = 100.0) -> None:
        """Harness-only, between missions: a fresh battery, as a crew would swap it."""
        response = await self._http.post(f"/vehicles/{self.index_of[drone_id]}/battery", json={"pct": pct})
        response.raise_for_status()


class GatewayTruth:
    """State as the gateway's own telemetry tools report it (for a gateway without sim access)."""

    source = "the gateway's telemetry (no simulator access)"

    def __init__(self, link: McpLink) -> None:
        self.link = link

    async def _structured(self, tool: str, drone_id: str) -> dict[str, Any]:
        result = await self.link.client.call_tool(tool, {"drone_id": drone_id})
        if result.is_error or not isinstance(result.structured_content, dict):
            text = " ".join(getattr(b, "text", "") for b in result.content)
            raise StackError(f"{tool}({drone_id}) failed: {text}")
        return result.structured_content

    async def snapshot(self, drone_ids: Sequence[str]) -> dict[str, DroneTruth]:
        out = {}
        for d in drone_ids:
            pos = await self._structured("get_position", d)
            armed = await self._structured("get_armed", d)
            battery = await self._structured("get_battery", d)
            out[d] = DroneTruth(
                pos["lat_deg"],
                pos["lon_deg"],
                pos["alt_m"],
                bool(armed.get("value")),
                battery.get("remaining_pct"),
            )
        return out

    async def homes(self, drone_ids: Sequence[str]) -> dict[str, tuple[float, float, float]]:
        out = {}
        for d in drone_ids:
            pos = await self._structured("get_position", d)
            out[d] = (pos["lat_deg"], pos["lon_deg"], pos["alt_amsl_m"] - pos["alt_m"])
        return out


class Sampler:
    """Samples the true state a few times a second while a mission runs (the track the checks read)."""

    def __init__(self, truth: Truth, drone_ids: Sequence[str], period_s: float = 0.25) -> None:
        self.truth, self.drone_ids, self.period_s = truth, list(drone_ids), period_s
        self.tracks: dict[str, list[DroneTruth]] = {d: [] for d in self.drone_ids}
        self._task: asyncio.Task[None] | None = None

    async def _run(self) -> None:
        while True:
            with contextlib.suppress(httpx.HTTPError, StackError):
                snap = await self.truth.snapshot(self.drone_ids)
                for d, t in snap.items():
                    self.tracks[d].append(t)
            await asyncio.sleep(self.period_s)

    async def __aenter__(self) -> Sampler:
        self._task = asyncio.create_task(self._run())
        return self

    async def __aexit__(self, *exc: object) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task


async def reset_drones(
    link: McpLink,
    truth: Truth,
    drone_ids: Sequence[str],
    timeout_s: float = 240.0,
    battery_pct: dict[str, float] | None = None,
) -> None:
    """Harness step between missions (not measured): every drone on the ground and disarmed, through the
    gateway's own tools (land, then wait), and a fresh battery where the simulator allows it."""
    deadline = time.monotonic() + timeout_s
    for d in drone_ids:
        state = (await truth.snapshot([d]))[d]
        if not state.landed:
            await link.call_tool("land", {"drone_id": d})
        while True:
            state = (await truth.snapshot([d]))[d]
            if state.landed and not state.armed:
                break
            if time.monotonic() > deadline:
                raise StackError(f"{d} did not land and disarm between missions: {state}")
            if state.landed and state.armed:
                await link.call_tool("disarm_drone", {"drone_id": d})
            else:
                await link.call_tool("monitor_flight", {"drone_id": d})
            await asyncio.sleep(0.5)
        if isinstance(truth, SimTruth):
            pct = (battery_pct or {}).get(d, 100.0)
            await truth.recharge(d, pct)
            await _until_gateway_sees_battery(link, d, pct, deadline)


async def _until_gateway_sees_battery(link: McpLink, drone_id: str, pct: float, deadline: float) -> None:
    """Wait until the gateway's telemetry reports the battery the harness just set (it streams at about
    1 Hz), so that a mission asking about the battery does not race the harness."""
    while True:
        result = await link.client.call_tool("get_battery", {"drone_id": drone_id})
        data = result.structured_content if isinstance(result.structured_content, dict) else {}
        seen = data.get("remaining_pct")
        if isinstance(seen, int | float) and abs(seen - pct) <= 1.0:
            return
        if time.monotonic() > deadline:
            raise StackError(f"the gateway still reports {drone_id} battery {seen} %, set to {pct:g} %")
        await asyncio.sleep(0.3)


class LocalStack:
    """``async with LocalStack(["alpha", "bravo"], speedup=5) as s:`` -> ``s.mcp_url``, ``s.truth()``."""

    def __init__(
        self,
        drone_ids: Sequence[str],
        *,
        speedup: float = 5.0,
        env: dict[str, str] | None = None,
        ready_timeout_s: float = 120.0,
    ) -> None:
        self.drone_ids = list(drone_ids)
        self.speedup = speedup
        self.extra_env = dict(env or {})
        self.ready_timeout_s = ready_timeout_s
        # An agent token, so the host's bearer auth against the gateway's /mcp is exercised too.
        self.token: str = secrets.token_urlsafe(18)
        self.operator_token: str = secrets.token_urlsafe(18)  # for the REST registration
        self.mcp_url = ""
        self.api_url = ""
        self.sim_control_url = ""
        self.vehicle_urls: list[str] = []
        self._procs: list[asyncio.subprocess.Process] = []
        self._dir = tempfile.TemporaryDirectory(prefix="fleet-agent-stack-")
        self._truth: SimTruth | None = None

    @property
    def workdir(self) -> Path:
        return Path(self._dir.name)

    def log_tail(self, name: str, n: int = 30) -> str:
        path = self.workdir / f"{name}.log"
        if not path.exists():
            return ""
        return "\n".join(path.read_text(errors="replace").splitlines()[-n:])

    async def __aenter__(self) -> LocalStack:
        try:
            await self._start_sim()
            await self._start_gateway()
            await self._register_and_wait()
        except BaseException:
            await self._stop()
            raise
        return self

    async def __aexit__(self, *exc: object) -> None:
        await self._stop()

    def truth(self) -> SimTruth:
        if self._truth is None:
            self._truth = SimTruth(self.sim_control_url, {d: i for i, d in enumerate(self.drone_ids)})
        return self._truth

    # --- processes ---------------------------------------------------------------------------------

    async def _spawn(self, name: str, args: list[str], env: dict[str, str]) -> asyncio.subprocess.Process:
        log = _open_log(self.workdir / f"{name}.log")
        try:
            proc = await asyncio.create_subprocess_exec(
                sys.executable, "-m", "gateway.cli", *args,
                stdout=asyncio.subprocess.PIPE if name == "sim" else log, stderr=log,
                stdin=asyncio.subprocess.DEVNULL, start_new_session=True,
                env={**os.environ, "PYTHONUNBUFFERED": "1", **env},
            )  # fmt: skip
        finally:
            log.close()
        self._procs.append(proc)
        return proc

    async def _start_sim(self) -> None:
        proc = await self._spawn("sim", [
            "sim", "--count", str(len(self.drone_ids)), "--tcp-base-port", "0", "--control-port", "0",
            "--speedup", f"{self.speedup:g}", "--seed", "1",
        ], {})  # fmt: skip

        async def banner() -> None:
            assert proc.stdout is not None
            while True:
                raw = await proc.stdout.readline()
                if not raw:
                    raise StackError(f"the simulator exited before it was ready:\n{self.log_tail('sim')}")
                line = raw.decode().strip()
                m = _VEHICLE_LINE.match(line)
                if m:
                    self.vehicle_urls.append(m.group(3))
                elif line.startswith("control "):
                    self.sim_control_url = line.split(" ", 1)[1]
                elif line == "ready":
                    return

        try:
            await asyncio.wait_for(banner(), 60)
        except TimeoutError:
            raise StackError(f"the simulator did not start:\n{self.log_tail('sim')}") from None

    async def _start_gateway(self, attempts: int = 4) -> None:
        """Start ``fleet-gateway serve`` on a free port. A free port can be taken by another process
        before the gateway binds it: then the gateway exits with "address already in use" and this
        tries another port. Ready = this process's own uvicorn says it listens there, and /healthz."""
        for attempt in range(attempts):
            port = free_tcp_port()
            self.api_url = f"http://127.0.0.1:{port}"
            self.mcp_url = f"{self.api_url}/mcp"
            env = {
                "GATEWAY_HOST": "127.0.0.1",
                "GATEWAY_PORT": str(port),
                "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{self.workdir / 'gateway.db'}",
                "GATEWAY_LOG_LEVEL": "INFO",  # uvicorn's "running on" line is the proof of our bind
                "GATEWAY_AGENT_TOKENS": self.token,
                "GATEWAY_OPERATOR_TOKENS": self.operator_token,
                "GATEWAY_VIEWER_TOKENS": "",
                **self.extra_env,
            }
            proc = await self._spawn("gateway", ["serve"], env)
            if await self._gateway_ready(proc, port):
                return
            self._procs.remove(proc)
            if "address already in use" not in self.log_tail("gateway").lower() or attempt == attempts - 1:
                raise StackError(f"the gateway exited at start:\n{self.log_tail('gateway')}")

    async def _gateway_ready(self, proc: asyncio.subprocess.Process, port: int) -> bool:
        """True once ready; False if the process exited (the caller reads its log)."""
        banner = f"running on http://127.0.0.1:{port}"
        deadline = time.monotonic() + 60
        async with httpx.AsyncClient(timeout=5) as http:
            while True:
                if proc.returncode is not None:
                    return False
                if banner in self.log_tail("gateway", 200).lower():
                    with contextlib.suppress(httpx.HTTPError):
                        if (await http.get(f"{self.api_url}/healthz")).status_code == 200:
                            return True
                if time.monotonic() > deadline:
                    raise StackError(f"the gateway did not become ready:\n{self.log_tail('gateway')}")
                await asyncio.sleep(0.2)

    async def _register_and_wait(self) -> None:
        headers = {"Authorization": f"Bearer {self.operator_token}"}
        async with httpx.AsyncClient(base_url=f"{self.api_url}/api/v1", timeout=10, headers=headers) as http:
            for drone_id, url in zip(self.drone_ids, self.vehicle_urls, strict=True):
                r = await http.post("/vehicles", json={"id": drone_id, "url": url})
                if r.status_code != 201:
                    raise StackError(f"registering {drone_id} failed: {r.status_code} {r.text}")
            deadline = time.monotonic() + self.ready_timeout_s
            pending = set(self.drone_ids)
            while pending:
                for d in sorted(pending):
                    r = await http.get(f"/vehicles/{d}")
                    if r.status_code == 200 and _state_of(r.json()) == "ready":
                        pending.discard(d)
                if not pending:
                    break
                if time.monotonic() > deadline:
                    raise StackError(f"drones not ready: {sorted(pending)}\n{self.log_tail('gateway')}")
                await asyncio.sleep(0.5)

    async def _stop(self) -> None:
        if self._truth is not None:
            await self._truth.aclose()
            self._truth = None
        for proc in reversed(self._procs):  # the gateway first: it ends its sidecars
            await _stop_process(proc)
        self._procs.clear()
        self._dir.cleanup()


def _open_log(path: Path) -> Any:
    """The child's log file (a quick local open; the child inherits it and this side closes it)."""
    return open(path, "wb")


def _state_of(view: dict[str, Any]) -> str | None:
    state = view.get("state")
    if isinstance(state, dict):
        state = state.get("state")
    return state


async def _stop_process(proc: asyncio.subprocess.Process, grace_s: float = 15.0) -> None:
    if proc.returncode is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGTERM)
        try:
            await asyncio.wait_for(proc.wait(), grace_s)
        except TimeoutError:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(proc.pid, signal.SIGKILL)
            await proc.wait()
    else:  # the leader is gone; make sure nothing of its group is left (e.g. sidecars)
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, signal.SIGKILL)
