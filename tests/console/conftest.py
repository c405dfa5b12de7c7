"""Fixtures of the console tests: a real gateway with tokens over simulated drones, an agent connected
over MCP with its token, and headless Chromium (Debian's package) driven by Playwright.

The browser tests skip, saying why, where Playwright or Chromium is missing; `.ci/run` installs Chromium.
With FLEET_WRITE_SCREENSHOTS=1 they also write the screenshots of docs/console.md (docs/console/*.png).
"""

from __future__ import annotations

import contextlib
import os
import shutil
from collections.abc import AsyncIterator
from pathlib import Path
from typing import Any

import httpx
import httpx2
import pytest
import pytest_asyncio
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import Implementation

from gateway.fleet import geo
from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack, gateway_stack

OPERATOR_TOKEN = "console-test-operator-6f1c2a"
VIEWER_TOKEN = "console-test-viewer-93be07"
AGENT_TOKEN = "console-test-agent-d4a851"
TAGS = {"d1": ["north", "survey"], "d2": ["north"], "d3": ["south"]}

ROOT = Path(__file__).resolve().parents[2]
SCREENSHOT_DIR = ROOT / "docs" / "console"
WRITE_SCREENSHOTS = os.environ.get("FLEET_WRITE_SCREENSHOTS", "") == "1"
CHROMIUM_CANDIDATES = ("chromium", "chromium-browser", "/usr/lib/chromium/chromium", "google-chrome")


def chromium_executable() -> str | None:
    """FLEET_CHROMIUM, else Debian's chromium (or another Chromium on PATH); None when there is none."""
    explicit = os.environ.get("FLEET_CHROMIUM")
    if explicit:
        return explicit if Path(explicit).is_file() else None
    for name in CHROMIUM_CANDIDATES:
        found = shutil.which(name)
        if found:
            return found
    return None


def ui_timeout_ms(seconds: float = 20.0) -> float:
    """A deadline for the page to show something (Playwright waits in milliseconds)."""
    return scaled(seconds) * 1000.0


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def console_stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    """A gateway with operator, viewer and agent tokens over three simulated drones d1..d3 (tagged)."""
    async with gateway_stack(
        tmp_path_factory.mktemp("console"),
        count=3,
        token=OPERATOR_TOKEN,
        tags=TAGS,
        operator_tokens=OPERATOR_TOKEN,
        viewer_tokens=VIEWER_TOKEN,
        agent_tokens=AGENT_TOKEN,
    ) as stack:
        await stack_geofences(stack)
        yield stack


def _square(lat: float, lon: float, north_m: float, east_m: float, half_m: float) -> list[list[float]]:
    corners = [(-1, -1), (-1, 1), (1, 1), (1, -1), (-1, -1)]
    ring = []
    for dn, de in corners:
        c_lat, c_lon = geo.offset_position(lat, lon, north_m + dn * half_m, east_m + de * half_m)
        ring.append([c_lon, c_lat])
    return ring


async def stack_geofences(stack: Stack) -> None:
    """A keep-in square of 400 m around the drones and a keep-out square 40 m south-west (set over REST)."""
    home = (await stack.true_state("d1"))["home"]
    zones = {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {"kind": "keep_in", "name": "airfield"},
                "geometry": {
                    "type": "Polygon",
                    "coordinates": [_square(home["lat"], home["lon"], 0, 0, 200)],
                },
            },
            {
                "type": "Feature",
                "properties": {"kind": "keep_out", "name": "barn"},
                "geometry": {
                    "type": "Polygon",
                    "coordinates": [_square(home["lat"], home["lon"], -40, -40, 10)],
                },
            },
        ],
    }
    headers = {"Authorization": f"Bearer {OPERATOR_TOKEN}"}
    async with httpx.AsyncClient(base_url=stack.base_url, headers=headers, timeout=scaled(30)) as http:
        (await http.put("/api/v1/fleet/geofences", json=zones)).raise_for_status()


@contextlib.asynccontextmanager
async def agent(stack: Stack, name: str = "console-test-agent") -> AsyncIterator[Client]:
    """An MCP client over Streamable HTTP with the agent token, as an LLM host would connect."""
    http = httpx2.AsyncClient(headers={"Authorization": f"Bearer {AGENT_TOKEN}"}, timeout=scaled(120))
    async with (
        http,
        Client(
            streamable_http_client(stack.mcp_url, http_client=http),
            client_info=Implementation(name=name, version="1.0"),
        ) as client,
    ):
        yield client


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def browser() -> AsyncIterator[Any]:
    try:
        from playwright.async_api import async_playwright
    except ImportError:
        pytest.skip("Playwright is not installed: make install (it is a dev dependency)")
    executable = chromium_executable()
    if executable is None:
        pytest.skip(
            "no Chromium to drive: apt-get install chromium (Debian's package; .ci/run does it) "
            "or point FLEET_CHROMIUM at a Chromium binary"
        )
    async with async_playwright() as playwright:
        launched = await playwright.chromium.launch(executable_path=executable, headless=True)
        try:
            yield launched
        finally:
            await launched.close()


async def screenshot(page: Any, name: str) -> None:
    """docs/console/<name>.png, only when FLEET_WRITE_SCREENSHOTS=1 (normal runs leave the tree alone)."""
    if WRITE_SCREENSHOTS:
        SCREENSHOT_DIR.mkdir(parents=True, exist_ok=True)
        await page.screenshot(path=str(SCREENSHOT_DIR / f"{name}.png"))
