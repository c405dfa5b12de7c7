"""Integration fixtures of the MCP tests: a simulator with N drones, a real gateway app (REST + /mcp) served
by uvicorn on a free loopback port with a real SQLite file and one mavsdk_server per drone, and MCP
clients over Streamable HTTP.

One gateway + simulator is shared by the tests of a module (module-scoped, module event loop); each test
flies its own drone so the tests stay independent.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
from collections.abc import AsyncIterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import pytest
import pytest_asyncio
from mcp import Client
from mcp.types import CallToolResult, Implementation

from gateway.app import create_app
from gateway.config import Settings
from gateway.fleet import geo
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store
from tests.api.server import serve_in_process, serve_in_thread
from tests.helpers import sim_process
from tests.helpers.sqlite_at_head import at_head
from tests.helpers.timing import scaled
from tests.registry.procs import mavsdk_servers_of

WAIT_S = scaled(90.0)  # generous: waiting is never an assertion


@dataclass
class Stack:
    """A running gateway (base_url) over a simulator (sim), with its settings object (shared, live)."""

    base_url: str
    sim: Any
    settings: Settings
    app: Any
    drone_ids: list[str]
    calls: dict[str, int] = field(default_factory=dict)
    figures: dict[str, float] = field(default_factory=dict)
    #: the bearer token rest() sends (when the gateway has operator tokens)
    token: str | None = None

    @property
    def mcp_url(self) -> str:
        return f"{self.base_url}/mcp"

    def index(self, drone_id: str) -> int:
        return self.drone_ids.index(drone_id)

    async def true_state(self, drone_id: str) -> dict[str, Any]:
        return await self.sim.control.state(self.index(drone_id))

    async def rest(self, path: str, **params: Any) -> Any:
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        async with httpx.AsyncClient(base_url=self.base_url, timeout=scaled(30), headers=headers) as http:
            r = await http.get(f"/api/v1{path}", params=params)
            r.raise_for_status()
            return r.json()

    def client(self, mode: str = "auto", name: str = "mcp-test", **kw: Any) -> Client:
        return Client(self.mcp_url, mode=mode, client_info=Implementation(name=name, version="1.0"), **kw)

    async def call(self, client: Client, tool: str, args: dict[str, Any], **kw: Any) -> CallToolResult:
        """Call a tool and count it (per drone) for the audit check."""
        key = str(args.get("drone_id"))
        self.calls[key] = self.calls.get(key, 0) + 1
        return await client.call_tool(tool, args, **kw)


def integration_settings(tmp: Path, **overrides: Any) -> Settings:
    base: dict[str, Any] = {
        "database_url": f"sqlite+aiosqlite:///{tmp / 'gateway.db'}",
        "spool_path": str(tmp / "spool.jsonl"),  # not the working directory's default: the checkout
        "sidecar_backoff_initial_s": 0.2,
        "sidecar_backoff_max_s": 1.0,
        "link_lost_after_s": 3.0,
        "track_flush_s": 0.5,
        "arrival_tolerance_m": 2.0,
    }
    base.update(overrides)
    return Settings(_env_file=None, **base)


@contextlib.asynccontextmanager
async def gateway_stack(
    tmp: Path,
    count: int,
    speedup: float = 8.0,
    *,
    token: str | None = None,
    tags: dict[str, list[str]] | None = None,
    sim_args: tuple[str, ...] = (),
    own_process: bool = False,
    **overrides: Any,
) -> AsyncIterator[Stack]:
    """Drones d1..dN (with ``tags`` by id); ``token`` is what ``Stack.rest`` authenticates with;
    ``sim_args``: more arguments of the simulator; ``own_process``: the gateway a ``fleet-gateway
    serve`` process (``Stack.app`` None; its settings fixed at its start), not an app in this one."""
    async with sim_process(count=count, speedup=speedup, extra_args=sim_args) as sim:
        settings = integration_settings(tmp, **overrides)
        ids = [f"d{i + 1}" for i in range(count)]
        store = await Store.open(await at_head(settings.database_url))
        try:
            for vid, url, sysid in zip(ids, sim.urls, sim.sysids, strict=True):
                spec = VehicleSpec(id=vid, url=url, expected_sysid=sysid, tags=(tags or {}).get(vid, []))
                await store.add_vehicle(spec)
        finally:
            await store.close()
        app = None if own_process else create_app(settings)
        serving = serve_in_process(settings, tmp / "gateway.log") if app is None else serve_in_thread(app)
        try:
            with serving as base_url:
                stack = Stack(base_url, sim, settings, app, ids, token=token)
                await wait_ready(stack)
                yield stack
        finally:
            assert mavsdk_servers_of() == [], "a mavsdk_server survived the gateway"


async def wait_ready(stack: Stack) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + WAIT_S
    while True:
        body = await stack.rest("/vehicles")
        states = {v["id"]: v.get("state") for v in body["items"]}
        if all(states.get(d) == "ready" for d in stack.drone_ids):
            return
        if loop.time() > deadline:
            raise AssertionError(f"drones not ready: {states}\n{stack.sim.log_tail()}")
        await asyncio.sleep(0.25)


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def stack(
    request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory
) -> AsyncIterator[Stack]:
    """The module's gateway over ``DRONES`` simulated drones (a module-level constant, default 4)."""
    count = getattr(request.module, "DRONES", 4)
    async with gateway_stack(tmp_path_factory.mktemp("mcp"), count=count) as s:
        yield s
        if s.figures:
            print(f"\nMCP figures ({request.module.__name__}): {s.figures}")


async def wait_audited(stack: Stack, drone_id: str) -> None:
    """The audit table holds exactly the calls this test session made on ``drone_id``."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(15.0)
    while True:
        total = (await stack.rest("/audit", vehicle_id=drone_id, limit=1))["total"]
        if total == stack.calls.get(drone_id, 0) or loop.time() > deadline:
            break
        await asyncio.sleep(0.2)
    assert total == stack.calls.get(drone_id, 0), f"audit has {total} rows for {drone_id}"


async def wait_until_true(stack: Stack, drone_id: str, predicate: Any, what: str) -> dict[str, Any]:
    """Poll the simulator's true state until predicate(state) (a generous timeout, never asserted)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + WAIT_S
    while True:
        state = await stack.true_state(drone_id)
        if predicate(state):
            return state
        if loop.time() > deadline:
            raise AssertionError(f"{drone_id}: {what} not reached; true state {state}")
        await asyncio.sleep(0.2)


def distance_m(state: dict[str, Any], lat: float, lon: float) -> float:
    return geo.horizontal_distance_m(state["lat"], state["lon"], lat, lon)


def point_from(state: dict[str, Any], north_m: float, east_m: float) -> tuple[float, float]:
    return geo.offset_position(state["lat"], state["lon"], north_m, east_m)


def structured(r: CallToolResult) -> dict[str, Any]:
    assert not r.is_error, r.content[0].text if r.content else r
    assert r.structured_content is not None
    return r.structured_content


def error_text(r: CallToolResult) -> str:
    assert r.is_error, r.structured_content
    return r.content[0].text


def finite(x: Any) -> bool:
    return isinstance(x, int | float) and math.isfinite(x)
