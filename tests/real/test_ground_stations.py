"""A ground station beside the gateway, on real ArduCopter SITL (and PX4 SIH): the drone is registered with a
``gcs_endpoints`` entry (PATCH over REST), the gateway then holds its link and relays it, and a pymavlink
ground station listening there sees the drone as if connected to it: HEARTBEAT and GLOBAL_POSITION_INT
(the climb of the agent's takeoff among them), the COMMAND_ACK of its own request. Its switch to LAND
while the gateway holds the drone in GUIDED is a takeover the gateway reports; the drone lands in it."""

from __future__ import annotations

import asyncio
import time
from pathlib import Path
from typing import Any

import pytest
from pymavlink import mavutil

from gateway.util.ports import free_udp_port
from tests.helpers.autopilots import Autopilot
from tests.helpers.timing import scaled
from tests.real.test_tour_ardupilot import ARDUCOPTER
from tests.real.test_tour_px4 import PX4
from tests.real.tour import Profile, Tour, gateway_over

pytestmark = [pytest.mark.real, pytest.mark.timeout(scaled(600))]

GCS_SYSID = 250
#: DO_SET_MODE param2/param3 for LAND: ArduCopter's custom mode 9; PX4's main mode AUTO (4), sub LAND (6)
ARDUCOPTER_LAND = (9.0, 0.0)
PX4_LAND = (4.0, 6.0)
#: how long the ground station waits for an answer before it sends its request again
RESEND_S = 3.0


class GroundStation:
    """pymavlink listening on a loopback UDP port, as QGroundControl does on 14550."""

    def __init__(self) -> None:
        self.port = free_udp_port()
        self.conn = mavutil.mavlink_connection(
            f"udpin:127.0.0.1:{self.port}", source_system=GCS_SYSID, source_component=190
        )

    def close(self) -> None:
        self.conn.close()

    def drain(self) -> None:
        """Read what queued up while nobody read (a full socket buffer drops what comes next)."""
        while self.conn.recv_match(blocking=False) is not None:
            pass

    def wait(self, kind: str, within_s: float, condition: Any = None) -> Any:
        deadline = time.monotonic() + scaled(within_s)
        while time.monotonic() < deadline:
            msg = self.conn.recv_match(type=kind, blocking=True, timeout=0.5)
            if msg is not None and (condition is None or condition(msg)):
                return msg
        raise AssertionError(f"the ground station got no {kind} within {scaled(within_s):g} s")

    def seen(self, kinds: set[str], within_s: float, send: Any) -> dict[str, Any]:
        """The first message of each kind (in any order) within ``within_s``, calling ``send()`` again
        every ``RESEND_S`` until all came, as a ground station retries a command (QGroundControl sends
        one up to four times): a starved PX4 answered one request neither way within 45 s."""
        found: dict[str, Any] = {}
        deadline = time.monotonic() + scaled(within_s)
        resend_at = 0.0
        while time.monotonic() < deadline and set(found) != kinds:
            if time.monotonic() >= resend_at:
                send()
                resend_at = time.monotonic() + RESEND_S
            msg = self.conn.recv_match(type=list(kinds - set(found)), blocking=True, timeout=0.5)
            if msg is not None:
                found[msg.get_type()] = msg
        missing = kinds - set(found)
        assert not missing, (
            f"the ground station got no {', '.join(sorted(missing))} within {scaled(within_s):g} s"
        )
        return found

    def command(self, target: int, command: int, *params: float) -> Any:
        """COMMAND_LONG from this ground station; its COMMAND_ACK (addressed to it)."""
        self.drain()
        self.conn.mav.heartbeat_send(
            mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0
        )
        p = [*params, 0, 0, 0, 0, 0, 0, 0][:7]
        self.conn.mav.command_long_send(target, 1, command, 0, *p)
        return self.wait("COMMAND_ACK", 15, lambda m: m.command == command and m.target_system == GCS_SYSID)


async def ready(t: Tour, drone: str) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(120)
    while (state := (await t.rest("GET", f"/vehicles/{drone}"))["state"]) != "ready":
        assert loop.time() < deadline, f"{drone} is {state}, not ready, after reconnecting through the relay"
        await asyncio.sleep(0.5)


async def test_a_ground_station_at_gcs_endpoints_sees_and_commands_arducopter(
    arducopter: Autopilot, tmp_path: Path
) -> None:
    await sees_and_commands(
        arducopter, tmp_path, ARDUCOPTER, mavutil.mavlink.MAV_AUTOPILOT_ARDUPILOTMEGA, ARDUCOPTER_LAND
    )


async def test_a_ground_station_at_gcs_endpoints_sees_and_commands_px4(
    px4: Autopilot, tmp_path: Path
) -> None:
    await sees_and_commands(px4, tmp_path, PX4, mavutil.mavlink.MAV_AUTOPILOT_PX4, PX4_LAND)


async def sees_and_commands(
    autopilot: Autopilot, tmp_path: Path, profile: Profile, mav_autopilot: int, land: tuple[float, float]
) -> None:
    gcs = GroundStation()
    endpoint = f"udpout://127.0.0.1:{gcs.port}"
    try:
        async with gateway_over(tmp_path, profile, [autopilot]) as (t, _settings):
            d = t.ids[0]
            body = await t.rest("PATCH", f"/vehicles/{d}", json={"gcs_endpoints": [endpoint]})
            assert body["gcs_endpoints"] == [endpoint], body
            await ready(t, d)
            sysid = (await t.rest("GET", f"/vehicles/{d}"))["status"]["sysid"]

            hb = await asyncio.to_thread(gcs.wait, "HEARTBEAT", 20, lambda m: m.get_srcSystem() == sysid)
            assert hb.autopilot == mav_autopilot, hb
            assert hb.type == mavutil.mavlink.MAV_TYPE_QUADROTOR, hb
            home = await t.ok("get_home_position", drone_id=d)
            pos = await asyncio.to_thread(
                gcs.wait, "GLOBAL_POSITION_INT", 20, lambda m: m.get_srcSystem() == sysid
            )
            assert abs(pos.lat / 1e7 - home["lat_deg"]) < 1e-3 and abs(pos.lon / 1e7 - home["lon_deg"]) < 1e-3
            await asyncio.to_thread(gcs.drain)

            def request_version() -> None:
                # a ground station says what it is first: the relay holds back what comes before
                gcs.conn.mav.heartbeat_send(
                    mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0
                )
                gcs.conn.mav.command_long_send(
                    sysid, 1, mavutil.mavlink.MAV_CMD_REQUEST_MESSAGE, 0,
                    mavutil.mavlink.MAVLINK_MSG_ID_AUTOPILOT_VERSION, 0, 0, 0, 0, 0, 0,
                )  # fmt: skip

            # the autopilot answers with the message and the ACK, in either order (PX4: message first)
            answer = await asyncio.to_thread(
                gcs.seen, {"COMMAND_ACK", "AUTOPILOT_VERSION"}, 15, request_version
            )
            ack = answer["COMMAND_ACK"]
            assert ack.target_system == GCS_SYSID and ack.result == mavutil.mavlink.MAV_RESULT_ACCEPTED, ack

            op = await t.finish(await t.ok("takeoff", drone_id=d, alt_m=10), 90)
            assert op["status"] == "succeeded", op
            await asyncio.to_thread(gcs.drain)
            climbed = await asyncio.to_thread(
                gcs.wait, "GLOBAL_POSITION_INT", 20, lambda m: m.relative_alt > 7000
            )
            print(f"\nFIGURE ground station saw the drone at {climbed.relative_alt / 1000:.1f} m above home")

            ack = await asyncio.to_thread(
                gcs.command,
                sysid,
                mavutil.mavlink.MAV_CMD_DO_SET_MODE,
                mavutil.mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED,
                *land,
            )
            assert ack.result == mavutil.mavlink.MAV_RESULT_ACCEPTED, ack
            loop = asyncio.get_running_loop()
            deadline = loop.time() + scaled(30)
            while (taken := (await t.rest("GET", f"/vehicles/{d}"))["taken_over"]) is None:
                assert loop.time() < deadline, "the ground station's LAND was not reported as a takeover"
                await asyncio.sleep(0.5)
            assert "LAND" in taken["reason"], taken
            await t.refused("hold_position", "taken_over", drone_id=d)
            await t.until("get_armed", lambda r: r["value"] is False, 180, "landed and disarmed", drone_id=d)
            vehicle = await t.rest("GET", f"/vehicles/{d}")
            [station] = vehicle["status"]["ground_stations"]
            assert GCS_SYSID in station["system_ids"] and station["error"] is None, station
            assert vehicle["status"]["other_sysids_on_link"] == [], vehicle["status"]
    except AssertionError as exc:
        raise AssertionError(f"{exc}\n--- {autopilot.log.name}\n{autopilot.log_tail(20)}") from None
    finally:
        gcs.close()
