"""A small real MCP server for the host's tests: two drones with the gateway's tool shapes, served over
Streamable HTTP.

It is not the gateway: it exists so the agent loop can be tested over the real MCP transport (progress
notifications, tool errors, bearer auth) independently of the gateway's own tools."""

from __future__ import annotations

import asyncio
import threading
import time
from dataclasses import dataclass, field
from typing import Annotated, Any

import uvicorn
from mcp.server.auth.provider import AccessToken, TokenVerifier
from mcp.server.auth.settings import AuthSettings
from mcp.server.mcpserver import Context, MCPServer
from mcp.server.mcpserver.exceptions import ToolError
from mcp.types import CallToolResult, TextContent, ToolAnnotations
from pydantic import Field

from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

TOKEN = "toy-agent-token"
MAX_ALT_M = 120.0
HOME = (47.3977, 8.5456)  # every toy drone's home; a metre north is 1 / 111_195 degree


def toy_lat_lon(d: ToyDrone) -> tuple[float, float]:
    lat = HOME[0] + d.north_m / 111_195.0
    return lat, HOME[1] + d.east_m / (111_195.0 * 0.6769)  # cos(47.3977 deg)


@dataclass
class ToyDrone:
    alt_m: float = 0.0
    north_m: float = 0.0
    east_m: float = 0.0
    armed: bool = False
    battery_pct: float = 90.0


@dataclass
class ToyWorld:
    drones: dict[str, ToyDrone] = field(default_factory=lambda: {"alpha": ToyDrone(), "bravo": ToyDrone()})
    calls: list[tuple[str, dict]] = field(default_factory=list)


class _Verifier(TokenVerifier):
    def __init__(self, resource: str) -> None:
        self.resource = resource

    async def verify_token(self, token: str) -> AccessToken | None:
        if token != TOKEN:
            return None
        return AccessToken(
            token=token,
            client_id="agent",
            scopes=["fleet"],
            resource=self.resource,
            expires_at=int(time.time()) + 3600,
        )


def build_toy_server(world: ToyWorld, url: str) -> MCPServer:
    mcp = MCPServer(
        "toy-fleet",
        token_verifier=_Verifier(url),
        auth=AuthSettings(
            issuer_url="http://127.0.0.1:9/issuer",
            resource_server_url=url,
            required_scopes=["fleet"],
            validate_token_resource=True,
        ),
    )

    def drone(drone_id: str) -> ToyDrone:
        if drone_id not in world.drones:
            raise ToolError(f"unknown drone {drone_id!r}; known: {sorted(world.drones)}")
        return world.drones[drone_id]

    @mcp.tool(meta={"fleet-gateway/toolset": "flight"})
    async def takeoff(
        drone_id: Annotated[str, Field(description="drone id")],
        alt_m: Annotated[float, Field(description="metres above home")],
        ctx: Context,
    ) -> Any:
        """Take off and climb to alt_m above home; waits until reached."""
        world.calls.append(("takeoff", {"drone_id": drone_id, "alt_m": alt_m}))
        d = drone(drone_id)
        if alt_m > MAX_ALT_M:
            return refusal("max_altitude", f"altitude {alt_m:g} m exceeds the limit of {MAX_ALT_M:g} m")
        d.armed = True
        for i in range(1, 4):
            await asyncio.sleep(0.02)
            d.alt_m = alt_m * i / 3
            await ctx.report_progress(i, 3, message=f"climbing {d.alt_m:.1f}/{alt_m:g} m")
        return {"status": "reached", "alt_m": d.alt_m}

    @mcp.tool(meta={"fleet-gateway/toolset": "navigation"})
    async def move_to_relative(
        drone_id: str,
        ctx: Context,
        north_m: Annotated[float, Field(ge=-1000, le=1000)] = 0.0,
        east_m: Annotated[float, Field(ge=-1000, le=1000)] = 0.0,
        up_m: float | None = None,
        alt_m: float | None = None,
    ) -> Any:
        """Fly north_m/east_m from where the drone is (up_m or alt_m: the height)."""
        world.calls.append(("move_to_relative", {"drone_id": drone_id, "north_m": north_m, "east_m": east_m}))
        d = drone(drone_id)
        if d.alt_m <= 0:
            raise ToolError(f"{drone_id} is on the ground: take off first")
        d.north_m, d.east_m = d.north_m + north_m, d.east_m + east_m
        d.alt_m = alt_m if alt_m is not None else d.alt_m + (up_m or 0.0)
        await ctx.report_progress(1, 1, message=f"arrived {d.north_m:g} m north")
        return {"status": "arrived", "north_m": d.north_m, "east_m": d.east_m}

    @mcp.tool(meta={"fleet-gateway/toolset": "navigation"})
    def go_to_location(drone_id: str, lat_deg: float, lon_deg: float, alt_m: float) -> dict[str, Any]:
        """Fly to a point at alt_m above home."""
        world.calls.append(("go_to_location", {"drone_id": drone_id, "lat_deg": lat_deg, "lon_deg": lon_deg}))
        d = drone(drone_id)
        d.north_m = (lat_deg - HOME[0]) * 111_195.0
        d.east_m = (lon_deg - HOME[1]) * 111_195.0 * 0.6769
        d.alt_m = alt_m
        return {"status": "arrived"}

    @mcp.tool(meta={"fleet-gateway/toolset": "flight"})
    def land(drone_id: str) -> dict[str, str]:
        """Land and disarm."""
        world.calls.append(("land", {"drone_id": drone_id}))
        d = drone(drone_id)
        d.alt_m, d.armed = 0.0, False
        return {"status": "landed"}

    @mcp.tool(meta={"fleet-gateway/toolset": "fleet"}, annotations=ToolAnnotations(readOnlyHint=True))
    def list_drones() -> dict[str, Any]:
        """All drones (the gateway's shape: drone_id, state, in_air, alt_m, battery_pct)."""
        rows = [
            {
                "drone_id": i,
                "state": "ready",
                "in_air": d.alt_m > 0,
                "alt_m": d.alt_m,
                "lat_deg": toy_lat_lon(d)[0],
                "lon_deg": toy_lat_lon(d)[1],
                "battery_pct": d.battery_pct,
            }
            for i, d in world.drones.items()
        ]
        return {"count": len(rows), "drones": rows}

    @mcp.tool(meta={"fleet-gateway/toolset": "telemetry"}, annotations=ToolAnnotations(readOnlyHint=True))
    def get_position(drone_id: str) -> str:
        """Where a drone is, in metres north of home and above home."""
        d = drone(drone_id)
        return f"{drone_id}: {d.north_m:g} m north, {d.alt_m:g} m up, armed={d.armed}"

    @mcp.tool(meta={"fleet-gateway/toolset": "telemetry"}, annotations=ToolAnnotations(readOnlyHint=True))
    def get_battery(drone_id: str) -> str:
        """A drone's battery, as the gateway words it."""
        return f"{drone_id} battery {drone(drone_id).battery_pct:g}%, 11.8 V"

    return mcp


def refusal(rule: str, message: str) -> CallToolResult:
    """A refusal as the gateway sends one: the text, and code, rule and message as structured content."""
    return CallToolResult(
        content=[TextContent(type="text", text=f"Refused: {message}")],
        structured_content={"code": "safety_refusal", "message": message, "rule": rule, "details": {}},
        is_error=True,
    )


class ToyServer:
    """Runs the toy MCP server with uvicorn in a thread on a free loopback port."""

    def __init__(self) -> None:
        self.world = ToyWorld()
        self.port = free_tcp_port()
        self.url = f"http://127.0.0.1:{self.port}/mcp"
        self.mcp = build_toy_server(self.world, self.url)
        app = self.mcp.streamable_http_app()
        self._server = uvicorn.Server(
            uvicorn.Config(app, host="127.0.0.1", port=self.port, log_level="warning", lifespan="on")
        )
        self._thread = threading.Thread(target=self._server.run, name="toy-mcp", daemon=True)

    def __enter__(self) -> ToyServer:
        self._thread.start()
        deadline = time.monotonic() + scaled(30)
        while not self._server.started:
            if not self._thread.is_alive() or time.monotonic() > deadline:
                raise RuntimeError("toy MCP server did not start")
            time.sleep(0.02)
        return self

    def __exit__(self, *exc: object) -> None:
        self._server.should_exit = True
        self._thread.join(timeout=scaled(10))
