"""`make demo` runs `fleet-gateway demo`: the gateway with simulated drones that an MCP client can use."""

from __future__ import annotations

import asyncio
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from fleet_agent.mcp_link import McpLink
from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled


def _children_of(pid: int) -> set[int]:
    """Every live process whose parent chain reaches ``pid``."""
    parents: dict[int, int] = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            parents[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
    found: set[int] = set()
    frontier = {pid}
    while frontier:
        frontier = {child for child, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


async def _read_until(proc: subprocess.Popen, marker: str, timeout_s: float) -> list[str]:
    lines: list[str] = []
    deadline = time.monotonic() + scaled(timeout_s)
    assert proc.stdout is not None
    while time.monotonic() < deadline:
        line = await asyncio.to_thread(proc.stdout.readline)
        if not line:
            raise AssertionError("demo exited early:\n" + "".join(lines))
        lines.append(line)
        if marker in line:
            return lines
    raise AssertionError("demo did not get ready:\n" + "".join(lines))


def _start_demo(port: int) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "gateway.cli", "demo", "--port", str(port), "--speedup", "10"],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )


def _alive(pids: set[int]) -> list[int]:
    return [pid for pid in pids if Path(f"/proc/{pid}").exists()]


async def test_demo_serves_three_ready_drones_over_mcp_and_stops_cleanly(process_reaper: list) -> None:
    port = free_tcp_port()
    proc = _start_demo(port)
    process_reaper.append(proc)
    lines = await _read_until(proc, "Ctrl-C stops", timeout_s=150)
    text = "".join(lines)
    mcp_url = f"http://127.0.0.1:{port}/mcp"
    assert f"MCP endpoint (Streamable HTTP): {mcp_url}" in text
    assert f"claude mcp add --transport http fleet-gateway {mcp_url}" in text
    # what a person reads up to the banner is the demo's own lines: no log records (they go to its log)
    noise = [line for line in lines if "HTTP Request" in line or " INFO " in line or line.startswith("INFO")]
    assert not noise, "log lines before the banner:\n" + "".join(noise)

    async with McpLink(mcp_url) as link:
        outcome = await link.call_tool("list_drones", {})
    assert not outcome.is_error, outcome
    drones = {d["drone_id"]: d for d in outcome.structured["drones"]}
    assert sorted(drones) == ["alpha", "bravo", "charlie"]
    assert all(d["state"] == "ready" for d in drones.values()), drones

    helpers = _children_of(proc.pid)
    assert helpers, "the demo runs its simulator and gateway as child processes"
    proc.send_signal(signal.SIGINT)
    assert await asyncio.to_thread(proc.wait, scaled(60)) == 0
    rest = proc.stdout.read() if proc.stdout else ""
    assert "stopped" in rest
    still_alive = _alive(helpers)
    assert not still_alive, f"processes left behind: {still_alive}"
