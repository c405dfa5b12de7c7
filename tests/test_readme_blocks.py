"""README.md's "Run the gateway" block and its bearer-token Python snippet, run as written (the ports from
GATEWAY_PORT and SIM_PORT, which the block reads, picked free here): the drones come up ready, and the
snippet's takeoff answers once the climb is done rather than timing out while the drone flies.

`make install` is the block's first line; the test runs in the environment it made (.venv), so that line
is the one left out."""

from __future__ import annotations

import os
import re
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx
import pytest

from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()
TOKEN = "readme-agent-token"


def block_after(heading: str, language: str) -> str:
    section = README[README.index(heading) :]
    found = re.search(rf"```{language}\n(.*?)```", section, re.S)
    assert found is not None, f"no {language} block after {heading!r}"
    return found.group(1)


def python_block_with(words: str) -> str:
    for block in re.findall(r"```python\n(.*?)```", README, re.S):
        if words in block:
            return str(block)
    raise AssertionError(f"no python block of README.md says {words!r}")


def _bindable(port: int) -> bool:
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


def free_sim_base() -> int:
    """A port P with P, P+10 and P+20 free (the simulator's three drones)."""
    for _ in range(200):
        base = free_tcp_port()
        if base < 60000 and all(_bindable(base + k) for k in (10, 20)):
            return base
    raise AssertionError("no three free ports 10 apart")


def test_run_the_gateway_block_and_the_bearer_snippet_work_as_pasted(tmp_path: Path) -> None:
    if not (ROOT / ".venv" / "bin" / "fleet-gateway").exists():
        pytest.skip("needs `make install` (the block's first line): .venv/bin/fleet-gateway is missing")
    block = block_after("## Run the gateway", "bash")
    assert block.splitlines()[0] == "make install"
    script = "\n".join(block.splitlines()[1:])
    port, sim = free_tcp_port(), free_sim_base()
    env = {
        **os.environ,
        "GATEWAY_PORT": str(port),
        "SIM_PORT": str(sim),
        "GATEWAY_DATABASE_URL": f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}",
        "GATEWAY_AGENT_TOKENS": TOKEN,
        "FLEET_AGENT_TOKEN": TOKEN,
    }
    log = tmp_path / "block.log"  # a file, not a pipe: the block's background processes keep theirs open
    with log.open("w") as sink:
        shell = subprocess.Popen(
            ["bash", "-e", "-c", script],
            cwd=ROOT,
            env=env,
            stdout=sink,
            stderr=subprocess.STDOUT,
            start_new_session=True,  # the block's background processes too: one group, stopped at the end
        )
    try:
        shell.wait(timeout=scaled(120))
        out = log.read_text()
        assert shell.returncode == 0, out
        assert "Connection refused" not in out and "alpha" in out and "bravo" in out, out
        api = f"http://127.0.0.1:{port}/api/v1/vehicles"
        deadline = time.monotonic() + scaled(90)
        while True:
            states = {v["id"]: v["state"] for v in httpx.get(api, timeout=scaled(10)).json()["items"]}
            if states == {"alpha": "ready", "bravo": "ready"}:
                break
            assert time.monotonic() < deadline, states
            time.sleep(0.5)

        snippet = python_block_with("FLEET_AGENT_TOKEN")
        done = subprocess.run(
            [sys.executable, "-c", snippet], env=env, capture_output=True, text=True, timeout=scaled(180)
        )
        assert done.returncode == 0, done.stderr[-2000:]
        assert "succeeded" in done.stdout and "is_error=False" in done.stdout.replace(" ", ""), done.stdout
    finally:
        try:  # the session's group is the shell's pid, whether or not the shell is still running
            os.killpg(shell.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        _wait_gone(port)


def _wait_gone(port: int) -> None:
    deadline = time.monotonic() + scaled(30)
    while not _bindable(port) and time.monotonic() < deadline:
        time.sleep(0.2)
