"""The fleet as the compiler reads it, from the gateway's telemetry over MCP (``list_drones``, one call for
every drone, read again after each action) and, for named places, from another MCP server's tool."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any

from fleet_agent.compiler import CompileError, DroneState
from fleet_agent.records import Arguments, ToolOutcome

#: reads through the host, so that each appears among the turn's calls
ReadFn = Callable[[str, Arguments], Awaitable[ToolOutcome]]


class McpSensors:
    def __init__(self, read: ReadFn, place_tool: str | None = None, place_read: ReadFn | None = None) -> None:
        self._read = read
        self._place_tool = place_tool
        self._place_read = place_read or read
        self._fleet: dict[str, DroneState] | None = None
        self._at_start: dict[str, DroneState] = {}  # the fleet as the turn found it

    def invalidate(self) -> None:
        """Called after every action: the next reading is fresh."""
        self._fleet = None

    async def drone_ids(self) -> list[str]:
        return list(await self._all())

    async def state(self, drone: str) -> DroneState:
        fleet = await self._all()
        if drone not in fleet:
            raise CompileError(f"{drone} is not in the gateway's fleet")
        return fleet[drone]

    async def home(self, drone: str) -> tuple[float, float]:
        """Where it stood on the ground when the turn began (its pad: it arms there, and the home its
        autopilot reports may be an earlier flight's), else the autopilot's home."""
        start = (self._at_start or await self._all()).get(drone)
        if start is not None and not start.flying and start.lat is not None and start.lon is not None:
            return start.lat, start.lon
        out = await self._read("get_home_position", {"drone_id": drone})
        return _lat_lon(out, f"{drone}'s home")

    async def place(self, name: str) -> tuple[float, float]:
        if self._place_tool is None:
            raise CompileError(f"no server offers named places, so {name!r} is unknown")
        out = await self._place_read(self._place_tool, {"place": name})
        return _lat_lon(out, repr(name))

    async def _all(self) -> dict[str, DroneState]:
        if self._fleet is None:
            out = await self._read("list_drones", {})
            rows = (out.structured or {}).get("drones") or []
            self._fleet = {str(r["drone_id"]): _state(r) for r in rows}
            self._at_start = self._at_start or self._fleet
        return self._fleet


def _state(row: dict[str, Any]) -> DroneState:
    return DroneState(row.get("lat_deg"), row.get("lon_deg"), row.get("alt_m"), bool(row.get("in_air")),
                      row.get("battery_pct"), row.get("flight_mode"))  # fmt: skip


def _lat_lon(out: ToolOutcome, what: str) -> tuple[float, float]:
    data = out.structured or {}
    if out.is_error or "lat_deg" not in data or "lon_deg" not in data:
        raise CompileError(f"the position of {what} is unknown: {out.text}")
    return float(data["lat_deg"]), float(data["lon_deg"])
