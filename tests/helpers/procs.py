"""Starting and reliably stopping child processes in their own process group."""

from __future__ import annotations

import asyncio

from gateway.util.procs import stop_process_group


async def stop_process(proc: asyncio.subprocess.Process, grace_s: float = 5.0) -> None:
    """SIGTERM the process group, wait, then SIGKILL; never raises."""
    await stop_process_group(proc, grace_s)


def tail(path: str, n: int = 40) -> str:
    try:
        with open(path, errors="replace") as fh:
            return "".join(fh.readlines()[-n:])
    except OSError:
        return ""
