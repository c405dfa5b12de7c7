"""The takeover scenarios that tests/real/test_takeover_ardupilot.py and test_takeover_px4.py fly.

A pilot or ground station always wins, on the real autopilots: an agent's go_to_location is flying
(through MCP over HTTP, the gateway with its SQLite store and a mavsdk_server), when a second ground
station (pymavlink, on the autopilot's other port: ArduCopter SITL's SERIAL1 TCP port, PX4's GCS MAVLink
instance) switches the mode, as a pilot's RC switch or QGroundControl does. The waiting call returns
saying so, the autopilot keeps the pilot's mode while the agent keeps trying and is refused, and after
an operator's release (REST) the agent flies the drone again.

Figures (the call's return after the mode change) are printed, never asserted."""

from __future__ import annotations

import asyncio
import math
import time
from pathlib import Path
from typing import Any

from pymavlink import mavutil

from gateway.fleet import geo
from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.mcp.conftest import structured
from tests.real.tour import Profile, Tour, distance, fleet_finish, gateway_over

MAV_CMD_DO_SET_MODE = 176
MAV_CMD_DO_REPOSITION = 192


#: the second ground station's connection per address, kept for the test (or for the autopilot's life,
#: when the module keeps the autopilot): PX4's GCS instance answers the first partner it heard (its
#: address and port), not a new one
_GCS: dict[str, Any] = {}


def second_gcs(address: str) -> tuple[Any, int]:
    """The second ground station's connection on ``address`` (opened once, kept) and the autopilot's
    system id, once the autopilot is heard there."""
    conn = _GCS.get(address)
    if conn is None:
        conn = _GCS[address] = mavutil.mavlink_connection(address, source_system=250, source_component=190)
    else:  # kept open: what the autopilot sent since (an earlier COMMAND_ACK among it) is not an answer
        while conn.recv_msg() is not None:
            pass
    deadline = time.monotonic() + scaled(20)
    while True:  # PX4's GCS instance answers once it heard us: say hello until it does
        conn.mav.heartbeat_send(mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0)
        hb = conn.recv_match(type="HEARTBEAT", blocking=True, timeout=1.0)
        if hb is not None and hb.type != mavutil.mavlink.MAV_TYPE_GCS:
            return conn, hb.get_srcSystem()
        if time.monotonic() > deadline:
            raise AssertionError(f"no HEARTBEAT from the autopilot on {address}")


def second_gcs_sets_mode(address: str, custom_mode: int, px4_modes: tuple[int, int] | None = None) -> float:
    """Another ground station switches the mode: SET_MODE for ArduCopter (Mission Planner's mode
    buttons), DO_SET_MODE with main/sub mode for PX4 (QGroundControl's). Returns when it was sent
    (monotonic)."""
    conn, target = second_gcs(address)
    if px4_modes is None:
        conn.mav.set_mode_send(target, mavutil.mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, custom_mode)
    else:
        main, sub = px4_modes
        conn.mav.command_long_send(target, 1, MAV_CMD_DO_SET_MODE, 0, 1, main, sub, 0, 0, 0, 0)
    sent = time.monotonic()
    conn.recv_match(type="COMMAND_ACK", blocking=True, timeout=2.0)
    return sent


async def takeover_mid_goto(
    t: Tour, ap: Autopilot, *, switch: dict[str, Any], from_mode: str, to_mode: str, reported: str
) -> None:
    d = t.ids[0]
    assert ap.gcs is not None
    op = await t.ok("takeoff", drone_id=d, alt_m=12)
    op = await t.finish(op, 90)
    assert op["status"] == "succeeded", op
    home = await t.ok("get_home_position", drone_id=d)
    lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], 400, 0)
    waiting = asyncio.create_task(
        t.call("go_to_location", {"drone_id": d, "lat_deg": lat, "lon_deg": lon, "alt_m": 12, "wait": True})
    )
    away = lambda p: distance(p, home["lat_deg"], home["lon_deg"]) > 40  # noqa: E731
    await t.until("get_position", away, 120, "40 m out", drone_id=d)
    assert not waiting.done()
    returned: list[float] = []
    waiting.add_done_callback(lambda _task: returned.append(time.monotonic()))
    switched = await asyncio.to_thread(second_gcs_sets_mode, ap.gcs, **switch)
    result = await asyncio.wait_for(waiting, scaled(30))
    returned_s = returned[0] - switched
    r = structured(result)
    name = t.profile.autopilot
    print(f"\nFIGURE {name}: go_to_location returned {returned_s:.2f} s after the mode change was sent")
    if r["status"] == "running":  # the wait cap ran out first: that is a failure of its own
        raise AssertionError(f"the goto did not end when the mode changed: {r}")
    assert r["status"] == "interrupted", r
    assert f"the autopilot switched from {from_mode} to {to_mode}" in r["message"], r
    arrival = await t.ok("check_arrival", drone_id=d)
    assert arrival["status"] == "interrupted" and to_mode in arrival["message"], arrival

    # the agent keeps trying for 10 s; every try is refused and the pilot's mode stays
    loop = asyncio.get_running_loop()
    until = loop.time() + 10.0
    tries = 0
    while loop.time() < until:
        text = await t.refused("move_to_relative", "taken_over", f"taken over in {to_mode}",
                               drone_id=d, north_m=20, east_m=0)  # fmt: skip
        assert f"DELETE /api/v1/vehicles/{d}/takeover" in text
        await t.refused("hold_position", "taken_over", drone_id=d)
        assert (await t.ok("get_flight_mode", drone_id=d))["value"] == reported
        tries += 1
        await asyncio.sleep(0.5)
    assert tries >= 5
    row = next(r for r in (await t.ok("list_drones"))["drones"] if r["drone_id"] == d)
    assert row["locked"] and f"taken over in {to_mode}" in row["locked"], row
    taken = (await t.rest("GET", f"/vehicles/{d}"))["taken_over"]
    assert taken is not None and to_mode in taken["reason"], taken

    # whatever the pilot's mode does with the drone, it ends on the ground: then an operator releases it
    await t.until("get_armed", lambda r: r["value"] is False, 180, "down and disarmed", drone_id=d)
    assert (await t.rest("DELETE", f"/vehicles/{d}/takeover"))["was_locked"] is True
    op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=8), 90)
    assert op["status"] == "succeeded", op
    moved = await t.finish(await t.ok("move_to_relative", drone_id=d, north_m=10, east_m=0), 60)
    assert moved["status"] == "succeeded", moved
    landed = await t.finish(await t.ok("land", drone_id=d), 120)
    assert landed["status"] == "succeeded", landed
    assert (await t.rest("GET", f"/vehicles/{d}"))["taken_over"] is None


def second_gcs_pauses(address: str) -> float:
    """Another ground station pauses the drone where it is, as QGroundControl's Pause does on PX4: a
    DO_REPOSITION without a position (the mode stays Hold). Returns when it was sent (monotonic)."""
    conn, target = second_gcs(address)
    nan = math.nan
    conn.mav.command_long_send(target, 1, MAV_CMD_DO_REPOSITION, 0, -1, 1, 0, nan, nan, nan, nan)
    sent = time.monotonic()
    ack = conn.recv_match(type="COMMAND_ACK", blocking=True, timeout=3.0)
    assert ack is not None and ack.result == 0, ack
    return sent


async def px4_paused_by_a_second_gcs_mid_goto(t: Tour, ap: Autopilot) -> None:
    """PX4 flies the gateway's gotos in Hold, so a second ground station's Hold selection changes nothing
    (PX4 keeps flying the goto: measured) and its Pause (a reposition to where the drone is) leaves the
    mode as it was. The autopilot's own target tells: the waiting goto ends interrupted, the drone holds
    where the ground station put it while the agent keeps trying, and after an operator's release the
    agent flies it again."""
    d = t.ids[0]
    assert ap.gcs is not None
    op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=12), 90)
    assert op["status"] == "succeeded", op
    home = await t.ok("get_home_position", drone_id=d)
    lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], 400, 0)
    waiting = asyncio.create_task(
        t.call("go_to_location", {"drone_id": d, "lat_deg": lat, "lon_deg": lon, "alt_m": 12, "wait": True})
    )
    away = lambda p: distance(p, home["lat_deg"], home["lon_deg"]) > 40  # noqa: E731
    await t.until("get_position", away, 120, "40 m out", drone_id=d)
    # Hold selected by the second ground station: accepted, and nothing changes (the goto flies on)
    await asyncio.to_thread(second_gcs_sets_mode, ap.gcs, 0, (4, 3))
    before = await t.position(d)
    await t.until("get_position", lambda p: distance(p, before["lat_deg"], before["lon_deg"]) > 15, 30,
                  "the goto flying on after a Hold selection", drone_id=d)  # fmt: skip
    assert not waiting.done()
    returned: list[float] = []
    waiting.add_done_callback(lambda _task: returned.append(time.monotonic()))
    paused = await asyncio.to_thread(second_gcs_pauses, ap.gcs)
    r = structured(await asyncio.wait_for(waiting, scaled(60)))
    print(f"\nFIGURE px4: go_to_location returned {returned[0] - paused:.2f} s after the Pause was sent")
    assert r["status"] == "interrupted", r
    assert "the autopilot left the gateway's target while staying in AUTO.LOITER" in r["message"], r
    assert "another ground station repositioned or paused it" in r["message"], r

    loop = asyncio.get_running_loop()
    until = loop.time() + 10.0
    held = await t.position(d)
    while loop.time() < until:
        await t.refused("move_to_relative", "taken_over", drone_id=d, north_m=20, east_m=0)
        assert (await t.ok("get_flight_mode", drone_id=d))["value"] == "HOLD"
        await asyncio.sleep(0.5)
    assert distance(await t.position(d), held["lat_deg"], held["lon_deg"]) < 10  # where the GCS paused it
    assert (await t.rest("DELETE", f"/vehicles/{d}/takeover"))["was_locked"] is True
    moved = await t.finish(await t.ok("move_to_relative", drone_id=d, north_m=10, east_m=0), 60)
    assert moved["status"] == "succeeded", moved
    landed = await t.finish(await t.ok("land", drone_id=d), 120)
    assert landed["status"] == "succeeded", landed


def second_gcs_flies_to(address: str, lat: float, lon: float, alt_m: float) -> float:
    """Another ground station sends the drone elsewhere in GUIDED (SET_POSITION_TARGET_GLOBAL_INT, as a
    ground station's "fly to here" does): the mode stays. Returns when it was sent (monotonic)."""
    conn, target = second_gcs(address)
    position_only = 0b110111111000
    conn.mav.set_position_target_global_int_send(
        0, target, 1, mavutil.mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, position_only,
        int(lat * 1e7), int(lon * 1e7), alt_m, 0, 0, 0, 0, 0, 0, 0, 0,
    )  # fmt: skip
    return time.monotonic()


async def arducopter_sent_elsewhere_by_a_second_gcs_mid_goto(t: Tour, ap: Autopilot) -> None:
    """In GUIDED a second ground station sends the drone 150 m east of its goto: the mode stays GUIDED,
    the autopilot's target tells. The waiting goto ends interrupted, the agent is refused, and after an
    operator's release the agent lands it."""
    d = t.ids[0]
    assert ap.gcs is not None
    op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=12), 90)
    assert op["status"] == "succeeded", op
    home = await t.ok("get_home_position", drone_id=d)
    lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], 400, 0)
    waiting = asyncio.create_task(
        t.call("go_to_location", {"drone_id": d, "lat_deg": lat, "lon_deg": lon, "alt_m": 12, "wait": True})
    )
    away = lambda p: distance(p, home["lat_deg"], home["lon_deg"]) > 40  # noqa: E731
    here = await t.until("get_position", away, 120, "40 m out", drone_id=d)
    await asyncio.to_thread(second_gcs, ap.gcs)
    returned: list[float] = []
    waiting.add_done_callback(lambda _task: returned.append(time.monotonic()))
    elsewhere = geo.offset_position(here["lat_deg"], here["lon_deg"], 0, 150)
    sent = await asyncio.to_thread(second_gcs_flies_to, ap.gcs, *elsewhere, 12)
    r = structured(await asyncio.wait_for(waiting, scaled(60)))
    after = returned[0] - sent
    print(f"\nFIGURE ardupilot: go_to_location returned {after:.2f} s after the new target was sent")
    assert r["status"] == "interrupted", r
    assert "the autopilot left the gateway's target while staying in GUIDED" in r["message"], r
    await t.refused("move_to_relative", "taken_over", drone_id=d, north_m=20, east_m=0)
    assert (await t.ok("get_flight_mode", drone_id=d))["value"] == "GUIDED"
    assert (await t.rest("DELETE", f"/vehicles/{d}/takeover"))["was_locked"] is True
    landed = await t.finish(await t.ok("land", drone_id=d), 120)
    assert landed["status"] == "succeeded", landed


def second_gcs_repositions(address: str, lat: float, lon: float, alt_amsl_m: float) -> float:
    """Another ground station sends the drone elsewhere as QGroundControl's "Go to location" does on PX4:
    a DO_REPOSITION (COMMAND_INT, global frame) with a position; the mode stays Hold. Returns when it was
    sent (monotonic)."""
    conn, target = second_gcs(address)
    conn.mav.command_int_send(
        target, 1, mavutil.mavlink.MAV_FRAME_GLOBAL, MAV_CMD_DO_REPOSITION, 0, 0,
        -1, mavutil.mavlink.MAV_DO_REPOSITION_FLAGS_CHANGE_MODE, 0, math.nan,
        int(lat * 1e7), int(lon * 1e7), alt_amsl_m,
    )  # fmt: skip
    sent = time.monotonic()
    ack = conn.recv_match(type="COMMAND_ACK", blocking=True, timeout=3.0)
    assert ack is not None and ack.result == 0, ack
    return sent


async def pilot_target_during_a_hold(t: Tour, ap: Autopilot) -> None:
    """The agent held the drone; a second ground station sends it 250 m away at 40 m in the mode the
    hold flies in (ArduCopter: SET_POSITION_TARGET_GLOBAL_INT in GUIDED; PX4: QGroundControl's "Go to
    location", a DO_REPOSITION, in Hold): a takeover (seen in REST), the agent's next move is refused;
    after an operator's release the agent lands it."""
    d = t.ids[0]
    assert ap.gcs is not None
    op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=12), 90)
    assert op["status"] == "succeeded", op
    await t.ok("hold_position", drone_id=d)
    here = await t.position(d)
    await asyncio.to_thread(second_gcs, ap.gcs)
    loop = asyncio.get_running_loop()
    until = loop.time() + 3.0
    while loop.time() < until:  # the hold's own target, reported for 3 s: nobody took it
        assert (await t.rest("GET", f"/vehicles/{d}"))["taken_over"] is None
        await asyncio.sleep(0.25)
    elsewhere = geo.offset_position(here["lat_deg"], here["lon_deg"], 250, 0)
    if t.profile.autopilot == "px4":
        home = await t.ok("get_home_position", drone_id=d)
        amsl = home["alt_amsl_m"] + 40
        sent = await asyncio.to_thread(second_gcs_repositions, ap.gcs, *elsewhere, amsl)
    else:
        sent = await asyncio.to_thread(second_gcs_flies_to, ap.gcs, *elsewhere, 40)
    deadline = time.monotonic() + scaled(30)
    while not (taken := (await t.rest("GET", f"/vehicles/{d}"))["taken_over"]):
        assert time.monotonic() < deadline, "no takeover 30 s after the new target"
        await asyncio.sleep(0.05)
    print(f"\nFIGURE {t.profile.autopilot}: hold taken over {time.monotonic() - sent:.2f} s after the new "
          "target was sent")  # fmt: skip
    assert "the autopilot left the gateway's target" in taken["reason"], taken
    await t.refused("go_to_location", "taken_over", drone_id=d, lat_deg=here["lat_deg"],
                    lon_deg=here["lon_deg"], alt_m=12)  # fmt: skip
    assert (await t.ok("get_flight_mode", drone_id=d))["value"] == t.profile.hold_mode
    assert (await t.rest("DELETE", f"/vehicles/{d}/takeover"))["was_locked"] is True
    landed = await t.finish(await t.ok("land", drone_id=d), 180)
    assert landed["status"] == "succeeded", landed


async def interrupted_by_second_gcs(
    t: Tour, ap: Autopilot, waiting: asyncio.Task[Any], switch: dict[str, Any], what: str
) -> dict[str, Any]:
    """The second ground station switches the mode while ``waiting`` (a tool call) waits; its answer."""
    assert ap.gcs is not None and not waiting.done()
    returned: list[float] = []
    waiting.add_done_callback(lambda _task: returned.append(time.monotonic()))
    switched = await asyncio.to_thread(second_gcs_sets_mode, ap.gcs, **switch)
    r = structured(await asyncio.wait_for(waiting, scaled(60)))
    after = returned[0] - switched
    print(f"\nFIGURE {t.profile.autopilot}: {what} returned {after:.2f} s after the mode change was sent")
    return r


async def released_when_down(t: Tour, d: str) -> None:
    await t.until("get_armed", lambda r: r["value"] is False, 180, "down and disarmed", drone_id=d)
    assert (await t.rest("DELETE", f"/vehicles/{d}/takeover"))["was_locked"] is True


async def takeover_mid_takeoff_and_mission(
    t: Tour, ap: Autopilot, *, takeoff: tuple[dict[str, Any], str], mission: tuple[dict[str, Any], str]
) -> None:
    """Takeoff: the second GCS switches at 5 m of a 30 m climb; mission (from the ground): at 40 m of a
    300 m leg. Each call ends interrupted naming the modes, the agent is refused, an operator releases
    the drone (after the takeoff once it is down, after the mission in the air) and the agent flies it."""
    d = t.ids[0]
    waiting = asyncio.create_task(t.call("takeoff", {"drone_id": d, "alt_m": 30}))
    await t.until("get_position", lambda p: p["alt_m"] > 5, 60, "5 m up", drone_id=d)
    r = await interrupted_by_second_gcs(t, ap, waiting, takeoff[0], "takeoff")
    assert r["status"] == "interrupted" and takeoff[1] in r["message"], r
    await t.refused("takeoff", "taken_over", drone_id=d, alt_m=10)
    await released_when_down(t, d)

    home = await t.ok("get_home_position", drone_id=d)
    lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], 300, 0)
    items = [
        {"lat_deg": home["lat_deg"], "lon_deg": home["lon_deg"], "alt_m": 12, "kind": "takeoff"},
        {"lat_deg": lat, "lon_deg": lon, "alt_m": 12},
    ]
    waiting = asyncio.create_task(t.call("initiate_mission", {"drone_id": d, "waypoints": items}))
    away = lambda p: distance(p, home["lat_deg"], home["lon_deg"]) > 40  # noqa: E731
    await t.until("get_position", away, 180, "40 m along the mission", drone_id=d)
    r = await interrupted_by_second_gcs(t, ap, waiting, mission[0], "initiate_mission")
    assert r["status"] == "interrupted" and mission[1] in r["message"], r
    await t.refused("resume_mission", "taken_over", drone_id=d)
    # the pilot is done (PX4's Hold hovers on; ArduCopter's RTL flies home): released in the air, the
    # agent lands it
    assert (await t.rest("DELETE", f"/vehicles/{d}/takeover"))["was_locked"] is True
    landed = await t.finish(await t.ok("land", drone_id=d), 180)
    assert landed["status"] == "succeeded", landed


def close_second_gcs(address: str | None) -> None:
    """Close the second ground station's connection on ``address``, if one is open."""
    conn = _GCS.pop(address or "", None)
    if conn is not None:
        conn.close()


async def run(
    tmp: Path, profile: Profile, ap: Autopilot, scenario: Any, *, keep_second_gcs: bool = False, **kw: Any
) -> None:
    """Fly ``scenario`` through a fresh gateway over ``ap``. The second ground station's connection is
    closed at the end unless ``keep_second_gcs`` (the autopilot flies the module's next test too, and
    PX4's GCS instance answers only the partner it heard first): then whoever stops the autopilot closes
    it (``close_second_gcs``)."""
    async with gateway_over(tmp, profile, [ap], mcp_wait_cap_s=120.0) as (tour, _settings):  # a long wait
        try:
            await scenario(tour, ap, **kw)
        except AssertionError as exc:
            raise AssertionError(f"{exc}\n--- {ap.log.name}\n{ap.log_tail(20)}") from None
        finally:
            if not keep_second_gcs:
                close_second_gcs(ap.gcs)


async def takeover_mid_formation(
    t: Tour, aps: list[Autopilot], *, switch: dict[str, Any], from_mode: str, to_mode: str, reported: str
) -> None:
    """Two drones take off together and fly a line formation 300 m north; 40 m out the second ground
    station switches the second drone's mode. The waiting formation_goto returns aborted: that drone
    `interrupted` naming both modes, the other `held` (docs/safety.md: a formation is planned together, so
    it stops). The pilot's mode stays while the agent keeps trying for 10 s; once the pilot has it down,
    an operator releases it and the agent flies it again."""
    first, taken = t.ids
    gcs = aps[1].gcs
    assert gcs is not None
    rise = await fleet_finish(t, await t.ok("fleet_takeoff", drone_ids=t.ids, alt_m=10, wait=False), 150)
    assert rise["status"] == "succeeded", rise
    home = await t.ok("get_home_position", drone_id=first)
    lat, lon = geo.offset_position(home["lat_deg"], home["lon_deg"], 300, 0)
    args = {"drone_ids": t.ids, "formation": "line", "center_lat_deg": lat, "center_lon_deg": lon,
            "alt_m": 12, "spacing_m": 12, "wait": True}  # fmt: skip
    waiting = asyncio.create_task(t.call("formation_goto", args))
    away = lambda p: distance(p, home["lat_deg"], home["lon_deg"]) > 40  # noqa: E731
    await t.until("get_position", away, 150, "40 m along the formation leg", drone_id=taken)
    r = await interrupted_by_second_gcs(t, aps[1], waiting, switch, "formation_goto")
    assert r["status"] == "aborted", r
    members = {m["drone_id"]: m for m in r["drones"]}
    assert members[taken]["status"] == "interrupted", members
    assert f"the autopilot switched from {from_mode} to {to_mode}" in members[taken]["message"], members
    assert members[first]["status"] == "held", members
    arrival = await t.ok("check_arrival", drone_id=taken)
    assert arrival["status"] == "interrupted" and to_mode in arrival["message"], arrival

    # the agent keeps trying for 10 s: on the drone, and with a new formation; the pilot's mode stays
    loop = asyncio.get_running_loop()
    until = loop.time() + 10.0
    tries = 0
    while loop.time() < until:
        await t.refused("move_to_relative", "taken_over", f"taken over in {to_mode}",
                        drone_id=taken, north_m=20, east_m=0)  # fmt: skip
        again = await t.call("formation_goto", {**args, "wait": False})
        assert again.is_error and "taken_over" in again.content[0].text, again
        assert (await t.ok("get_flight_mode", drone_id=taken))["value"] == reported
        tries += 1
        await asyncio.sleep(0.5)
    assert tries >= 5
    # the other drone still holds where the formation left it, in the gateway's hands
    assert (await t.ok("get_flight_mode", drone_id=first))["value"] == t.profile.hold_mode

    await released_when_down(t, taken)
    op = await t.finish(await t.ok("takeoff", drone_id=taken, alt_m=8), 90)
    assert op["status"] == "succeeded", op
    down = await fleet_finish(t, await t.ok("fleet_land", drone_ids=t.ids, wait=False), 240)
    assert down["status"] == "succeeded", down


async def run_formation(tmp: Path, profile: Profile, aps: list[Autopilot], **kw: Any) -> None:
    async with gateway_over(tmp, profile, aps, mcp_wait_cap_s=120.0) as (tour, _settings):
        try:
            await takeover_mid_formation(tour, aps, **kw)
        except AssertionError as exc:
            logs = "\n".join(f"--- {a.log.name}\n{a.log_tail(15)}" for a in aps)
            raise AssertionError(f"{exc}\n{logs}") from None
        finally:
            close_second_gcs(aps[1].gcs)
