"""The safety evaluation's harness: a hostile agent (and, where the scenario is an operator's, a REST
client) against a real gateway over the simulator, each attempt judged by what reached the autopilot.

A scenario (``Scenario``) is data and a judge: the state the drone is put in first (``Setup``), what the
attacker does (``attack``: MCP tool calls over a real client, REST requests, another ground station's
MAVLink), how long the autopilot is watched afterwards, and the judge, a function of the simulator's own
record (``gateway.sim.record``: what it received, the parameters written, the missions it stored, its true
track and extremes) that returns what went through, or None when the rule held. The gateway's answers are
kept for the table but never judged: a refusal that still let something reach the autopilot is a failure,
and so is an acceptance whose effect broke a limit.

One ``Arena`` (a simulator, a gateway with agent, scoped-agent and operator tokens, and a second ground
station on each drone's other port) serves every scenario of a module; it puts the drone back into the
scenario's setup (landed, or hovering near its first home in GUIDED), lifts locks, takeovers and zones,
restores parameters a scenario wrote, and starts a new record before each attack.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
from collections.abc import AsyncIterator, Awaitable, Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import httpx
import httpx2
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import CallToolResult, Implementation
from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.fleet import geo
from gateway.sim.params import ParamTable
from tests.helpers.raw import RawMavlink, raw_mavlink
from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack, gateway_stack

AGENT_TOKEN = "eval-agent-token-1"
SCOPED_TOKEN = "eval-agent-token-d1-only"
OPERATOR_TOKEN = "eval-operator-token"
VIEWER_TOKEN = "eval-viewer-token"
OTHER_GCS_SYSID = 200  # the other ground station that stores missions beside the gateway
DRONES = ("d1", "d2", "d3", "d4")
#: limits of the evaluation's gateway (the defaults, written out so the judges read the same numbers)
LIMITS = {
    "max_altitude_m": 120.0,
    "max_distance_m": 1000.0,
    "max_speed_mps": 15.0,
    "max_vertical_speed_mps": 5.0,
}
#: d4 flies the walking-origin scenarios under a short distance limit (cheap to fly on the simulator)
SHORT_DISTANCE_M = 60.0
SPEEDUP = 10.0


@dataclass(frozen=True)
class Setup:
    """Where the drone is before the attack: on the ground (``alt_m`` None) or hovering ``alt_m`` above its
    first home in GUIDED; ``mission``: items another ground station stored on it first."""

    drone: str = "d1"
    alt_m: float | None = None
    mission: tuple[dict[str, Any], ...] = ()


@dataclass
class Answer:
    """What the gateway answered (for the table; never judged)."""

    text: str
    refused: bool


@dataclass(frozen=True)
class Scenario:
    name: str
    rule: str
    attack: Callable[[Attacker], Awaitable[None]]
    judge: Callable[[Record], str | None]
    setup: Setup = Setup()
    #: simulated seconds the autopilot is watched after the attack
    watch_s: float = 0.0
    #: the door an open fix has not closed yet: the scenario runs as a strict expected failure
    open_door: str | None = None
    door: str = "mcp"


@dataclass
class Record:
    """The simulator's record of one drone for one scenario, and the evaluation's context."""

    raw: dict[str, Any]
    drone: str
    limits: dict[str, float]
    zones: list[dict[str, Any]] = field(default_factory=list)

    @property
    def received(self) -> list[dict[str, Any]]:
        return self.raw["received"]

    def commands(self, *ids: int) -> list[dict[str, Any]]:
        return [m for m in self.received if m.get("command") in ids and m["kind"].startswith("COMMAND")]

    def param_sets(self, name: str | None = None) -> list[dict[str, Any]]:
        sets = [m for m in self.received if m["kind"] == "PARAM_SET"]
        return sets if name is None else [m for m in sets if m["name"].upper() == name.upper()]

    def mission_uploads(self) -> list[dict[str, Any]]:
        return [m for m in self.received if m["kind"] in ("MISSION_COUNT", "MISSION_CLEAR_ALL")]

    def mode_commands(self) -> list[int]:
        """Custom mode numbers asked for by DO_SET_MODE or SET_MODE."""
        modes = [int(m["params"][1]) for m in self.commands(mav.MAV_CMD_DO_SET_MODE)]
        modes += [m["custom_mode"] for m in self.received if m["kind"] == "SET_MODE"]
        return modes

    @property
    def modes(self) -> list[str]:
        return [name for _t, name in self.raw["modes"]]


@dataclass
class Attacker:
    """What a scenario's attack may use: MCP clients (the agent's, a legacy-era one, a scoped agent's),
    REST as operator or with any headers, the other ground station, and the simulator's control."""

    arena: Arena
    drone: str
    exit_stack: contextlib.AsyncExitStack
    answers: list[Answer] = field(default_factory=list)
    clients: dict[str, Client] = field(default_factory=dict)
    #: what the door itself got wrong (a server error): counted as through beside the judge's finding
    door_failures: list[str] = field(default_factory=list)

    def no_server_error(self, r: httpx.Response) -> None:
        if r.status_code >= 500:
            self.door_failures.append(f"HTTP {r.status_code} from {r.request.method} {r.request.url.path}")

    async def audit_total(self) -> int:
        page = await self.arena.operator("GET", "/audit", params={"vehicle_id": self.drone, "limit": 1})
        return int(page["total"])

    async def audited(self, before: int, action: str) -> None:
        """The request left its audit row (``action``) after ``before`` rows (the rows are written behind)."""
        deadline = asyncio.get_running_loop().time() + scaled(10)
        while True:
            page = await self.arena.operator("GET", "/audit", params={"vehicle_id": self.drone, "limit": 20})
            new = page["items"][: max(0, int(page["total"]) - before)]
            if any(row.get("action") == action for row in new):
                return
            if asyncio.get_running_loop().time() > deadline:
                self.door_failures.append(f"no audit row {action} for the request")
                return
            await asyncio.sleep(0.2)

    @property
    def index(self) -> int:
        return self.arena.stack.index(self.drone)

    async def tool(self, name: str, args: dict[str, Any], *, client: str = "agent") -> CallToolResult:
        c = await self.client(client)
        try:
            r = await asyncio.wait_for(c.call_tool(name, args), scaled(60))
        except Exception as exc:  # a protocol error is a refusal too
            self.answers.append(Answer(f"{name}: {type(exc).__name__}: {exc}"[:300], True))
            raise _Refused from None
        text = r.content[0].text if r.content else str(r.structured_content)
        self.answers.append(Answer(f"{name}: {text}"[:300], bool(r.is_error)))
        return r

    async def client(self, name: str) -> Client:
        """An MCP client over HTTP, opened on first use for this scenario: ``agent`` (this era),
        ``legacy`` (the 2025 era, with its session), ``scoped`` (a token confined to d1)."""
        if name not in self.clients:
            token, mode = {"agent": (AGENT_TOKEN, "auto"), "legacy": (AGENT_TOKEN, "legacy"),
                           "scoped": (SCOPED_TOKEN, "auto")}[name]  # fmt: skip
            http = await self.exit_stack.enter_async_context(
                httpx2.AsyncClient(headers={"authorization": f"Bearer {token}"}, timeout=scaled(90))
            )
            client = Client(
                streamable_http_client(self.arena.stack.mcp_url, http_client=http),
                client_info=Implementation(name=f"hostile-{name}", version="1.0"),
                mode=mode,
            )
            self.clients[name] = await self.exit_stack.enter_async_context(client)
        return self.clients[name]

    async def try_tool(
        self, name: str, args: dict[str, Any], *, client: str = "agent"
    ) -> CallToolResult | None:
        with contextlib.suppress(_Refused):
            return await self.tool(name, args, client=client)
        return None

    async def rest(
        self, method: str, path: str, *, token: str | None = OPERATOR_TOKEN, **kw: Any
    ) -> httpx.Response:
        headers = dict(kw.pop("headers", {}))
        if token:
            headers.setdefault("Authorization", f"Bearer {token}")
        r = await self.arena.http.request(method, f"/api/v1{path}", headers=headers, **kw)
        self.answers.append(
            Answer(f"{method} {path}: HTTP {r.status_code} {r.text[:200]}", r.status_code >= 400)
        )
        return r

    async def state(self) -> dict[str, Any]:
        return await self.arena.stack.sim.control.state(self.index)

    async def watch(self, sim_s: float) -> None:
        await self.arena.watch(self.index, sim_s)

    def point(self, north_m: float, east_m: float) -> tuple[float, float]:
        home = self.arena.first_home[self.drone]
        return geo.offset_position(home[0], home[1], north_m, east_m)


class _Refused(Exception):
    pass


@dataclass
class Verdict:
    scenario: str
    rule: str
    through: str | None
    answers: list[Answer]
    reached: str

    @property
    def held(self) -> bool:
        return self.through is None


class Arena:
    def __init__(self, stack: Stack, gcs: dict[str, RawMavlink], http: httpx.AsyncClient) -> None:
        self.stack = stack
        self.gcs = gcs
        #: the operator's and the attacker's REST requests (each with its own headers): one client for
        #: the module, as a new one loads the CA bundle again (about 0.1 s of CPU at load)
        self.http = http
        self.first_home: dict[str, tuple[float, float, float]] = {}
        self.defaults: dict[str, dict[str, float]] = {}

    # -- running one scenario -------------------------------------------------------------------------
    async def run(self, scenario: Scenario) -> Verdict:
        drone = scenario.setup.drone
        index = self.stack.index(drone)
        await self.prepare(scenario.setup)
        control = self.stack.sim.control
        await control.reset_record(index)
        async with contextlib.AsyncExitStack() as clients:
            attacker = Attacker(self, drone, clients)
            with contextlib.suppress(_Refused):
                await scenario.attack(attacker)
        if scenario.watch_s:
            await self.watch(index, scenario.watch_s)
        await self.settle(index)
        raw = await control.record(index)
        zones = await self.operator("GET", "/geofences")
        record = Record(raw, drone, dict(LIMITS), zones.get("features", []))
        if drone == "d4":
            record.limits["max_distance_m"] = SHORT_DISTANCE_M
        found = [f for f in (scenario.judge(record), *attacker.door_failures) if f]
        through = "; ".join(found) or None
        await self.restore(index, raw)
        return Verdict(scenario.name, scenario.rule, through, attacker.answers, reached(record))

    async def watch(self, index: int, sim_s: float) -> None:
        """Let ``sim_s`` simulated seconds pass (the simulator's own clock)."""
        control = self.stack.sim.control
        start = (await control.state(index))["t_boot_s"]
        deadline = asyncio.get_running_loop().time() + scaled(60)
        while (await control.state(index))["t_boot_s"] - start < sim_s:
            if asyncio.get_running_loop().time() > deadline:
                raise AssertionError(f"the simulator's clock did not advance {sim_s} s")
            await asyncio.sleep(0.05)

    async def settle(self, index: int) -> None:
        """Half a simulated second for messages still in flight to reach the simulator."""
        await self.watch(index, 0.5)

    # -- putting the drone back -----------------------------------------------------------------------
    async def prepare(self, setup: Setup) -> None:
        drone, index = setup.drone, self.stack.index(setup.drone)
        await self.stack.sim.control.set_battery(
            index, 100.0
        )  # a fresh pack: limits, not the battery, are judged
        await self.fresh_pack_seen(drone)
        await self.operator("DELETE", f"/vehicles/{drone}/takeover", ok=(200, 404, 409))
        await self.operator("DELETE", f"/vehicles/{drone}/lock", ok=(200, 404, 409))
        await self.operator("DELETE", "/fleet/lock", ok=(200, 404, 409))
        await self.operator("DELETE", "/fleet/geofences", ok=(200, 204, 404))
        state = await self.stack.sim.control.state(index)
        if setup.alt_m is None:
            if state["armed"] or not state["landed"]:
                await self.operator("POST", f"/vehicles/{drone}/land")
                await self.until(index, lambda s: not s["armed"] and s["landed"], "landed and disarmed")
        else:
            await self.hover(drone, index, setup.alt_m, state)
        await self.clear_mission(drone)
        if setup.mission:
            await self.store_mission(drone, setup.mission)
        await self.wait_ready(drone)

    async def hover(self, drone: str, index: int, alt_m: float, state: dict[str, Any]) -> None:
        if not state["armed"] or state["landed"] or state["mode"] not in ("GUIDED",):
            if state["armed"] and not state["landed"] and state["mode"] != "GUIDED":
                await self.operator("POST", f"/vehicles/{drone}/hold")
            elif not state["armed"] or state["landed"]:
                await self.wait_ready(drone)
                await self.operator("POST", f"/vehicles/{drone}/takeoff", json={"alt_rel_m": alt_m})
                await self.until(
                    index, lambda s: s["armed"] and abs(s["rel_alt_m"] - alt_m) < 1.5, f"{alt_m} m"
                )
        lat, lon, _ = self.first_home[drone]
        await self.operator(
            "POST", f"/vehicles/{drone}/goto", json={"lat": lat, "lon": lon, "alt_rel_m": alt_m}
        )

        def there(s: dict[str, Any]) -> bool:
            near = geo.horizontal_distance_m(s["lat"], s["lon"], lat, lon) < 3.0
            return near and abs(s["rel_alt_m"] - alt_m) < 1.5 and s["ground_speed_mps"] < 1.0

        await self.until(index, there, f"hovering {alt_m} m over its first home")

    async def restore(self, index: int, raw: dict[str, Any]) -> None:
        """Put back every parameter the scenario wrote (as another ground station would)."""
        drone = self.stack.drone_ids[index]
        for name in {m["name"] for m in raw["received"] if m["kind"] == "PARAM_SET"}:
            if name in self.defaults[drone]:
                await self.stack.sim.control.set_param(index, name, self.defaults[drone][name])

    async def clear_mission(self, drone: str) -> None:
        gcs = self.gcs[drone]
        mark = gcs.mark()
        gcs.send(mav.MAVLink_mission_clear_all_message(gcs.target_system, 1, 0))
        await gcs.wait("MISSION_ACK", since=mark, timeout_s=scaled(10))

    async def store_mission(self, drone: str, items: Sequence[dict[str, Any]]) -> None:
        """Another ground station stores ``items`` (MISSION_ITEM_INT fields, or ``north_m``/``east_m`` from
        the drone's first home; home is seq 0)."""
        home = self.first_home[drone]
        placed = []
        for item in items:
            item = dict(item)
            if "north_m" in item:
                lat, lon = geo.offset_position(home[0], home[1], item.pop("north_m"), item.pop("east_m"))
                item.update(lat=lat, lon=lon)
            placed.append(item)
        await upload_from_gcs(self.gcs[drone], placed)

    async def until_taken_over(self, drone: str) -> None:
        deadline = asyncio.get_running_loop().time() + scaled(30)
        while True:
            body = await self.operator("GET", "/takeovers")
            if any(lock.get("scope") == drone for lock in body.get("items", [])):
                return
            if asyncio.get_running_loop().time() > deadline:
                raise AssertionError(f"the gateway did not see the takeover of {drone}: {body}")
            await asyncio.sleep(0.1)

    async def fresh_pack_seen(self, drone: str) -> None:
        """Until the gateway's own battery reading shows the fresh pack: the simulator's clock runs ahead
        of a loaded machine's, so a long run drains the pack between scenarios, and the battery streams
        come at their rest rate; a leg judged on the old reading would be refused for the battery."""
        deadline = asyncio.get_running_loop().time() + scaled(60)
        while True:
            body = await self.operator("GET", f"/vehicles/{drone}")
            battery = (body.get("telemetry") or {}).get("battery")
            if battery and not battery.get("stale") and (battery.get("remaining_pct") or 0) >= 90:
                return
            if asyncio.get_running_loop().time() > deadline:
                raise AssertionError(f"{drone}: the gateway never read the fresh pack: {battery}")
            await asyncio.sleep(0.2)

    async def wait_ready(self, drone: str) -> None:
        deadline = asyncio.get_running_loop().time() + scaled(60)
        while True:
            body = await self.operator("GET", f"/vehicles/{drone}")
            if body.get("state") == "ready":
                return
            if asyncio.get_running_loop().time() > deadline:
                raise AssertionError(f"{drone} not ready: {body.get('state')}")
            await asyncio.sleep(0.2)

    async def until(self, index: int, predicate: Callable[[dict[str, Any]], bool], what: str) -> None:
        deadline = asyncio.get_running_loop().time() + scaled(90)
        while True:
            state = await self.stack.sim.control.state(index)
            if predicate(state):
                return
            if asyncio.get_running_loop().time() > deadline:
                raise AssertionError(f"{what} not reached: {state}")
            await asyncio.sleep(0.1)

    async def operator(
        self, method: str, path: str, ok: tuple[int, ...] = (200, 201, 204), **kw: Any
    ) -> dict[str, Any]:
        headers = {"Authorization": f"Bearer {OPERATOR_TOKEN}"}
        r = await self.http.request(method, f"/api/v1{path}", headers=headers, **kw)
        if r.status_code not in ok:
            raise AssertionError(f"operator {method} {path}: HTTP {r.status_code} {r.text[:300]}")
        return (
            r.json() if r.content and r.headers.get("content-type", "").startswith("application/json") else {}
        )


def reached(record: Record) -> str:
    """One line of what reached the autopilot and what it did."""
    raw = record.raw
    sent = [
        f"cmd {m['command']}"
        if "command" in m and m["kind"].startswith("COMMAND")
        else f"{m['name']}={m['value']}"
        if m["kind"] == "PARAM_SET"
        else m["kind"]
        for m in raw["received"]
    ]
    parts = [f"received: {', '.join(dict.fromkeys(sent)) or 'nothing'}"]
    if raw["modes"]:
        parts.append("modes: " + ">".join(name for _t, name in raw["modes"]))
    if raw["max_rel_alt_m"] is not None:
        parts.append(
            f"max alt {raw['max_alt_above_first_home_m']} m, "
            f"{raw['max_distance_first_home_m']} m from first home, {raw['max_ground_speed_mps']} m/s"
        )
    if raw["disarmed_in_air"]:
        parts.append(f"disarmed in the air at {raw['disarmed_in_air'][0]['rel_alt_m']} m")
    return "; ".join(parts)


async def upload_from_gcs(gcs: RawMavlink, items: Sequence[dict[str, Any]]) -> None:
    """The mission protocol as a ground station speaks it: COUNT, answer each REQUEST, wait for the ACK."""
    full = [{"command": mav.MAV_CMD_NAV_WAYPOINT, "frame": mav.MAV_FRAME_GLOBAL}, *items]
    mark = gcs.mark()
    gcs.send(mav.MAVLink_mission_count_message(gcs.target_system, 1, len(full), 0))
    sent: set[int] = set()
    while len(sent) < len(full):
        req = await gcs.wait("MISSION_REQUEST", lambda m: m.seq not in sent, timeout_s=scaled(10), since=mark)
        item = full[req.seq]
        gcs.send(
            mav.MAVLink_mission_item_int_message(
                gcs.target_system,
                1,
                req.seq,
                item.get("frame", mav.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT),
                item["command"],
                0,
                1,
                *(float(item.get(f"param{i}", 0.0)) for i in range(1, 5)),
                round(item.get("lat", 0.0) * 1e7),
                round(item.get("lon", 0.0) * 1e7),
                float(item.get("z", 0.0)),
                0,
            )
        )
        sent.add(req.seq)
    ack = await gcs.wait("MISSION_ACK", timeout_s=scaled(10), since=mark)
    if ack.type != mav.MAV_MISSION_ACCEPTED:
        raise AssertionError(f"the other ground station's mission was refused: {ack}")


@contextlib.asynccontextmanager
async def arena(tmp: Path) -> AsyncIterator[Arena]:
    """A simulator with four drones, a gateway with every token kind, MCP clients of both protocol eras."""
    tokens = {
        "operator_tokens": OPERATOR_TOKEN,
        "viewer_tokens": VIEWER_TOKEN,
        "agent_tokens": f"{AGENT_TOKEN},{SCOPED_TOKEN}",
        "agent_scopes": {SCOPED_TOKEN: ["d1"]},
        "vehicle_limits": {"d4": {"max_distance_m": SHORT_DISTANCE_M}},
    }
    async with gateway_stack(
        tmp, count=len(DRONES), speedup=SPEEDUP, token=OPERATOR_TOKEN,
        sim_args=("--gcs-base-port", "0"), **tokens,
    ) as stack, contextlib.AsyncExitStack() as stack_exit:  # fmt: skip
        gcs: dict[str, RawMavlink] = {}
        for drone, url, sysid in zip(stack.drone_ids, stack.sim.gcs_urls, stack.sim.sysids, strict=True):
            assert url is not None
            link = await stack_exit.enter_async_context(raw_mavlink(url, OTHER_GCS_SYSID))
            link.target_system = sysid
            gcs[drone] = link
        http = await stack_exit.enter_async_context(
            httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(60))
        )
        a = Arena(stack, gcs, http)
        for drone in stack.drone_ids:
            state = await stack.sim.control.state(stack.index(drone))
            home = state["home"] or {"lat": state["lat"], "lon": state["lon"], "alt": state["alt_amsl_m"]}
            a.first_home[drone] = (home["lat"], home["lon"], home["alt"])
            table = ParamTable(
                "4.7", {"MAV_SYSID": stack.sim.sysids[stack.index(drone)], "SIM_SPEEDUP": SPEEDUP}
            )
            a.defaults[drone] = {p.name: p.value for p in table}
        yield a


def finite(x: Any) -> bool:
    return isinstance(x, int | float) and math.isfinite(x)
