"""Protocol behaviour at MAVLink level, compared with the ArduCopter SITL reference (raw, no MAVSDK)."""

from __future__ import annotations

import asyncio
import itertools
import time

import pytest
from pymavlink.dialects.v20 import ardupilotmega as mav

from tests.helpers import sim_process
from tests.helpers.raw import raw_mavlink
from tests.helpers.timing import eventually
from tests.sim.flying import SPEEDUP

ACCEPTED, DENIED, FAILED = mav.MAV_RESULT_ACCEPTED, mav.MAV_RESULT_DENIED, mav.MAV_RESULT_FAILED
SILENT_DEFAULTS = {"HEARTBEAT", "TIMESYNC", "STATUSTEXT", "PARAM_VALUE", "HOME_POSITION", "GPS_GLOBAL_ORIGIN"}


async def test_streams_silent_until_requested_then_interval_and_data_stream() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        first = await gcs.wait("HEARTBEAT")
        assert (first.type, first.autopilot, first.mavlink_version) == (2, 3, 3)
        assert first.get_srcSystem() == sim.sysids[0] and first.get_srcComponent() == 1
        await gcs.wait("HOME_POSITION", since=0, timeout_s=30)  # sent once when the EKF origin is set
        kinds = {m.get_type() for _t, m in gcs.received}
        assert kinds <= SILENT_DEFAULTS, kinds - SILENT_DEFAULTS

        ack = await gcs.command(mav.MAV_CMD_SET_MESSAGE_INTERVAL, 33, 200_000)
        assert ack.result == ACCEPTED
        t0 = time.monotonic()
        mark = gcs.last_mark

        async def six_positions() -> list:
            positions = [m for _t, m in gcs.received[mark:] if m.get_type() == "GLOBAL_POSITION_INT"]
            return positions if len(positions) >= 6 else []

        positions = await eventually(six_positions, "6 GLOBAL_POSITION_INT at the new rate", within_s=10)
        gaps = {b.time_boot_ms - a.time_boot_ms for a, b in itertools.pairwise(positions)}
        assert all(150 <= g <= 260 for g in gaps), gaps  # 5 Hz in simulated time
        allowed = SILENT_DEFAULTS | {"GLOBAL_POSITION_INT", "COMMAND_ACK"}
        assert {m.get_type() for m in gcs.since(t0)} <= allowed

        ack = await gcs.command(mav.MAV_CMD_GET_MESSAGE_INTERVAL, 33)
        assert ack.result == ACCEPTED
        interval = await gcs.wait("MESSAGE_INTERVAL", lambda m: m.message_id == 33, since=gcs.last_mark)
        assert interval.interval_us == 200_000

        assert (await gcs.command(mav.MAV_CMD_SET_MESSAGE_INTERVAL, 9999, 100_000)).result == DENIED
        text = gcs.wait("STATUSTEXT", lambda m: "9999" in m.text, since=gcs.last_mark)
        assert (await text).text == "No ap_message for mavlink id (9999)"
        assert (await gcs.command(mav.MAV_CMD_REQUEST_MESSAGE, 9999)).result == FAILED

        gcs.send(mav.MAVLink_request_data_stream_message(sim.sysids[0], 1, mav.MAV_DATA_STREAM_ALL, 4, 1))
        await gcs.wait("SIMSTATE")
        t1 = time.monotonic()
        expected = {"ATTITUDE", "SYS_STATUS", "GPS_RAW_INT", "VFR_HUD", "RC_CHANNELS", "RAW_IMU"}
        expected |= {"BATTERY_STATUS", "MISSION_CURRENT", "SIMSTATE", "LOCAL_POSITION_NED"}

        async def streamed() -> set[str]:
            got = {m.get_type() for m in gcs.since(t1)}
            return got if expected <= got else set()

        kinds = await eventually(streamed, "every stream of the requested groups", within_s=20)
        assert "EXTENDED_SYS_STATE" not in kinds  # not part of any stream group

        gcs.send(mav.MAVLink_param_request_read_message(sim.sysids[0], 1, b"MAV1_EXTRA1", -1))
        value = await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "MAV1_EXTRA1")
        assert value.param_value == 4.0


async def test_command_ack_table_and_heartbeat_modes() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        await gcs.wait("HEARTBEAT")
        arm = await gcs.command(mav.MAV_CMD_COMPONENT_ARM_DISARM, 1)
        assert arm.result == FAILED  # EKF not ready yet
        assert (await gcs.command(mav.MAV_CMD_NAV_TAKEOFF, 0, 0, 0, 0, 0, 0, 10)).result == FAILED

        expected_base = {0: 81, 2: 81, 3: 89, 4: 89, 5: 89, 6: 89, 9: 89, 16: 89, 17: 89, 21: 89}
        await gcs.wait("HEARTBEAT", lambda m: m.system_status == mav.MAV_STATE_STANDBY)
        for mode, base in expected_base.items():
            ack = await gcs.command(mav.MAV_CMD_DO_SET_MODE, mav.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, mode)
            assert ack.result == ACCEPTED, mode  # mode checks are skipped while disarmed
            hb = await gcs.wait("HEARTBEAT", lambda m, mode=mode: m.custom_mode == mode)
            assert hb.base_mode == base and hb.system_status == mav.MAV_STATE_STANDBY

        ack = await gcs.command(mav.MAV_CMD_DO_SET_MODE, mav.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, 99)
        assert ack.result == FAILED
        await gcs.wait("STATUSTEXT", lambda m: m.text == "No such mode 99", since=gcs.last_mark)
        assert (await gcs.command(mav.MAV_CMD_DO_SET_MODE, 128, 0)).result == ACCEPTED  # no custom flag
        hb = await gcs.wait("HEARTBEAT")
        assert hb.custom_mode == 21 and not hb.base_mode & mav.MAV_MODE_FLAG_SAFETY_ARMED

        gcs.send(mav.MAVLink_set_mode_message(sim.sysids[0], 1, 4))  # legacy SET_MODE: no ACK
        await gcs.wait("HEARTBEAT", lambda m: m.custom_mode == 4)
        assert not any(m.get_type() == "COMMAND_ACK" and m.command == 11 for _t, m in gcs.received)

        assert (await gcs.command(mav.MAV_CMD_REQUEST_MESSAGE, 148)).result == ACCEPTED
        version = await gcs.wait("AUTOPILOT_VERSION", since=gcs.last_mark)
        assert version.capabilities == 64495 and version.flight_sw_version == 0x04070000
        assert (await gcs.command(mav.MAV_CMD_REQUEST_AUTOPILOT_CAPABILITIES, 1)).result == ACCEPTED
        assert (await gcs.command(mav.MAV_CMD_COMPONENT_ARM_DISARM, 0)).result == ACCEPTED  # already disarmed
        assert (await gcs.command(12345)).result == mav.MAV_RESULT_UNSUPPORTED


async def test_mission_protocol_details() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        sysid = sim.sysids[0]
        await gcs.wait("HEARTBEAT")
        gcs.send(mav.MAVLink_mission_count_message(sysid, 1, 3, 0))
        request = await gcs.wait("MISSION_REQUEST")  # the deprecated #40, as ArduPilot asks
        assert request.seq == 0
        item = mav.MAVLink_mission_item_int_message(sysid, 1, 1, 6, 16, 0, 1, 0, 0, 0, 0, 0, 0, 5.0, 0)
        nack = asyncio.create_task(gcs.wait("MISSION_ACK"))
        gcs.send(item)  # seq 1 while 0 was asked
        assert (await nack).type == mav.MAV_MISSION_INVALID_SEQUENCE
        for seq in range(3):
            mark = gcs.mark()
            command = 22 if seq == 1 else 16
            lat, lon = (-353620000, 1491652000) if seq == 2 else (0, 0)
            gcs.send(
                mav.MAVLink_mission_item_int_message(
                    sysid, 1, seq, 6, command, 0, 1, 0, 0, 0, 0, lat, lon, 12, 0
                )
            )
            if seq < 2:
                assert (await gcs.wait("MISSION_REQUEST")).seq == seq + 1
        ack = await gcs.wait("MISSION_ACK", since=mark)
        assert ack.type == mav.MAV_MISSION_ACCEPTED
        total = await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "MIS_TOTAL", since=mark)
        assert total.param_value == 3 and total.param_index == 65535  # counts home

        gcs.send(mav.MAVLink_mission_request_list_message(sysid, 1, 0))
        assert (await gcs.wait("MISSION_COUNT")).count == 3
        gcs.send(mav.MAVLink_mission_request_int_message(sysid, 1, 0, 0))
        home = await gcs.wait("MISSION_ITEM_INT")
        assert home.seq == 0 and home.frame == 0 and home.z > 500  # home, absolute altitude
        gcs.send(mav.MAVLink_mission_request_int_message(sysid, 1, 7, 0))
        assert (await gcs.wait("MISSION_ACK")).type == mav.MAV_MISSION_INVALID_SEQUENCE

        assert (await gcs.command(mav.MAV_CMD_DO_SET_MISSION_CURRENT, 2)).result == ACCEPTED
        assert (await gcs.command(mav.MAV_CMD_DO_SET_MISSION_CURRENT, 9)).result == FAILED
        gcs.send(mav.MAVLink_mission_clear_all_message(sysid, 1, 0))
        assert (await gcs.wait("MISSION_ACK")).type == mav.MAV_MISSION_ACCEPTED
        gcs.send(mav.MAVLink_mission_request_list_message(sysid, 1, 0))
        assert (await gcs.wait("MISSION_COUNT")).count == 1


async def test_parameter_protocol_quirks() -> None:
    async with sim_process(1, speedup=SPEEDUP, sysid_base=15) as sim, raw_mavlink(sim.urls[0]) as gcs:
        gcs.target_system = 15
        await gcs.wait("HEARTBEAT")
        gcs.send(mav.MAVLink_param_request_read_message(15, 1, b"MAV_SYSID", -1))
        value = await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "MAV_SYSID")
        assert (value.param_value, value.param_type) == (15, mav.MAV_PARAM_TYPE_INT16)
        assert (value.param_index, value.param_count) == (65535, 1354)
        gcs.send(mav.MAVLink_param_request_read_message(15, 1, b"", 10))
        by_index = await gcs.wait("PARAM_VALUE", lambda m: m.param_index == 10)
        assert (by_index.param_id, by_index.param_value) == ("RTL_LOIT_TIME", 5000)

        gcs.send(mav.MAVLink_param_set_message(15, 1, b"RTL_ALT", 1200.0, mav.MAV_PARAM_TYPE_REAL32))
        echo = await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "RTL_ALT")
        assert (echo.param_value, echo.param_index) == (1200, 65535)
        assert echo.param_type == mav.MAV_PARAM_TYPE_INT32  # its own type, although sent as REAL32

        t0 = time.monotonic()
        gcs.send(mav.MAVLink_param_request_read_message(15, 1, b"SYSID_THISMAV", -1))  # 4.6 name
        gcs.send(mav.MAVLink_param_set_message(15, 1, b"NO_SUCH_PARAM", 1.0, mav.MAV_PARAM_TYPE_REAL32))
        await asyncio.sleep(10.0 / SPEEDUP)
        replies = [m for m in gcs.since(t0) if m.get_type() == "PARAM_VALUE"]
        assert not [m for m in replies if m.param_id in ("SYSID_THISMAV", "NO_SUCH_PARAM")]  # no reply at all


async def test_firmware_46_names() -> None:
    async with sim_process(1, speedup=SPEEDUP, firmware="4.6") as sim, raw_mavlink(sim.urls[0]) as gcs:
        await gcs.wait("HEARTBEAT")
        gcs.send(mav.MAVLink_param_request_read_message(1, 1, b"SYSID_THISMAV", -1))
        assert (await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "SYSID_THISMAV")).param_value == 1
        gcs.send(mav.MAVLink_param_request_read_message(1, 1, b"SR0_POSITION", -1))
        await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "SR0_POSITION")
        assert (await gcs.command(mav.MAV_CMD_REQUEST_MESSAGE, 148)).result == ACCEPTED
        assert (await gcs.wait("AUTOPILOT_VERSION", since=gcs.last_mark)).flight_sw_version == 0x04060000


async def test_link_faults_drop_traffic_both_ways() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim, raw_mavlink(sim.urls[0]) as gcs:
        await gcs.wait("HEARTBEAT")
        await sim.control.link_down(0)
        await asyncio.sleep(0.5)  # let frames already on their way arrive
        mark = gcs.mark()
        with pytest.raises(TimeoutError):  # the ACK wait (1 s or more) spans 24+ simulated heartbeats
            await gcs.command(mav.MAV_CMD_REQUEST_MESSAGE, 148, timeout_s=1.0)
        assert not [m for _t, m in gcs.received[mark:]]  # nothing out, the command was not heard either

        await sim.control.link_up(0)
        await sim.control.set_packet_loss(0, 100)
        await asyncio.sleep(0.5)
        mark = gcs.mark()
        await asyncio.sleep(0.5)
        assert not gcs.received[mark:]
        await sim.control.set_packet_loss(0, 0)
        assert (await gcs.command(mav.MAV_CMD_REQUEST_MESSAGE, 148)).result == ACCEPTED


async def test_mav_sysid_takes_effect_at_reboot() -> None:
    async with sim_process(1, speedup=SPEEDUP) as sim:
        async with raw_mavlink(sim.urls[0]) as gcs:
            await gcs.wait("HEARTBEAT")
            gcs.send(mav.MAVLink_param_set_message(1, 1, b"MAV_SYSID", 42, mav.MAV_PARAM_TYPE_INT16))
            echo = await gcs.wait("PARAM_VALUE", lambda m: m.param_id == "MAV_SYSID")
            assert echo.param_value == 42 and echo.get_srcSystem() == 1  # still 1 until the next boot
            assert (await gcs.command(mav.MAV_CMD_PREFLIGHT_REBOOT_SHUTDOWN, 1)).result == ACCEPTED
        async with raw_mavlink(sim.urls[0]) as gcs:
            heartbeat = await gcs.wait("HEARTBEAT")
            assert heartbeat.get_srcSystem() == 42
        assert (await sim.control.state(0))["boots"] == 2
