"""``sim_process``: run ``fleet-gateway sim`` as a subprocess on free loopback ports."""

from __future__ import annotations

import asyncio
import contextlib
import os
import re
import sys
import tempfile
from collections.abc import AsyncIterator, Sequence
from dataclasses import dataclass, field

from gateway.sim.control import SimControl
from tests.helpers.procs import stop_process, tail
from tests.helpers.timing import scaled

_VEHICLE_LINE = re.compile(r"^vehicle (\d+) sysid (\d+) (\S+)")


@dataclass
class SimProcess:
    """A running simulator: one URL (mavsdk_server syntax) and system id per vehicle, and its control API."""

    urls: list[str]
    sysids: list[int]
    control: SimControl
    control_url: str
    pid: int
    log_path: str
    udp_urls: list[str | None] = field(default_factory=list)
    #: each vehicle's second ground station port (``extra_args=["--gcs-base-port", "0"]``)
    gcs_urls: list[str | None] = field(default_factory=list)

    def log_tail(self, n: int = 40) -> str:
        return tail(self.log_path, n)


@contextlib.asynccontextmanager
async def sim_process(
    count: int = 1,
    *,
    speedup: float = 10.0,
    seed: int = 1,
    sysid_base: int = 1,
    firmware: str = "4.7",
    home: str | None = None,
    extra_args: Sequence[str] = (),
    start_timeout_s: float = 30.0,
) -> AsyncIterator[SimProcess]:
    """Start ``fleet-gateway sim --count N`` with OS-chosen free TCP and control ports; yield a SimProcess.

    The process runs in its own process group and is always stopped (SIGTERM, then SIGKILL) on exit.
    """
    log = tempfile.NamedTemporaryFile(prefix="sim-", suffix=".log", delete=False)
    args = [
        sys.executable, "-m", "gateway.cli", "sim",
        "--count", str(count), "--tcp-base-port", "0", "--control-port", "0",
        "--speedup", str(speedup), "--seed", str(seed), "--sysid-base", str(sysid_base),
        "--firmware", firmware,
    ]  # fmt: skip
    if home:
        args += ["--home", home]
    args += list(extra_args)
    proc = await asyncio.create_subprocess_exec(
        *args,
        stdout=asyncio.subprocess.PIPE,
        stderr=log,
        stdin=asyncio.subprocess.DEVNULL,
        start_new_session=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )
    log.close()
    control: SimControl | None = None
    try:
        urls: list[str] = []
        udp_urls: list[str | None] = []
        gcs_urls: list[str | None] = []
        sysids: list[int] = []
        control_url = ""

        async def read_banner() -> None:
            nonlocal control_url
            assert proc.stdout is not None
            while True:
                raw = await proc.stdout.readline()
                if not raw:
                    raise RuntimeError(f"simulator exited before it was ready:\n{tail(log.name)}")
                line = raw.decode().strip()
                match = _VEHICLE_LINE.match(line)
                if match:
                    sysids.append(int(match.group(2)))
                    urls.append(match.group(3))
                    udp = re.search(r" udp (\S+)", line)
                    udp_urls.append(udp.group(1) if udp else None)
                    gcs = re.search(r" gcs (\S+)", line)
                    gcs_urls.append(gcs.group(1) if gcs else None)
                elif line.startswith("control "):
                    control_url = line.split(" ", 1)[1]
                elif line == "ready":
                    return

        await asyncio.wait_for(read_banner(), scaled(start_timeout_s))
        control = SimControl(control_url, timeout=scaled(10))  # the simulator answers late on a busy machine
        yield SimProcess(urls, sysids, control, control_url, proc.pid, log.name, udp_urls, gcs_urls)
    finally:
        if control is not None:
            await control.aclose()
        await stop_process(proc)
        with contextlib.suppress(OSError):
            os.unlink(log.name)
