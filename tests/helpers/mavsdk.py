"""``mavsdk_system``: a real ``mavsdk_server`` sidecar on a free gRPC port, and a connected System."""

from __future__ import annotations

import asyncio
import contextlib
import os
import tempfile
import time
from collections.abc import AsyncIterator
from dataclasses import dataclass
from pathlib import Path

import mavsdk_grpc
from mavsdk_grpc import System

from gateway.util.ports import free_tcp_port
from tests.helpers.procs import stop_process, tail
from tests.helpers.timing import scaled


def mavsdk_server_binary() -> Path:
    return Path(mavsdk_grpc.__file__).parent / "bin" / "mavsdk_server"


@dataclass
class MavsdkServer:
    process: asyncio.subprocess.Process
    grpc_port: int
    url: str
    log_path: str

    def log_tail(self, n: int = 40) -> str:
        return tail(self.log_path, n)


async def _port_open(port: int) -> bool:
    try:
        _reader, writer = await asyncio.open_connection("127.0.0.1", port)
    except OSError:
        return False
    writer.close()
    with contextlib.suppress(Exception):
        await writer.wait_closed()
    return True


@contextlib.asynccontextmanager
async def start_mavsdk_server(
    url: str, *, timeout_s: float = 60.0, sysid: int = 245, extra_args: tuple[str, ...] = ()
) -> AsyncIterator[MavsdkServer]:
    """Start ``mavsdk_server -p <free port> <url>`` and wait until its gRPC port accepts connections
    (mavsdk_server opens it only once it has discovered a vehicle). Always stopped on exit."""
    log = tempfile.NamedTemporaryFile(prefix="mavsdk-", suffix=".log", delete=False)
    last_error = ""
    for _attempt in range(3):  # the free port can be taken between picking and binding it
        port = free_tcp_port()
        proc = await asyncio.create_subprocess_exec(
            str(mavsdk_server_binary()), "-p", str(port), "--sysid", str(sysid), *extra_args, url,
            stdout=log, stderr=log, stdin=asyncio.subprocess.DEVNULL, start_new_session=True,
        )  # fmt: skip
        try:
            deadline = time.monotonic() + scaled(timeout_s)
            while time.monotonic() < deadline and proc.returncode is None:
                if await _port_open(port):
                    break
                await asyncio.sleep(0.1)
            if proc.returncode is None and await _port_open(port):
                log.close()
                try:
                    yield MavsdkServer(proc, port, url, log.name)
                finally:
                    await stop_process(proc)
                    with contextlib.suppress(OSError):
                        os.unlink(log.name)
                return
            last_error = tail(log.name)
        except BaseException:
            await stop_process(proc)
            raise
        await stop_process(proc)
    log.close()
    raise RuntimeError(f"mavsdk_server for {url} never opened its gRPC port:\n{last_error}")


@contextlib.asynccontextmanager
async def mavsdk_system(url: str, *, timeout_s: float = 60.0) -> AsyncIterator[System]:
    """A ``mavsdk_grpc.System`` connected through its own mavsdk_server sidecar to the vehicle at ``url``."""
    async with start_mavsdk_server(url, timeout_s=timeout_s) as server:
        system = System(mavsdk_server_address="127.0.0.1", port=server.grpc_port)
        await asyncio.wait_for(system.connect(), scaled(timeout_s))
        yield system
