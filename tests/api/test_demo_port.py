"""`fleet-gateway demo` takes its HTTP port from GATEWAY_PORT when --port is not given, as `serve` does:
with the port GATEWAY_PORT names already taken, the demo refuses in one line naming that port (it would
otherwise check 8765 and start there). A GATEWAY_PORT that is no number is refused naming it."""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

from tests.helpers.timing import scaled


def _descendants(root: int) -> list[int]:
    """Every process below ``root``, from /proc."""
    children: dict[int, list[int]] = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        with contextlib.suppress(OSError, ValueError, IndexError):
            fields = stat.read_text().rsplit(")", 1)[1].split()
            children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    found, todo = [], [root]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def _demo(env: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    """Run the demo in its own process group; one that starts (the port was not refused) is stopped
    with everything it started when the deadline passes, and the test fails."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "gateway.cli", "demo", *args],
        env={**os.environ, **env},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        out, err = proc.communicate(timeout=scaled(20))  # a refusal comes at once
    except subprocess.TimeoutExpired:
        tree = _descendants(proc.pid)  # the simulator and gateway it started run in their own groups
        for pid in [proc.pid, *tree]:
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGTERM)
        try:
            out, err = proc.communicate(timeout=scaled(20))
        finally:
            for pid in [proc.pid, *_descendants(proc.pid), *tree]:
                with contextlib.suppress(ProcessLookupError):
                    os.kill(pid, signal.SIGKILL)
        raise AssertionError(f"the demo started instead of refusing: {err[-2000:]}") from None
    return subprocess.CompletedProcess(proc.args, proc.returncode, out, err)


def test_demo_uses_gateway_port() -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        done = _demo({"GATEWAY_PORT": str(port)}, "--count", "1")
    assert done.returncode == 2, done.stdout + done.stderr
    assert f"port {port} on 127.0.0.1 is already in use" in done.stderr, done.stderr


def test_demo_refuses_a_gateway_port_that_is_no_number() -> None:
    done = _demo({"GATEWAY_PORT": "http"}, "--count", "1")
    assert done.returncode == 2
    assert done.stderr.strip() == (
        "fleet-gateway demo: error: GATEWAY_PORT must be a port number 1-65535; got 'http'"
    ), done.stderr
