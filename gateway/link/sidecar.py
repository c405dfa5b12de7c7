"""One ``mavsdk_server`` process per vehicle: spawn, watch, restart, stop.

What mavsdk_server 4.0.5 does that shapes this module (measured):

* It opens its gRPC port only after it has discovered a vehicle on its MAVLink URL; until then a gRPC
  client waiting for the channel hangs. The supervisor therefore watches the process output for
  ``Server set to listen on 0.0.0.0:<port>`` and only then reports the sidecar as serving.
* The gRPC port is bound with SO_REUSEPORT: a second mavsdk_server on the same port starts "fine" and
  the kernel splits connections between the two, i.e. a client could silently talk to another
  vehicle's sidecar. After the listen line the supervisor checks in /proc that every listening socket
  on the port belongs to its own process; otherwise it respawns on another port.
* A port held by a non-reuseport socket makes it exit with ``Failed to bind server to port``: also
  retried on another port, not counted as a crash.
* It binds gRPC on 0.0.0.0. Sidecars run from a confined copy (``gateway.link.confine``): by default
  one that serves on a unix socket in a private directory (``gateway.link.sidecar_socket``: the
  supervisor checks in /proc that the process listens there, the link removes the path once its own
  channel is connected and checks that the sidecar holds that one connection only, ``seal``); with
  ``loopback``, one bound to 127.0.0.1, checked in /proc after every start to listen on a loopback
  address only. A process that listens anywhere else is stopped and the vehicle fails closed, whatever
  binary or architecture made it. ``SpawnPlan`` / ``Sidecar.confine`` is the
  one place where a wrapper (network namespace, an emulator) is inserted around the command.

Sidecars start a few at a time (``STARTS``, ``gateway.link.pacing``): a start holds its slot from the
spawn until it serves, at most 5 s.

Every sidecar runs in its own process group with PR_SET_PDEATHSIG=SIGKILL (set by an exec wrapper,
see ``die_with_parent``), so it dies with the gateway even when the gateway is SIGKILLed; ``stop()``
terminates the group, then kills it; an atexit hook kills what is left at interpreter exit.
"""

from __future__ import annotations

import asyncio
import atexit
import enum
import functools
import ipaddress
import logging
import os
import re
import shutil
import signal
import sys
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from gateway.config import Settings
from gateway.link import confine, pacing, sidecar_socket
from gateway.link.child_watch import wait_for_children_on_the_loop
from gateway.link.proc_sockets import listening_addresses, listening_inodes, socket_inodes
from gateway.util.json_types import JsonObject
from gateway.util.ports import free_tcp_port

log = logging.getLogger("gateway.sidecar")

_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_LEVEL = re.compile(r"^\[\d\d:\d\d:\d\d\|(\w+)\s*\]\s*")
_LISTEN = re.compile(r"Server set to listen on [^\s]*:(\d+)")
_BIND_FAILED = "Failed to bind server to port"
_DISCOVERED = "System discovered"
# mavsdk_server prints this when it cannot open its link (e.g. a missing serial device) and then waits
# forever without retrying: the supervisor restarts it instead (and, if it keeps failing, gives up).
_LINK_FAILED = "Connection failed"

#: how long a sidecar must stay up before its crash counter is reset
STABLE_AFTER_S = 20.0
#: attempts at finding a gRPC port nobody else holds, per start
PORT_ATTEMPTS = 5
#: identical output lines within this window are logged once, with a repeat count
REPEAT_WINDOW_S = 30.0
#: grace between SIGTERM and SIGKILL when stopping
TERM_GRACE_S = 3.0

#: sidecars starting at once (spawned, not yet serving), per event loop; a start holds its slot until
#: its sidecar serves, at most ``hold_at_most_s`` (a vehicle that never answers frees it)
STARTS = pacing.Pace(slots=8, hold_at_most_s=5.0)


# Every live sidecar process group, so the interpreter's exit path can still kill them.
_LIVE_PGIDS: set[int] = set()

# PR_SET_PDEATHSIG is set by an exec wrapper, not a preexec_fn: forking a process that runs gRPC
# threads and then running Python code in the child (preexec_fn also runs gRPC's at-fork hooks)
# segfaults now and then. setpriv (util-linux) does it in C; else a tiny Python exec shim.
_PDEATHSIG_SHIM = (
    "import ctypes,ctypes.util,os,signal,sys;"
    "ctypes.CDLL(ctypes.util.find_library('c') or 'libc.so.6').prctl(1,signal.SIGKILL,0,0,0);"
    "os.getppid()==int(sys.argv[1]) or sys.exit(1);"
    "os.execv(sys.argv[2],sys.argv[2:])"
)


def die_with_parent(argv: list[str]) -> list[str]:
    """``argv`` wrapped so the process gets SIGKILL when the gateway dies, even by SIGKILL."""
    setpriv = shutil.which("setpriv")
    if setpriv:
        return [setpriv, "--pdeathsig", "KILL", "--", *argv]
    return [sys.executable, "-c", _PDEATHSIG_SHIM, str(os.getpid()), *argv]


@atexit.register
def _kill_leftovers() -> None:
    for pgid in list(_LIVE_PGIDS):
        try:
            os.killpg(pgid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    _LIVE_PGIDS.clear()


def mavsdk_server_binary(settings: Settings) -> str:
    """The binary sidecars start from: by default the loopback-only copy made by ``confine``, so no
    sidecar's gRPC port is reachable from another host (GATEWAY_SIDECAR_CONFINEMENT=none: as shipped)."""
    return _confined_binary(
        settings.sidecar_confinement, settings.mavsdk_server_path, settings.sidecar_cache_dir
    )


@functools.lru_cache(maxsize=8)
def _confined_binary(confinement: str, explicit_path: str | None, cache_dir: str | None) -> str:
    # cached: confine reads and hashes the whole binary (tens of MB), once per configuration is enough
    return str(confine.sidecar_binary(confinement, explicit_path, Path(cache_dir) if cache_dir else None))


class SidecarState(enum.StrEnum):
    STOPPED = "stopped"
    STARTING = "starting"  # process spawned, waiting for the vehicle to be discovered
    SERVING = "serving"  # gRPC port open and verified as ours
    BACKOFF = "backoff"  # died, waiting before the next start
    FAILED = "failed"  # gave up after repeated crashes


@dataclass
class SpawnPlan:
    """The command and environment of one sidecar start; a confinement wrapper rewrites it."""

    argv: list[str]
    env: dict[str, str]
    grpc_port: int


#: A confinement wrapper: takes the plan, returns the plan to execute (e.g. ``["ip", "netns", "exec",
#: ns, *argv]`` or an LD_PRELOAD entry in env). The gRPC port must stay reachable on 127.0.0.1.
Confine = Callable[[SpawnPlan], SpawnPlan]


@dataclass
class SidecarInfo:
    state: SidecarState = SidecarState.STOPPED
    pid: int | None = None
    grpc_port: int | None = None
    restarts: int = 0
    consecutive_failures: int = 0
    last_error: str | None = None
    started_at: float | None = None  # monotonic, of the current process
    #: socket confinement: the current process's private directory, holding its gRPC socket until sealed
    socket_dir: Path | None = None
    serving_since: float | None = None
    discovered: bool = False
    #: the latest error/warning mavsdk_server printed while waiting for its vehicle (cleared when serving)
    complaint: str | None = None
    recent_output: deque[str] = field(default_factory=lambda: deque(maxlen=20))


@dataclass
class _Watch:
    """What the sidecar's output showed before it ended or was ended."""

    bind_failed: bool = False
    foreign_listener: bool = False
    exposed_on: list[str] = field(default_factory=list)
    link_failed: str | None = None

    @property
    def fatal(self) -> bool:
        return self.foreign_listener or self.bind_failed or bool(self.link_failed) or bool(self.exposed_on)


class Sidecar:
    """Supervises the mavsdk_server of one vehicle.

    ``on_serving(port)`` is called (from the event loop) each time a process is serving on a verified
    port; ``on_down(reason)`` each time a serving or starting process goes away unexpectedly.
    """

    def __init__(
        self,
        vehicle_id: str,
        url: str,
        settings: Settings,
        *,
        on_serving: Callable[[int], None] | None = None,
        on_down: Callable[[str], None] | None = None,
        confine: Confine | None = None,
    ) -> None:
        self.vehicle_id = vehicle_id
        self.url = url
        self.settings = settings
        self.info = SidecarInfo()
        self._on_serving = on_serving
        self._on_down = on_down
        self._confine = confine
        self._proc: asyncio.subprocess.Process | None = None
        self._task: asyncio.Task[None] | None = None
        self._serving = asyncio.Event()
        self._stopping = False
        self._start_slot: pacing.Slot | None = None
        self._log = logging.getLogger(f"gateway.sidecar.{vehicle_id}")
        self._repeat: tuple[str, int, float] = ("", 0, 0.0)  # last line, times repeated, first seen

    # --- public -----------------------------------------------------------------------------------
    @property
    def state(self) -> SidecarState:
        return self.info.state

    @property
    def pid(self) -> int | None:
        return self.info.pid

    @property
    def grpc_port(self) -> int | None:
        """The gRPC port while serving (with socket confinement: the number that names its socket)."""
        return self.info.grpc_port if self.info.state == SidecarState.SERVING else None

    @property
    def on_socket(self) -> bool:
        return self.settings.sidecar_confinement == "socket"

    @property
    def grpc_address(self) -> str:
        """What a gRPC client puts before ``:<port>``: the private socket's path (``unix:<dir>/sk``) or
        127.0.0.1."""
        directory = self.info.socket_dir
        if self.on_socket and directory is not None:
            return "unix:" + str(directory / confine.SOCKET_NAME.format(port="")).removesuffix(":")
        return "127.0.0.1"

    def seal(self) -> str | None:
        """Socket confinement: the gateway's channel is connected; remove the socket's path so no other
        process can connect, and check that the gateway's is its one connection (None: so; else what
        is wrong, and the process is recycled). Nothing to do otherwise."""
        directory, port = self.info.socket_dir, self.info.grpc_port
        if not self.on_socket or directory is None or port is None:
            return None
        wrong = sidecar_socket.seal(directory, port)
        if wrong is not None:
            self._log.error("%s: %s; restarting its sidecar", self.vehicle_id, wrong)
            self.recycle()
        return wrong

    def status(self) -> JsonObject:
        return {
            "state": self.info.state.value,
            "pid": self.info.pid,
            "grpc_port": self.grpc_port,
            "restarts": self.info.restarts,
            "vehicle_discovered": self.info.discovered,
            "last_error": self.info.last_error,
        }

    def start(self) -> None:
        """Start supervising (idempotent). Returns at once; see ``wait_serving``."""
        if self._task is not None and not self._task.done():
            return
        self._stopping = False
        self.info = SidecarInfo()
        self._task = asyncio.create_task(self._supervise(), name=f"sidecar-{self.vehicle_id}")

    async def wait_serving(self, within_s: float) -> bool:
        """True once serving; False after ``within_s`` (never hangs, e.g. while no vehicle answers)."""
        try:
            await asyncio.wait_for(self._serving.wait(), within_s)
        except TimeoutError:
            return False
        return True

    def recycle(self) -> None:
        """Terminate the current process; the supervisor starts a new one (counted as a failure)."""
        proc = self._proc
        if proc is not None and proc.returncode is None:
            self._log.warning("recycling mavsdk_server pid %d of %s", proc.pid, self.vehicle_id)
            try:
                os.killpg(proc.pid, signal.SIGTERM)
            except ProcessLookupError:
                pass

    async def stop(self) -> None:
        """Stop supervising and leave no process behind."""
        self._stopping = True
        task, self._task = self._task, None
        if task is not None:
            task.cancel()
            try:
                await task
            except (asyncio.CancelledError, Exception):  # stopping: nothing to report
                pass
        await self._terminate()
        self.info.state = SidecarState.STOPPED
        self.info.pid = None
        self._serving.clear()

    # --- supervision ------------------------------------------------------------------------------
    async def _supervise(self) -> None:
        backoff = self.settings.sidecar_backoff_initial_s
        while not self._stopping:
            try:
                reason = await self._run_once()
            except confine.ConfinementError as exc:  # fail closed: never fall back to an exposed binary
                self.info.state = SidecarState.FAILED
                self.info.last_error = str(exc)
                self._log.error("%s: %s", self.vehicle_id, exc)
                return
            if self._stopping:
                return
            stable = (
                self.info.serving_since is not None
                and time.monotonic() - self.info.serving_since >= STABLE_AFTER_S
            )
            if stable:
                self.info.consecutive_failures = 0
                backoff = self.settings.sidecar_backoff_initial_s
            self.info.consecutive_failures += 1
            self.info.last_error = reason
            self._log.warning("mavsdk_server for %s went down: %s", self.vehicle_id, reason)
            if self._on_down is not None:
                self._on_down(reason)
            if self.info.consecutive_failures > self.settings.sidecar_max_restarts:
                self.info.state = SidecarState.FAILED
                self.info.last_error = (
                    f"mavsdk_server gave up after {self.info.consecutive_failures} consecutive failures; "
                    f"last: {reason}"
                )
                self._log.error("%s: %s", self.vehicle_id, self.info.last_error)
                return
            self.info.state = SidecarState.BACKOFF
            await asyncio.sleep(backoff)
            backoff = min(backoff * 2, self.settings.sidecar_backoff_max_s)
            self.info.restarts += 1

    async def _run_once(self) -> str:
        """Start one process (retrying ports) and wait until it ends; return why it ended."""
        self.info.state = SidecarState.STARTING
        slot = self._start_slot = await STARTS.take()  # released once serving (``_serve``) at the latest
        try:
            for _attempt in range(PORT_ATTEMPTS):
                port = sidecar_socket.socket_port() if self.on_socket else free_tcp_port()
                outcome = await self._spawn_and_watch(port)
                if outcome != "port-taken":
                    return outcome
                self._log.info("gRPC port %d of %s taken; retrying on another port", port, self.vehicle_id)
            return f"no free gRPC port after {PORT_ATTEMPTS} attempts"
        finally:
            slot.release()

    def plan(self, port: int) -> SpawnPlan:
        """The command line for one start; the confinement wrapper is applied here and only here."""
        argv = [
            mavsdk_server_binary(self.settings),
            "-p",
            str(port),
            "--sysid",
            str(self.settings.gcs_sysid),
            "--compid",
            "190",
        ]
        # No --heartbeat-watchdog-timeout here: with it, mavsdk_server sends no GCS heartbeat until the
        # watchdog is fed over gRPC, and gRPC opens only after discovery, so a vehicle that waits to
        # hear from its ground station first (udpout://) is never discovered. The vehicle session
        # enables the watchdog through the Core RPC once connected (see Vehicle._feed_watchdog).
        argv.append(self.url)
        plan = SpawnPlan(argv=argv, env=dict(os.environ), grpc_port=port)
        return self._confine(plan) if self._confine is not None else plan

    async def _spawn_and_watch(self, port: int) -> str:
        plan = self.plan(port)
        self.info.state = SidecarState.STARTING
        self.info.grpc_port = plan.grpc_port
        self.info.discovered = False
        self.info.serving_since = None
        sidecar_socket.remove(self.info.socket_dir)
        self.info.socket_dir = sidecar_socket.private_directory(self.vehicle_id) if self.on_socket else None
        wait_for_children_on_the_loop()
        try:
            proc = await asyncio.create_subprocess_exec(
                *die_with_parent(plan.argv),
                stdin=asyncio.subprocess.DEVNULL,
                stdout=asyncio.subprocess.PIPE,
                stderr=asyncio.subprocess.STDOUT,
                env=plan.env,
                cwd=self.info.socket_dir,  # socket confinement: where its gRPC socket is made
                start_new_session=True,  # own process group: stop() kills the whole group
            )
        except OSError as exc:
            return f"cannot start mavsdk_server ({plan.argv[0]}): {exc}"
        self._proc = proc
        _LIVE_PGIDS.add(proc.pid)
        self.info.pid = proc.pid
        self.info.started_at = time.monotonic()
        self._log.info(
            "started mavsdk_server pid %d for %s on gRPC port %d: %s",
            proc.pid,
            self.vehicle_id,
            port,
            self.url,
        )
        watch = _Watch()
        try:
            await self._watch_output(proc, plan.grpc_port, watch)
        finally:
            was_serving = self.info.state == SidecarState.SERVING
            self._serving.clear()
            if watch.fatal or self._stopping:
                await self._terminate()
            code = await proc.wait()
            _LIVE_PGIDS.discard(proc.pid)
            self._proc = None
            self.info.pid = None
            sidecar_socket.remove(self.info.socket_dir)
            self.info.socket_dir = None
        return self._exit_reason(watch, code, was_serving)

    async def _watch_output(self, proc: asyncio.subprocess.Process, port: int, watch: _Watch) -> None:
        """Read the sidecar's output until it ends or shows a fault that ends the sidecar."""
        assert proc.stdout is not None
        async for raw in proc.stdout:
            line = self._log_line(raw)
            if line is None:
                continue
            if _DISCOVERED in line:
                self.info.discovered = True
            elif _LINK_FAILED in line and not self.info.discovered:
                earlier = [m for m in list(self.info.recent_output)[:-1] if m != line]
                watch.link_failed = f"{earlier[-1]}; {line}" if earlier else line
                return
            elif _BIND_FAILED in line:
                watch.bind_failed = True
            elif await self._on_listen_line(proc.pid, port, line, watch):
                return

    async def _on_listen_line(self, pid: int, port: int, line: str, watch: _Watch) -> bool:
        """Serve once the sidecar listens where it should; True when it listens elsewhere or the port
        belongs to another process (the watch ends)."""
        match = _LISTEN.search(line)
        if match and self.on_socket:
            if not await self._socket_is_ours(pid, port):
                watch.exposed_on = [line.removeprefix("Server set to listen on ")]
                return True
            self._serve(port)
        elif match and int(match.group(1)) == port:
            if not await self._port_is_ours(pid, port):
                watch.foreign_listener = True
                return True
            watch.exposed_on = self._exposed_listeners(pid, port)
            if watch.exposed_on:
                return True
            self._serve(port)
        return False

    def _exit_reason(self, watch: _Watch, code: int, was_serving: bool) -> str:
        if watch.exposed_on:
            where = "its private unix socket" if self.on_socket else "loopback only"
            raise confine.ConfinementError(
                f"mavsdk_server for {self.vehicle_id} listened for gRPC on {', '.join(watch.exposed_on)}, "
                f"not on {where}; it was stopped. Use mavsdk-grpc 4.0.5's binary, or set "
                "GATEWAY_SIDECAR_CONFINEMENT=none and firewall the sidecar ports yourself."
            )
        if watch.foreign_listener or watch.bind_failed:
            return "port-taken"
        if watch.link_failed:
            return f"mavsdk_server could not open {self.url}: {watch.link_failed}"
        last = self.info.recent_output[-1] if self.info.recent_output else "no output"
        where = "while serving" if was_serving else "before serving"
        return f"mavsdk_server exited {where} with code {code} (last output: {last})"

    def _log_line(self, raw: bytes) -> str | None:
        text = _ANSI.sub("", raw.decode("utf-8", "replace")).rstrip()
        if not text.strip():
            return None
        match = _LEVEL.match(text)
        level_name = match.group(1) if match else "Info"
        message = text[match.end() :] if match else text
        level = {"Error": logging.ERROR, "Warn": logging.WARNING, "Debug": logging.DEBUG}.get(
            level_name, logging.INFO
        )
        if "Received ack for not-existing command" in message:
            level = logging.DEBUG  # the ACK of a COMMAND_LONG the gateway sent raw (mavlink_direct)
        now = time.monotonic()
        last, repeats, since = self._repeat
        if message == last and now - since < REPEAT_WINDOW_S:
            self._repeat = (last, repeats + 1, since)  # e.g. "Sending message failed" while a link is down
            return message
        if repeats:
            self._log.log(level, "[%s] (previous line repeated %d more times)", self.vehicle_id, repeats)
        self._repeat = (message, 0, now)
        if level >= logging.WARNING and self.info.state == SidecarState.STARTING:
            self.info.complaint = message
        self.info.recent_output.append(message)
        self._log.log(level, "[%s] %s", self.vehicle_id, message)
        return message

    def _serve(self, port: int) -> None:
        if self._start_slot is not None:
            self._start_slot.release()  # the next sidecar may start
        self.info.state = SidecarState.SERVING
        self.info.complaint = None
        self.info.serving_since = time.monotonic()
        self._serving.set()
        if self._on_serving is not None:
            self._on_serving(port)

    async def _socket_is_ours(self, pid: int, port: int) -> bool:
        """Socket confinement: the process listens on its private unix socket (the listen line comes a
        moment before the socket shows in /proc)."""
        for _ in range(20):
            if sidecar_socket.listener_is_ours(pid, port):
                return True
            await asyncio.sleep(0.05)
        return False

    async def _port_is_ours(self, pid: int, port: int) -> bool:
        """No other process listens on ``port`` (SO_REUSEPORT makes sharing it silent).

        When the socket is not visible at all (a confinement wrapper put the sidecar in its own network
        namespace, where it cannot collide with anything), the port counts as ours.
        """
        for _ in range(20):
            listeners = listening_inodes(port)
            ours = socket_inodes(pid)
            if listeners - ours:
                return False
            if listeners:
                return True
            await asyncio.sleep(0.05)  # the listen line comes a moment before the socket shows up
        self._log.debug("gRPC port %d of %s not visible in /proc/net; not verified", port, self.vehicle_id)
        return True

    def _exposed_listeners(self, pid: int, port: int) -> list[str]:
        """With loopback confinement on: the addresses other than loopback ``pid`` listens on at ``port``."""
        if self.settings.sidecar_confinement != "loopback":
            return []
        addresses = listening_addresses(port, socket_inodes(pid))
        return sorted(a for a in addresses if not ipaddress.ip_address(a).is_loopback)

    async def _terminate(self) -> None:
        proc = self._proc
        if proc is None or proc.returncode is not None:
            return
        for sig, grace in ((signal.SIGTERM, TERM_GRACE_S), (signal.SIGKILL, TERM_GRACE_S)):
            try:
                os.killpg(proc.pid, sig)
            except ProcessLookupError:
                break
            try:
                await asyncio.wait_for(proc.wait(), grace)
                break
            except TimeoutError:
                continue
        _LIVE_PGIDS.discard(proc.pid)
