"""Registry, persistence and link states against real sidecars and bare MAVLink heartbeat senders.

A heartbeat-only vehicle never becomes 'ready' (no position, no home): these tests cover what does not
need a flying simulator: registration, restore, identity checks, link loss, sidecar restarts, teardown.
"""

from __future__ import annotations

import asyncio
import os
import signal

import pytest

from gateway.errors import CommandFailed, DuplicateVehicle, InvalidArgument, UnknownVehicle, VehicleNotReady
from gateway.fleet.vehicles.registry import Registry
from gateway.fleet.vehicles.vehicle import ConnectionState
from gateway.registry.spec import VehicleSpec
from gateway.util.ports import free_udp_port
from tests.helpers.timing import settled
from tests.registry.conftest import fast_settings, wait_until
from tests.registry.heartbeat import HeartbeatVehicle
from tests.registry.procs import alive, mavsdk_servers_of


def _spec(vid: str, port: int, **kw: object) -> VehicleSpec:
    return VehicleSpec(id=vid, url=f"udpin://127.0.0.1:{port}", **kw)  # type: ignore[arg-type]


async def test_register_persist_restore_and_stop(store, registries) -> None:
    ports = [free_udp_port() for _ in range(2)]
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(ports[0], sysid=11), HeartbeatVehicle(ports[1], sysid=12):
        a = await reg.add(_spec("alpha", ports[0], name="Alpha", tags=["t1"]))
        b = await reg.add(_spec("bravo", ports[1]), connect=False)
        assert b.state == ConnectionState.REGISTERED
        await a.wait_for_state(ConnectionState.CONNECTED)
        await wait_until(lambda: a.sysid == 11, what="sysid from HEARTBEAT")
        assert a.autopilot == "ardupilot"
        assert a.telemetry.fresh("flight_mode") == "GUIDED"  # ArduCopter custom_mode 4 from HEARTBEAT
        status = a.status()
        assert status["sidecar"]["pid"] and status["sidecar"]["grpc_port"]
        assert status["last_heartbeat_age_s"] is not None and status["sysid_mismatch"] is False
        assert status["last_heartbeat_at"].endswith("+00:00")
        # not ready: no position/home from a heartbeat-only vehicle; actions say so instead of hanging
        # (asked to wait at most 2 s; the heartbeat-only vehicle gives no reason, so the gateway's is named)
        with pytest.raises(VehicleNotReady, match="connected but not ready"):
            await a.takeoff(10, within_s=2.0)
        with pytest.raises(DuplicateVehicle):
            await reg.add(_spec("alpha", ports[1]))
        with pytest.raises(UnknownVehicle, match="alpha, bravo"):
            reg.get("zulu")
        with pytest.raises(InvalidArgument, match="url"):
            await reg.add({"id": "charlie", "url": "http://example.com"})
        assert [v.id for v in reg.all()] == ["alpha", "bravo"]
        pid = status["sidecar"]["pid"]
        await reg.stop()
        assert not alive(pid)
        assert mavsdk_servers_of() == []

        # a new registry on the same database restores both; only alpha auto-connects
        reg2 = Registry(fast_settings(), store)
        registries.append(reg2)
        await reg2.start()
        a2, b2 = reg2.get("alpha"), reg2.get("bravo")
        assert a2.spec.name == "Alpha" and a2.spec.tags == ["t1"]
        assert b2.state == ConnectionState.REGISTERED
        await a2.wait_for_state(ConnectionState.CONNECTED)
        await reg2.connect("bravo")
        await b2.wait_for_state(ConnectionState.CONNECTED)
        await reg2.disconnect("alpha")
        assert a2.state == ConnectionState.REGISTERED
        assert (await store.get_vehicle("alpha")).auto_connect is False
        await reg2.remove("bravo")
        assert await store.get_vehicle("bravo") is None
        assert [v.id for v in reg2.all()] == ["alpha"]


async def test_wrong_and_duplicate_sysid_are_flagged(store, registries) -> None:
    ports = [free_udp_port() for _ in range(3)]
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with (
        HeartbeatVehicle(ports[0], sysid=5),
        HeartbeatVehicle(ports[1], sysid=7),
        HeartbeatVehicle(ports[2], sysid=7),
    ):
        wrong = await reg.add(_spec("wrong", ports[0], expected_sysid=4))
        twin1 = await reg.add(_spec("twin-1", ports[1]))
        twin2 = await reg.add(_spec("twin-2", ports[2]))
        await wait_until(lambda: wrong.sysid == 5 and twin1.sysid == 7 and twin2.sysid == 7, what="sysids")
        st = wrong.status()
        assert st["sysid_mismatch"] is True and st["sysid"] == 5 and st["expected_sysid"] == 4
        assert "system id mismatch" in (st["last_error"] or "")
        with pytest.raises(VehicleNotReady, match="reports system id 5 but 4 is expected"):
            wrong.require_ready()
        assert twin1.status()["duplicate_sysid"] == ["twin-2"]
        assert twin2.status()["duplicate_sysid"] == ["twin-1"]
        assert wrong.status()["duplicate_sysid"] == []


async def test_link_lost_and_back(store, registries) -> None:
    port = free_udp_port()
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(port, sysid=21):
        v = await reg.add(_spec("echo", port))
        await v.wait_for_state(ConnectionState.CONNECTED)
    # heartbeats stopped
    await v.wait_for_state(ConnectionState.LINK_LOST)
    assert "no heartbeat" in (v.status()["last_error"] or "")
    with pytest.raises(VehicleNotReady, match="link_lost"):
        v.require_ready()
    async with HeartbeatVehicle(port, sysid=21):
        await v.wait_for_state(ConnectionState.CONNECTED)
        assert v.status()["last_error"] is None  # the link is back: the error is over


async def test_killed_sidecar_restarts_others_untouched(store, registries) -> None:
    ports = [free_udp_port() for _ in range(2)]
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(ports[0], sysid=31), HeartbeatVehicle(ports[1], sysid=32):
        v1 = await reg.add(_spec("kilo", ports[0]))
        v2 = await reg.add(_spec("lima", ports[1]))
        await v1.wait_for_state(ConnectionState.CONNECTED)
        await v2.wait_for_state(ConnectionState.CONNECTED)
        seen: list[tuple[str, str, str]] = []
        reg.on_state_change(lambda v, old, new: seen.append((v.id, old.value, new.value)))
        pid1, pid2 = v1.status()["sidecar"]["pid"], v2.status()["sidecar"]["pid"]
        os.kill(pid1, signal.SIGKILL)
        await wait_until(lambda: v1.status()["sidecar"]["pid"] not in (None, pid1), what="new sidecar")
        await v1.wait_for_state(ConnectionState.CONNECTED)
        await wait_until(lambda: v1.sysid == 31, what="heartbeats in the new session")
        assert v1.status()["sidecar"]["restarts"] == 1
        assert v1.sessions == 2
        assert "code -9" in (v1.link.sidecar.info.last_error or "")  # the sidecar keeps its history
        assert v1.last_error is None  # the link is back
        assert v2.status()["sidecar"]["pid"] == pid2
        assert all(vid != "lima" for vid, _, _ in seen)
        assert ("kilo", "connected", "connecting") in seen


async def test_raw_commands_modes_and_unknown_parameter(store, registries) -> None:
    port = free_udp_port()
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(port, sysid=41) as fake:
        v = await reg.add(_spec("mike", port))
        await v.wait_for_state(ConnectionState.CONNECTED)
        await wait_until(lambda: v.sysid == 41, what="heartbeat")
        # DO_SET_MODE goes out through mavlink_direct, is ACKed, and the HEARTBEAT confirms it
        await v.set_flight_mode("circle")
        assert fake.custom_mode == 7
        await wait_until(lambda: v.telemetry.fresh("flight_mode") == "CIRCLE", what="mode in cache")
        refusal = r"mode 'WARP' is not a mode of drone 'mike' \(ArduCopter\); its modes: HOLD, GUIDED"
        with pytest.raises(InvalidArgument, match=refusal):
            await v.set_flight_mode("WARP")
        assert fake.custom_mode == 7
        # the gateway asked for MISSION_CURRENT by id, and probed for SIMSTATE (FAILED: not a simulator)
        await wait_until(
            lambda: any(
                m.get_type() == "COMMAND_LONG" and m.command == 511 and m.param1 == 42 for m in fake.received
            ),
            what="MISSION_CURRENT interval request",
        )
        assert v.is_simulator is False
        # ArduPilot ignores unknown parameter names: MAVSDK times out, the gateway says what it means
        with pytest.raises(CommandFailed, match="unknown parameter 'NO_SUCH_PARAM'"):
            await v.get_param("NO_SUCH_PARAM")
        with pytest.raises(InvalidArgument, match="parameter name"):
            await v.get_param("BAD NAME!")


async def test_heartbeat_watchdog_stops_gcs_heartbeats_when_not_fed(store, registries) -> None:
    port = free_udp_port()
    reg = Registry(fast_settings(sidecar_heartbeat_watchdog_s=2), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(port, sysid=51) as fake:
        v = await reg.add(_spec("november", port))
        await v.wait_for_state(ConnectionState.CONNECTED)

        def gcs_heartbeats() -> int:
            return sum(1 for m in fake.received if m.get_type() == "HEARTBEAT" and m.get_srcSystem() == 245)

        start = gcs_heartbeats()
        await wait_until(
            lambda: gcs_heartbeats() >= start + 3, what="GCS heartbeats while the watchdog is fed"
        )
        # a hung gateway stops feeding: mavsdk_server stops the GCS heartbeat, so the autopilot's own
        # GCS failsafe can act
        feeder = next(t for t in asyncio.all_tasks() if t.get_name() == "watchdog-november")
        feeder.cancel()

        async def count() -> int:
            return gcs_heartbeats()

        # the watchdog (2 s) runs out, then no GCS heartbeat for 2.5 s in a row
        await settled(count, lambda a, b: a == b, "GCS heartbeats stop", window_s=2.5, within_s=30)


async def test_unreachable_vehicle_says_why_and_failed_vehicle_reconnects(store, registries) -> None:
    from gateway.util.ports import free_tcp_port

    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    # nothing listens there: mavsdk_server retries every second, the vehicle stays 'connecting'
    v = await reg.add(VehicleSpec(id="oscar", url=f"tcpout://127.0.0.1:{free_tcp_port()}"))
    await wait_until(lambda: "Connection refused" in (v.status()["last_error"] or ""), what="complaint")
    assert v.state == ConnectionState.CONNECTING
    with pytest.raises(VehicleNotReady, match=r"still being established.*Connection refused"):
        v.require_ready()
    # a link that cannot be opened at all ends in 'failed'; connecting again starts afresh
    dead = await reg.add(VehicleSpec(id="papa", url="serial:///dev/fleet-gateway-no-such-device:57600"))
    await dead.wait_for_state(ConnectionState.FAILED)
    assert "No such file or directory" in dead.status()["last_error"]
    await reg.connect("papa")
    assert dead.state == ConnectionState.CONNECTING
    assert dead.status()["sidecar"]["restarts"] == 0


async def test_update_renames_and_moves_a_connected_vehicle(store, registries) -> None:
    ports = [free_udp_port() for _ in range(2)]
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(ports[0], sysid=61), HeartbeatVehicle(ports[1], sysid=62):
        v = await reg.add(_spec("quebec", ports[0]))
        await wait_until(lambda: v.sysid == 61, what="first link")
        old_pid = v.status()["sidecar"]["pid"]
        await reg.update("quebec", name="Q", tags=["moved"])
        assert v.spec.name == "Q" and v.status()["sidecar"]["pid"] == old_pid  # no reconnect needed
        await reg.update("quebec", url=f"udpin://127.0.0.1:{ports[1]}")
        await wait_until(lambda: v.sysid == 62, what="second link")
        assert not alive(old_pid)
        assert (await store.get_vehicle("quebec")).url.endswith(str(ports[1]))
        with pytest.raises(InvalidArgument):
            await reg.update("quebec", url="ftp://nowhere")
        assert v.spec.url.endswith(str(ports[1]))  # bad input changed nothing


async def test_flight_left_open_by_a_dead_gateway_is_closed_from_its_track(store, registries) -> None:
    from datetime import UTC, datetime, timedelta

    from gateway.registry.store import TrackSample

    await store.add_vehicle(VehicleSpec(id="romeo", url=f"udpin://127.0.0.1:{free_udp_port()}"))
    t0 = datetime.now(UTC) - timedelta(minutes=5)
    flight_id = await store.open_flight("romeo", t0, 47.0, 8.0, 500.0)
    await store.add_track_samples(
        [
            TrackSample(flight_id=flight_id, t=t0 + timedelta(seconds=i), lat=47.0 + i * 1e-4, lon=8.0,
                        alt_rel_m=5.0 * i, heading_deg=0.0, ground_speed_mps=11.0, battery_pct=90.0 - i)
            for i in range(4)
        ]
    )  # fmt: skip
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()  # restores romeo; its recorder closes the flight the previous run left open
    assert await store.list_open_flights("romeo") == []
    flight = await store.get_flight(flight_id)
    assert flight.duration_s == pytest.approx(3.0)
    assert flight.distance_m == pytest.approx(33.4, abs=0.5)  # 3 x 1e-4 deg of latitude
    assert flight.max_alt_rel_m == 15.0 and flight.battery_used_pct == pytest.approx(3.0)


async def test_watchdog_does_not_block_discovery_of_a_vehicle_that_waits_for_the_gcs(
    store, registries
) -> None:
    # mavsdk_server started with --heartbeat-watchdog-timeout sends nothing until fed, and can only be fed
    # once discovered: a udpout:// vehicle that speaks only after hearing its GCS would never be found.
    reg = Registry(fast_settings(sidecar_heartbeat_watchdog_s=2), store)
    registries.append(reg)
    await reg.start()
    async with HeartbeatVehicle(None, sysid=71) as shy:
        v = await reg.add(
            _spec("sierra", shy.port).model_copy(update={"url": f"udpout://127.0.0.1:{shy.port}"})
        )
        await v.wait_for_state(ConnectionState.CONNECTED)
        await wait_until(lambda: v.sysid == 71, what="heartbeat from the vehicle")
