"""The MCP conformance suite (@modelcontextprotocol/conformance, its `server` scenarios) against a real
gateway over real HTTP, and the answers it found wrong (a prompt that does not exist).

The suite is a Node.js package: install it with Node 22 into a folder once,

    mkdir -p ~/.cache/fleet-gateway/conformance && cd ~/.cache/fleet-gateway/conformance
    npm install node@22 @modelcontextprotocol/conformance

and the test finds it there (or in the folder MCP_CONFORMANCE_DIR names); without it the suite's test
is skipped, saying so. The scenarios that test the suite's own reference server (its tools, prompts and
resources by name, capabilities the gateway does not declare) are listed with why in
``conformance/expected-failures.yml``; every other scenario must pass.
"""

from __future__ import annotations

import asyncio
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from mcp import Client
from mcp.shared.exceptions import MCPError
from mcp.types import INVALID_PARAMS

from tests.api.live import live_settings, served
from tests.helpers.timing import scaled

EXPECTED_FAILURES = Path(__file__).parent / "conformance" / "expected-failures.yml"
DEFAULT_DIR = Path.home() / ".cache" / "fleet-gateway" / "conformance"


def _node_major(node: str) -> int | None:
    out = subprocess.run([node, "--version"], capture_output=True, timeout=60, check=False).stdout
    found = re.match(rb"v(\d+)\.", out)
    return int(found.group(1)) if found else None


def _suite() -> tuple[str, str]:
    """(node, the suite's CLI script), or skip saying what is missing."""
    folder = Path(os.environ.get("MCP_CONFORMANCE_DIR", "") or DEFAULT_DIR).expanduser()
    cli = folder / "node_modules" / "@modelcontextprotocol" / "conformance" / "dist" / "index.js"
    if not cli.is_file():
        pytest.skip(
            f"the MCP conformance suite is not installed in {folder} (there: npm install node@22 "
            "@modelcontextprotocol/conformance; or set MCP_CONFORMANCE_DIR)"
        )
    local = folder / "node_modules" / "node" / "bin" / "node"
    node = str(local) if local.is_file() else shutil.which("node")
    if node is None:
        pytest.skip(f"no Node.js to run the MCP conformance suite in {folder} (npm install node@22 there)")
    major = _node_major(node)
    if major is None or major < 22:
        pytest.skip(f"the MCP conformance suite needs Node.js 22 or later; {node} is {major}")
    return node, str(cli)


async def test_the_mcp_conformance_suite_passes_against_a_real_gateway(tmp_path: Path) -> None:
    node, cli = _suite()
    async with served(live_settings(tmp_path / "gateway.db")) as (_app, http):
        url = f"{str(http.base_url).rstrip('/')}/mcp"
        proc = await asyncio.create_subprocess_exec(
            node,
            cli,
            "server",
            "--url",
            url,
            "--expected-failures",
            str(EXPECTED_FAILURES),
            "--output-dir",
            str(tmp_path / "results"),
            cwd=tmp_path,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.STDOUT,
        )
        try:
            out, _ = await asyncio.wait_for(proc.communicate(), scaled(600))
        finally:
            if proc.returncode is None:
                proc.kill()
                await proc.wait()
    text = out.decode(errors="replace")
    assert proc.returncode == 0, text[-6000:]
    assert "all failures are expected" in text, text[-3000:]


async def test_a_prompt_that_does_not_exist_or_lacks_its_arguments_is_invalid_params(tmp_path: Path) -> None:
    """JSON-RPC -32602 naming the prompts there are (the SDK answered with error code 0)."""
    async with served(live_settings(tmp_path / "gateway.db")) as (_app, http):
        async with Client(f"{str(http.base_url).rstrip('/')}/mcp", mode="legacy") as client:
            with pytest.raises(MCPError) as unknown:
                await client.get_prompt("test_simple_prompt")
            assert unknown.value.error.code == INVALID_PARAMS, unknown.value.error
            assert "unknown prompt 'test_simple_prompt'; the prompts: " in unknown.value.error.message
            assert "preflight_check" in unknown.value.error.message
            with pytest.raises(MCPError) as bare:
                await client.get_prompt("preflight_check")
            assert bare.value.error.code == INVALID_PARAMS, bare.value.error
            assert "prompt 'preflight_check': " in bare.value.error.message
            answer = await client.get_prompt("preflight_check", {"drone_id": "d1"})
            assert "d1" in str(answer.messages[0].content)
