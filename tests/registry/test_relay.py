"""The ground station relay (gateway/link/relay.py) on real loopback sockets and a pseudo-terminal:
framing, routing (each frame to whom it concerns, system ids kept) and every kind of endpoint. pymavlink
plays the drone, the sidecar and the ground stations."""

from __future__ import annotations

import asyncio
import os
import socket
import sys
import time
import tty
from collections.abc import AsyncIterator
from typing import Any

import pytest
import pytest_asyncio
from pydantic import ValidationError

os.environ.setdefault("MAVLINK20", "1")  # the peers speak MAVLink 2 (addressed COMMAND_ACK)
from pymavlink import mavutil
from pymavlink.dialects.v10 import ardupilotmega as mavlink1
from pymavlink.dialects.v20 import ardupilotmega as mavlink

from gateway.link.ground_commands import acting
from gateway.link.mavlink_frames import FrameSplitter, target_system
from gateway.link.relay import Relay
from gateway.util.ports import free_tcp_port, free_udp_port
from tests.helpers.timing import scaled

DRONE, SIDECAR, GCS_A, GCS_B = 1, 245, 255, 250


def frame(msg: Any, sysid: int = DRONE) -> bytes:
    return bytes(msg.pack(mavlink.MAVLink(None, srcSystem=sysid, srcComponent=1)))


def heartbeat() -> Any:
    return mavlink.MAVLink_heartbeat_message(2, 3, 81, 4, 3, 3)


def ack(target: int) -> Any:
    return mavlink.MAVLink_command_ack_message(176, 0, 0, 0, target, 190)


def test_frames_are_cut_from_a_stream_with_noise_and_bad_frames_between() -> None:
    good = frame(heartbeat())
    targeted = frame(ack(GCS_A))
    broken = bytearray(frame(heartbeat()))
    broken[-1] ^= 0xFF  # its CRC no longer matches
    stream = b"\x00\xfe\x13noise" + good + bytes(broken) + targeted + good[:7]
    splitter = FrameSplitter()
    frames = splitter.feed(stream[:20]) + splitter.feed(stream[20:])
    assert [f.data for f in frames] == [good, targeted]
    assert [f.sysid for f in frames] == [DRONE, DRONE]
    assert [f.msgid for f in frames] == [0, 77]
    assert splitter.feed(good[7:]) and [target_system(f) for f in frames] == [0, GCS_A]
    v1 = bytes(mavlink1.MAVLink_heartbeat_message(2, 3, 81, 4, 3, 3).pack(mavlink1.MAVLink(None, 1, 1)))
    assert v1[0] == 0xFE and [f.data for f in FrameSplitter().feed(v1)] == [v1]


class Peer:
    """A pymavlink connection with a background-free receive helper."""

    def __init__(self, address: str, sysid: int) -> None:
        self.conn = mavutil.mavlink_connection(address, source_system=sysid, source_component=1)
        # MAVLink 2 whichever wire version mavutil was first imported with (another test module collected
        # earlier may have loaded it as MAVLink 1): COMMAND_ACK's target_system exists only in MAVLink 2
        self.conn.mav = mavlink.MAVLink(self.conn, srcSystem=sysid, srcComponent=1)
        self.conn.mav.robust_parsing = self.conn.robust_parsing

    def receive(self, kind: str, within_s: float, condition: Any = None) -> Any | None:
        deadline = time.monotonic() + scaled(within_s)
        while time.monotonic() < deadline:
            msg = self.conn.recv_match(type=kind, blocking=True, timeout=0.2)
            if msg is not None and (condition is None or condition(msg)):
                return msg
        return None

    def close(self) -> None:
        self.conn.close()


async def sidecar_peer(relay: Relay) -> Peer:
    """pymavlink connected to the relay as the drone's sidecar is (its URL in pymavlink's words)."""
    assert relay.sidecar_url.startswith("tcpout://")
    return await asyncio.to_thread(Peer, relay.sidecar_url.replace("tcpout://", "tcp:"), SIDECAR)


@pytest_asyncio.fixture
async def relay_with_peers() -> AsyncIterator[tuple[Relay, dict[str, Peer]]]:
    """Drone at udpin (the relay sends to it), ground station A at a tcpin endpoint, B at udpout."""
    drone_port, tcp_port, udp_port = free_udp_port(), free_tcp_port(), free_udp_port()
    drone = Peer(f"udpin:127.0.0.1:{drone_port}", DRONE)
    gcs_b = Peer(f"udpin:127.0.0.1:{udp_port}", GCS_B)
    relay = Relay(
        "r1",
        f"udpout://127.0.0.1:{drone_port}",
        [f"tcpin://127.0.0.1:{tcp_port}", f"udpout://127.0.0.1:{udp_port}"],
    )
    await relay.start()
    sidecar = await sidecar_peer(relay)
    gcs_a = await asyncio.to_thread(Peer, f"tcp:127.0.0.1:{tcp_port}", GCS_A)
    peers = {"drone": drone, "sidecar": sidecar, "a": gcs_a, "b": gcs_b}
    try:
        yield relay, peers
    finally:
        for peer in peers.values():
            peer.close()
        await relay.close()


async def test_frames_go_to_whom_they_concern_with_their_system_ids(
    relay_with_peers: tuple[Relay, dict[str, Peer]],
) -> None:
    relay, p = relay_with_peers
    # the sidecar and ground station A speak first: the drone (udpin) learns where the relay is
    for name in ("sidecar", "a"):
        p[name].conn.mav.heartbeat_send(6, 8, 0, 0, 0)
    heard = set()
    for _ in range(2):
        hb = await asyncio.to_thread(p["drone"].receive, "HEARTBEAT", 10)
        assert hb is not None, f"the drone heard only {heard}"
        heard.add(hb.get_srcSystem())
    assert heard == {SIDECAR, GCS_A}  # each keeps its own system id

    p["drone"].conn.mav.heartbeat_send(2, 3, 81, 4, 3)
    for name in ("sidecar", "a", "b"):
        hb = await asyncio.to_thread(p[name].receive, "HEARTBEAT", 10, lambda m: m.get_srcSystem() == DRONE)
        assert hb is not None, f"{name} got no HEARTBEAT from the drone"
    p["b"].conn.mav.heartbeat_send(6, 8, 0, 0, 0)  # B (udpin) answers whoever sent to it: the relay
    hb = await asyncio.to_thread(p["drone"].receive, "HEARTBEAT", 10)
    assert hb is not None and hb.get_srcSystem() == GCS_B

    # addressed frames: only where their system was heard
    p["drone"].conn.write(frame(ack(GCS_A)))
    p["drone"].conn.write(frame(ack(SIDECAR)))
    got_a = await asyncio.to_thread(p["a"].receive, "COMMAND_ACK", 10)
    got_sidecar = await asyncio.to_thread(p["sidecar"].receive, "COMMAND_ACK", 10)
    assert got_a is not None and got_a.target_system == GCS_A
    assert got_sidecar is not None and got_sidecar.target_system == SIDECAR
    assert await asyncio.to_thread(p["a"].receive, "COMMAND_ACK", 1) is None  # not the sidecar's
    assert await asyncio.to_thread(p["b"].receive, "COMMAND_ACK", 1) is None  # neither for B
    assert await asyncio.to_thread(p["sidecar"].receive, "COMMAND_ACK", 1) is None

    # a ground station's traffic goes to the drone only, never to the sidecar
    p["a"].conn.mav.command_long_send(DRONE, 1, 176, 0, 1, 5, 0, 0, 0, 0, 0)
    cmd = await asyncio.to_thread(p["drone"].receive, "COMMAND_LONG", 10)
    assert cmd is not None and cmd.get_srcSystem() == GCS_A
    assert await asyncio.to_thread(p["sidecar"].receive, "COMMAND_LONG", 1) is None
    status = {s["url"].split(":")[0]: s for s in relay.status()}
    assert status["tcpin"]["system_ids"] == [GCS_A] and status["udpout"]["system_ids"] == [GCS_B]
    assert status["tcpin"]["frames_in"] >= 2 and status["tcpin"]["frames_out"] >= 2
    assert status["tcpin"]["peer"] is not None and status["tcpin"]["error"] is None


async def test_a_serial_vehicle_is_relayed() -> None:
    master, slave = os.openpty()
    tty.setraw(master)
    udp_port = free_udp_port()
    gcs = Peer(f"udpin:127.0.0.1:{udp_port}", GCS_A)
    relay = Relay("r2", f"serial://{os.ttyname(slave)}:115200", [f"udpout://127.0.0.1:{udp_port}"])
    await relay.start()
    try:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(10)
        while relay.vehicle.peer is None:  # the device is opened by the relay's own task
            assert loop.time() < deadline, relay.complaint
            await asyncio.sleep(0.05)
        os.write(master, frame(heartbeat()))
        hb = await asyncio.to_thread(gcs.receive, "HEARTBEAT", 10)
        assert hb is not None and hb.get_srcSystem() == DRONE
        gcs.conn.mav.heartbeat_send(6, 8, 0, 0, 0)  # a ground station says what it is first
        gcs.conn.mav.command_long_send(DRONE, 1, 176, 0, 1, 5, 0, 0, 0, 0, 0)
        splitter, got = FrameSplitter(), []
        os.set_blocking(master, False)
        while not any(f.msgid == 76 for f in got):
            assert loop.time() < deadline + scaled(10), f"no COMMAND_LONG reached the serial device: {got}"
            await asyncio.sleep(0.05)
            try:
                got += splitter.feed(os.read(master, 4096))
            except BlockingIOError:
                continue
        assert {f.sysid for f in got} == {GCS_A}
    finally:
        await relay.close()
        gcs.close()
        os.close(master)
        os.close(slave)


async def test_a_vehicle_nobody_answers_for_is_named_with_the_reason() -> None:
    port = free_tcp_port()
    relay = Relay("r3", f"tcpout://127.0.0.1:{port}", [f"udpout://127.0.0.1:{free_udp_port()}"])
    await relay.start()
    try:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(10)
        while relay.complaint is None:
            assert loop.time() < deadline
            await asyncio.sleep(0.05)
        assert f"cannot connect to 127.0.0.1:{port}: Connection refused" in relay.complaint
    finally:
        await relay.close()


async def test_a_ground_station_port_already_taken_is_reported_and_opened_once_free() -> None:
    port = free_tcp_port()
    blocker = await asyncio.start_server(lambda r, w: None, "127.0.0.1", port)
    relay = Relay("r4", f"udpout://127.0.0.1:{free_udp_port()}", [f"tcpin://127.0.0.1:{port}"])
    try:
        await relay.start()
        [status] = relay.status()
        assert status["error"] == f"cannot open tcpin://127.0.0.1:{port}: Address already in use", status
        assert relay.sidecar_url.startswith("tcpout://127.0.0.1:")
        blocker.close()
        await blocker.wait_closed()
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(20)
        while relay.status()[0]["error"] is not None:  # tried again until the port is free
            assert loop.time() < deadline, relay.status()
            await asyncio.sleep(0.1)
        gcs = await asyncio.to_thread(Peer, f"tcp:127.0.0.1:{port}", GCS_A)
        gcs.close()
    finally:
        await relay.close()
        blocker.close()


@pytest.mark.parametrize("bad", ["serial:///dev/ttyS0", "http://127.0.0.1:1", "udpout://127.0.0.1"])
def test_bad_endpoints_are_refused_in_one_line(bad: str) -> None:
    from pydantic import ValidationError

    from gateway.registry.spec import VehicleSpec

    with pytest.raises(ValidationError) as err:
        VehicleSpec(id="a", url="tcpout://127.0.0.1:5760", gcs_endpoints=[bad])
    [e] = err.value.errors()
    assert e["loc"] == ("gcs_endpoints",)
    assert f"'{bad}' is not accepted" in e["msg"] and "udpout://host:port" in e["msg"]


async def test_only_the_sidecar_process_is_taken_as_the_sidecar() -> None:
    """Another local process connecting to the relay's sidecar port does not get between the sidecar and
    the drone: its frames are dropped, and the drone's still go to the sidecar."""
    drone_port = free_udp_port()
    drone = Peer(f"udpin:127.0.0.1:{drone_port}", DRONE)
    relay = Relay("r5", f"udpout://127.0.0.1:{drone_port}", [], sidecar_pid=os.getpid)
    await relay.start()
    port = relay.sidecar.bound_port
    intruder = frame(mavlink.MAVLink_heartbeat_message(6, 8, 0, 0, 0, 3), sysid=66).hex()
    script = (  # connects, sends a HEARTBEAT and waits for the relay to close the connection
        f"import contextlib,socket\ns=socket.create_connection(('127.0.0.1',{port}))\n"
        f"s.sendall(bytes.fromhex('{intruder}'))\nwith contextlib.suppress(OSError):\n    s.recv(1)"
    )
    sidecar = await sidecar_peer(relay)
    try:
        proc = await asyncio.create_subprocess_exec(sys.executable, "-c", script)
        assert await asyncio.wait_for(proc.wait(), scaled(20)) == 0
        sidecar.conn.mav.heartbeat_send(6, 8, 0, 0, 0)
        hb = await asyncio.to_thread(drone.receive, "HEARTBEAT", 10)
        assert hb is not None and hb.get_srcSystem() == SIDECAR
        assert (
            await asyncio.to_thread(drone.receive, "HEARTBEAT", 1, lambda m: m.get_srcSystem() == 66) is None
        )
        drone.conn.mav.heartbeat_send(2, 3, 81, 4, 3)
        assert await asyncio.to_thread(sidecar.receive, "HEARTBEAT", 10) is not None
    finally:
        sidecar.close()
        drone.close()
        await relay.close()


def test_a_ground_stations_frames_that_act_on_the_drone_are_told_from_its_reads() -> None:
    """What a ground station sends that acts on the drone (targets, commands, mission changes, parameter
    writes) is named; its reads, mode switches (the HEARTBEAT tells those) and frames to another system
    are not."""

    def said(msg: Any) -> str | None:
        [one] = FrameSplitter().feed(frame(msg, GCS_A))
        return acting(one, {DRONE})

    nan = float("nan")
    target = mavlink.MAVLink_set_position_target_global_int_message(
        0, DRONE, 1, 6, 0xDF8, 1, 1, 10.0, 0, 0, 0, 0, 0, 0, 0, 0
    )
    assert said(target) == "SET_POSITION_TARGET_GLOBAL_INT"
    reposition = mavlink.MAVLink_command_long_message(DRONE, 1, 192, 0, -1, 1, 0, nan, nan, nan, nan)
    assert said(reposition) == "COMMAND_LONG MAV_CMD_DO_REPOSITION"
    assert said(mavlink.MAVLink_mission_set_current_message(DRONE, 1, 3)) == "MISSION_SET_CURRENT"
    assert said(mavlink.MAVLink_param_set_message(DRONE, 1, b"WPNAV_SPEED", 4000, 9)) == "PARAM_SET"
    speed = mavlink.MAVLink_command_long_message(DRONE, 1, 178, 0, 1, 12, -1, 0, 0, 0, 0)
    assert said(speed) == "COMMAND_LONG MAV_CMD_DO_CHANGE_SPEED"
    yaw = mavlink.MAVLink_command_int_message(DRONE, 1, 0, 115, 0, 0, 90, 0, 0, 0, 0, 0, 0)
    assert said(yaw) == "COMMAND_INT MAV_CMD_CONDITION_YAW"
    for read in (
        heartbeat(),
        mavlink.MAVLink_param_request_list_message(DRONE, 1),
        mavlink.MAVLink_mission_request_list_message(DRONE, 1, 0),
        mavlink.MAVLink_command_long_message(DRONE, 1, 512, 0, 148, 0, 0, 0, 0, 0, 0),
        mavlink.MAVLink_command_long_message(DRONE, 1, 511, 0, 33, 1e5, 0, 0, 0, 0, 0),
        mavlink.MAVLink_command_long_message(DRONE, 1, 176, 0, 1, 5, 0, 0, 0, 0, 0),  # DO_SET_MODE
        mavlink.MAVLink_set_mode_message(DRONE, 1, 5),
        mavlink.MAVLink_command_long_message(7, 1, 192, 0, -1, 1, 0, nan, nan, nan, nan),  # to system 7
    ):
        assert said(read) is None, read


async def test_an_endpoint_whose_peer_is_another_vehicle_is_stopped_and_nothing_of_it_relayed() -> None:
    """A ground station endpoint cross-wired to another drone's autopilot port (here a tcpout to a peer
    that speaks as autopilot system 2, telemetry first): what it sends before its HEARTBEAT is held back,
    its HEARTBEAT says it is a vehicle, the endpoint is stopped and reported (status, on_refused); the
    drone's own link goes on."""

    async def other_vehicle(_reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        position = mavlink.MAVLink_global_position_int_message(0, 1, 1, 10, 10, 0, 0, 0, 0)
        writer.write(frame(position, 2) + frame(heartbeat(), 2))
        await writer.drain()

    drone_port = free_udp_port()
    server = await asyncio.start_server(other_vehicle, "127.0.0.1", 0)
    vehicle_port = server.sockets[0].getsockname()[1]
    drone = Peer(f"udpin:127.0.0.1:{drone_port}", DRONE)
    refused: list[tuple[str, str]] = []
    endpoint = f"tcpout://127.0.0.1:{vehicle_port}"
    relay = Relay(
        "r6", f"udpout://127.0.0.1:{drone_port}", [endpoint], on_refused=lambda *a: refused.append(a)
    )
    await relay.start()
    sidecar = await sidecar_peer(relay)
    try:
        sidecar.conn.mav.heartbeat_send(6, 8, 0, 0, 0)  # the drone (udpin) learns where the relay is
        assert await asyncio.to_thread(drone.receive, "HEARTBEAT", 10) is not None
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(10)
        while not refused:
            assert loop.time() < deadline, relay.status()
            await asyncio.sleep(0.05)
        [(url, reason)] = refused
        assert url == endpoint and "its peer is another vehicle (system 2" in reason, reason
        [station] = relay.status()
        assert station["refused"] is True and "nothing from it was relayed" in station["error"], station
        got = await asyncio.to_thread(drone.receive, "GLOBAL_POSITION_INT", 1)
        assert got is None, "the other vehicle's telemetry reached the drone"
        drone.conn.mav.heartbeat_send(2, 3, 81, 4, 3)  # the drone's own link goes on
        hb = await asyncio.to_thread(sidecar.receive, "HEARTBEAT", 10, lambda m: m.get_srcSystem() == DRONE)
        assert hb is not None
    finally:
        drone.close()
        sidecar.close()
        await relay.close()
        server.close()


def test_an_endpoint_that_is_another_drones_link_or_carries_credentials_is_refused() -> None:
    from gateway.registry.spec import VehicleSpec, gcs_endpoint_conflict

    bravo = VehicleSpec(id="bravo", url="tcpout://127.0.0.1:5770")
    listening = VehicleSpec(id="charlie", url="udpin://0.0.0.0:14560")
    for crossed, other in (
        ("tcpout://127.0.0.1:5770", "bravo"),
        ("tcpout://localhost:5770", "bravo"),
        ("udpout://127.0.0.1:14560", "charlie"),  # into charlie's own listening port
    ):
        alpha = VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760", gcs_endpoints=[crossed])
        said = gcs_endpoint_conflict(alpha, [bravo, listening], 8765)
        assert said is not None and f"is drone '{other}''s own link" in said, said
    fine = ["udpout://127.0.0.1:14550", "tcpout://127.0.0.1:5771", "tcpin://127.0.0.1:5790"]
    alpha = VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760", gcs_endpoints=fine)
    assert gcs_endpoint_conflict(alpha, [bravo, listening], 8765) is None
    gateway = VehicleSpec(
        id="alpha", url="tcpout://127.0.0.1:5760", gcs_endpoints=["tcpout://127.0.0.1:8765"]
    )
    assert "the gateway's own HTTP port" in str(gcs_endpoint_conflict(gateway, [], 8765))
    with pytest.raises(ValueError, match="is the drone's own link") as own:
        VehicleSpec(id="alpha", url="udpin://0.0.0.0:14540", gcs_endpoints=["udpout://127.0.0.1:14540"])
    assert "udpout://127.0.0.1:14540" in str(own.value)
    with pytest.raises(ValidationError) as creds:
        VehicleSpec(
            id="alpha", url="tcpout://127.0.0.1:5760", gcs_endpoints=["tcpout://user:pw@127.0.0.1:5772"]
        )
    [error] = creds.value.errors()
    assert "credentials in a MAVLink URL are not accepted" in error["msg"], error
    assert ":pw@" not in error["msg"] and "***@127.0.0.1:5772" in error["msg"], error


async def test_a_burst_from_the_drone_reaches_a_sidecar_that_is_not_reading_without_loss() -> None:
    """The drone's parameter list comes as a burst (~1,300 PARAM_VALUE at once on ArduPilot); a
    mavsdk_server that is not scheduled for a moment must still get every frame of it once it reads, or
    its parameter reads time out. The sidecar here reads nothing until the relay has passed the whole
    burst on, then counts what it gets."""
    count = 4000
    mav = mavlink.MAVLink(None, srcSystem=DRONE, srcComponent=1)
    burst = b"".join(
        bytes(mavlink.MAVLink_param_value_message(f"P{i:05d}".encode(), float(i), 9, count, i).pack(mav))
        for i in range(count)
    )

    async def drone(_reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        writer.write(burst)
        await writer.drain()
        await _reader.read()  # held open until the relay closes

    server = await asyncio.start_server(drone, "127.0.0.1", 0)
    relay = Relay("r7", f"tcpout://127.0.0.1:{server.sockets[0].getsockname()[1]}", [])
    await relay.start()
    scheme, _, address = relay.sidecar_url.partition("://")
    host, _, port = address.rpartition(":")
    if scheme == "tcpout":
        sidecar = socket.create_connection((host, int(port)))
    else:  # a udpin relay answers the latest sender
        sidecar = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        sidecar.connect((host, int(port)))
        sidecar.send(frame(heartbeat(), SIDECAR))
    try:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(30)
        while relay.vehicle.stats.bytes_in < len(burst):
            got_bytes = relay.vehicle.stats.bytes_in
            assert loop.time() < deadline, f"the relay got {got_bytes} of {len(burst)} bytes"
            await asyncio.sleep(0.05)
        sidecar.settimeout(scaled(2))
        got: list[int] = []
        splitter = FrameSplitter()
        while len(got) < count:
            try:
                data = await asyncio.to_thread(sidecar.recv, 65536)
            except TimeoutError:
                break
            if not data:
                break
            got += [f.msgid for f in splitter.feed(data)]
        params = [m for m in got if m == mavlink.MAVLINK_MSG_ID_PARAM_VALUE]
        assert len(params) == count, f"the sidecar got {len(params)} of the {count} PARAM_VALUE"
    finally:
        sidecar.close()
        await relay.close()
        server.close()


async def test_without_ground_stations_the_drones_bytes_go_to_the_sidecar_and_the_log_as_read() -> None:
    """Nothing to route without ground stations: what the drone sends reaches the sidecar byte for byte
    (bytes between frames too: mavsdk_server skips them as it does on a direct link) and the raw log's
    sink gets the same reads; the sidecar's frames reach the drone."""
    sent = b"\x00noise" + frame(heartbeat()) + frame(ack(SIDECAR))
    drone_got = bytearray()

    async def drone(reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        writer.write(sent)
        await writer.drain()
        while chunk := await reader.read(4096):
            drone_got.extend(chunk)

    server = await asyncio.start_server(drone, "127.0.0.1", 0)
    logged = bytearray()
    relay = Relay("r8", f"tcpout://127.0.0.1:{server.sockets[0].getsockname()[1]}", [])
    relay.on_vehicle_bytes = logged.extend
    await relay.start()
    _, _, address = relay.sidecar_url.partition("://")
    host, _, port = address.rpartition(":")
    sidecar = socket.create_connection((host, int(port)))
    try:
        sidecar.settimeout(scaled(10))
        got = bytearray()
        while len(got) < len(sent):
            data = await asyncio.to_thread(sidecar.recv, 65536)
            assert data, f"the relay closed the sidecar's connection after {bytes(got)!r}"
            got += data
        assert bytes(got) == sent and bytes(logged) == sent
        own = frame(heartbeat(), SIDECAR)
        sidecar.sendall(b"\x00" + own)  # a stray byte, then a frame: the drone gets the frame
        loop = asyncio.get_running_loop()
        deadline = loop.time() + scaled(10)
        while bytes(drone_got) != own:
            assert loop.time() < deadline, f"the drone got {bytes(drone_got)!r}"
            await asyncio.sleep(0.02)
    finally:
        sidecar.close()
        await relay.close()
        server.close()
