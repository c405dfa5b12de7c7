"""The vehicle layer against the project's simulator through real mavsdk_server sidecars.

Figures (time to ready, restart time, sidecar RSS) are printed for the report, never asserted.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import os
import signal
import time

import pytest

from gateway.errors import CommandFailed, InvalidArgument, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.caller import Caller
from gateway.fleet.vehicles.registry import Registry
from gateway.fleet.vehicles.vehicle import ConnectionState, Vehicle
from gateway.registry.spec import VehicleSpec
from gateway.runtime import Gateway
from tests.helpers.sim import sim_process
from tests.registry.conftest import WAIT_S, fast_settings, wait_until
from tests.registry.procs import alive, mavsdk_servers_of, rss_kib

SPEEDUP = 10.0
READY = ConnectionState.READY


async def _all_ready(vehicles: list[Vehicle]) -> None:
    await asyncio.gather(*(v.wait_for_state(READY, within_s=WAIT_S) for v in vehicles))


async def test_three_drones_ready_restored_and_one_sidecar_killed(store, registries) -> None:
    async with sim_process(3, speedup=SPEEDUP) as sim:
        reg = Registry(fast_settings(), store)
        registries.append(reg)
        await reg.start()
        t0 = time.monotonic()
        vehicles = [
            await reg.add(VehicleSpec(id=f"d{i + 1}", url=url, expected_sysid=sysid))
            for i, (url, sysid) in enumerate(zip(sim.urls, sim.sysids, strict=True))
        ]
        await _all_ready(vehicles)
        print(
            f"\nFIGURE 3 drones registered -> all ready: {time.monotonic() - t0:.1f} s (speedup {SPEEDUP:g})"
        )
        # a simulator is known as one once its SIMSTATE arrives, asked for after the rates: a drone may be
        # ready before that (its home announced at boot)
        await wait_until(lambda: all(v.status()["is_simulator"] for v in vehicles), what="SIMSTATE")
        for v in vehicles:
            st = v.status()
            assert st["is_simulator"] is True and st["autopilot"] == "ardupilot"
            assert st["sysid"] == v.spec.expected_sysid and st["duplicate_sysid"] == []
            print(f"FIGURE sidecar RSS {v.id}: {rss_kib(st['sidecar']['pid'])} KiB")

        transitions: list[tuple[str, str, str]] = []
        reg.on_state_change(lambda v, old, new: transitions.append((v.id, old.value, new.value)))
        victim = reg.get("d2")
        pid = victim.status()["sidecar"]["pid"]
        t_kill = time.monotonic()
        os.kill(pid, signal.SIGKILL)
        await wait_until(lambda: victim.status()["sidecar"]["restarts"] == 1, what="sidecar restart")
        await victim.wait_for_state(READY, within_s=WAIT_S)
        print(f"FIGURE kill -9 sidecar -> vehicle ready again: {time.monotonic() - t_kill:.1f} s")
        assert not alive(pid)
        assert ("d2", "ready", "connecting") in transitions
        assert [t for t in transitions if t[0] != "d2"] == []  # the other two never left ready
        assert all(v.state == READY for v in vehicles)

        pids = [v.status()["sidecar"]["pid"] for v in vehicles]
        await reg.stop()
        assert not any(alive(p) for p in pids)
        assert mavsdk_servers_of() == []

        # a new registry on the same database restores all three, and they fly-ready again
        reg2 = Registry(fast_settings(), store)
        registries.append(reg2)
        await reg2.start()
        assert [v.id for v in reg2.all()] == ["d1", "d2", "d3"]
        await _all_ready(reg2.all())
        assert [v.spec.expected_sysid for v in reg2.all()] == sim.sysids


async def test_link_loss_staleness_and_wrong_sysid(store, registries) -> None:
    async with sim_process(2, speedup=SPEEDUP) as sim:
        reg = Registry(fast_settings(link_lost_after_s=2.0), store)
        registries.append(reg)
        await reg.start()
        good = await reg.add(VehicleSpec(id="good", url=sim.urls[0], expected_sysid=sim.sysids[0]))
        wrong = await reg.add(VehicleSpec(id="wrong", url=sim.urls[1], expected_sysid=99))
        await good.wait_for_state(READY, within_s=WAIT_S)
        await wait_until(lambda: wrong.sysid == sim.sysids[1], what="sysid of the wrong vehicle")
        await wait_until(lambda: good.telemetry.fresh("health") is not None, what="health")
        # wrong system id: flagged, never ready, actions refused with the reason
        assert wrong.status()["sysid_mismatch"] is True
        assert wrong.state == ConnectionState.CONNECTED
        with pytest.raises(VehicleNotReady, match=f"reports system id {sim.sysids[1]} but 99 is expected"):
            await wrong.takeoff(5)

        snap = good.telemetry.snapshot()
        for part in ("position", "home", "attitude", "velocity_ned", "battery", "gps_info", "health", "imu"):
            assert snap[part] is not None, part
            assert snap[part]["stale"] is False and 0 <= snap[part]["age_s"] < 2.0, (part, snap[part])
        assert 0 <= snap["battery"]["remaining_pct"] <= 100  # MAVSDK gives percent already, never x100
        json.dumps(snap, allow_nan=False)  # strict JSON: MAVSDK's NaN "unknown" values became None

        # GPS loss: the vehicle is still connected, but no longer ready to fly
        await sim.control.gps_loss(0, True)
        await good.wait_for_state(ConnectionState.CONNECTED, within_s=WAIT_S)
        # (asked to wait at most 2 s: the refusal comes in the autopilot's words, or in the gateway's)
        with pytest.raises(VehicleNotReady, match=r"cannot arm yet: autopilot says|connected but not ready"):
            await good.takeoff(5, within_s=2.0)
        await sim.control.gps_loss(0, False)
        await good.wait_for_state(READY, within_s=WAIT_S)

        await sim.control.link_down(0)
        await good.wait_for_state(ConnectionState.LINK_LOST, within_s=WAIT_S)
        # every value is stale once the link is lost, even one that came a moment after the last heartbeat
        snap = good.telemetry.snapshot()
        parts = [part for name, part in snap.items() if name != "status_texts" and part is not None]
        assert parts and all(part["stale"] is True for part in parts), snap
        assert good.telemetry.fresh("position") is None  # stale values are not presented as current
        with pytest.raises(VehicleNotReady, match="link_lost"):
            await good.goto(0.0, 0.0, 10)
        await sim.control.link_up(0)
        await good.wait_for_state(READY, within_s=WAIT_S)
        assert good.telemetry.fresh("position") is not None

        # streams lost while heartbeats go on (what an autopilot reboot does to the rates): the gateway
        # notices the silent position stream and requests the rates again by itself
        # SET_MESSAGE_INTERVAL(GLOBAL_POSITION_INT, -1): the vehicle stops sending it, as after a reboot
        await good.link.command_long(511, 33, -1, what="disable GLOBAL_POSITION_INT")
        await good.link.command_long(511, 30, -1, what="disable ATTITUDE")
        await wait_until(lambda: good.telemetry.fresh("position", max_age_s=1.0) is None, what="silence")
        await wait_until(
            lambda: good.telemetry.fresh("position", max_age_s=0.5) is not None, what="rates back"
        )


@contextlib.asynccontextmanager
async def one_ready_drone(store, registries: list[Registry], vehicle_id: str):  # type: ignore[no-untyped-def]
    """One simulated drone (its own simulator process) in a started registry, ready: (simulator, vehicle)."""
    async with sim_process(1, speedup=SPEEDUP) as sim:
        reg = Registry(fast_settings(), store)
        registries.append(reg)
        await reg.start()
        v = await reg.add(VehicleSpec(id=vehicle_id, url=sim.urls[0]))
        await v.wait_for_state(READY, within_s=WAIT_S)
        yield sim, v


async def _wait_alt(v: Vehicle, alt: float) -> None:
    await wait_until(
        lambda: (p := v.telemetry.fresh("position")) is not None and p.rel_alt_m >= alt,
        what=f"altitude {alt}",
    )


async def test_flight_through_vehicle_api_is_logged(store, registries) -> None:
    async with one_ready_drone(store, registries, "flyer") as (sim, v):
        with pytest.raises(InvalidArgument, match="latitude"):
            await v.goto(123.0, 0.0, 10)
        await v.takeoff(10)  # arms in GUIDED first
        await _wait_alt(v, 9.5)
        assert v.telemetry.fresh("armed") is True
        home = v.telemetry.home.value
        lat, lon = geo.offset_position(home.lat_deg, home.lon_deg, 100.0, 0.0)
        await v.goto(lat, lon, 10)
        await wait_until(
            lambda: (
                (p := v.telemetry.fresh("position")) is not None
                and geo.horizontal_distance_m(p.lat_deg, p.lon_deg, lat, lon) < 2.0
            ),
            what="arrival",
        )
        pos = v.telemetry.fresh("position")
        assert pos.abs_alt_m == pytest.approx(home.abs_alt_m + 10, abs=1.0)  # relative -> AMSL done right
        await v.hold()
        assert (await sim.control.state(0))["mode"] == "GUIDED"  # hold is never LOITER
        await v.set_yaw(90)
        await wait_until(
            lambda: (h := v.telemetry.fresh("heading_deg")) is not None and abs(h - 90) < 5, what="heading 90"
        )
        with pytest.raises(CommandFailed, match="disarm"):
            await v.disarm()  # ArduCopter refuses to disarm in flight
        await v.set_max_speed(8)
        await v.return_to_launch()
        await wait_until(lambda: v.telemetry.fresh("flight_mode") == "RTL", what="RTL mode")
        await wait_until(lambda: v.telemetry.fresh("armed") is False, what="disarmed after RTL")
        await v.kill()  # accepted on the ground, changes nothing

        async def flight_closed() -> bool:
            flights, _ = await store.list_flights(vehicle_id="flyer")
            return bool(flights) and flights[0].ended_at is not None

        deadline = time.monotonic() + WAIT_S
        while not await flight_closed():
            assert time.monotonic() < deadline, "flight never closed"
            await asyncio.sleep(0.2)
        flights, total = await store.list_flights(vehicle_id="flyer")
        assert total == 1
        flight = flights[0]
        assert 150 <= flight.distance_m <= 260, flight  # out 100 m and back
        assert 9 <= flight.max_alt_rel_m <= 16, flight  # RTL climbs to RTL_ALT (15 m)
        assert flight.home_alt_amsl == pytest.approx(home.abs_alt_m)
        assert flight.duration_s > 0 and flight.battery_used_pct is not None
        track = await store.get_track(flight.id)
        assert len(track) >= 3
        assert max(s.alt_rel_m for s in track) >= 9
        assert all(0 <= s.battery_pct <= 100 for s in track)
        texts = await store.list_status_texts("flyer", limit=200)
        in_flight = [t.text for t in texts if t.flight_id == flight.id]
        assert "Disarming motors" in in_flight, texts  # received during the flight, stored with it
        assert any("Arming motors" in t.text for t in texts)


async def test_a_takeoff_behind_a_stale_armed_cache_arms_for_real(store, registries, monkeypatch) -> None:
    """ "armed" comes with the 1 Hz heartbeat, so the cache can say armed a beat after the autopilot
    disarmed on the ground (a landing, DISARM_DELAY). The takeoff that trusted it is refused by the
    autopilot; the gateway then arms for real and takes off, instead of failing the call."""
    async with one_ready_drone(store, registries, "stale") as (sim, v):
        assert (await sim.control.state(0))["armed"] is False
        real_fresh = v.telemetry.fresh
        asked: list[str] = []

        def armed_a_beat_ago(name: str, max_age_s: float | None = None):
            if name == "armed" and "armed" not in asked:
                asked.append(name)
                return True  # the cached heartbeat from before the disarm
            return real_fresh(name, max_age_s)

        monkeypatch.setattr(v.telemetry, "fresh", armed_a_beat_ago)
        await v.takeoff(5)
        assert asked == ["armed"]
        await _wait_alt(v, 4.5)
        assert (await sim.control.state(0))["armed"] is True


async def test_a_takeoff_whose_ack_was_lost_counts_if_the_drone_flies(store, registries, monkeypatch) -> None:
    """MAVSDK gives up on a COMMAND_ACK after its retries ("Timeout"); a starved PX4 SIH ran the takeoff
    and its ACKs came too late. A drone on the ground before the call and in the air after it took off:
    the takeoff is accepted. One still on the ground after the same timeout did not: it is refused."""
    async with one_ready_drone(store, registries, "unacked") as (_sim, v):
        real_call = v.link.call
        lose_ack_after_running = True

        async def ack_lost(what: str, aw, timeout_s: float = 10.0):  # type: ignore[no-untyped-def]
            if what != "takeoff":
                return await real_call(what, aw, timeout_s)
            if lose_ack_after_running:
                await real_call(what, aw, timeout_s)
                await wait_until(lambda: v.on_ground() is False, WAIT_S, "in the air")
            else:
                aw.close()  # never sent
            raise CommandFailed("takeoff on drone 'unacked' failed: Timeout (TIMEOUT)", result="TIMEOUT")

        monkeypatch.setattr(v.link, "call", ack_lost)
        await v.takeoff(5)
        await _wait_alt(v, 4.5)
        await v.land()
        await wait_until(lambda: v.telemetry.fresh("armed") is False, WAIT_S, "landed and disarmed")
        await wait_until(lambda: v.on_ground() is True, WAIT_S, "on the ground")  # its in-air state may lag
        lose_ack_after_running = False
        with pytest.raises(CommandFailed, match=r"Timeout \(TIMEOUT\)"):
            await v.takeoff(5)


async def test_a_land_or_return_whose_ack_was_lost_counts_once_the_mode_shows_it(
    store, registries, monkeypatch
) -> None:
    """As the takeoff above: a land or a return MAVSDK gave up on counts as run once the autopilot's own
    mode is one the dialect says that command flies in (a stop must not report failed while the drone
    lands); one the autopilot never ran is still the timeout it was."""
    async with one_ready_drone(store, registries, "unacked") as (_sim, v):
        real_call = v.link.call
        run_it = False

        async def ack_lost(what: str, aw, timeout_s: float = 10.0):  # type: ignore[no-untyped-def]
            if what not in ("land", "return to launch"):
                return await real_call(what, aw, timeout_s)
            if run_it:
                await real_call(what, aw, timeout_s)
            else:
                aw.close()  # never sent
            raise CommandFailed(f"{what} on drone 'unacked' failed: Timeout (TIMEOUT)", result="TIMEOUT")

        monkeypatch.setattr(v.link, "call", ack_lost)
        dialect = v.require_dialect()
        await v.takeoff(3)
        await _wait_alt(v, 2.5)
        with pytest.raises(CommandFailed, match=r"Timeout \(TIMEOUT\)"):
            await v.return_to_launch()
        with pytest.raises(CommandFailed, match=r"Timeout \(TIMEOUT\)"):
            await v.land()
        run_it = True
        await v.return_to_launch()
        assert v.telemetry.fresh("flight_mode") in dialect.commanded_modes("return_to_launch")
        await v.land()
        assert v.telemetry.fresh("flight_mode") in dialect.commanded_modes("land")
        await wait_until(lambda: v.telemetry.fresh("armed") is False, WAIT_S, "landed and disarmed")


async def test_mission_round_trip_run_and_parameters(store, registries) -> None:
    async with one_ready_drone(store, registries, "surveyor") as (sim, v):
        home = v.telemetry.home.value
        p1 = geo.offset_position(home.lat_deg, home.lon_deg, 40.0, 0.0)
        p2 = geo.offset_position(home.lat_deg, home.lon_deg, 40.0, 40.0)
        items = [
            MissionItem(kind="takeoff", alt_rel_m=10),
            MissionItem(lat=p1[0], lon=p1[1], alt_rel_m=15),
            MissionItem(lat=p2[0], lon=p2[1], alt_rel_m=15, speed_mps=8),
            MissionItem(kind="land"),
        ]
        assert await v.upload_mission(items) == 4
        back = await v.download_mission()
        assert [i.kind for i in back] == ["takeoff", "waypoint", "waypoint", "land"]
        assert back[1].lat == pytest.approx(p1[0], abs=1e-6) and back[1].alt_rel_m == pytest.approx(15)
        assert back[2].speed_mps == pytest.approx(8)
        # on the wire, seq 0 is the vehicle's home, and user item 1 is wire item 1
        wire = await v.system.mission_raw.download_mission()
        assert wire[0].seq == 0 and wire[0].x == round(home.lat_deg * 1e7)
        assert wire[1].command == 22 and wire[2].command == 16
        with pytest.raises(InvalidArgument, match=r"1\.\.4"):
            await v.set_current_mission_item(5)

        await v.start_mission()  # on the ground: arm in GUIDED + MISSION_START
        await wait_until(
            lambda: (mp := v.telemetry.fresh("mission_progress")) is not None and mp.current >= 2,
            what="mission progress",
        )
        assert v.telemetry.fresh("mission_progress").total == 4
        await wait_until(lambda: v.telemetry.fresh("armed") is False, what="landed at the end of the mission")
        # the land item is "reached" once landed, a moment after the disarm
        await wait_until(lambda: v.telemetry.mission_progress.value.finished, what="mission finished")
        assert v.telemetry.mission_progress.value.current == 4
        assert await v.is_mission_finished()

        # parameters: typed reads and writes, the 4.7 rename, a clear error for unknown names
        value, kind = await v.get_param("WPNAV_SPEED")
        assert kind == "float" and value > 0
        assert await v.set_param("WPNAV_SPEED", 750) == (750.0, "float")
        assert (await v.get_param("WPNAV_SPEED"))[0] == pytest.approx(750)
        sysid, kind = await v.get_param("SYSID_THISMAV")  # renamed MAV_SYSID in 4.7: found anyway
        assert (sysid, kind) == (sim.sysids[0], "int")
        with pytest.raises(InvalidArgument, match="integer"):
            await v.set_param("SYSID_THISMAV", 1.5)
        with pytest.raises(CommandFailed, match="unknown parameter 'NOPE_PARAM'"):
            await v.get_param("NOPE_PARAM")
        params = await v.list_params()
        assert len(params) > 100 and params["WPNAV_SPEED"] == pytest.approx(750)
        await v.clear_mission()
        assert await v.download_mission() == []


async def test_a_mission_the_autopilot_refuses_on_upload_is_refused_in_its_words_and_never_armed_for(
    db_url: str,
) -> None:
    """ArduPilot answers a mission longer than its storage with MISSION_ACK NO_SPACE and "Only N items
    are supported", and keeps the mission it had. The caller hears that refusal; initiate_mission then
    arms nothing (not even for the mission still on board) until a mission is uploaded that fits."""
    agent = Caller(via="mcp", principal="agent-1", session="s1")
    async with sim_process(1, speedup=SPEEDUP) as sim, Gateway(fast_settings(database_url=db_url)) as gateway:
        vehicle = await gateway.require_registry().add(VehicleSpec(id="d1", url=sim.urls[0]))
        await vehicle.wait_for_state(READY, within_s=WAIT_S)
        commander = gateway.commander
        home = vehicle.telemetry.home.value
        p1 = geo.offset_position(home.lat_deg, home.lon_deg, 30.0, 0.0)
        land = MissionItem(kind="land", lat=home.lat_deg, lon=home.lon_deg)
        fits = [MissionItem(kind="takeoff", alt_rel_m=5), land]
        too_long = [
            MissionItem(kind="takeoff", alt_rel_m=5),
            MissionItem(lat=p1[0], lon=p1[1], alt_rel_m=10),
            land,
        ]
        assert (await commander.upload_mission(agent, "d1", fits)).facts == {"items": 2}
        await sim.control.set_mission_capacity(0, 3)  # home + 2 items

        with pytest.raises(CommandFailed) as refused:
            await commander.upload_mission(agent, "d1", too_long)
        assert "'Only 3 items are supported'" in refused.value.message, refused.value.message
        assert refused.value.details["result"] == "TOO_MANY_MISSION_ITEMS", refused.value.details
        assert len(await vehicle.download_mission()) == 2  # the autopilot kept the mission it had

        with pytest.raises(CommandFailed, match="upload a corrected mission first") as not_started:
            await commander.start_mission(agent, "d1", label="initiate_mission")
        assert "Only 3 items are supported" in not_started.value.message, not_started.value.message
        with pytest.raises(CommandFailed, match="Only 3 items are supported"):
            await commander.start_mission(agent, "d1", too_long, label="initiate_mission")
        state = await sim.control.state(0)
        assert state["armed"] is False and state["mode"] != "AUTO", state
        texts = [text for _t, _sev, text in await sim.control.status_texts(0)]
        assert not any("Arming motors" in t for t in texts), texts

        # a mission that fits clears the refusal: it is started and flown
        await commander.upload_mission(agent, "d1", fits)
        started = await commander.start_mission(agent, "d1", label="initiate_mission")
        assert (await commander.wait(started.operation_id, WAIT_S)).status == "succeeded"
    assert mavsdk_servers_of() == []


async def test_vehicle_reboot_rates_are_requested_again(store, registries) -> None:
    """A rebooted autopilot forgets every stream rate and mavsdk_server does not ask again: the
    gateway notices (heartbeats back, streams silent) and requests them itself."""
    from gateway.util.ports import free_tcp_port

    port = free_tcp_port()
    same_port = ["--tcp-base-port", str(port)]  # argparse keeps the last value given
    reg = Registry(fast_settings(), store)
    registries.append(reg)
    await reg.start()
    async with sim_process(1, speedup=SPEEDUP, extra_args=same_port) as sim:
        v = await reg.add(VehicleSpec(id="phoenix", url=sim.urls[0]))
        assert sim.urls[0].endswith(f":{port}")
        await v.wait_for_state(READY, within_s=WAIT_S)
        sidecar_pid = v.status()["sidecar"]["pid"]
    # the simulator process is gone (the "vehicle" is off); a new one boots on the same port
    await v.wait_for_state(ConnectionState.LINK_LOST, within_s=WAIT_S)
    async with sim_process(1, speedup=SPEEDUP, extra_args=same_port):
        await v.wait_for_state(READY, within_s=WAIT_S)
        await wait_until(lambda: v.telemetry.fresh("position", max_age_s=0.5) is not None, what="position")
        assert v.status()["sidecar"]["pid"] == sidecar_pid  # same sidecar: mavsdk_server reconnected
