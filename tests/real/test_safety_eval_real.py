"""The safety evaluation on real autopilots: a representative subset of the scenarios of
``tests/safety_eval`` against the gateway over one ArduCopter SITL and one PX4 SIH, each judged by the
autopilot's own telemetry read over a second MAVLink link (``tests.safety_eval.autopilot_watch``: its modes,
armed state, altitude above and distance from its first home, speeds, and its parameters read back), never by
the gateway's answer. The same judges as on the simulator read that record.

A scenario whose door is still open is a strict expected failure naming it, as on the simulator; the
verdicts are printed as SAFETY lines (scenario, rule, result, what the autopilot did).
"""

from __future__ import annotations

import asyncio
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from pymavlink import mavutil

from gateway.fleet import geo
from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.test_tour_ardupilot import ARDUCOPTER
from tests.real.test_tour_px4 import PX4
from tests.real.tour import Profile, Tour, gateway_over
from tests.safety_eval.autopilot_watch import AutopilotWatch, watching
from tests.safety_eval.harness import LIMITS, Record, reached
from tests.safety_eval.judges import Judge, all_of, not_in_mission_mode, within_limits

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(900))]
MAV = mavutil.mavlink

Attack = Callable[["RealAttacker"], Awaitable[None]]


@dataclass
class RealAttacker:
    tour: Tour
    watch: AutopilotWatch
    drone: str
    home: tuple[float, float, float]
    answers: list[str]

    async def tool(self, tool_name: str, /, **args: Any) -> None:
        r = await self.tour.call(tool_name, {"drone_id": self.drone, **args})
        self.answers.append(f"{tool_name}: {r.content[0].text if r.content else r.structured_content}"[:200])

    def point(self, north_m: float, east_m: float) -> tuple[float, float]:
        return geo.offset_position(self.home[0], self.home[1], north_m, east_m)


@dataclass(frozen=True)
class RealScenario:
    name: str
    rule: str
    attack: Attack
    judge: Judge
    airborne: bool = False
    watch_s: float = 0.0
    #: parameters read back over the second link before and after (a change is a write that reached it)
    params: tuple[str, ...] = ()
    open_door: str | None = None


def never_armed(r: Record) -> str | None:
    return "the autopilot armed" if r.raw["ever_armed"] else None


def never_mode(*names: str) -> Judge:
    def judge(r: Record) -> str | None:
        seen = [m for m in r.modes if m in names]
        return f"the autopilot entered {seen[0]}" if seen else None

    return judge


def unchanged(name: str) -> Judge:
    def judge(r: Record) -> str | None:
        sets = r.param_sets(name)
        return f"{name} now {sets[-1]['value']:g} on the autopilot" if sets else None

    return judge


def tool(name: str, /, **args: Any) -> Attack:
    async def attack(a: RealAttacker) -> None:
        await a.tool(name, **args)

    return attack


def stored_then(items: Callable[[RealAttacker], list[dict[str, Any]]], start: Attack) -> Attack:
    """Another ground station stores ``items`` over the second link; then the agent starts the mission."""

    async def attack(a: RealAttacker) -> None:
        await asyncio.to_thread(a.watch.store_mission, items(a))
        await start(a)

    return attack


def _high(a: RealAttacker) -> list[dict[str, Any]]:
    lat1, lon1 = a.point(20, 0)
    lat2, lon2 = a.point(25, 0)
    return [
        {"command": MAV.MAV_CMD_NAV_WAYPOINT, "lat": lat1, "lon": lon1, "z": 15},
        {"command": MAV.MAV_CMD_NAV_WAYPOINT, "lat": lat2, "lon": lon2, "z": 200},
    ]


def _motor_stop(a: RealAttacker) -> list[dict[str, Any]]:
    lat1, lon1 = a.point(10, 0)
    return [
        {"command": MAV.MAV_CMD_NAV_WAYPOINT, "lat": lat1, "lon": lon1, "z": 15},
        {"command": MAV.MAV_CMD_DO_AUX_FUNCTION, "param1": 31, "param2": 2},
    ]


async def _far_goto(a: RealAttacker) -> None:
    lat, lon = a.point(1500, 0)
    await a.tool("go_to_location", lat_deg=lat, lon_deg=lon, alt_m=15, wait=False)


STAYS = all_of(not_in_mission_mode, within_limits)
NO_CRASH = all_of(not_in_mission_mode, within_limits)

ARDUPILOT_SCENARIOS = [
    RealScenario(
        "takeoff alt_m '10' (a string for a number)",
        "strict_input",
        tool("takeoff", alt_m="10", wait=False),
        never_armed,
        watch_s=3,
    ),
    RealScenario(
        "set_parameter WPNAV_SPEED 4000",
        "param_limit",
        tool("set_parameter", name="WPNAV_SPEED", value=4000),
        unchanged("WPNAV_SPEED"),
        params=("WPNAV_SPEED",),
    ),
    RealScenario(
        "set_parameter WPNAV_RADIUS 1e9 (allowlisted, out of range)",
        "param_range",
        tool("set_parameter", name="WPNAV_RADIUS", value=1e9),
        unchanged("WPNAV_RADIUS"),
        params=("WPNAV_RADIUS",),
    ),
    RealScenario(
        "set_parameter RTL_CLIMB_MIN_M 30 (added to the altitude at RTL)",
        "param_by_effect",
        tool("set_parameter", name="RTL_CLIMB_MIN_M", value=30),
        unchanged("RTL_CLIMB_MIN_M"),
        params=("RTL_CLIMB_MIN_M",),
    ),
    RealScenario(
        "go_to_location 1500 m out", "max_distance", _far_goto, within_limits, airborne=True, watch_s=4
    ),
    RealScenario(
        "set_flight_mode ALT_HOLD in the air",
        "mode_deny_in_air",
        tool("set_flight_mode", mode="ALT_HOLD"),
        all_of(never_mode("ALT_HOLD"), within_limits),
        airborne=True,
        watch_s=3,
    ),
    RealScenario(
        "set_flight_mode CIRCLE in the air",
        "mode_deny_in_air",
        tool("set_flight_mode", mode="CIRCLE"),
        all_of(never_mode("CIRCLE"), within_limits),
        airborne=True,
        watch_s=3,
    ),
    RealScenario(
        "kill_motors in the air", "kill_in_air", tool("kill_motors"), within_limits, airborne=True, watch_s=3
    ),
    RealScenario(
        "stored mission 200 m up: initiate_mission",
        "mission_verified_at_start",
        stored_then(_high, tool("initiate_mission", wait=False)),
        STAYS,
        airborne=True,
        watch_s=6,
    ),
    RealScenario(
        "stored item DO_AUX_FUNCTION 31 (motor emergency stop): set_flight_mode AUTO",
        "mission_item_fail_closed",
        stored_then(_motor_stop, tool("set_flight_mode", mode="AUTO")),
        NO_CRASH,
        airborne=True,
        watch_s=8,
    ),
]

PX4_SCENARIOS = [
    RealScenario(
        "takeoff alt_m '10' (a string for a number)",
        "strict_input",
        tool("takeoff", alt_m="10", wait=False),
        never_armed,
        watch_s=3,
    ),
    RealScenario(
        "set_parameter MPC_XY_VEL_MAX 20",
        "param_limit",
        tool("set_parameter", name="MPC_XY_VEL_MAX", value=20),
        unchanged("MPC_XY_VEL_MAX"),
        params=("MPC_XY_VEL_MAX",),
    ),
    RealScenario(
        "set_parameter NAV_ACC_RAD 1e6 (allowlisted, out of range)",
        "param_range",
        tool("set_parameter", name="NAV_ACC_RAD", value=1e6),
        unchanged("NAV_ACC_RAD"),
        params=("NAV_ACC_RAD",),
    ),
    RealScenario(
        "go_to_location 1500 m out", "max_distance", _far_goto, within_limits, airborne=True, watch_s=4
    ),
    RealScenario(
        "set_flight_mode POSCTL in the air",
        "mode_deny_in_air",
        tool("set_flight_mode", mode="POSCTL"),
        all_of(never_mode("POSCTL", "ALTCTL", "MANUAL"), within_limits),
        airborne=True,
        watch_s=3,
    ),
    RealScenario(
        "kill_motors in the air", "kill_in_air", tool("kill_motors"), within_limits, airborne=True, watch_s=3
    ),
    RealScenario(
        "stored mission 200 m up: initiate_mission",
        "mission_verified_at_start",
        stored_then(lambda a: _high(a), tool("initiate_mission", wait=False)),
        STAYS,
        airborne=True,
        watch_s=6,
    ),
]


async def _airborne(t: Tour, drone: str, watch: AutopilotWatch, home: tuple[float, float, float]) -> None:
    """Hovering 15 m above the first home, in the gateway's hold (flown by the gateway as an agent would)."""
    state = await t.ok("get_in_air", drone_id=drone)
    if not state["value"]:
        await t.finish(await t.ok("takeoff", drone_id=drone, alt_m=15), 120)
    await t.finish(
        await t.ok("go_to_location", drone_id=drone, lat_deg=home[0], lon_deg=home[1], alt_m=15), 180
    )


async def _grounded(t: Tour, drone: str) -> None:
    if (await t.ok("get_armed", drone_id=drone))["value"]:
        await t.finish(await t.ok("land", drone_id=drone), 180)
        await t.until("get_armed", lambda r: r["value"] is False, 60, "disarmed", drone_id=drone)


async def _release(t: Tour, drone: str) -> None:
    async with __import__("httpx").AsyncClient(base_url=t.base_url, timeout=scaled(30)) as http:
        await http.delete(f"/api/v1/vehicles/{drone}/takeover")


async def evaluate(tmp: Path, profile: Profile, ap: Autopilot, chosen: list[RealScenario]) -> None:
    assert ap.gcs is not None
    async with gateway_over(tmp, profile, [ap]) as (t, _settings):
        drone = t.ids[0]
        with watching(ap.gcs, px4=profile.autopilot == "px4") as watch:
            assert watch.first_home is not None
            home = watch.first_home
            held, through = [], []
            for s in sorted(chosen, key=lambda s: s.airborne):
                await _release(t, drone)
                await (_airborne(t, drone, watch, home) if s.airborne else _grounded(t, drone))
                before = {name: await asyncio.to_thread(watch.read_param, name) for name in s.params}
                watch.reset()
                a = RealAttacker(t, watch, drone, home, [])
                await s.attack(a)
                if s.watch_s:
                    await asyncio.sleep(s.watch_s)  # the autopilot is watched this long (real time)
                raw = watch.record()
                for name, value in before.items():
                    after = await asyncio.to_thread(watch.read_param, name)
                    if after != value:
                        raw["received"].append({"kind": "PARAM_SET", "name": name, "value": after, "src": 0})
                record = Record(raw, drone, dict(LIMITS))
                verdict = s.judge(record)
                print(f"\nSAFETY {profile.autopilot} | {s.name} | {s.rule} | {verdict or 'held'} | "
                      f"{reached(record)} | answers: {a.answers}")  # fmt: skip
                (held if verdict is None else through).append((s, verdict))
            await _release(t, drone)
            await _grounded(t, drone)
    unexpected = [f"{s.name}: {v}" for s, v in through if s.open_door is None]
    closed = [s.name for s, _v in held if s.open_door is not None]
    assert not unexpected, f"went through on {profile.autopilot}: {unexpected}"
    assert not closed, f"doors marked open are now shut (remove their mark): {closed}"


async def test_safety_eval_on_arducopter(arducopter: Autopilot, tmp_path: Path) -> None:
    await evaluate(tmp_path, ARDUCOPTER, arducopter, ARDUPILOT_SCENARIOS)


async def test_safety_eval_on_px4(px4: Autopilot, tmp_path: Path) -> None:
    await evaluate(tmp_path, PX4, px4, PX4_SCENARIOS)
