"""Dialects are found in a registry keyed by the autopilot the HEARTBEAT names; an autopilot without one
is read (landed state, MAVSDK's mode names) but every action of the vehicle refuses it in one line
before anything is sent, and the directory refuses to hand it out to be flown."""

from __future__ import annotations

import inspect
from typing import Any

import pytest

from gateway.config import Settings
from gateway.errors import NoDialect
from gateway.fleet import dialects
from gateway.fleet.dialects import ARDUPILOT, PX4_DIALECT, dialect_for, dialect_named, flying_dialect
from gateway.fleet.dialects.ardupilot import ArduPilot
from gateway.fleet.vehicles.protocols import VehicleActions
from gateway.fleet.vehicles.vehicle import Vehicle
from gateway.link.rawlink import MAV_AUTOPILOT_ARDUPILOTMEGA, MAV_AUTOPILOT_PX4
from gateway.link.telemetry import TelemetryCache
from gateway.registry.spec import VehicleSpec

MAV_AUTOPILOT_GENERIC = 0

#: an argument for every parameter without a default, by name
SAMPLE: dict[str, Any] = {
    "alt_m": 30.0, "alt_rel_m": 10.0, "lat": 47.4, "lon": 8.5, "heading_deg": 90.0, "mps": 5.0,
    "name": "RTL", "items": ["not validated before the refusal"], "user_index": 1, "value": 1.0,
}  # fmt: skip


def test_the_registry_finds_each_dialect_by_the_autopilot_its_heartbeat_names() -> None:
    assert dialect_for(MAV_AUTOPILOT_ARDUPILOTMEGA) is ARDUPILOT
    assert dialect_for(MAV_AUTOPILOT_PX4) is PX4_DIALECT
    assert dialect_for(None) is ARDUPILOT  # no HEARTBEAT yet
    assert dialect_named("px4") is PX4_DIALECT and dialect_named("ardupilot") is ARDUPILOT
    unknown = dialect_for(MAV_AUTOPILOT_GENERIC)
    assert unknown is dialect_named("mav_autopilot_0") and unknown not in dialects.dialects()
    assert unknown.name == "MAV_AUTOPILOT_GENERIC (0)" and unknown.mode_names() == []
    assert unknown.resolve_mode("GUIDED") is None and unknown.commanded_modes("goto") == frozenset()
    cache = TelemetryCache()
    cache.put("in_air", True)
    assert unknown.on_ground(cache) is False  # read: MAVSDK's in_air


def test_a_registered_dialect_flies_its_autopilot() -> None:
    copter_like = ArduPilot()
    dialects.register(99, copter_like)
    try:
        assert dialect_for(99) is copter_like and flying_dialect(99, "d1") is copter_like
    finally:
        dialects._REGISTRY.pop(99)
    with pytest.raises(NoDialect, match=r"autopilot MAV_AUTOPILOT 99, which this gateway has no dialect"):
        flying_dialect(99, "d1")


async def test_every_action_refuses_an_autopilot_without_a_dialect_before_sending() -> None:
    """The vehicle has no link (never connected): an action that got past the refusal would fail on the
    missing session instead, so each refusal here was given before anything was sent."""
    vehicle = Vehicle(VehicleSpec(id="g1", url="udpin://127.0.0.1:14540"), Settings(_env_file=None))
    vehicle.link.facts.autopilot = MAV_AUTOPILOT_GENERIC
    assert vehicle.on_ground() is None and vehicle.mode_names() == []  # reads answer
    actions = [name for name in dir(VehicleActions) if not name.startswith("_")]
    assert len(actions) == 21, actions
    for name in actions:
        method = getattr(vehicle, name)
        params = inspect.signature(method).parameters.values()
        args = [SAMPLE[p.name] for p in params if p.default is inspect.Parameter.empty]
        with pytest.raises(NoDialect) as refused:
            await method(*args)
        assert refused.value.message == (
            "drone 'g1' runs autopilot MAV_AUTOPILOT_GENERIC (0), which this gateway has no dialect for, so "
            "it sends it no command (its telemetry and status are still shown): fly it from its own ground "
            "station, or connect a drone running ArduPilot or PX4"
        ), name
    with pytest.raises(NoDialect):
        vehicle.return_altitude_param()  # asked only before writing it
