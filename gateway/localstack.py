"""A local simulator + gateway pair: the demo, the agent benchmark and end-to-end tests run on it.

``LocalStack`` starts ``fleet-gateway sim`` and ``fleet-gateway serve`` as subprocesses on loopback
ports (own process groups, always stopped), registers one drone per simulated vehicle through the REST
API and waits until every drone is ready.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import re
import secrets
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import BinaryIO

import httpx

from gateway.util.json_types import JsonMapping
from gateway.util.ports import free_tcp_port
from gateway.util.procs import stop_process_group

_VEHICLE_LINE = re.compile(r"^vehicle (\d+) sysid (\d+) (\S+)")


class StackError(RuntimeError):
    """The local sim or gateway did not come up; the message holds the tail of its log."""


class LocalStack:
    """``async with LocalStack(["alpha", "bravo"], speedup=5) as s:`` -> ``s.mcp_url``, ``s.truth()``."""

    def __init__(
        self,
        drone_ids: Sequence[str],
        *,
        speedup: float = 5.0,
        env: dict[str, str] | None = None,
        ready_timeout_s: float = 120.0,
        port: int | None = None,
        auth: bool = True,
        workdir: Path | None = None,
    ) -> None:
        """``port``: the gateway's HTTP port (default: a free one, retried if taken meanwhile).
        ``auth``: give the gateway random agent and operator tokens (``token``, ``operator_token``);
        without, it serves loopback only with no tokens, as a first run on a laptop does.
        ``workdir``: where the database and logs go (default: a temporary directory, removed at exit)."""
        self.drone_ids = list(drone_ids)
        self.speedup = speedup
        self.extra_env = dict(env or {})
        self.ready_timeout_s = ready_timeout_s
        self.fixed_port = port
        # An agent token, so a host's bearer auth against the gateway's /mcp is exercised too.
        self.token: str = secrets.token_urlsafe(18) if auth else ""
        self.operator_token: str = secrets.token_urlsafe(18) if auth else ""  # for the REST registration
        self.mcp_url = ""
        self.api_url = ""
        self.sim_control_url = ""
        self.vehicle_urls: list[str] = []
        self._procs: list[asyncio.subprocess.Process] = []
        self._tmp = None if workdir else tempfile.TemporaryDirectory(prefix="fleet-gateway-stack-")
        self._workdir = Path(workdir) if workdir else Path(self._tmp.name)  # type: ignore[union-attr]

    @property
    def workdir(self) -> Path:
        return self._workdir

    @property
    def database_url(self) -> str:
        return f"sqlite+aiosqlite:///{self.workdir / 'gateway.db'}"

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
        if self.fixed_port is not None:
            attempts = 1
        for attempt in range(attempts):
            port = self.fixed_port if self.fixed_port is not None else free_tcp_port()
            self.api_url = f"http://127.0.0.1:{port}"
            self.mcp_url = f"{self.api_url}/mcp"
            env = {
                "GATEWAY_HOST": "127.0.0.1",
                "GATEWAY_PORT": str(port),
                "GATEWAY_DATABASE_URL": self.database_url,
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
            if "already in use" not in self.log_tail("gateway").lower() or attempt == attempts - 1:
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
        headers = {"Authorization": f"Bearer {self.operator_token}"} if self.operator_token else {}
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
        for proc in reversed(self._procs):  # the gateway first: it ends its sidecars
            await stop_process_group(proc, grace_s=15.0)
        self._procs.clear()
        if self._tmp is not None:
            self._tmp.cleanup()


def _open_log(path: Path) -> BinaryIO:
    """The child's log file (a quick local open; the child inherits it and this side closes it)."""
    return open(path, "wb")


def _state_of(view: JsonMapping) -> str | None:
    state = view.get("state")
    if isinstance(state, dict):
        state = state.get("state")
    return state if isinstance(state, str) else None
