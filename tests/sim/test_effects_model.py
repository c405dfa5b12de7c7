"""What the simulator flies for the settings whose effect the safety policy judges, as ArduCopter flies
it: RTL_CLIMB_MIN added to the altitude RTL starts from, CIRCLE round a centre one radius ahead that
sinks without RC throttle, home moved at every arming. Stepped in simulated time (no sockets)."""

from __future__ import annotations

import math

from gateway.sim.modes import Mode
from gateway.sim.vehicle import SimVehicle

HOME = (-35.363261, 149.165230, 584.0, 353.0)


def _vehicle() -> SimVehicle:
    return SimVehicle(0, 1, HOME, tcp_port=0, seed=1)


def _run(v: SimVehicle, predicate, limit_s: float = 400.0) -> float:
    start = v.t
    while not predicate():
        assert v.t - start < limit_s, "condition not reached in simulated time"
        v._step(0.05)
    return v.t - start


def _flying_guided(v: SimVehicle, alt: float) -> None:
    _run(v, lambda: v.position_ok)
    assert v.flight.set_mode(Mode.GUIDED)[0]
    assert v.flight.arm(force=False) == (True, [])
    assert v.flight.takeoff(alt)
    _run(v, lambda: abs(v.rel_alt() - alt) < 0.05 and not v.flight.is_taking_off())


def test_rtl_climbs_rtl_climb_min_above_the_altitude_it_starts_from() -> None:
    v = _vehicle()
    v.params.set("RTL_CLIMB_MIN", 1000.0)  # 10 m; RTL_ALT stays 15 m
    _flying_guided(v, 20.0)
    assert v.flight.guided_goto(v.body.north + 60.0, v.body.east, v.body.up)
    _run(v, lambda: v.body.north > 59.0 and v.body.ground_speed < 0.3)
    assert v.flight.set_mode(Mode.RTL)[0]
    highest = 0.0

    def home_reached() -> bool:
        nonlocal highest
        highest = max(highest, v.rel_alt())
        return v.flight.rtl_phase in ("loiter", "final")

    _run(v, home_reached)
    assert 29.5 < highest < 30.5, highest  # 20 m + 10 m, above RTL_ALT 15 m


def test_rtl_without_climb_min_returns_at_the_altitude_flown_above_rtl_alt() -> None:
    v = _vehicle()
    _flying_guided(v, 20.0)
    assert v.flight.set_mode(Mode.RTL)[0]
    highest = 0.0

    def home_reached() -> bool:
        nonlocal highest
        highest = max(highest, v.rel_alt())
        return v.flight.rtl_phase in ("loiter", "final")

    _run(v, home_reached)
    assert highest < 20.3, highest


def test_circle_centre_lies_one_radius_ahead_and_it_sinks_without_rc_throttle() -> None:
    v = _vehicle()
    v.params.set("CIRCLE_RADIUS", 3000.0)  # 30 m
    _flying_guided(v, 30.0)
    assert v.flight.guided_goto(v.body.north + 50.0, v.body.east, v.body.up)  # heading north
    _run(v, lambda: v.body.north > 49.0 and v.body.ground_speed < 0.3)
    start_n, start_e, yaw = v.body.north, v.body.east, v.body.yaw
    assert v.flight.set_mode(Mode.CIRCLE)[0]
    circle = v.flight.circle
    assert circle is not None
    expected = (start_n + 30 * math.cos(math.radians(yaw)), start_e + 30 * math.sin(math.radians(yaw)))
    assert math.hypot(circle.centre_n - expected[0], circle.centre_e - expected[1]) < 1.0
    farthest = 0.0

    def landed() -> bool:
        nonlocal farthest
        farthest = max(farthest, math.hypot(v.body.north - start_n, v.body.east - start_e))
        return v.landed

    _run(v, landed)
    assert farthest > 55.0, farthest  # the far side: two radii from where CIRCLE began
    assert v.armed  # sank to the ground in CIRCLE and stays armed there, as on SITL


def test_arming_moves_home_to_where_the_vehicle_stands() -> None:
    v = _vehicle()
    _flying_guided(v, 10.0)
    first_home = v.home
    assert v.flight.guided_goto(v.body.north + 200.0, v.body.east, v.body.up)
    _run(v, lambda: v.body.north > 199.0 and v.body.ground_speed < 0.3)
    assert v.flight.set_mode(Mode.LAND)[0]
    _run(v, lambda: not v.armed)
    assert v.flight.set_mode(Mode.GUIDED)[0]
    assert v.flight.arm(force=False) == (True, [])
    assert v.home is not None and first_home is not None
    moved = v.frame.to_ne(v.home[0], v.home[1])
    first = v.frame.to_ne(first_home[0], first_home[1])
    assert math.hypot(moved[0] - first[0], moved[1] - first[1]) > 195.0
