"""GUIDED commands, MISSION_START and in-flight ACKs at MAVLink level (no MAVSDK)."""

from __future__ import annotations

import asyncio
import math

from pymavlink.dialects.v20 import ardupilotmega as mav

from tests.helpers import sim_process
from tests.helpers.raw import RawMavlink, raw_mavlink
from tests.helpers.timing import scaled
from tests.sim.flying import SPEEDUP, distance_m, offset

ACCEPTED, DENIED, FAILED = mav.MAV_RESULT_ACCEPTED, mav.MAV_RESULT_DENIED, mav.MAV_RESULT_FAILED
CUSTOM = mav.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED
GUIDED, LOITER, LAND = 4, 5, 9
POS_ONLY = 0b0000_1111_1111_1000  # type_mask: use position only


async def _until(sim, predicate, timeout_s: float = 60.0) -> dict:
    """Poll the simulator's true state until predicate(state) holds (a scaled deadline, never asserted)."""
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(timeout_s)
    while not predicate(state := await sim.control.state(0)):
        if loop.time() > deadline:
            raise AssertionError(f"condition not reached within {scaled(timeout_s):g} s; last state {state}")
        await asyncio.sleep(0.05)
    return state


async def _armed_in_guided(sim, gcs: RawMavlink) -> None:
    await gcs.wait("HEARTBEAT")
    assert (await gcs.command(mav.MAV_CMD_DO_SET_MODE, CUSTOM, GUIDED)).result == ACCEPTED
    await _until(sim, lambda s: s["position_ok"])
    assert (await gcs.command(mav.MAV_CMD_COMPONENT_ARM_DISARM, 1)).result == ACCEPTED


async def test_guided_targets_yaw_and_inflight_refusals() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        await _armed_in_guided(sim, gcs)
        assert (await gcs.command(mav.MAV_CMD_NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 10)).result == ACCEPTED
        start = await _until(sim, lambda s: s["rel_alt_m"] > 9.9)
        assert (await gcs.command(mav.MAV_CMD_NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 10)).result == FAILED  # flying
        assert (await gcs.command(mav.MAV_CMD_COMPONENT_ARM_DISARM, 0)).result == FAILED  # no force in flight

        # DO_REPOSITION as COMMAND_LONG: ArduPilot reads the altitude relative to home
        lat, lon = offset(start["lat"], start["lon"], 30.0, 0.0)
        ack = await gcs.command(mav.MAV_CMD_DO_REPOSITION, -1, 1, 0, math.nan, lat, lon, 20.0)
        assert ack.result == ACCEPTED
        # (COMMAND_LONG carries lat/lon as float32: about 0.4 m resolution here, as on ArduPilot)
        state = await _until(sim, lambda s: distance_m(s["lat"], s["lon"], lat, lon) < 1.0)
        state = await _until(sim, lambda s: abs(s["rel_alt_m"] - 20.0) < 0.2)
        assert state["mode"] == "GUIDED"
        assert (await gcs.command(mav.MAV_CMD_DO_REPOSITION, -1, 1, 0, 0, 0, 0, 20.0)).result == DENIED

        # SET_POSITION_TARGET_LOCAL_NED, body-offset frame: 10 m forward (north here after yawing to 0)
        assert (await gcs.command(mav.MAV_CMD_CONDITION_YAW, 0, 30, 0, 0)).result == ACCEPTED
        state = await _until(sim, lambda s: min(s["heading_deg"], 360 - s["heading_deg"]) < 0.5)
        before = state
        forward = mav.MAVLink_set_position_target_local_ned_message(
            0, sim.sysids[0], 1, mav.MAV_FRAME_BODY_OFFSET_NED, POS_ONLY, 10, 0, 0, *([0] * 8)
        )
        gcs.send(forward)
        target = offset(before["lat"], before["lon"], 10.0, 0.0)
        await _until(sim, lambda s: distance_m(s["lat"], s["lon"], *target) < 0.5)

        # SET_POSITION_TARGET_GLOBAL_INT with relative altitude
        lat2, lon2 = offset(before["lat"], before["lon"], 0.0, 25.0)
        frame = mav.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT
        there = mav.MAVLink_set_position_target_global_int_message(
            0, sim.sysids[0], 1, frame, POS_ONLY, round(lat2 * 1e7), round(lon2 * 1e7), 12.0, *([0] * 8)
        )
        gcs.send(there)
        await _until(
            sim, lambda s: distance_m(s["lat"], s["lon"], lat2, lon2) < 0.5 and s["rel_alt_m"] < 12.2
        )

        # force disarm in flight (21196): motors stop, the vehicle falls
        ack = await gcs.command(mav.MAV_CMD_COMPONENT_ARM_DISARM, 0, 21196)
        assert ack.result == ACCEPTED
        state = await _until(sim, lambda s: s["landed"])
        assert not state["armed"]


async def test_mission_start_on_the_ground_takes_off_and_lands() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        sysid = sim.sysids[0]
        await gcs.wait("HEARTBEAT")
        items = [
            (16, 0, 0, 0, 0.0),  # home placeholder
            (22, 0, 0, 0, 8.0),  # takeoff 8 m
            (19, 2.0, 0, 0, 8.0),  # loiter 2 s here
            (21, 0, 0, 0, 0.0),  # land here
        ]
        mark = gcs.mark()
        gcs.send(mav.MAVLink_mission_count_message(sysid, 1, len(items), 0))
        for seq, (cmd, p1, lat, lon, alt) in enumerate(items):
            await gcs.wait("MISSION_REQUEST", lambda m, seq=seq: m.seq == seq, since=mark)
            mark = gcs.mark()
            gcs.send(
                mav.MAVLink_mission_item_int_message(
                    sysid, 1, seq, 6, cmd, 0, 1, p1, 0, 0, 0, lat, lon, alt, 0
                )
            )
        assert (await gcs.wait("MISSION_ACK", since=mark)).type == mav.MAV_MISSION_ACCEPTED

        assert (await gcs.command(mav.MAV_CMD_DO_SET_MODE, CUSTOM, LOITER)).result == ACCEPTED
        await _until(sim, lambda s: s["position_ok"])
        assert (await gcs.command(mav.MAV_CMD_COMPONENT_ARM_DISARM, 1)).result == ACCEPTED
        reached = asyncio.create_task(gcs.wait("MISSION_ITEM_REACHED", lambda m: m.seq == 2, timeout_s=60))
        assert (await gcs.command(mav.MAV_CMD_MISSION_START, 0, 0)).result == ACCEPTED
        state = await _until(sim, lambda s: s["rel_alt_m"] > 7.5)
        assert state["mode"] == "AUTO"
        await reached
        state = await _until(sim, lambda s: not s["armed"])
        assert state["landed"] and state["mode"] == "AUTO"
        texts = [t for _t, _s, t in await sim.control.status_texts(0)]
        assert "Mission: 1 Takeoff" in texts and "Mission: 3 Land" in texts


async def test_geofence_refuses_outside_targets_and_breach_returns_home() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        await sim.control.set_param(0, "FENCE_ENABLE", 1)
        await sim.control.set_param(0, "FENCE_RADIUS", 80)
        await _armed_in_guided(sim, gcs)
        assert (await gcs.command(mav.MAV_CMD_NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 10)).result == ACCEPTED
        start = await _until(sim, lambda s: s["rel_alt_m"] > 9.9)
        far = offset(start["lat"], start["lon"], 120.0, 0.0)
        assert (await gcs.command(mav.MAV_CMD_DO_REPOSITION, -1, 1, 0, math.nan, *far, 10.0)).result == FAILED
        near = offset(start["lat"], start["lon"], 50.0, 0.0)
        assert (
            await gcs.command(mav.MAV_CMD_DO_REPOSITION, -1, 1, 0, math.nan, *near, 10.0)
        ).result == ACCEPTED
        await _until(sim, lambda s: distance_m(s["lat"], s["lon"], *near) < 1.0)

        await sim.control.set_param(0, "FENCE_RADIUS", 30)  # now 50 m out: outside the circle
        await _until(sim, lambda s: s["mode"] == "RTL")
        texts = [t for _t, _s, t in await sim.control.status_texts(0)]
        assert "Circle fence breached" in texts
        await _until(sim, lambda s: distance_m(s["lat"], s["lon"], start["lat"], start["lon"]) < 2.0)
