"""Pure logic of the vehicle layer: mission encoding, parameter aliases, the telemetry cache."""

from __future__ import annotations

import time
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
from gateway.link.telemetry import BatteryValue, MissionProgressValue, PositionValue, Sample, TelemetryCache
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

    from gateway.link.telemetry_feed import ACTIVE_RATES_HZ, STREAM_RATES_HZ, TelemetryFeed

    class Landed(enum.Enum):
        ON_GROUND = 1
        IN_AIR = 2
        TAKING_OFF = 3
        UNKNOWN = 0

    landed: asyncio.Queue[Landed] = asyncio.Queue()
    subscribed: list[str] = []
    rates: list[tuple[str, float]] = []

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

    cache = TelemetryCache()
    system = SimpleNamespace(telemetry=Telemetry(), mission_raw=SimpleNamespace(mission_progress=silent))
    feed = TelemetryFeed("d1", system, cache, use_mavsdk_flight_mode=lambda: False)
    feed.start()
    try:
        await feed.request_rates(call)
        assert dict(rates) == STREAM_RATES_HZ  # at rest: every stream at its rest rate
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
