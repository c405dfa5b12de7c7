"""Starting and reliably stopping child processes in their own process group."""

from __future__ import annotations

import asyncio
import os
import signal
import subprocess

from gateway.util.procs import stop_process_group
from tests.helpers.timing import scaled


async def stop_process(proc: asyncio.subprocess.Process, grace_s: float = 5.0) -> None:
    """SIGTERM the process group, wait, then SIGKILL; never raises."""
    await stop_process_group(proc, grace_s)


def stop_popen_group(proc: subprocess.Popen[bytes], grace_s: float) -> None:
    """SIGTERM the group of ``proc`` (started with ``start_new_session``), wait up to ``grace_s``
    (scaled), then SIGKILL it."""
    if proc.poll() is not None:
        return
    os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.wait(timeout=scaled(grace_s))
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=scaled(5))


def tail(path: str, n: int = 40) -> str:
    try:
        with open(path, errors="replace") as fh:
            return "".join(fh.readlines()[-n:])
    except OSError:
        return ""
