"""Pure logic of the vehicle layer: mission encoding, parameter aliases, the telemetry cache."""

from __future__ import annotations

import asyncio
import time
import typing
from types import SimpleNamespace

import pytest
from pydantic import ValidationError

from gateway.errors import InvalidArgument
from gateway.fleet.dialects import ARDUPILOT, PX4_DIALECT
from gateway.fleet.dialects.base import mission_progress
from gateway.fleet.dialects.modes import require_mode
from gateway.fleet.missions import mission
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.operations.trackers import LandingTracker
from gateway.fleet.vehicles.params import param_aliases
from gateway.link import telemetry
from gateway.link.telemetry import (
    STREAM_TYPES,
    VALUE_TYPES,
    BatteryValue,
    MissionProgressValue,
    PositionValue,
    Sample,
    TelemetryCache,
)
from tests.fakes import FakeVehicle

HOME = (47.397742, 8.545594, 488.0)


def test_mission_encoding_hides_home_and_keeps_user_numbers() -> None:
    items = [
        MissionItem(kind="takeoff", alt_rel_m=10),
        MissionItem(lat=47.3980, lon=8.5460, alt_rel_m=20, hold_s=2),
        MissionItem(lat=47.3990, lon=8.5470, alt_rel_m=25, speed_mps=5),
        MissionItem(kind="rtl"),
    ]
    plan = mission.encode(items, HOME)
    assert plan.items[0].seq == 0 and plan.items[0].frame == mission.MAV_FRAME_GLOBAL
    assert plan.items[0].x == round(HOME[0] * 1e7)
    # user item 1 is wire item 1; the speed change is a companion item before user item 3
    assert plan.user_to_wire == [1, 2, 4, 5]
    assert plan.items[3].command == mission.MAV_CMD_DO_CHANGE_SPEED and plan.items[3].param2 == 5
    assert plan.items[2].param1 == 2 and plan.items[2].z == 20
    assert [plan.user_index(s) for s in (0, 1, 2, 3, 4, 5)] == [1, 1, 2, 3, 3, 4]
    assert plan.wire_seq(3) == 4
    wire = [SimpleNamespace(**vars(w)) for w in plan.items]
    back, plan2 = mission.decode(wire)
    assert [i.kind for i in back] == ["takeoff", "waypoint", "waypoint", "rtl"]
    assert back[2].speed_mps == 5 and back[1].speed_mps is None
    assert back[1].lat == pytest.approx(47.3980) and back[1].hold_s == 2
    assert plan2.user_to_wire == plan.user_to_wire


def test_px4_mission_has_no_home_slot() -> None:
    """PX4 flies seq 0 like any item: a home placeholder there flew the drone to home at ground level."""
    items = [
        MissionItem(lat=47.3980, lon=8.5460, alt_rel_m=20),
        MissionItem(lat=47.3990, lon=8.5470, alt_rel_m=25, speed_mps=5),
        MissionItem(kind="land"),
    ]
    plan = mission.encode(items, HOME, home_slot=False)
    assert [w.seq for w in plan.items] == [0, 1, 2, 3]
    assert plan.items[0].command == mission.MAV_CMD_NAV_WAYPOINT and plan.items[0].z == 20
    assert plan.items[0].frame == mission.MAV_FRAME_GLOBAL_RELATIVE_ALT
    assert all(w.x != round(HOME[0] * 1e7) for w in plan.items)  # nothing at home
    assert min(w.z for w in plan.items if w.command == mission.MAV_CMD_NAV_WAYPOINT) == 20
    assert plan.user_to_wire == [0, 2, 3]
    assert [plan.user_index(s) for s in (0, 1, 2, 3)] == [1, 2, 2, 3]
    wire = [SimpleNamespace(**vars(w)) for w in plan.items]
    back, plan2 = mission.decode(wire, home_slot=False)
    assert [(i.kind, i.alt_rel_m) for i in back] == [("waypoint", 20), ("waypoint", 25), ("land", 0)]
    assert back[1].speed_mps == 5
    assert plan2.user_to_wire == plan.user_to_wire


@pytest.mark.parametrize(
    ("name", "px4", "native", "custom_mode"),
    [
        ("hold", False, "GUIDED", 4),
        ("RTL", False, "RTL", 6),
        ("mission", False, "AUTO", 3),
        ("LOITER", False, "GUIDED", 4),  # a hold: ArduCopter's LOITER sinks without RC throttle
        ("POSITION", False, "GUIDED", 4),
        ("brake", False, "BRAKE", 17),
        ("HOLD", True, "AUTO.LOITER", (4 << 16) | (3 << 24)),
        ("RTL", True, "AUTO.RTL", (4 << 16) | (5 << 24)),
        ("LAND", True, "AUTO.LAND", (4 << 16) | (6 << 24)),
        ("MISSION", True, "AUTO.MISSION", (4 << 16) | (4 << 24)),
        ("takeoff", True, "AUTO.TAKEOFF", (4 << 16) | (2 << 24)),
        ("POSITION", True, "AUTO.LOITER", (4 << 16) | (3 << 24)),
        ("loiter", True, "AUTO.LOITER", (4 << 16) | (3 << 24)),
        ("AUTO", True, "AUTO.MISSION", (4 << 16) | (4 << 24)),
        ("auto.rtl", True, "AUTO.RTL", (4 << 16) | (5 << 24)),
    ],
)
def test_common_mode_names_map_per_autopilot(name: str, px4: bool, native: str, custom_mode: int) -> None:
    choice = require_mode(name, PX4_DIALECT if px4 else ARDUPILOT, "alpha")
    assert (choice.native, choice.custom_mode) == (native, custom_mode)


@pytest.mark.parametrize(
    ("name", "px4", "message"),
    [
        ("TAKEOFF", False, "mode 'TAKEOFF' is not a mode of drone 'alpha' (ArduCopter); its modes: HOLD,"),
        ("SMART_RTL", True, "(PX4); its modes: HOLD, GUIDED, RTL, LAND, MISSION, TAKEOFF, AUTO.LOITER,"),
        ("POSCTL", True, "not a mode of drone 'alpha' (PX4)"),  # needs a pilot's sticks
        ("FLIP", False, "its modes: HOLD, GUIDED, RTL, LAND, MISSION, BRAKE, SMART_RTL, CIRCLE, STABILIZE"),
        ("GUIDED_NOGPS", True, "not a mode of drone 'alpha' (PX4)"),
        ("", False, "mode must be a flight mode name; got ''"),
    ],
)
def test_a_mode_the_drone_lacks_is_refused_with_its_modes(name: str, px4: bool, message: str) -> None:
    with pytest.raises(InvalidArgument) as caught:
        require_mode(name, PX4_DIALECT if px4 else ARDUPILOT, "alpha")
    assert message in caught.value.message


@pytest.mark.parametrize(
    "bad, message",
    [
        ({"kind": "waypoint", "lat": 91, "lon": 0, "alt_rel_m": 10}, "latitude"),
        ({"kind": "waypoint", "lat": 0, "lon": 0, "alt_rel_m": 10}, "needs a position"),
        ({"kind": "takeoff", "alt_rel_m": 0}, "alt_rel_m > 0"),
        ({"kind": "waypoint", "lat": float("nan"), "lon": 1, "alt_rel_m": 1}, "finite"),
        ({"kind": "teleport", "lat": 1, "lon": 1}, "kind"),
        ({"lat": 1, "lon": 1, "speed_mps": -1}, "speed_mps"),
    ],
)
def test_mission_item_validation(bad: dict, message: str) -> None:
    with pytest.raises((ValidationError, ValueError), match=message):
        MissionItem.model_validate(bad)


def test_param_aliases_cover_47_renames() -> None:
    assert param_aliases("SYSID_THISMAV") == ["MAV_SYSID"]
    assert param_aliases("MAV_SYSID") == ["SYSID_THISMAV"]
    assert param_aliases("SR0_POSITION") == ["MAV1_POSITION"]
    assert param_aliases("MAV1_POSITION") == ["SR0_POSITION"]
    assert param_aliases("WPNAV_SPEED") == []


def test_streams_asked_for_slower_at_rest_are_stale_after_as_many_more_seconds() -> None:
    """Home, the attitude and heading, the GPS report, the IMU and odometry come every 5 s at rest: a
    sample 10 s old is current there (stale after 5 x 3 s), while the position at 1 Hz is stale after
    3 s; a lost link makes every value stale however young."""
    cache = TelemetryCache(stale_after_s=3.0)
    ten_s_ago = time.monotonic() - 10.0
    cache.home = Sample(PositionValue(47.0, 8.0, 500.0, 0.0), ten_s_ago)
    cache.position = Sample(PositionValue(47.0, 8.0, 500.0, 0.0), ten_s_ago)
    cache.heading_deg = Sample(90.0, ten_s_ago)
    assert cache.stale_limit_s("home") == cache.stale_limit_s("heading_deg") == 15.0
    assert cache.stale_limit_s("position") == cache.stale_limit_s("battery") == 3.0
    assert cache.fresh("home") is not None and cache.fresh("heading_deg") == 90.0
    assert cache.fresh("position") is None
    snap = cache.snapshot()
    assert snap["home"]["stale"] is False and snap["position"]["stale"] is True
    assert not cache.is_stale("home", 14.0) and cache.is_stale("home", 16.0)
    assert cache.is_stale("position", 4.0)
    cache.home = Sample(PositionValue(47.0, 8.0, 500.0, 0.0), time.monotonic() - 16.0)
    assert cache.fresh("home") is None and cache.snapshot()["home"]["stale"] is True
    cache.heading_deg = Sample(90.0, time.monotonic())
    cache.live = False
    assert cache.fresh("heading_deg") is None and cache.is_stale("heading_deg", 0.0)
    # the limits follow the configured link-lost time
    assert TelemetryCache(stale_after_s=10.0).stale_limit_s("home") == 50.0


def test_each_stream_is_stale_after_three_of_its_rest_periods_and_the_safety_reads_stay_at_1_hz() -> None:
    """The rest rates and the stale limits agree: a stream asked for slower than 1 Hz at rest is stale
    only after three of its periods, and what a safety or readiness check reads fresh (position and
    velocity, SYS_STATUS with the battery and health, the landed state, the EKF status) is asked for at
    1 Hz at least, so that one lost message never makes it stale (3 s)."""
    from gateway.link.telemetry_feed import ACTIVE_RATES_HZ, STREAM_RATES_HZ

    fills = {  # the cache streams each rate fills
        "position": ("position", "velocity_ned"),
        "home": ("home",),
        "attitude_euler": ("attitude", "heading_deg"),
        "landed_state": ("landed_state", "in_air"),
        "gps_info": ("gps_info",),
        "battery": ("battery",),
        "health": ("health", "rc_status"),
        "imu": ("imu",),
        "raw_imu": ("imu",),
        "odometry": ("odometry",),
    }
    cache = TelemetryCache(stale_after_s=3.0)
    for rate, streams in fills.items():
        for stream in streams:
            assert cache.stale_limit_s(stream) >= 3.0 / STREAM_RATES_HZ[rate], (rate, stream)
    for rate in ("position", "health", "battery", "landed_state", "ekf_status"):
        assert STREAM_RATES_HZ[rate] >= 1.0, rate
    # armed or in the air, home (moved at arming) and the GPS report come at 1 Hz for the flight log
    assert ACTIVE_RATES_HZ["home"] >= 1.0 and ACTIVE_RATES_HZ["gps_info"] >= 1.0


def test_cache_snapshot_reports_ages_and_staleness() -> None:
    cache = TelemetryCache(stale_after_s=3.0)
    assert cache.snapshot()["position"] is None
    cache.put("position", PositionValue(47.0, 8.0, 500.0, 12.0))
    cache.battery = Sample(BatteryValue(81.0, 15.9), time.monotonic() - 10.0)
    snap = cache.snapshot()
    assert snap["position"]["rel_alt_m"] == 12.0 and snap["position"]["stale"] is False
    assert snap["battery"]["remaining_pct"] == 81.0
    assert snap["battery"]["stale"] is True and snap["battery"]["age_s"] >= 10.0
    assert cache.fresh("battery") is None  # stale values are never presented as current
    assert cache.fresh("position").lat_deg == 47.0
    cache.live = False  # link lost: nothing is current, however young
    assert cache.fresh("position") is None and cache.snapshot()["position"]["stale"] is True
    cache.live = True
    got = []
    cache.on_status_text(got.append)
    cache.add_status_text("warning", "PreArm: Need Position Estimate")
    assert got[0].text == "PreArm: Need Position Estimate"
    assert cache.snapshot()["status_texts"][-1]["severity"] == "warning"
    with pytest.raises(KeyError):
        cache.put("warp_drive", 1)
    assert cache.message_counts == {"position": 1, "status_text": 1}


def test_every_stream_has_a_fresh_overload_typed_by_its_value() -> None:
    """The cache's fields are the one list of streams; ``fresh``'s overloads must name each of them with
    the type of its value (mypy reads the overloads, the cache reads the fields)."""
    returns: dict[str, object] = {}
    for variant in typing.get_overloads(TelemetryCache.fresh):
        hints = typing.get_type_hints(variant, vars(telemetry))
        if typing.get_origin(hints["name"]) is typing.Literal:
            returns.update(dict.fromkeys(typing.get_args(hints["name"]), hints["return"]))
    assert STREAM_TYPES and TelemetryCache.FIELDS == tuple(STREAM_TYPES)
    assert returns == {name: kind | None for name, kind in STREAM_TYPES.items()}
    assert VALUE_TYPES["position"] is PositionValue and "armed" not in VALUE_TYPES


async def test_the_return_altitude_is_written_in_each_autopilots_parameter_and_units() -> None:
    from gateway.config import Settings
    from gateway.errors import CommandFailed
    from gateway.fleet.operations.fleet_steps import set_rtl_altitude_param
    from gateway.fleet.vehicles.vehicle import Vehicle
    from gateway.link.rawlink import MAV_AUTOPILOT_ARDUPILOTMEGA, MAV_AUTOPILOT_PX4
    from gateway.registry.spec import VehicleSpec

    written: list[tuple[str, float]] = []
    known = {"RTL_ALT", "RTL_RETURN_ALT"}

    async def record(name: str, value: float) -> tuple[float, str]:
        if name not in known:
            raise CommandFailed(f"unknown parameter '{name}'", result="UNKNOWN_PARAMETER")
        written.append((name, value))
        return value, "float"

    v = Vehicle(VehicleSpec(id="rtl", url="udpin://127.0.0.1:14540"), Settings(_env_file=None))
    v.set_param = record  # type: ignore[method-assign]
    v.link.facts.autopilot = MAV_AUTOPILOT_ARDUPILOTMEGA
    await set_rtl_altitude_param(v, 22.5)  # ArduPilot before 4.7: centimetres
    known = {"RTL_ALT_M"}
    v = Vehicle(VehicleSpec(id="rtl", url="udpin://127.0.0.1:14540"), Settings(_env_file=None))
    v.set_param = record  # type: ignore[method-assign]
    v.link.facts.autopilot = MAV_AUTOPILOT_ARDUPILOTMEGA
    await set_rtl_altitude_param(v, 22.5)  # 4.7: RTL_ALT_M in metres
    assert v.return_altitude_param() == ("RTL_ALT_M", 1.0)
    await set_rtl_altitude_param(v, 30)  # remembered: the missing name is not asked again
    known = {"RTL_RETURN_ALT"}
    v.link.facts.autopilot = MAV_AUTOPILOT_PX4
    await set_rtl_altitude_param(v, 22.5)
    assert written == [("RTL_ALT", 2250), ("RTL_ALT_M", 22.5), ("RTL_ALT_M", 30), ("RTL_RETURN_ALT", 22.5)]


def test_each_dialect_protects_its_safety_parameters_whatever_the_deny_list_says() -> None:
    from gateway.config import DEFAULT_PARAM_DENY_PATTERNS, Settings
    from gateway.errors import SafetyRefusal
    from gateway.fleet.policy.safety import SafetyPolicy
    from gateway.fleet.policy.vehicle_limits import split_patterns

    for dialect in (ARDUPILOT, PX4_DIALECT):  # the default deny list names every dialect's patterns
        assert set(dialect.protected_params) <= set(split_patterns(DEFAULT_PARAM_DENY_PATTERNS)), dialect.name
    narrowed = SafetyPolicy(Settings(_env_file=None, param_deny_patterns="WPNAV_*"))
    for dialect, name in ((PX4_DIALECT, "COM_ARM_WO_GPS"), (PX4_DIALECT, "GF_ACTION"),
                          (PX4_DIALECT, "NAV_DLL_ACT"), (ARDUPILOT, "ARMING_CHECK")):  # fmt: skip
        with pytest.raises(SafetyRefusal, match=f"parameter {name} matches the protected pattern"):
            narrowed.check_param_write(name, vehicle_id="alpha", protected=dialect.protected_params)
    narrowed.check_param_write(  # not protected, and governed by the speed limit
        "MPC_XY_VEL_MAX", 5, protected=PX4_DIALECT.protected_params, governed=PX4_DIALECT.limit_params
    )
    narrowed.check_param_write("COM_ARM_WO_GPS", via="rest", protected=PX4_DIALECT.protected_params)


def test_px4_is_on_the_ground_by_its_land_detector_not_by_in_air() -> None:
    cache = TelemetryCache()
    cache.put("in_air", False)
    cache.put("landed_state", "TAKING_OFF")
    assert PX4_DIALECT.on_ground(cache) is False and ARDUPILOT.on_ground(cache) is True
    cache.put("landed_state", "ON_GROUND")
    assert PX4_DIALECT.on_ground(cache) is True
    assert PX4_DIALECT.on_ground(TelemetryCache()) is None


async def test_trackers_read_the_landed_state_through_the_dialect_however_old() -> None:
    """Trackers judge staleness themselves: they read the cached landed state (fresh=False), and on PX4
    a landing is over by the land detector, not by MAVSDK's in_air."""
    cache = TelemetryCache(stale_after_s=0.0)  # everything is stale at once
    cache.put("in_air", False)
    cache.put("landed_state", "LANDING")
    assert PX4_DIALECT.on_ground(cache) is None and ARDUPILOT.on_ground(cache) is None
    assert PX4_DIALECT.on_ground(cache, fresh=False) is False
    assert ARDUPILOT.on_ground(cache, fresh=False) is True

    class Px4Fake(FakeVehicle):
        def on_ground(self, fresh: bool = True) -> bool | None:
            return PX4_DIALECT.on_ground(self.telemetry, fresh=fresh)

    drone = Px4Fake("px1")
    drone.set(armed=False, in_air=False, landed_state="LANDING")
    tracker = LandingTracker(kind="land")
    assert not (await tracker.poll(drone)).done
    drone.set(landed_state="ON_GROUND")
    assert (await tracker.poll(drone)).done


def test_mission_progress_is_counted_in_user_items_per_dialect() -> None:
    items = [
        MissionItem(lat=47.398, lon=8.546, alt_rel_m=20),
        MissionItem(lat=47.399, lon=8.547, alt_rel_m=20),
    ]
    ap = ARDUPILOT.encode_mission(items, HOME)
    px = PX4_DIALECT.encode_mission(items, HOME)
    # MISSION_CURRENT on ArduPilot: seq 2 of total 2 (home left out) is the second user item
    assert mission_progress(ARDUPILOT, 2, 2, ap, False, from_mission_current=True) == MissionProgressValue(
        2, 2
    )
    assert mission_progress(ARDUPILOT, 1, 3, ap, False, from_mission_current=False).current == 1
    assert mission_progress(PX4_DIALECT, 0, 2, px, False, from_mission_current=True) == MissionProgressValue(
        1, 2
    )
    assert mission_progress(
        PX4_DIALECT, 1, 2, None, True, from_mission_current=False
    ) == MissionProgressValue(2, 2, True)
    assert PX4_DIALECT.mission_rejection("Mission rejected: takeoff not first waypoint item")
    assert not ARDUPILOT.mission_rejection("Mission rejected: whatever")  # ArduPilot says it in the ACK


async def test_a_booting_autopilots_zero_or_nan_position_is_never_cached() -> None:
    """While ArduCopter boots it streams latitude/longitude 0, 0 (before its EKF origin): that is no
    position, so get_position says "no position yet" instead of 0, 0 marked fresh; a real fix is kept,
    and a later 0, 0 does not replace it (the old one ages and goes stale instead)."""
    import asyncio
    import math
    from types import SimpleNamespace

    from gateway.link.telemetry_feed import TelemetryFeed

    def item(lat: float, lon: float) -> SimpleNamespace:
        return SimpleNamespace(
            latitude_deg=lat, longitude_deg=lon, absolute_altitude_m=584.0, relative_altitude_m=0.0
        )

    fed = asyncio.Event()
    booting = [item(0.0, 0.0), item(math.nan, math.nan), item(0.0, 0.0)]

    async def positions():
        for p in booting:
            yield p
        fed.set()
        await asyncio.Event().wait()  # the stream stays open

    async def silent():
        await asyncio.Event().wait()
        yield None

    class Telemetry:
        def __getattr__(self, name: str):
            return positions if name in ("position", "home") else silent

    cache = TelemetryCache()
    system = SimpleNamespace(telemetry=Telemetry(), mission_raw=SimpleNamespace(mission_progress=silent))
    feed = TelemetryFeed("d1", system, cache)
    feed.start()
    try:
        await asyncio.wait_for(fed.wait(), 10)
        assert cache.position is None and cache.home is None
        booting[:] = [item(-35.36, 149.16), item(0.0, 0.0)]
        fed.clear()
        await feed.stop()
        feed.start()
        await asyncio.wait_for(fed.wait(), 10)
        assert cache.position is not None and (
            cache.position.value.lat_deg,
            cache.position.value.lon_deg,
        ) == (
            -35.36,
            149.16,
        )
    finally:
        await feed.stop()


def test_mavsdk_health_fields_land_in_health_value_by_their_meaning() -> None:
    """Each of MAVSDK's Health flags fills the HealthValue field of the same meaning (the conversion is
    one table in field order)."""
    from dataclasses import fields
    from types import SimpleNamespace

    from gateway.link.telemetry import HealthValue
    from gateway.link.telemetry_feed import HEALTH_FIELDS, _health

    assert len(HEALTH_FIELDS) == len(fields(HealthValue))
    for n, name in enumerate(HEALTH_FIELDS):
        item = SimpleNamespace(**{other: other == name for other in HEALTH_FIELDS})
        value = _health(item)
        ours = fields(HealthValue)[n].name
        assert [f.name for f in fields(HealthValue) if getattr(value, f.name)] == [ours]
        words = ours.removesuffix("_ok").removeprefix("is_").split("_")
        assert all(w[:3] in name for w in words), (name, ours)


async def test_telemetry_rates_follow_the_drone_between_rest_and_active() -> None:
    """At rest the streams are asked for at their rest rates; the first landed state that shows the drone
    in the air (or an armed HEARTBEAT) switches position to 5 Hz for the trackers, and back to 1 Hz once
    it is disarmed on the ground. in_air is taken from the landed state (no stream of its own), and
    MAVSDK's flight mode stream is not subscribed where the link names the modes itself."""
    import asyncio
    import enum

    from gateway.link.telemetry_feed import ACTIVE_RATES_HZ, MESSAGE_IDS, STREAM_RATES_HZ, TelemetryFeed

    class Landed(enum.Enum):
        ON_GROUND = 1
        IN_AIR = 2
        TAKING_OFF = 3
        UNKNOWN = 0

    landed: asyncio.Queue[Landed] = asyncio.Queue()
    subscribed: list[str] = []
    rates: list[tuple[str, float]] = []
    via_mavsdk: list[str] = []

    async def landed_states():
        while True:
            yield await landed.get()

    async def silent():
        await asyncio.Event().wait()
        yield None

    class Telemetry:
        def __getattr__(self, name: str):
            if name.startswith("set_rate_"):

                async def set_rate(hz: float) -> None:
                    rates.append((name.removeprefix("set_rate_"), hz))
                    via_mavsdk.append(name.removeprefix("set_rate_"))

                return set_rate
            subscribed.append(name)
            return landed_states if name == "landed_state" else silent

    async def call(_what: str, aw):
        return await aw

    async def until(predicate, what: str) -> None:
        deadline = asyncio.get_running_loop().time() + 10
        while not predicate():
            assert asyncio.get_running_loop().time() < deadline, f"timed out waiting for {what}"
            await asyncio.sleep(0.01)

    names_by_id = {message_id: name for name, message_id in MESSAGE_IDS.items()}

    async def set_message_rate(message_id: int, hz: float) -> None:  # the session's COMMAND_LONG
        rates.append((names_by_id[message_id], hz))

    cache = TelemetryCache()
    system = SimpleNamespace(telemetry=Telemetry(), mission_raw=SimpleNamespace(mission_progress=silent))
    feed = TelemetryFeed(
        "d1", system, cache, use_mavsdk_flight_mode=lambda: False, set_message_rate=set_message_rate
    )
    feed.start()
    try:
        await feed.request_rates(call)
        assert dict(rates) == STREAM_RATES_HZ  # at rest: every stream at its rest rate
        # every one through the session's COMMAND_LONG: MAVSDK's setters can report set a request that
        # mavsdk_server never sent (an ACK of the same command id completes it while it waits its turn)
        assert via_mavsdk == []
        assert "in_air" not in subscribed and "armed" not in subscribed and "heading" not in subscribed
        rates.clear()
        landed.put_nowait(Landed.TAKING_OFF)
        await until(lambda: dict(rates) == ACTIVE_RATES_HZ, "the active rates")
        assert cache.fresh("in_air") is True and cache.fresh("landed_state") == "TAKING_OFF"
        rates.clear()
        landed.put_nowait(Landed.UNKNOWN)  # keeps the last answer, as MAVSDK's in_air does
        await until(lambda: cache.fresh("landed_state") == "UNKNOWN", "the unknown landed state")
        assert cache.fresh("in_air") is True and feed.active and rates == []
        cache.put("armed", True)  # landed but still armed: still active
        landed.put_nowait(Landed.ON_GROUND)
        await until(lambda: cache.fresh("in_air") is False, "on the ground")
        assert feed.active and rates == []
        cache.put("armed", False)  # disarmed: the next item brings the rest rates back
        landed.put_nowait(Landed.ON_GROUND)
        await until(lambda: dict(rates) == {k: STREAM_RATES_HZ[k] for k in ACTIVE_RATES_HZ}, "the rest rates")
        assert not feed.active and "flight_mode" not in subscribed
    finally:
        await feed.stop()


async def test_the_rates_are_asked_for_one_request_at_a_time_while_items_arrive() -> None:
    """A position item that comes while the session's first rate request runs (the drone at rest) starts
    no second request beside it: every stream is asked for once, one MAV_CMD_SET_MESSAGE_INTERVAL at a
    time. Two at once made mavsdk_server match an ACK to a command of the same id that had not been sent
    yet (a drone then never got SYS_STATUS); the gateway's own COMMAND_ACK matching is by command id too."""
    import asyncio

    from gateway.link.telemetry_feed import MESSAGE_IDS, STREAM_RATES_HZ, TelemetryFeed

    names_by_id = {message_id: name for name, message_id in MESSAGE_IDS.items()}
    asked: list[str] = []
    in_flight = 0
    most_in_flight = 0
    positions: asyncio.Queue[object] = asyncio.Queue()
    at_rest = SimpleNamespace(
        latitude_deg=-35.36, longitude_deg=149.16, absolute_altitude_m=584.0, relative_altitude_m=0.0
    )

    async def set_message_rate(message_id: int, _hz: float) -> None:
        nonlocal in_flight, most_in_flight
        asked.append(names_by_id[message_id])
        in_flight += 1
        most_in_flight = max(most_in_flight, in_flight)
        if len(asked) == 2:
            positions.put_nowait(at_rest)
        await asyncio.sleep(0.02)  # the answer takes a moment: the item is handled meanwhile
        in_flight -= 1

    async def position_items():
        while True:
            yield await positions.get()

    async def silent():
        await asyncio.Event().wait()
        yield None

    class Telemetry:
        def __getattr__(self, name: str):
            return position_items if name == "position" else silent

    async def call(_what: str, aw):
        return await aw

    cache = TelemetryCache()
    system = SimpleNamespace(telemetry=Telemetry(), mission_raw=SimpleNamespace(mission_progress=silent))
    feed = TelemetryFeed(
        "d1", system, cache, use_mavsdk_flight_mode=lambda: False, set_message_rate=set_message_rate
    )
    feed.start()
    try:
        await feed.request_rates(call)
        deadline = asyncio.get_running_loop().time() + 10
        while cache.position is None:  # the item came and was handled
            assert asyncio.get_running_loop().time() < deadline, "the position item was not handled"
            await asyncio.sleep(0.01)
        await asyncio.sleep(0.1)  # a switch begun by the item would ask now
        assert most_in_flight == 1, asked
        assert sorted(asked) == sorted(STREAM_RATES_HZ), asked
    finally:
        await feed.stop()


async def test_an_unknown_parameter_is_refused_from_the_listed_names_without_asking() -> None:
    """Older ArduPilot never answers a read of a name it lacks (MAVSDK waits ~3 s): once the autopilot's
    list is in hand, such a name is refused without a read; a listed name is still read afresh."""
    from gateway.errors import CommandFailed
    from gateway.fleet.vehicles.params import Parameters

    reads: list[str] = []

    async def get_param_int(name: str) -> int:
        reads.append(name)
        return 3

    async def get_all_params() -> SimpleNamespace:
        return SimpleNamespace(int_params=[SimpleNamespace(name="FENCE_ENABLE", value=1)], float_params=[])

    system = SimpleNamespace(
        param=SimpleNamespace(get_param_int=get_param_int, get_all_params=get_all_params)
    )

    async def call(what: str, awaitable: object, timeout_s: float) -> object:
        return await awaitable  # type: ignore[misc]

    params = Parameters("d1", call, lambda: system)  # type: ignore[arg-type,return-value]
    with pytest.raises(
        CommandFailed, match="unknown parameter 'NO_SUCH_PARAM' on drone 'd1': not among the 1"
    ):
        await params.get("NO_SUCH_PARAM")
    assert reads == []  # refused from the list: the autopilot was not asked
    assert await params.get("FENCE_ENABLE") == (3, "int") and reads == ["FENCE_ENABLE"]


async def test_a_rate_request_without_an_answer_is_asked_again_and_a_refusal_is_not() -> None:
    """A rate request that timed out on a busy link is asked for again (only that stream, after a wait
    that grows while it still gets no answer); one the vehicle refused stays refused. A drone missing its
    health or home stream would otherwise never be ready."""
    from gateway.errors import CommandFailed
    from gateway.link.telemetry_feed import MESSAGE_IDS, UNANSWERED_RETRY_S, TelemetryFeed

    asked: list[str] = []
    silent_streams = {"health"}
    names_by_id = {message_id: name for name, message_id in MESSAGE_IDS.items()}

    async def set_message_rate(message_id: int, _hz: float) -> None:  # the session's COMMAND_LONG
        stream = names_by_id[message_id]
        asked.append(stream)
        if stream in silent_streams:
            raise CommandFailed("rate on drone 'd1': no COMMAND_ACK after 3 attempts")
        if stream == "odometry":
            raise CommandFailed("rate on drone 'd1' refused: UNSUPPORTED", result="UNSUPPORTED")

    async def call(_what: str, aw):
        return await aw

    feed = TelemetryFeed("d1", SimpleNamespace(), TelemetryCache(), set_message_rate=set_message_rate)
    refused = await feed.request_rates(call)
    assert refused == {"odometry": refused["odometry"]} and set(feed.unanswered_rates) == {"health"}
    assert feed.rates_to_ask_again() == frozenset()  # not yet: UNANSWERED_RETRY_S after the request
    feed._ask_again_at -= UNANSWERED_RETRY_S * 2
    assert feed.rates_to_ask_again() == frozenset({"health"})
    asked.clear()
    await feed.request_rates(call, only=feed.rates_to_ask_again())  # still no answer: the wait doubles
    assert asked == ["health"] and set(feed.unanswered_rates) == {"health"}
    assert feed._ask_again_at - time.monotonic() > UNANSWERED_RETRY_S * 1.5
    silent_streams.clear()
    feed._ask_again_at = 0.0
    await feed.request_rates(call, only=feed.rates_to_ask_again())
    assert feed.unanswered_rates == {} and set(feed.unsupported_rates) == {"odometry"}
    assert feed.rates_to_ask_again() == frozenset()


async def test_a_parameter_set_inside_mavsdk_waits_for_the_list_being_fetched() -> None:
    """MAVSDK's param client answers one request at a time: the takeoff altitude (a parameter MAVSDK sets
    itself) is sent only once the session's list fetch is done, so its own timeout never runs out
    behind the whole list."""
    from gateway.fleet.vehicles.params import Parameters

    listed = asyncio.Event()

    async def get_all_params() -> SimpleNamespace:
        await listed.wait()
        return SimpleNamespace(int_params=[], float_params=[])

    system = SimpleNamespace(param=SimpleNamespace(get_all_params=get_all_params))

    async def call(what: str, awaitable: object, timeout_s: float) -> object:
        return await awaitable  # type: ignore[misc]

    params = Parameters("d1", call, lambda: system)  # type: ignore[arg-type,return-value]
    fetch = asyncio.create_task(params.prefetch())
    await asyncio.sleep(0)
    waiting = asyncio.create_task(params.not_fetching())
    for _ in range(5):
        await asyncio.sleep(0)
    assert not waiting.done()  # the list is still being fetched
    listed.set()
    await asyncio.wait_for(waiting, 5)
    await fetch
    await asyncio.wait_for(params.not_fetching(), 5)  # nothing fetched: at once
