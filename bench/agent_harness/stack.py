"""The agent benchmark's view of a local sim + gateway, and ways to read the drones' true state.

``LocalStack`` is ``gateway.localstack.LocalStack`` plus ``truth()``. ``SimTruth`` reads the simulator's
true state (the judge of the benchmark); ``GatewayTruth`` falls back to the gateway's own telemetry tools
for an external gateway.
"""

from __future__ import annotations

import asyncio
import contextlib
import re
import time
from collections.abc import Sequence
from typing import Any, Protocol

import httpx

from bench.agent_harness.missions import DroneTruth
from fleet_agent.mcp_link import McpLink
from gateway.localstack import LocalStack as BaseLocalStack
from gateway.localstack import StackError

_VEHICLE_LINE = re.compile(r"^vehicle (\d+) sysid (\d+) (\S+)")


class Truth(Protocol):
    source: str

    async def snapshot(self, drone_ids: Sequence[str]) -> dict[str, DroneTruth]: ...

    async def homes(self, drone_ids: Sequence[str]) -> dict[str, tuple[float, float, float]]: ...


BATTERY_MAH = 3300.0  # the simulated battery (ArduCopter SITL's default BATT_CAPACITY)


class SimTruth:
    """True state from the simulator's control API (vehicle index per drone id)."""

    source = "the simulator (true state)"

    def __init__(self, control_url: str, index_of: dict[str, int]) -> None:
        self.index_of = dict(index_of)
        self._http = httpx.AsyncClient(base_url=control_url.rstrip("/"), timeout=10.0)

    async def aclose(self) -> None:
        await self._http.aclose()

    async def state(self, drone_id: str) -> dict[str, Any]:
        response = await self._http.get(f"/vehicles/{self.index_of[drone_id]}")
        response.raise_for_status()
        return response.json()

    async def snapshot(self, drone_ids: Sequence[str]) -> dict[str, DroneTruth]:
        out = {}
        for d in drone_ids:
            s = await self.state(d)
            out[d] = DroneTruth(
                float(s["lat"]),
                float(s["lon"]),
                float(s["rel_alt_m"]),
                bool(s["armed"]),
                s.get("battery_pct"),
            )
        return out

    async def homes(self, drone_ids: Sequence[str]) -> dict[str, tuple[float, float, float]]:
        """Where each drone stands now (it arms there, so that becomes its home for the mission)."""
        out = {}
        for d in drone_ids:
            s = await self.state(d)
            out[d] = (float(s["lat"]), float(s["lon"]), float(s["alt_amsl_m"]) - float(s["rel_alt_m"]))
        return out

    async def recharge(self, drone_id: str, pct: float = 100.0, speedup: float = 1.0) -> None:
        """Harness-only, between missions: a fresh battery, as a crew would swap it. Its capacity is
        multiplied by the sim's speed-up: the model thinks in wall time while the drone hovers in sim time,
        and a 90 s mission at 5x would otherwise drain a 7-minute battery (measured: 22 % left during
        "fly both 100 m north", below the gateway's 25 % needed for a new leg)."""
        index = self.index_of[drone_id]
        capacity = {"name": "BATT_CAPACITY", "value": BATTERY_MAH * max(1.0, speedup)}
        before = (await self.state(drone_id))["t_boot_s"]
        (await self._http.post(f"/vehicles/{index}/param", json=capacity)).raise_for_status()
        await self._until_stepped(drone_id, before)
        (await self._http.post(f"/vehicles/{index}/battery", json={"pct": pct})).raise_for_status()

    async def _until_stepped(self, drone_id: str, after_t_s: float, timeout_s: float = 30.0) -> None:
        """Wait until the vehicle has stepped past ``after_t_s`` (its clock): it takes a new BATT_CAPACITY
        on its next step, and a level set before that would be a share of the old capacity."""
        deadline = time.monotonic() + timeout_s
        while (await self.state(drone_id))["t_boot_s"] <= after_t_s:
            if time.monotonic() > deadline:
                raise StackError(f"{drone_id}: the simulator did not step within {timeout_s:g} s")
            await asyncio.sleep(0.05)


class GatewayTruth:
    """State as the gateway's own telemetry tools report it (for a gateway without sim access)."""

    source = "the gateway's telemetry (no simulator access)"

    def __init__(self, link: McpLink) -> None:
        self.link = link

    async def _structured(self, tool: str, drone_id: str) -> dict[str, Any]:
        result = await self.link.client.call_tool(tool, {"drone_id": drone_id})
        if result.is_error or not isinstance(result.structured_content, dict):
            text = " ".join(getattr(b, "text", "") for b in result.content)
            raise StackError(f"{tool}({drone_id}) failed: {text}")
        return result.structured_content

    async def snapshot(self, drone_ids: Sequence[str]) -> dict[str, DroneTruth]:
        out = {}
        for d in drone_ids:
            pos = await self._structured("get_position", d)
            armed = await self._structured("get_armed", d)
            battery = await self._structured("get_battery", d)
            out[d] = DroneTruth(
                pos["lat_deg"],
                pos["lon_deg"],
                pos["alt_m"],
                bool(armed.get("value")),
                battery.get("remaining_pct"),
            )
        return out

    async def homes(self, drone_ids: Sequence[str]) -> dict[str, tuple[float, float, float]]:
        out = {}
        for d in drone_ids:
            pos = await self._structured("get_position", d)
            out[d] = (pos["lat_deg"], pos["lon_deg"], pos["alt_amsl_m"] - pos["alt_m"])
        return out


class Sampler:
    """Samples the true state a few times a second while a mission runs (the track the checks read)."""

    def __init__(self, truth: Truth, drone_ids: Sequence[str], period_s: float = 0.25) -> None:
        self.truth, self.drone_ids, self.period_s = truth, list(drone_ids), period_s
        self.tracks: dict[str, list[DroneTruth]] = {d: [] for d in self.drone_ids}
        self._task: asyncio.Task[None] | None = None

    async def _run(self) -> None:
        while True:
            with contextlib.suppress(httpx.HTTPError, StackError):
                snap = await self.truth.snapshot(self.drone_ids)
                for d, t in snap.items():
                    self.tracks[d].append(t)
            await asyncio.sleep(self.period_s)

    async def __aenter__(self) -> Sampler:
        self._task = asyncio.create_task(self._run())
        return self

    async def __aexit__(self, *exc: object) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task


async def reset_drones(
    link: McpLink,
    truth: Truth,
    drone_ids: Sequence[str],
    timeout_s: float = 240.0,
    battery_pct: dict[str, float] | None = None,
    speedup: float = 1.0,
) -> None:
    """Harness step between missions (not measured): every drone on the ground and disarmed, through the
    gateway's own tools (land, then wait), and a fresh battery where the simulator allows it."""
    deadline = time.monotonic() + timeout_s
    for d in drone_ids:
        state = (await truth.snapshot([d]))[d]
        if not state.landed:
            await link.call_tool("land", {"drone_id": d})
        while True:
            state = (await truth.snapshot([d]))[d]
            if state.landed and not state.armed:
                break
            if time.monotonic() > deadline:
                raise StackError(f"{d} did not land and disarm between missions: {state}")
            if state.landed and state.armed:
                await link.call_tool("disarm_drone", {"drone_id": d})
            else:
                await link.call_tool("monitor_flight", {"drone_id": d})
            await asyncio.sleep(0.5)
        if isinstance(truth, SimTruth):
            pct = (battery_pct or {}).get(d, 100.0)
            await truth.recharge(d, pct, speedup)
            await _until_gateway_sees_battery(link, d, pct, deadline)


async def _until_gateway_sees_battery(link: McpLink, drone_id: str, pct: float, deadline: float) -> None:
    """Wait until the gateway's telemetry reports the battery the harness just set (it streams at about
    1 Hz), so that a mission asking about the battery does not race the harness."""
    while True:
        result = await link.client.call_tool("get_battery", {"drone_id": drone_id})
        data = result.structured_content if isinstance(result.structured_content, dict) else {}
        seen = data.get("remaining_pct")
        if isinstance(seen, int | float) and abs(seen - pct) <= 1.0:
            return
        if time.monotonic() > deadline:
            raise StackError(f"the gateway still reports {drone_id} battery {seen} %, set to {pct:g} %")
        await asyncio.sleep(0.3)


class LocalStack(BaseLocalStack):
    """The local stack plus the simulator's true state, the judge of the benchmark's checks."""

    _truth: SimTruth | None = None

    def truth(self) -> SimTruth:
        if self._truth is None:
            self._truth = SimTruth(self.sim_control_url, {d: i for i, d in enumerate(self.drone_ids)})
        return self._truth

    async def __aexit__(self, *exc: object) -> None:
        if self._truth is not None:
            await self._truth.aclose()
            self._truth = None
        await super().__aexit__(*exc)
