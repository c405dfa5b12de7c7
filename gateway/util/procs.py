"""Stopping child processes that run in their own process group (sim, gateway, sidecars under it)."""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal


async def stop_process_group(proc: asyncio.subprocess.Process, grace_s: float = 10.0) -> None:
    """SIGTERM the process's group, wait up to ``grace_s``, then SIGKILL it; never raises.

    When the leader is already gone its group may still hold children (e.g. sidecars of a killed
    gateway): they are killed too."""
    if proc.returncode is not None:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, signal.SIGKILL)
        return
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(proc.pid, signal.SIGTERM)
    try:
        await asyncio.wait_for(proc.wait(), grace_s)
    except TimeoutError:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, signal.SIGKILL)
        with contextlib.suppress(Exception):
            await asyncio.wait_for(proc.wait(), grace_s)
