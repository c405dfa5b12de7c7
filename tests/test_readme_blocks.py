"""Every shell and Python block of README.md, run as written against a fresh gateway and simulator, or
skipped with its reason named (a block this machine cannot run: a tool it lacks, a placeholder to fill
in, a build of the autopilots). A block the table below does not name fails the test, so a new block is
either run or given its reason.

The blocks run as a reader pastes them, in README order, in two rounds (side by side) each on its own
fresh gateway and simulator started by the "Run the gateway" block: one without agent tokens (the plain
MCP client, ground stations, the operator's curl lines), one with `GATEWAY_AGENT_TOKENS` (the
bearer-token snippet).
The only change is the ports: the ones picked free here stand for 8765 (the gateway) and 5760, 5770,
5780 (the simulator's drones), which the "Run the gateway" block itself reads from GATEWAY_PORT and
SIM_PORT. `make install`, the block's first line, made the environment the test runs in (.venv).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import httpx
import pytest

from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()
TOKEN = "readme-agent-token"


@dataclass(frozen=True)
class Block:
    language: str
    text: str
    line: int

    @property
    def label(self) -> str:
        first = next((ln for ln in self.text.splitlines() if ln.strip() and not ln.startswith("#")), "")
        return f"README.md:{self.line} {first[:60]}"


def readme_blocks(languages: tuple[str, ...] = ("bash", "sh", "shell", "python")) -> list[Block]:
    blocks = []
    for found in re.finditer(r"^```(\w*)\n(.*?)^```", README, re.S | re.M):
        if found.group(1) in languages:
            blocks.append(Block(found.group(1), found.group(2), README.count("\n", 0, found.start()) + 1))
    return blocks


def _claude_missing() -> str | None:
    return None if shutil.which("claude") else "needs Claude Code's `claude` command, not installed here"


#: blocks not run, each with why (a callable: the reason is probed on this machine), by words they hold
SKIPPED = {
    "make test   #": lambda: (
        "`make test` runs the whole suite, this test among it; `make demo` (the same "
        "block) serves on 8765 only, and tests/test_demo.py runs its `fleet-gateway demo`"
    ),
    "claude mcp add --transport http fleet-gateway": _claude_missing,
    "claude mcp add --transport stdio": lambda: (
        "a template: /ABSOLUTE/PATH is the reader's own path (and it needs Claude Code's `claude`)"
    ),
    'claude mcp add --transport http --header "Authorization': _claude_missing,
    "npx @modelcontextprotocol/inspector": lambda: (
        "starts the MCP Inspector's interactive web page and waits for a person at the browser"
    ),
    "drones add x500-1 udpin://0.0.0.0:14540": lambda: (
        "needs a PX4 SITL on UDP 14540, and binds "
        "0.0.0.0 (the tests bind loopback only); tests/real/test_tour_px4.py registers PX4 so on loopback"
    ),
    "git clone --recursive https://github.com/ArduPilot/ardupilot": lambda: (
        "clones and builds ArduPilot "
        "and PX4 (network, about an hour of compiling); tests/real runs with the prebuilt binaries"
    ),
    "docker compose -f deploy/docker-compose.yml up": lambda: (
        "builds container images and needs a "
        "container engine that can run them (root podman or docker); `make swarm-test` runs this file"
    ),
}
#: blocks run, by words they hold: the round (the gateway's agent tokens) each runs in
RUN = {
    "fleet-gateway sim --count 3": "both",
    "from mcp import Client\n\n\nasync def main": "open",
    "drones add charlie tcpout://127.0.0.1:5780": "open",
    "/api/v1/vehicles/alpha/lock": "open",
    'os.environ["FLEET_AGENT_TOKEN"]': "tokens",
}


def _key(block: Block, table: dict[str, object]) -> str | None:
    keys = [k for k in table if k in block.text]
    assert len(keys) <= 1, f"{block.label}: several entries match: {keys}"
    return keys[0] if keys else None


def test_every_block_is_run_or_skipped_with_its_reason() -> None:
    blocks = readme_blocks()
    assert len(blocks) >= 12, [b.label for b in blocks]
    for block in blocks:
        run, skipped = _key(block, RUN), _key(block, SKIPPED)  # type: ignore[arg-type]
        assert (run is None) != (skipped is None), f"{block.label}: neither run nor skipped with a reason"
    for table in (RUN, SKIPPED):
        for key in table:
            assert any(key in b.text for b in blocks), f"no README block holds {key!r} any more"


def test_the_json_blocks_are_json() -> None:
    for block in readme_blocks(("json",)):
        json.loads(block.text)


@pytest.mark.parametrize("block", [b for b in readme_blocks() if _key(b, SKIPPED)], ids=lambda b: b.label)
def test_block_not_run_here(block: Block) -> None:
    key = _key(block, SKIPPED)
    assert key is not None
    reason = SKIPPED[key]()
    if reason is None:
        pytest.fail(f"{block.label}: could run here; give it a place in RUN")
    pytest.skip(f"{block.label}: {reason}")


def _bindable(port: int) -> bool:
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


#: ports this module has handed out: the two gateway rounds run side by side in one process, and the OS can
#: hand both the same free port (a CI run saw the tokens round register its drone with the open round's
#: gateway, then the open round's own registration refused as a duplicate)
_HANDED_OUT: set[int] = set()
_HANDING = threading.Lock()


def _unique_port(span: tuple[int, ...] = (0,)) -> int:
    """A free port P with every P+k of ``span`` free and none handed out to another round before."""
    with _HANDING:
        for _ in range(200):
            base = free_tcp_port()
            ports = {base + k for k in span}
            if base < 60000 and not ports & _HANDED_OUT and all(_bindable(p) for p in ports):
                _HANDED_OUT.update(ports)
                return base
    raise AssertionError(f"no free ports at offsets {span} not handed out already")


def free_sim_base() -> int:
    """A port P with P, P+10 and P+20 free (the simulator's three drones)."""
    return _unique_port((0, 10, 20))


@dataclass
class Round:
    port: int
    sim: int
    env: dict[str, str]
    log: Path

    def text(self, block: Block) -> str:
        """The block with this round's ports for the README's 8765 and 5760 / 5770 / 5780."""
        text = block.text.replace("127.0.0.1:8765", f"127.0.0.1:{self.port}")
        for k in range(3):
            text = text.replace(f"127.0.0.1:{5760 + 10 * k}", f"127.0.0.1:{self.sim + 10 * k}")
        return text

    def run(self, block: Block, timeout_s: float = 120) -> str:
        if block.language == "python":
            done = subprocess.run(
                [sys.executable, "-c", self.text(block)],
                cwd=ROOT,
                env=self.env,
                capture_output=True,
                text=True,
                timeout=scaled(timeout_s),
            )
            assert done.returncode == 0, f"{block.label}\n{done.stderr[-3000:]}"
            return done.stdout
        done = subprocess.run(
            ["bash", "-e", "-c", self.text(block)],
            cwd=ROOT,
            env=self.env,
            capture_output=True,
            text=True,
            timeout=scaled(timeout_s),
        )
        assert done.returncode == 0, f"{block.label}\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}"
        return done.stdout + done.stderr

    def states(self) -> dict[str, str]:
        api = f"http://127.0.0.1:{self.port}/api/v1/vehicles"
        return {v["id"]: v["state"] for v in httpx.get(api, timeout=scaled(10)).json()["items"]}

    def wait_ready(self, *drones: str) -> None:
        deadline = time.monotonic() + scaled(90)
        while not all(self.states().get(d) == "ready" for d in drones):
            assert time.monotonic() < deadline, self.states()
            time.sleep(0.5)


def _block(key: str) -> Block:
    found = [b for b in readme_blocks() if key in b.text]
    assert len(found) == 1, f"{key!r}: {[b.label for b in found]}"
    return found[0]


@contextmanager
def gateway_round(tmp_path: Path, name: str, extra_env: dict[str, str]) -> Iterator[Round]:
    """The "Run the gateway" block (less its `make install`) started in its own session: the simulator,
    the gateway and two drones; everything it started is stopped at the end."""
    block = _block("fleet-gateway sim --count 3")
    assert block.text.splitlines()[0] == "make install"
    script = Block(block.language, "\n".join(block.text.splitlines()[1:]), block.line)
    port, sim = _unique_port(), free_sim_base()
    env = {k: v for k, v in os.environ.items() if not k.startswith("GATEWAY_")}
    env.update(
        GATEWAY_PORT=str(port),
        SIM_PORT=str(sim),
        GATEWAY_DATABASE_URL=f"sqlite+aiosqlite:///{tmp_path / f'{name}.db'}",
        **extra_env,
    )
    log = tmp_path / f"{name}.log"  # a file, not a pipe: the block's background processes keep theirs open
    with log.open("w") as sink:
        shell = subprocess.Popen(
            ["bash", "-e", "-c", script.text],
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
        ready = Round(port, sim, env, log)
        ready.wait_ready("alpha", "bravo")
        yield ready
    finally:
        try:  # the session's group is the shell's pid, whether or not the shell is still running
            os.killpg(shell.pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        _wait_gone(port)


def test_readme_blocks_run_as_pasted(tmp_path: Path) -> None:
    if not (ROOT / ".venv" / "bin" / "fleet-gateway").exists():
        pytest.skip("needs `make install` (the block's first line): .venv/bin/fleet-gateway is missing")
    # the two rounds share nothing (each its own ports, database, simulator and gateway): the tokens round
    # runs in a thread beside the open one, so the test waits for the longer round, not for both in turn
    with ThreadPoolExecutor(max_workers=1) as beside:
        tokens = beside.submit(_tokens_round, tmp_path)
        ran = _open_round(tmp_path)
        ran += tokens.result()
    expected = [b.label for b in readme_blocks() if _key(b, RUN)]
    assert sorted(ran) == sorted(expected)


def _open_round(tmp_path: Path) -> list[str]:
    """The round without agent tokens; the labels of the blocks it ran."""
    ran: list[str] = []
    with gateway_round(tmp_path, "open", {}) as open_round:
        ran.append(_block("fleet-gateway sim --count 3").label)

        client = _block("from mcp import Client\n\n\nasync def main")
        out = open_round.run(client)
        assert re.match(r"\d+ tools\n", out) and "is_error=False" in out.replace(" ", ""), out
        ran.append(client.label)

        stations = _block("drones add charlie tcpout://127.0.0.1:5780")
        out = open_round.run(stations)
        assert "registered charlie" in out and '"gcs_endpoints"' in out, out
        open_round.wait_ready("charlie")
        ran.append(stations.label)

        operator = _block("/api/v1/vehicles/alpha/lock")
        out = open_round.run(operator)
        assert '"reason":"battery swap"' in out and '"items"' in out, out
        ran.append(operator.label)
    return ran


def _tokens_round(tmp_path: Path) -> list[str]:
    """The round with ``GATEWAY_AGENT_TOKENS``; the labels of the blocks it ran."""
    with gateway_round(tmp_path, "tokens", {"GATEWAY_AGENT_TOKENS": TOKEN, "FLEET_AGENT_TOKEN": TOKEN}) as r:
        bearer = _block('os.environ["FLEET_AGENT_TOKEN"]')
        out = r.run(bearer, timeout_s=180)
        # the takeoff answers once the climb is done, not a timeout while the drone flies
        assert "succeeded" in out and "is_error=False" in out.replace(" ", ""), out
        return [bearer.label]


def _wait_gone(port: int) -> None:
    deadline = time.monotonic() + scaled(30)
    while not _bindable(port) and time.monotonic() < deadline:
        time.sleep(0.2)
