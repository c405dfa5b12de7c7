"""In-process units of the flight model, stepped in simulated time (no sockets, no wall clock).

Durations here are *simulated* seconds compared with the ArduCopter SITL reference (README section 8),
not wall-clock measurements.
"""

from __future__ import annotations

import itertools
import time

from gateway.sim.modes import Mode
from gateway.sim.vehicle import SimVehicle

HOME = (-35.363261, 149.165230, 584.0, 353.0)


def _vehicle(**kw) -> SimVehicle:
    return SimVehicle(0, 1, HOME, tcp_port=0, seed=1, **kw)


def _run(v: SimVehicle, predicate, limit_s: float = 300.0) -> float:
    start = v.t
    while not predicate():
        assert v.t - start < limit_s, "condition not reached in simulated time"
        v._step(0.05)
    return v.t - start


def _flying_guided(v: SimVehicle, alt: float = 10.0) -> None:
    _run(v, lambda: v.position_ok)
    assert v.flight.set_mode(Mode.GUIDED)[0]
    assert v.flight.arm(force=False) == (True, [])
    assert v.flight.takeoff(alt)
    _run(v, lambda: abs(v.rel_alt() - alt) < 0.01 and not v.flight.is_taking_off())


def test_boot_timeline_matches_reference() -> None:
    v = _vehicle()
    _run(v, lambda: v.boot_state.prearm_failure(Mode.STABILIZE) is None)
    assert 22.0 <= v.t <= 23.5  # reference: 22.6 s
    assert v.boot_state.prearm_failure(Mode.GUIDED) == "Need Position Estimate"
    _run(v, lambda: v.boot_state.prearm_failure(Mode.GUIDED) is None)
    assert 41.0 <= v.t <= 44.5  # reference: 41.6-44 s
    texts = [text for _t, _s, text in v.status_texts]
    assert (
        texts.index("ArduPilot Ready")
        < texts.index("EKF3 IMU0 origin set")
        < texts.index("EKF3 IMU0 is using GPS")
    )


def test_takeoff_reposition_and_land_timings_like_sitl() -> None:
    v = _vehicle()
    _run(v, lambda: v.position_ok)
    v.flight.set_mode(Mode.GUIDED)
    v.flight.arm(force=False)
    v.flight.takeoff(10.0)
    liftoff = _run(v, lambda: v.rel_alt() > 0.2)
    assert 3.6 <= liftoff <= 4.6  # reference 4.1 s
    assert 7.5 <= liftoff + _run(v, lambda: v.rel_alt() > 9.5) <= 11.0  # reference 9.5-9.7 s
    _run(v, lambda: not v.flight.is_taking_off())
    north0 = v.body.north
    assert v.flight.guided_goto(north0 + 100.0, v.body.east, v.body.up)
    leg = _run(v, lambda: abs(v.body.north - north0 - 100.0) < 0.5 and v.body.ground_speed < 0.3)
    assert 12.0 <= leg <= 17.0  # reference 14.0-15.2 s at WPNAV_SPEED 10 m/s
    assert max(abs(v.body.north - north0 - 100.0), 0) < 0.5
    v.flight.set_mode(Mode.LAND)
    landing = _run(v, lambda: not v.armed)
    assert 20.0 <= landing <= 28.0  # reference 23.3-27.3 s
    assert v.landed and v.rel_alt() == 0.0


def test_brake_stops_ahead_without_turning_back() -> None:
    v = _vehicle()
    _flying_guided(v)
    v.flight.guided_goto(v.body.north + 500.0, v.body.east, v.body.up)
    _run(v, lambda: v.body.ground_speed > 9.9)
    start = v.body.north
    assert v.flight.set_mode(Mode.BRAKE)[0]
    positions = []
    _run(v, lambda: positions.append(v.body.north) or (v.body.ground_speed < 0.01 and len(positions) > 10))
    assert all(b >= a - 0.01 for a, b in itertools.pairwise(positions))  # never turns back (1 cm snap)
    assert 15.0 <= v.body.north - start <= 25.0  # v^2 / 2a = 20 m at 10 m/s and 2.5 m/s^2


def test_wpnav_speed_and_change_speed_are_honoured() -> None:
    v = _vehicle()
    _flying_guided(v)
    v.params.set("WPNAV_SPEED", 500)
    v.flight.guided_goto(v.body.north + 200.0, v.body.east, v.body.up)
    top = max(_speeds(v, 40.0))
    assert 4.9 <= top <= 5.01
    assert v.flight.change_speed(1, 8.0)
    v.flight.guided_goto(v.body.north + 300.0, v.body.east, v.body.up)
    assert 7.9 <= max(_speeds(v, 40.0)) <= 8.01


def _speeds(v: SimVehicle, seconds: float) -> list[float]:
    out = []
    end = v.t + seconds
    while v.t < end:
        v._step(0.05)
        out.append(v.body.ground_speed)
    return out


def test_auto_disarm_and_cpu_starvation_catch_up() -> None:
    v = _vehicle()
    _run(v, lambda: v.position_ok)
    v.flight.set_mode(Mode.GUIDED)
    v.flight.arm(force=False)
    disarm = _run(v, lambda: not v.armed)
    assert 9.9 <= disarm <= 10.2  # DISARM_DELAY 10 s

    # a tick after a long stall (CPU starvation) integrates the whole measured time in small steps
    late = _vehicle(speedup=20.0)
    late._wall_last = time.monotonic() - 2.5  # 2.5 s wall at speed-up 20: 50 simulated seconds
    late.tick()
    assert 49.9 <= late.t <= 51.0
    assert late.position_ok and late.home is not None  # every boot milestone on the way was run


def test_armed_in_stabilize_before_ekf_uses_gps_cannot_fly_guided() -> None:
    """Reference section 7: armable in STABILIZE at 22.6 s, GUIDED refused until the EKF uses GPS."""
    v = _vehicle()
    _run(v, lambda: v.boot_state.prearm_failure() is None)  # current mode: STABILIZE
    assert v.t < v.timeline.ekf_gps
    assert v.flight.arm(force=False) == (True, [])
    assert v.flight.set_mode(Mode.GUIDED) == (False, "requires position")
    assert v.status_texts[-1][2] == "Mode change to GUIDED failed: requires position"
    assert not v.flight.takeoff(10.0)  # still STABILIZE
    assert 9.9 <= _run(v, lambda: not v.armed) <= 10.2  # DISARM_DELAY


def test_auto_mission_with_rtl_item_comes_home_and_lands() -> None:
    from pymavlink.dialects.v20 import ardupilotmega as mav

    from gateway.sim.mission import Item

    v = _vehicle()
    _flying_guided(v, 10.0)
    lat, lon = v.frame.to_latlon(v.body.north + 60.0, v.body.east)
    v.mission.replace(
        [
            Item(mav.MAV_CMD_NAV_WAYPOINT),
            Item(mav.MAV_CMD_NAV_WAYPOINT, x=round(lat * 1e7), y=round(lon * 1e7), z=10.0),
            Item(mav.MAV_CMD_NAV_RETURN_TO_LAUNCH),
        ]
    )
    assert v.flight.set_mode(Mode.AUTO)[0]
    _run(v, lambda: v.auto.current == 2)
    _run(v, lambda: not v.armed)
    assert v.mode == Mode.AUTO and v.landed and v.auto.complete
    assert abs(v.body.north) < 0.5 and abs(v.body.east) < 0.5  # home
    texts = [t for _t, _s, t in v.status_texts]
    assert "Reached command #1" in texts and "Mission: 2 RTL" in texts


def test_remaining_battery_is_counted_against_batt_capacity_like_ardupilot() -> None:
    v, big = _vehicle(), _vehicle()
    big.params.set("BATT_CAPACITY", 6600.0)
    for drone in (v, big):
        _flying_guided(drone)
        drone.set_battery(100.0)
        end = drone.t + 60.0
        _run(drone, lambda d=drone, e=end: d.t >= e)  # one minute of hover
    used, used_big = 100.0 - v.battery.remaining_pct, 100.0 - big.battery.remaining_pct
    assert 13.0 < used < 15.0  # 27.8 A for 60 s of a 3300 mAh pack: 463 mAh, 14.0 %
    assert abs(used_big - used / 2) < 0.3


def test_streams_come_at_their_intervals_and_a_change_of_rate_counts_at_once() -> None:
    """A stream table sends each message when due (a message that fell behind once), sends nothing
    between (the vehicle asks at every physics step), and a rate set or cleared between two dues counts
    from the next step: a new message at once, a disabled group not again."""
    from gateway.sim.streams import StreamTable

    table = StreamTable()
    assert table.due(0.0) == []
    table.set_interval(33, 1e6)  # GLOBAL_POSITION_INT every second
    assert table.due(0.0) == [33]
    assert [table.due(t / 25) for t in range(1, 25)] == [[]] * 24
    assert table.due(1.0) == [33]
    assert table.due(3.5) == [33] and table.due(3.6) == [] and table.due(4.5) == [33]  # behind: once
    table.set_group(2, 0.2)  # EXT_STAT every 5 s: its messages at once, then every 5 s
    assert set(table.due(4.6)) >= {1, 42}
    assert 1 not in table.due(5.5) and 1 not in table.due(9.5) and 1 in table.due(9.6)
    table.set_group(2, 0.0)
    assert all(1 not in table.due(t) for t in (14.6, 20.0, 30.0))
    table.set_interval(33, -1)  # disabled
    assert table.due(40.0) == [] and table.due(100.0) == []
    table.clear()
    table.set_interval(30, 2e5)  # ATTITUDE at 5 Hz
    assert table.due(100.0) == [30] and table.due(100.1) == [] and table.due(100.2) == [30]
