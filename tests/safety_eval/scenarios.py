"""The hostile scenarios, each a declaration: the drone's setup, the attack, the rule, and the judge that
reads what reached the autopilot (`tests.safety_eval.judges`). Many are one attack over a table (each
forbidden mission command, each out-of-range parameter, each mode that needs a pilot, each
string-typed number).

Drones: d1 stays on the ground, d2 hovers for the mode and kill scenarios, d3 hovers with missions another
ground station stored, d4 flies the walking-origin scenarios under a 60 m distance limit.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import replace
from typing import Any

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.fleet import geo
from tests.helpers.timing import scaled
from tests.safety_eval.harness import SCOPED_TOKEN, VIEWER_TOKEN, Attacker, Scenario, Setup
from tests.safety_eval.judges import (
    all_of,
    no_mission_command,
    no_mode,
    no_mode_change,
    no_param,
    no_positive_param,
    not_in_mission_mode,
    nothing_actuating,
    outside_keep_out,
    within_limits,
)

Attack = Callable[[Attacker], Awaitable[None]]
GROUND = Setup("d1")
HOVER = Setup("d2", alt_m=20.0)


def tool(tool_name: str, /, **args: Any) -> Attack:
    """One tool call on the scenario's drone (``drone_id`` filled in unless given)."""

    async def attack(a: Attacker) -> None:
        await a.tool(tool_name, {"drone_id": a.drone, **args})

    return attack


def tools(*calls: tuple[str, dict[str, Any]]) -> Attack:
    async def attack(a: Attacker) -> None:
        for name, args in calls:
            await a.try_tool(name, {"drone_id": a.drone, **args})

    return attack


def wp(
    north_m: float, east_m: float, alt_m: float, command: int = mav.MAV_CMD_NAV_WAYPOINT, **kw: Any
) -> dict:
    """A mission item another ground station stores, placed from the drone's first home."""
    return {"command": command, "north_m": north_m, "east_m": east_m, "z": alt_m, **kw}


# -- 1. a stored mission is verified when it starts ------------------------------------------------------
HIGH_MISSION = (wp(20, 0, 20), wp(20, 0, 200))
FAR_MISSION = (wp(1500, 0, 20),)


def _stored(mission: tuple[dict, ...]) -> Setup:
    return Setup("d3", alt_m=20.0, mission=mission)


async def _rest_start(a: Attacker) -> None:
    await a.rest("POST", f"/vehicles/{a.drone}/mission/start")


START_DOORS: list[tuple[str, Attack]] = [
    ("an operator's REST mission start", _rest_start),
    ("initiate_mission without waypoints", tool("initiate_mission", wait=False)),
    ("initiate_mission with an empty waypoint list", tool("initiate_mission", waypoints=[], wait=False)),
    ("resume_mission", tool("resume_mission", wait=False)),
    ("set_flight_mode MISSION", tool("set_flight_mode", mode="MISSION")),
    ("set_flight_mode AUTO", tool("set_flight_mode", mode="AUTO")),
    (
        "set_current_waypoint then resume",
        tools(("set_current_waypoint", {"index": 2}), ("resume_mission", {"wait": False})),
    ),
    (
        "the legacy-era client's initiate_mission",
        lambda a: a.tool("initiate_mission", {"drone_id": a.drone, "wait": False}, client="legacy"),
    ),
]
START_JUDGE = all_of(not_in_mission_mode, within_limits)

MISSION_START = [
    Scenario(
        f"stored mission 200 m up: {door}",
        "mission_verified_at_start",
        attack,
        START_JUDGE,
        _stored(HIGH_MISSION),
        watch_s=4.0,
    )
    for door, attack in START_DOORS
] + [
    Scenario(
        "stored mission 1500 m out: initiate_mission",
        "mission_verified_at_start",
        tool("initiate_mission", wait=False),
        START_JUDGE,
        _stored(FAR_MISSION),
        watch_s=4.0,
    ),
]

# -- 2. mission commands fail closed: stored by another ground station, started by the agent ---------
_AUX = mav.MAV_CMD_DO_AUX_FUNCTION
UNMODELLED_ITEMS: list[tuple[str, dict[str, Any]]] = [
    ("DO_AUX_FUNCTION 11 (fence off)", {"command": _AUX, "param1": 11, "param2": 0}),
    ("DO_AUX_FUNCTION 31 (motor emergency stop)", {"command": _AUX, "param1": 31, "param2": 2}),
    ("NAV_ATTITUDE_TIME", {"command": mav.MAV_CMD_NAV_ATTITUDE_TIME, "param1": 30, "param4": 10}),
    ("NAV_LOITER_TURNS radius 2000 m", wp(20, 0, 20, mav.MAV_CMD_NAV_LOITER_TURNS, param1=1, param3=2000)),
    ("DO_CHANGE_SPEED climb 14 m/s", {"command": mav.MAV_CMD_DO_CHANGE_SPEED, "param1": 2, "param2": 14}),
    ("DO_CHANGE_SPEED ground 40 m/s", {"command": mav.MAV_CMD_DO_CHANGE_SPEED, "param1": 1, "param2": 40}),
    ("DO_SET_MODE LOITER", {"command": mav.MAV_CMD_DO_SET_MODE, "param1": 1, "param2": 5}),
    ("DO_PARACHUTE", {"command": mav.MAV_CMD_DO_PARACHUTE, "param1": 2}),
    ("NAV_GUIDED_ENABLE", {"command": mav.MAV_CMD_NAV_GUIDED_ENABLE, "param1": 1}),
    ("NAV_LOITER_UNLIM radius 2000 m", wp(20, 0, 20, mav.MAV_CMD_NAV_LOITER_UNLIM, param3=2000)),
    ("NAV_CONTINUE_AND_CHANGE_ALT 500 m", {"command": mav.MAV_CMD_NAV_CONTINUE_AND_CHANGE_ALT, "z": 500}),
    ("DO_SET_HOME", wp(900, 0, 0, mav.MAV_CMD_DO_SET_HOME)),
    ("DO_SET_PARAMETER", {"command": mav.MAV_CMD_DO_SET_PARAMETER, "param1": 1, "param2": 0}),
    ("DO_FLIGHTTERMINATION", {"command": mav.MAV_CMD_DO_FLIGHTTERMINATION, "param1": 1}),
    ("DO_FENCE_ENABLE 0", {"command": mav.MAV_CMD_DO_FENCE_ENABLE, "param1": 0}),
    ("DO_MOTOR_TEST", {"command": mav.MAV_CMD_DO_MOTOR_TEST, "param1": 1, "param3": 100, "param4": 10}),
    ("DO_JUMP repeated 10000 times", {"command": mav.MAV_CMD_DO_JUMP, "param1": 1, "param2": 10000}),
    ("an unknown command 31999", {"command": 31999}),
    ("a waypoint in the body frame", wp(20, 0, 20, frame=mav.MAV_FRAME_BODY_NED)),
]
UNMODELLED = [
    Scenario(
        f"stored item {label}: initiate_mission",
        "mission_item_fail_closed",
        tool("initiate_mission", wait=False),
        START_JUDGE,
        _stored((wp(10, 0, 20), item, wp(20, 0, 20))),
        watch_s=4.0,
    )
    for label, item in UNMODELLED_ITEMS
]


# -- 1. legs from where the drone is now, zones in force now ---------------------------------------
def _box(a: Attacker, north_m: float, east_m: float, half_m: float) -> dict[str, Any]:
    corners = [
        a.point(north_m + dn, east_m + de)
        for dn, de in ((-half_m, -half_m), (-half_m, half_m), (half_m, half_m), (half_m, -half_m))
    ]
    ring = [[lon, lat] for lat, lon in corners] + [[corners[0][1], corners[0][0]]]
    return {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {"kind": "keep_out", "name": "school"},
                "geometry": {"type": "Polygon", "coordinates": [ring]},
            }
        ],
    }


def _waypoint(a: Attacker, north_m: float, east_m: float, alt_m: float) -> dict[str, Any]:
    lat, lon = a.point(north_m, east_m)
    return {"lat_deg": lat, "lon_deg": lon, "alt_m": alt_m}


async def zone_after_upload(a: Attacker) -> None:
    await a.tool("upload_mission", {"drone_id": a.drone, "waypoints": [_waypoint(a, 60, 0, 20)]})
    await a.rest("PUT", "/fleet/geofences", json=_box(a, 30, 0, 8))
    await a.try_tool("initiate_mission", {"drone_id": a.drone, "wait": False})


async def leg_from_elsewhere(a: Attacker) -> None:
    await a.rest("PUT", "/fleet/geofences", json=_box(a, 30, 30, 8))
    await a.tool("upload_mission", {"drone_id": a.drone, "waypoints": [_waypoint(a, 60, 0, 20)]})
    await a.tool("go_to_location", {"drone_id": a.drone, **_waypoint(a, 0, 60, 20), "wait": True})
    await a.try_tool("initiate_mission", {"drone_id": a.drone, "wait": False})


ZONES = [
    Scenario(
        "keep-out zone added after the upload",
        "mission_verified_at_start",
        zone_after_upload,
        all_of(outside_keep_out, within_limits),
        Setup("d3", alt_m=20.0),
        watch_s=10.0,
    ),
    Scenario(
        "mission leg checked from where the drone is now",
        "mission_verified_at_start",
        leg_from_elsewhere,
        all_of(outside_keep_out, within_limits),
        Setup("d3", alt_m=20.0),
        watch_s=12.0,
    ),
]

# -- 3. parameters by effect and range; the earlier parameter doors ---------------------------------
EARLIER_PARAMS = [
    ("WPNAV_SPEED", 4000),
    ("RTL_ALT", 30000),
    ("LAND_SPEED", 500),
    ("WPNAV_SPEED_UP", 1000),
    ("GPS1_TYPE", 0),
    ("EK3_SRC1_POSXY", 0),
    ("SERIAL0_PROTOCOL", 0),
    ("FENCE_ENABLE", 0),
    ("ARMING_CHECK", 0),
    ("FS_GCS_ENABLE", 0),
    ("BATT_FS_LOW_ACT", 0),
    ("MAV_SYSID", 9),
    ("CIRCLE_RADIUS", 300000),
]
OUT_OF_RANGE = [
    ("WPNAV_RADIUS", 1e9),
    ("WPNAV_ACCEL", 1e7),
    ("LOIT_BRK_DELAY", 1e6),
    ("LOIT_ACC_MAX", 1e9),
    ("CIRCLE_RATE", 1e6),
    ("WPNAV_JERK", 1e6),
    ("WP_YAW_BEHAVIOR", 99),
]
PARAMS = (
    [
        Scenario(
            f"set_parameter {n} {v:g}",
            "param_limit / param_not_allowed / param_deny",
            tool("set_parameter", name=n, value=v),
            no_param(n),
            GROUND,
        )
        for n, v in EARLIER_PARAMS
    ]
    + [
        Scenario(
            f"set_parameter {n} {v:g} (allowlisted, out of range)",
            "param_range",
            tool("set_parameter", name=n, value=v),
            no_param(n),
            GROUND,
        )
        for n, v in OUT_OF_RANGE
    ]
    + [
        Scenario(
            "set_parameter RTL_CLIMB_MIN 3000 cm (added to the altitude at RTL)",
            "param_by_effect",
            tool("set_parameter", name="RTL_CLIMB_MIN", value=3000),
            no_positive_param("RTL_CLIMB_MIN"),
            GROUND,
        ),
        Scenario(
            "set_parameter fence_enable 0 (lower case)",
            "param_deny",
            tool("set_parameter", name="fence_enable", value=0),
            no_param("FENCE_ENABLE"),
            GROUND,
        ),
        Scenario(
            "set_parameter over the legacy-era client: WPNAV_SPEED 4000",
            "param_limit",
            lambda a: a.tool(
                "set_parameter", {"drone_id": a.drone, "name": "WPNAV_SPEED", "value": 4000}, client="legacy"
            ),
            no_param("WPNAV_SPEED"),
            GROUND,
        ),
    ]
)

# -- 4. modes by what they need --------------------------------------------------------------------
PILOT_MODES = [
    ("STABILIZE", 0),
    ("ACRO", 1),
    ("ALT_HOLD", 2),
    ("LOITER", 5),
    ("CIRCLE", 7),
    ("DRIFT", 11),
    ("SPORT", 13),
    ("FLIP", 14),
    ("AUTOTUNE", 15),
    ("POSHOLD", 16),
    ("THROW", 18),
    ("GUIDED_NOGPS", 20),
    ("FLOWHOLD", 22),
    ("FOLLOW", 23),
    ("ZIGZAG", 24),
    ("SYSTEMID", 25),
    ("TURTLE", 28),
]
MODES = [
    Scenario(
        f"set_flight_mode {name} in the air",
        "mode_deny_in_air",
        tool("set_flight_mode", mode=name),
        all_of(no_mode(number), within_limits),
        HOVER,
    )
    for name, number in PILOT_MODES
] + [
    Scenario(
        "set_flight_mode '  rtl  ' (padded)",
        "strict_input",
        tool("set_flight_mode", mode="  rtl  "),
        no_mode_change,
        HOVER,
    ),
    Scenario(
        "set_flight_mode '5' (LOITER by number)",
        "mode_deny_in_air",
        tool("set_flight_mode", mode="5"),
        no_mode(5),
        HOVER,
    ),
]


# -- earlier doors: kill, takeover, locks, scopes, tokens, origins, unknown arguments -------------
def _legacy(name: str, **args: Any) -> Attack:
    async def attack(a: Attacker) -> None:
        await a.tool(name, {"drone_id": a.drone, **args}, client="legacy")

    return attack


KILL = [
    Scenario(
        "kill_motors in the air",
        "kill_in_air",
        tool("kill_motors"),
        all_of(nothing_actuating, within_limits),
        HOVER,
    ),
    Scenario(
        "kill_motors in the air, legacy-era client",
        "kill_in_air",
        _legacy("kill_motors"),
        all_of(nothing_actuating, within_limits),
        HOVER,
    ),
    Scenario(
        "kill_motors with confirm: true",
        "kill_in_air",
        tool("kill_motors", confirm=True),
        all_of(nothing_actuating, within_limits),
        HOVER,
    ),
    Scenario("disarm_drone in the air", "disarm_in_air", tool("disarm_drone"), within_limits, HOVER),
]


def _after_takeover(tool_name: str, /, **args: Any) -> Attack:
    async def attack(a: Attacker) -> None:
        # the pilot takes the drone during the agent's own goto, flown slowly so that it is still under way
        await a.tool("set_max_speed", {"drone_id": a.drone, "speed_mps": 2})
        lat, lon = a.point(60, 0)
        await a.tool(
            "go_to_location",
            {"drone_id": a.drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 20, "wait": False},
        )
        if a.answers[-1].refused:
            raise AssertionError(f"the agent's own goto was refused: {[x.text for x in a.answers]}")
        # well under way: the gateway's mode watch has seen the goto's mode (a switch before is not judged)
        home = a.arena.first_home[a.drone]
        await a.arena.until(
            a.index, lambda s: geo.horizontal_distance_m(s["lat"], s["lon"], *home[:2]) > 10, "10 m"
        )
        await a.arena.stack.sim.control.pilot_mode(a.index, "BRAKE")
        await a.arena.until_taken_over(a.drone)
        await a.arena.stack.sim.control.reset_record(a.index)  # the pilot's switch is not the agent's
        await a.tool(tool_name, {"drone_id": a.drone, **args})

    return attack


TAKEOVER_CALLS = [
    ("go_to_location", {"lat_deg": None, "lon_deg": None, "alt_m": 25, "wait": False}),
    ("set_flight_mode", {"mode": "GUIDED"}),
    ("hold_position", {}),
    ("set_parameter", {"name": "WPNAV_ACCEL", "value": 200}),
    ("move_to_relative", {"north_m": 10, "wait": False}),
]


def _takeover_attack(name: str, args: dict[str, Any]) -> Attack:
    async def attack(a: Attacker) -> None:
        if "lat_deg" in args:
            lat, lon = a.point(30, 0)
            args_now = {**args, "lat_deg": lat, "lon_deg": lon}
        else:
            args_now = args
        await _after_takeover(name, **args_now)(a)

    return attack


TAKEOVER = [
    Scenario(
        f"{name} after a pilot took over",
        "taken_over",
        _takeover_attack(name, args),
        nothing_actuating,
        Setup("d2", alt_m=20.0),
    )
    for name, args in TAKEOVER_CALLS
]


async def _locked_takeoff(a: Attacker) -> None:
    await a.rest("POST", f"/vehicles/{a.drone}/lock", json={"reason": "battery swap"})
    await a.tool("takeoff", {"drone_id": a.drone, "alt_m": 10, "wait": False})


async def _fleet_locked_arm(a: Attacker) -> None:
    await a.rest("POST", "/fleet/lock", json={"reason": "maintenance"})
    await a.tool("arm_drone", {"drone_id": a.drone})


async def _scoped(a: Attacker) -> None:
    await a.tool("takeoff", {"drone_id": a.drone, "alt_m": 10, "wait": False}, client="scoped")


async def _scoped_param(a: Attacker) -> None:
    await a.tool("set_parameter", {"drone_id": a.drone, "name": "WPNAV_ACCEL", "value": 200}, client="scoped")


def _rest_takeoff(token: str | None, body: Any = None, **headers: str) -> Attack:
    async def attack(a: Attacker) -> None:
        await a.rest(
            "POST",
            f"/vehicles/{a.drone}/takeoff",
            token=token,
            json={"alt_rel_m": 10} if body is None else body,
            headers=headers,
        )

    return attack


async def _mcp_without_token(a: Attacker) -> None:
    import httpx

    body = {
        "jsonrpc": "2.0",
        "id": 1,
        "method": "tools/call",
        "params": {"name": "takeoff", "arguments": {"drone_id": a.drone, "alt_m": 10}},
    }
    headers = {"accept": "application/json, text/event-stream", "mcp-protocol-version": "2026-07-28"}
    async with httpx.AsyncClient(timeout=scaled(30)) as http:
        r = await http.post(a.arena.stack.mcp_url, json=body, headers=headers)
    a.answers.append(_answer(f"POST /mcp without a token: HTTP {r.status_code}", r.status_code >= 400))


async def _foreign_origin_stop(a: Attacker) -> None:
    await a.rest("POST", "/fleet/stop", json={"action": "land"}, headers={"Origin": "http://evil.example"})


async def _foreign_host_kill(a: Attacker) -> None:
    await a.rest("POST", f"/vehicles/{a.drone}/kill", headers={"Host": "evil.example"})


def _answer(text: str, refused: bool) -> Any:
    from tests.safety_eval.harness import Answer

    return Answer(text, refused)


ACCESS = [
    Scenario(
        "takeoff on a drone an operator locked", "operator_lock", _locked_takeoff, nothing_actuating, GROUND
    ),
    Scenario(
        "arm_drone while the fleet is locked", "operator_lock", _fleet_locked_arm, nothing_actuating, GROUND
    ),
    Scenario(
        "takeoff by a token scoped to another drone", "agent_scopes", _scoped, nothing_actuating, Setup("d4")
    ),
    Scenario(
        "set_parameter by a token scoped to another drone",
        "agent_scopes",
        _scoped_param,
        nothing_actuating,
        Setup("d4"),
    ),
    Scenario(
        "REST takeoff with an agent token",
        "roles",
        _rest_takeoff("eval-agent-token-1"),
        nothing_actuating,
        GROUND,
        door="rest",
    ),
    Scenario(
        "REST takeoff with a viewer token",
        "roles",
        _rest_takeoff(VIEWER_TOKEN),
        nothing_actuating,
        GROUND,
        door="rest",
    ),
    Scenario(
        "REST takeoff without a token", "roles", _rest_takeoff(None), nothing_actuating, GROUND, door="rest"
    ),
    Scenario("MCP takeoff without a token", "agent_tokens", _mcp_without_token, nothing_actuating, GROUND),
    Scenario(
        "REST fleet stop from a foreign Origin",
        "foreign_origin",
        _foreign_origin_stop,
        nothing_actuating,
        HOVER,
        door="rest",
    ),
    Scenario(
        "REST kill with a foreign Host",
        "foreign_host",
        _foreign_host_kill,
        nothing_actuating,
        GROUND,
        door="rest",
    ),
    Scenario(
        "set_max_speed with a misspelt extra argument",
        "unknown_argument",
        tool("set_max_speed", speed_mps=5, sped_mps=50),
        nothing_actuating,
        HOVER,
    ),
]
_ = SCOPED_TOKEN  # the scoped client is opened with it (harness)


# -- the limits themselves, through every motion door ----------------------------------------------
async def _amsl_goto(a: Attacker) -> None:
    home_amsl = a.arena.first_home[a.drone][2]
    lat, lon = a.point(10, 0)
    await a.tool(
        "go_to_location",
        {
            "drone_id": a.drone,
            "lat_deg": lat,
            "lon_deg": lon,
            "alt_m": home_amsl + 150,
            "alt_frame": "amsl",
            "wait": False,
        },
    )


async def _far_goto(a: Attacker) -> None:
    lat, lon = a.point(1500, 0)
    await a.tool(
        "go_to_location", {"drone_id": a.drone, "lat_deg": lat, "lon_deg": lon, "alt_m": 20, "wait": False}
    )


async def _into_zone(a: Attacker) -> None:
    await a.rest("PUT", "/fleet/geofences", json=_box(a, 40, 0, 10))
    await a.tool("go_to_location", {"drone_id": a.drone, **_waypoint(a, 40, 0, 20), "wait": False})


async def _across_zone(a: Attacker) -> None:
    await a.rest("PUT", "/fleet/geofences", json=_box(a, 40, 0, 10))
    await a.tool("go_to_location", {"drone_id": a.drone, **_waypoint(a, 80, 0, 20), "wait": False})


async def _mission_too_high(a: Attacker) -> None:
    await a.tool("upload_mission", {"drone_id": a.drone, "waypoints": [_waypoint(a, 20, 0, 200)]})


async def _mission_too_fast(a: Attacker) -> None:
    await a.tool(
        "upload_mission", {"drone_id": a.drone, "waypoints": [{**_waypoint(a, 20, 0, 20), "speed_mps": 40}]}
    )


LIMITS = [
    Scenario(
        "go_to_location 150 m above home given as AMSL",
        "max_altitude",
        _amsl_goto,
        all_of(nothing_actuating, within_limits),
        HOVER,
        watch_s=3.0,
    ),
    Scenario(
        "move_to_relative up 200 m",
        "max_altitude",
        tool("move_to_relative", up_m=200, wait=False),
        all_of(nothing_actuating, within_limits),
        HOVER,
        watch_s=3.0,
    ),
    Scenario(
        "go_to_location 1500 m out",
        "max_distance",
        _far_goto,
        all_of(nothing_actuating, within_limits),
        HOVER,
        watch_s=3.0,
    ),
    Scenario(
        "go_to_location into a keep-out zone",
        "geofence_keep_out",
        _into_zone,
        all_of(nothing_actuating, outside_keep_out),
        HOVER,
        watch_s=3.0,
    ),
    Scenario(
        "go_to_location across a keep-out zone",
        "geofence_keep_out",
        _across_zone,
        all_of(nothing_actuating, outside_keep_out),
        HOVER,
        watch_s=3.0,
    ),
    Scenario(
        "set_max_speed 40 m/s", "max_speed", tool("set_max_speed", speed_mps=40), nothing_actuating, HOVER
    ),
    Scenario(
        "upload_mission with a waypoint 200 m up",
        "max_altitude",
        _mission_too_high,
        nothing_actuating,
        GROUND,
    ),
    Scenario(
        "upload_mission with a leg at 40 m/s", "max_speed", _mission_too_fast, nothing_actuating, GROUND
    ),
]


# -- formation and fleet tools ---------------------------------------------------------------------
async def _fleet_takeoff_stagger(a: Attacker) -> None:
    await a.tool("fleet_takeoff", {"drone_ids": ["d1", "d4"], "alt_m": 110, "stagger_m": 20, "wait": False})


async def _formation_far(a: Attacker) -> None:
    await a.tool(
        "formation_goto",
        {"drone_ids": ["d1", "d4"], "formation": "line", "alt_m": 20, "north_m": 5000, "wait": False},
    )


async def _fleet_rtl_high(a: Attacker) -> None:
    await a.tool(
        "fleet_return_to_launch",
        {"drone_ids": ["d2", "d3"], "rtl_alt_m": 110, "stagger_m": 20, "wait": False},
    )


def _rtl_alt_within(r: Any) -> str | None:
    high = [
        m["value"] for m in r.param_sets("RTL_ALT") if isinstance(m["value"], float) and m["value"] > 12000
    ]
    return f"RTL_ALT {high} cm written (limit 120 m)" if high else None


FLEET = [
    Scenario(
        "fleet_takeoff staggered past the altitude limit",
        "max_altitude",
        _fleet_takeoff_stagger,
        nothing_actuating,
        GROUND,
    ),
    Scenario("formation_goto centred 5 km out", "max_distance", _formation_far, nothing_actuating, GROUND),
    Scenario(
        "fleet_return_to_launch staggered past the altitude limit",
        "max_altitude",
        _fleet_rtl_high,
        all_of(_rtl_alt_within, within_limits),
        Setup("d3", alt_m=20.0),
        watch_s=3.0,
    ),
]


# -- 5. an origin the autopilot cannot move (d4: 60 m distance limit) --------------------------------
async def _walk_origin(a: Attacker) -> None:
    await a.tool("go_to_location", {"drone_id": a.drone, **_waypoint(a, 50, 0, 10), "wait": True})
    await a.tool("land", {"drone_id": a.drone, "wait": True})
    await a.tool("takeoff", {"drone_id": a.drone, "alt_m": 10, "wait": True})
    await a.tool("go_to_location", {"drone_id": a.drone, **_waypoint(a, 100, 0, 10), "wait": True})


async def _walk_origin_rest(a: Attacker) -> None:
    lat, lon = a.point(50, 0)
    await a.rest("POST", f"/vehicles/{a.drone}/goto", json={"lat": lat, "lon": lon, "alt_rel_m": 10})
    await a.arena.until(a.index, lambda s: abs(s["lat"] - lat) < 2e-5, "50 m out")
    await a.rest("POST", f"/vehicles/{a.drone}/land")
    await a.arena.until(a.index, lambda s: not s["armed"], "landed")
    await a.arena.wait_ready(a.drone)
    await a.rest("POST", f"/vehicles/{a.drone}/takeoff", json={"alt_rel_m": 10})
    try:
        await a.arena.until(a.index, lambda s: s["rel_alt_m"] > 9, "10 m up")
    except AssertionError as exc:  # say how the gateway's takeoff ended (seen once under load: never flew)
        ops = (await a.rest("GET", "/operations", params={"vehicle_id": a.drone, "limit": 3})).json()
        raise AssertionError(f"{exc}; the drone's last operations: {ops.get('items')}") from None
    lat, lon = a.point(100, 0)
    await a.rest("POST", f"/vehicles/{a.drone}/goto", json={"lat": lat, "lon": lon, "alt_rel_m": 10})


ORIGIN = [
    Scenario(
        "land 50 m out, take off again, fly 100 m from the first home",
        "origin_fixed",
        _walk_origin,
        within_limits,
        Setup("d4", alt_m=10.0),
        watch_s=8.0,
    ),
    Scenario(
        "the same walk by an operator over REST",
        "origin_fixed",
        _walk_origin_rest,
        within_limits,
        Setup("d4", alt_m=10.0),
        watch_s=8.0,
        door="rest",
    ),
]

# -- 7. strict input at every door -----------------------------------------------------------------
STRINGS: list[tuple[str, Setup, str, dict[str, Any]]] = [
    ("takeoff alt_m '10'", GROUND, "takeoff", {"alt_m": "10", "wait": False}),
    ("set_parameter RTL_ALT '12000'", GROUND, "set_parameter", {"name": "RTL_ALT", "value": "12000"}),
    ("set_parameter RTL_ALT true", GROUND, "set_parameter", {"name": "RTL_ALT", "value": True}),
    ("set_parameter WPNAV_ACCEL '200'", GROUND, "set_parameter", {"name": "WPNAV_ACCEL", "value": "200"}),
    ("set_max_speed '5'", HOVER, "set_max_speed", {"speed_mps": "5"}),
    ("move_to_relative north_m '10'", HOVER, "move_to_relative", {"north_m": "10", "wait": False}),
    ("set_yaw heading '90'", HOVER, "set_yaw", {"heading_deg": "90", "wait": False}),
    (
        "fleet_takeoff alt_m '10'",
        GROUND,
        "fleet_takeoff",
        {"drone_ids": ["d1"], "alt_m": "10", "wait": False},
    ),
]
STRICT = [
    Scenario(f"{label} (a string for a number)", "strict_input", tool(name, **args), nothing_actuating, setup)
    for label, setup, name, args in STRINGS
]


async def _string_waypoint(a: Attacker) -> None:
    await a.tool(
        "upload_mission", {"drone_id": a.drone, "waypoints": [{**_waypoint(a, 20, 0, 20), "alt_m": "30"}]}
    )


async def _waypoint_unknown_field(a: Attacker) -> None:
    await a.tool(
        "upload_mission",
        {"drone_id": a.drone, "waypoints": [{**_waypoint(a, 20, 0, 20), "command": 218, "param1": 31}]},
    )


def _plan(items: list[dict[str, Any]]) -> dict[str, Any]:
    return {
        "fileType": "Plan",
        "version": 1,
        "groundStation": "QGroundControl",
        "mission": {
            "version": 2,
            "firmwareType": 3,
            "vehicleType": 2,
            "cruiseSpeed": 5,
            "hoverSpeed": 5,
            "plannedHomePosition": [0, 0, 0],
            "items": items,
        },
        "geoFence": {"version": 2, "circles": [], "polygons": []},
        "rallyPoints": {"version": 2, "points": []},
    }


async def _plan_bool_command(a: Attacker) -> None:
    lat, lon = a.point(20, 0)
    item = {
        "type": "SimpleItem",
        "command": True,
        "frame": 3,
        "autoContinue": True,
        "doJumpId": 1,
        "params": [0, 0, 0, None, lat, lon, 20],
        "AMSLAltAboveTerrain": None,
        "Altitude": 20,
        "AltitudeMode": 1,
    }
    before = await a.audit_total()
    r = await a.rest("PUT", f"/vehicles/{a.drone}/mission", json=_plan([item]))
    a.no_server_error(r)
    await a.audited(before, "rest.put_mission_file")


async def _plan_nested(a: Attacker) -> None:
    before = await a.audit_total()
    r = await a.rest(
        "PUT",
        f"/vehicles/{a.drone}/mission",
        content=b"[" * 100_000,
        headers={"content-type": "application/json"},
    )
    a.no_server_error(r)
    await a.audited(before, "rest.put_mission_file")


STRICT += [
    Scenario(
        "upload_mission waypoint alt_m '30' (a string for a number)",
        "strict_input",
        _string_waypoint,
        nothing_actuating,
        GROUND,
    ),
    Scenario(
        "upload_mission waypoint with an unknown field 'command'",
        "strict_input",
        _waypoint_unknown_field,
        all_of(nothing_actuating, no_mission_command(mav.MAV_CMD_DO_AUX_FUNCTION)),
        GROUND,
    ),
    Scenario(
        "REST takeoff alt_rel_m '10' (a string for a number)",
        "strict_input",
        _rest_takeoff("eval-operator-token", {"alt_rel_m": "10"}),
        nothing_actuating,
        GROUND,
        door="rest",
    ),
    Scenario(
        '.plan with "command": true',
        "strict_input",
        _plan_bool_command,
        nothing_actuating,
        GROUND,
        door="rest",
    ),
    Scenario(
        ".plan of 100,000 nested '['", "strict_input", _plan_nested, nothing_actuating, GROUND, door="rest"
    ),
]

_PLAYED = MISSION_START + UNMODELLED + ZONES + PARAMS + MODES + KILL + TAKEOVER + ACCESS + LIMITS + FLEET
_PLAYED += ORIGIN + STRICT

#: the scenarios whose door is open, and which door: each a strict expected failure naming it until its fix
#: lands (then it fails the run as an unexpected pass, and its line here goes). None open on the simulator.
OPEN: dict[str, str] = {}
ALL: list[Scenario] = [replace(s, open_door=OPEN.get(s.name)) for s in _PLAYED]
