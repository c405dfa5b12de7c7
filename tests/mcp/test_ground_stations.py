"""Ground stations beside the gateway, end to end: a drone registered with ``gcs_endpoints`` has its
MAVLink relayed by the gateway (real sidecar behind the relay, real REST and MCP over HTTP, real SQLite),
and a pymavlink ground station at the endpoint sees the drone as if connected to it: HEARTBEAT,
GLOBAL_POSITION_INT, the COMMAND_ACK of its own command. Its mode change while an agent's goto waits is
a takeover the gateway reports."""

from __future__ import annotations

import asyncio
import os
import signal
import socket
import time
from collections.abc import AsyncIterator
from typing import Any

import httpx
import pytest
import pytest_asyncio
from pymavlink import mavutil

from gateway.util.ports import free_udp_port
from tests.helpers import sim_process
from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack, gateway_stack, point_from, structured, wait_ready, wait_until_true

pytestmark = pytest.mark.asyncio(loop_scope="module")

ARDUCOPTER_LOITER = 5
GCS_SYSID = 250


class GroundStation:
    """A pymavlink ground station listening on a loopback UDP port (QGroundControl's way: the drone's
    traffic comes to it, it answers whoever sent it)."""

    def __init__(self) -> None:
        self.port = free_udp_port()
        self.conn = mavutil.mavlink_connection(
            f"udpin:127.0.0.1:{self.port}", source_system=GCS_SYSID, source_component=190
        )

    def wait(self, kind: str, timeout_s: float, condition: Any = None) -> Any:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            msg = self.conn.recv_match(type=kind, blocking=True, timeout=0.5)
            if msg is not None and (condition is None or condition(msg)):
                return msg
        raise AssertionError(f"the ground station got no {kind} within {timeout_s:g} s")

    def set_mode(self, target: int, custom_mode: int) -> Any:
        """COMMAND_LONG DO_SET_MODE, as a ground station's mode menu sends it; returns its COMMAND_ACK.

        What queued up while the test did not read is read first: a full socket buffer would drop the
        ACK (a real ground station reads all the time)."""
        while self.conn.recv_match(blocking=False) is not None:
            pass
        self.conn.mav.heartbeat_send(
            mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0
        )
        self.conn.mav.command_long_send(
            target,
            1,
            mavutil.mavlink.MAV_CMD_DO_SET_MODE,
            0,
            mavutil.mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED,
            custom_mode,
            0,
            0,
            0,
            0,
            0,
        )
        return self.wait(
            "COMMAND_ACK",
            scaled(15),
            lambda m: m.command == mavutil.mavlink.MAV_CMD_DO_SET_MODE and m.target_system == GCS_SYSID,
        )

    def close(self) -> None:
        self.conn.close()


@pytest_asyncio.fixture(scope="module", loop_scope="module")
async def stack(tmp_path_factory: pytest.TempPathFactory) -> AsyncIterator[Stack]:
    async with gateway_stack(tmp_path_factory.mktemp("gcs"), count=1) as s:
        yield s


async def patch(stack: Stack, drone_id: str, body: dict[str, Any]) -> httpx.Response:
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        return await http.patch(f"/api/v1/vehicles/{drone_id}", json=body)


async def test_a_bad_endpoint_is_named_and_changes_nothing(stack: Stack) -> None:
    r = await patch(stack, "d1", {"gcs_endpoints": ["http://127.0.0.1:14550"]})
    assert r.status_code == 422, r.text
    message = r.json()["error"]["message"]
    assert "gcs_endpoints" in message and "'http://127.0.0.1:14550' is not accepted" in message, message
    assert "udpout://host:port" in message and "tcpin://host:port" in message, message
    assert (await stack.rest("/vehicles/d1"))["gcs_endpoints"] == []


async def test_a_ground_station_sees_the_drone_and_takes_it(stack: Stack) -> None:
    gcs = GroundStation()
    try:
        endpoint = f"udpout://127.0.0.1:{gcs.port}"
        r = await patch(stack, "d1", {"gcs_endpoints": [endpoint]})
        assert r.status_code == 200, r.text
        assert r.json()["gcs_endpoints"] == [endpoint]
        await wait_ready(stack)  # the new endpoints reconnected the drone, now through the relay
        sysid = stack.sim.sysids[0]

        heartbeat = await asyncio.to_thread(
            gcs.wait, "HEARTBEAT", scaled(20), lambda m: m.get_srcSystem() == sysid
        )
        assert heartbeat.autopilot == mavutil.mavlink.MAV_AUTOPILOT_ARDUPILOTMEGA
        position = await asyncio.to_thread(
            gcs.wait, "GLOBAL_POSITION_INT", scaled(20), lambda m: m.get_srcSystem() == sysid
        )
        home = await stack.true_state("d1")
        assert abs(position.lat / 1e7 - home["lat"]) < 1e-4, (position, home)

        lat, lon = point_from(home, 400.0, 0.0)
        async with stack.client("auto", name="agent") as c:
            took_off = structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 10}))
            assert took_off["status"] == "succeeded", took_off
            goto = {"drone_id": "d1", "lat_deg": lat, "lon_deg": lon, "alt_m": 10}
            waiting = asyncio.create_task(stack.call(c, "go_to_location", goto))
            await wait_until_true(stack, "d1", lambda s: s["ground_speed_mps"] > 2.0, "d1 on its way")
            assert not waiting.done()

            ack = await asyncio.to_thread(gcs.set_mode, sysid, ARDUCOPTER_LOITER)
            assert ack.result == mavutil.mavlink.MAV_RESULT_ACCEPTED, ack
            r = structured(await asyncio.wait_for(waiting, scaled(30)))
            assert r["status"] == "interrupted", r
            assert "the autopilot switched from GUIDED to LOITER" in r["message"], r
            assert "a pilot or another ground station took control" in r["message"], r

        assert (await stack.true_state("d1"))["mode"] == "LOITER"
        vehicle = await stack.rest("/vehicles/d1")
        assert vehicle["taken_over"] is not None and "LOITER" in vehicle["taken_over"]["reason"]
        [station] = vehicle["status"]["ground_stations"]
        assert station["url"] == endpoint and station["error"] is None, station
        assert GCS_SYSID in station["system_ids"] and station["frames_in"] >= 2, station
        assert station["frames_out"] > 0, station
        # the gateway's own session still hears only the drone (the ground station's traffic goes to it)
        assert vehicle["status"]["other_sysids_on_link"] == [], vehicle["status"]
    finally:
        gcs.close()


async def test_the_ground_station_keeps_the_drone_while_the_sidecar_restarts(stack: Stack) -> None:
    """The relay holds the drone's link, so a sidecar killed and restarted by its supervisor costs the
    ground station nothing, and the gateway's own session comes back through the relay."""
    gcs = GroundStation()
    try:
        endpoint = f"udpout://127.0.0.1:{gcs.port}"  # its own, so this test runs alone as well
        r = await patch(stack, "d1", {"gcs_endpoints": [endpoint]})
        assert r.status_code == 200, r.text
        await wait_ready(stack)
        before = (await stack.rest("/vehicles/d1"))["status"]["sidecar"]
        assert before["state"] == "serving" and before["pid"], before
        os.kill(before["pid"], signal.SIGKILL)
        sysid = stack.sim.sysids[0]
        for _ in range(3):  # the drone's heartbeats go on reaching the ground station
            await asyncio.to_thread(gcs.wait, "HEARTBEAT", scaled(10), lambda m: m.get_srcSystem() == sysid)
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(60)
        while True:
            status = (await stack.rest("/vehicles/d1"))["status"]
            back = status["state"] == "ready" and status["sidecar"]["restarts"] > before["restarts"]
            if back and status["ground_stations"][0]["error"] is None:  # the closed port's ICMP forgotten
                break
            assert loop.time() < deadline, f"the sidecar did not come back through the relay: {status}"
            await asyncio.sleep(0.25)
        assert status["sidecar"]["pid"] != before["pid"]
        [station] = status["ground_stations"]
        assert station["error"] is None and station["frames_out"] > 0, station
        await asyncio.to_thread(
            gcs.wait, "GLOBAL_POSITION_INT", scaled(10), lambda m: m.get_srcSystem() == sysid
        )
    finally:
        gcs.close()


async def test_a_vehicle_port_the_relay_cannot_open_is_named_and_registered_with_its_endpoints(
    stack: Stack,
) -> None:
    """POST with gcs_endpoints: stored and shown; the vehicle's own port is taken, so the relay says so
    in the drone's last_error (and keeps trying) instead of failing the registration."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as taken:
        taken.bind(("127.0.0.1", 0))
        port = taken.getsockname()[1]
        gcs = f"tcpin://127.0.0.1:{free_udp_port()}"
        body = {"id": "d9", "url": f"udpin://127.0.0.1:{port}", "gcs_endpoints": [gcs]}
        async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
            r = await http.post("/api/v1/vehicles", json=body)
            assert r.status_code == 201, r.text
            assert r.json()["gcs_endpoints"] == [gcs]
            try:
                loop = asyncio.get_running_loop()
                deadline = loop.time() + scaled(20)
                expected = f"waiting for the vehicle on udpin://127.0.0.1:{port}: cannot open"
                while expected not in str(
                    (v := (await http.get("/api/v1/vehicles/d9")).json())["status"]["last_error"]
                ):
                    assert loop.time() < deadline, v
                    await asyncio.sleep(0.2)
                assert "Address already in use" in v["status"]["last_error"] and v["state"] == "connecting", v
                listed = (await http.get("/api/v1/vehicles")).json()["items"]
                assert next(x for x in listed if x["id"] == "d9")["gcs_endpoints"] == [gcs]
            finally:
                assert (await http.delete("/api/v1/vehicles/d9")).status_code == 204


async def test_a_ground_stations_new_target_through_the_relay_is_a_takeover_its_reads_are_not(
    stack: Stack,
) -> None:
    """The agent holds the drone; the ground station on the relay reads (heartbeats, parameter list,
    REQUEST_MESSAGE): nothing happens. Its SET_POSITION_TARGET_GLOBAL_INT, still in GUIDED, is a takeover
    naming the ground station and the message, and the agent's next move is refused."""
    gcs = GroundStation()
    try:
        endpoint = f"udpout://127.0.0.1:{gcs.port}"
        r = await patch(stack, "d1", {"gcs_endpoints": [endpoint]})
        assert r.status_code == 200, r.text
        await wait_ready(stack)
        sysid = stack.sim.sysids[0]
        await asyncio.to_thread(gcs.wait, "HEARTBEAT", scaled(20), lambda m: m.get_srcSystem() == sysid)
        async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
            await http.delete("/api/v1/vehicles/d1/takeover")  # an earlier test's takeover, if any
        async with stack.client("auto", name="agent") as c:
            if (await stack.true_state("d1"))["armed"]:
                structured(await stack.call(c, "land", {"drone_id": "d1"}))
            took = structured(await stack.call(c, "takeoff", {"drone_id": "d1", "alt_m": 10}))
            assert took["status"] == "succeeded", took
            structured(await stack.call(c, "hold_position", {"drone_id": "d1"}))
            here = await stack.true_state("d1")

            def reads() -> None:
                gcs.conn.mav.heartbeat_send(
                    mavutil.mavlink.MAV_TYPE_GCS, mavutil.mavlink.MAV_AUTOPILOT_INVALID, 0, 0, 0
                )
                gcs.conn.mav.param_request_list_send(sysid, 1)
                gcs.conn.mav.command_long_send(
                    sysid, 1, mavutil.mavlink.MAV_CMD_REQUEST_MESSAGE, 0,
                    mavutil.mavlink.MAVLINK_MSG_ID_AUTOPILOT_VERSION, 0, 0, 0, 0, 0, 0,
                )  # fmt: skip

            await asyncio.to_thread(reads)
            await asyncio.to_thread(gcs.wait, "PARAM_VALUE", scaled(10))  # the reads went through
            assert (await stack.rest("/vehicles/d1"))["taken_over"] is None
            lat, lon = point_from(here, 250.0, 0.0)
            gcs.conn.mav.set_position_target_global_int_send(
                0, sysid, 1, mavutil.mavlink.MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, 0xDF8,
                round(lat * 1e7), round(lon * 1e7), 40.0, 0, 0, 0, 0, 0, 0, 0, 0,
            )  # fmt: skip
            sent = time.monotonic()
            deadline = sent + scaled(30)
            while not (taken := (await stack.rest("/vehicles/d1"))["taken_over"]):
                assert time.monotonic() < deadline, "no takeover after the ground station's new target"
                await asyncio.sleep(0.05)
            print(f"\nFIGURE relay: hold taken over {time.monotonic() - sent:.2f} s after the relayed target")
            reason = taken["reason"]
            assert f"ground station system {GCS_SYSID} sent SET_POSITION_TARGET_GLOBAL_INT" in reason, reason
            refused = await stack.call(c, "move_to_relative", {"drone_id": "d1", "north_m": 5})
            assert refused.is_error and "taken_over" in refused.content[0].text, refused
    finally:
        gcs.close()


async def test_an_endpoint_that_is_another_vehicle_is_refused_or_stopped_and_credentials_are_refused(
    stack: Stack,
) -> None:
    """Registration refuses an endpoint that is another drone's link and one with credentials (never
    echoing them); an endpoint that turns out to lead to another autopilot (here a second simulator's
    port, as `tcpout://127.0.0.1:5772` is bravo's) is stopped at its first HEARTBEAT and reported in the
    status and the audit, nothing of it relayed, and the drone's own link is untouched."""
    d1_url = (await stack.rest("/vehicles/d1"))["url"]
    body = {"id": "d8", "url": "udpin://127.0.0.1:14999", "gcs_endpoints": [d1_url]}
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
        r = await http.post("/api/v1/vehicles", json=body)
    assert r.status_code in (400, 422), r.text
    message = r.json()["error"]["message"]
    assert f"is drone 'd1''s own link ({d1_url})" in message, message

    r = await patch(stack, "d1", {"gcs_endpoints": ["tcpout://user:secret@127.0.0.1:5772"]})
    assert r.status_code == 422, r.text
    message = r.json()["error"]["message"]
    assert "credentials in a MAVLink URL are not accepted" in message and "secret" not in r.text, message
    audit = await stack.rest("/audit", vehicle_id="d1", limit=20)
    assert "secret" not in str(audit["items"]), "the password reached the audit"

    async with sim_process(count=1, sysid_base=7) as other:
        crossed = other.urls[0]  # another autopilot's own port
        r = await patch(stack, "d1", {"gcs_endpoints": [crossed]})
        assert r.status_code == 200, r.text
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(30)
        while True:
            v = await stack.rest("/vehicles/d1")
            stations = v["status"]["ground_stations"]
            if stations and stations[0]["refused"]:
                break
            assert loop.time() < deadline, v["status"]
            await asyncio.sleep(0.2)
        assert "its peer is another vehicle (system 7" in stations[0]["error"], stations
        await wait_ready(stack)
        v = await stack.rest("/vehicles/d1")
        assert v["status"]["other_sysids_on_link"] == [] and v["status"]["sysid"] == stack.sim.sysids[0]
        rows = (await stack.rest("/audit", vehicle_id="d1", limit=50))["items"]
        row = next(r for r in rows if r["action"] == "gcs_endpoint_refused")
        assert row["outcome"] == "refused" and row["arguments"]["endpoint"] == crossed, row
        assert (await stack.true_state("d1"))["mode"] is not None
    r = await patch(stack, "d1", {"gcs_endpoints": []})
    assert r.status_code == 200, r.text
