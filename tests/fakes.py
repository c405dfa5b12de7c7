"""The one fake vehicle (and registry) of the unit tests. It implements `FlyingVehicle` (view and actions) and
`VehicleRegistry` (checked at the bottom), so unit tests run the real runtime `Gateway` (the real
Commander, policy, operations and a real SQLite store) with only the drones faked. Integration tests
use the simulator and real mavsdk_server sidecars instead.

The fake drone keeps its telemetry in a real `TelemetryCache` with the real value types, and streams it
like an autopilot (every value re-sent every 0.2 s while the registry runs), so freshness rules apply as
they do to a real drone. Commands are recorded in ``sent``; ``log`` keeps (time, command, args); hooks:
``latency_s`` (each command takes that long), ``barrier`` (every command waits at it: proof that a
dispatch is concurrent), ``fail`` (command name -> the autopilot's refusal), ``arm_delay_s``.
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import AsyncIterator, Callable, Coroutine, Mapping, Sequence
from pathlib import Path
from typing import Any, Unpack

from gateway.config import Settings
from gateway.errors import CommandFailed, UnknownVehicle, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.dialects import ARDUPILOT
from gateway.fleet.dialects.modes import ModeChoice, require_mode
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.origin import Origin, checked_point
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.fleet.vehicles.protocols import FlyingVehicle, Notify, VehicleActions, VehicleRegistry
from gateway.fleet.vehicles.vehicle import ConnectionState
from gateway.fleet.vehicles.waits import wait_for_state
from gateway.link import refusals
from gateway.link.contract import GroundCommand
from gateway.link.telemetry import (
    AttitudeValue,
    BatteryValue,
    GpsInfoValue,
    HealthValue,
    MissionProgressValue,
    PositionValue,
    RcStatusValue,
    TelemetryCache,
    VelocityNedValue,
)
from gateway.registry.records import utcnow
from gateway.registry.spec import VehicleChanges, VehicleSpec
from gateway.registry.store import Store
from gateway.runtime import Gateway
from tests.helpers.timing import scaled

HOME = (47.397742, 8.545594, 488.0)
STREAM_S = 0.2
NO_SESSION = (ConnectionState.REGISTERED, ConnectionState.CONNECTING, ConnectionState.FAILED)


def position_value(lat: float, lon: float, alt: float) -> PositionValue:
    return PositionValue(lat_deg=lat, lon_deg=lon, abs_alt_m=HOME[2] + alt, rel_alt_m=alt)


#: the actions a flying vehicle has (`VehicleActions`' members)
ACTIONS = frozenset(name for name in dir(VehicleActions) if not name.startswith("_"))


class FakeVehicle:
    """A drone that flies in straight lines at ``speed`` m/s toward its target."""

    def __init__(
        self,
        vid: str,
        *,
        east_m: float = 0.0,
        speed: float = 40.0,
        state: ConnectionState = ConnectionState.READY,
        spec: VehicleSpec | None = None,
        stale_after_s: float = 3.0,
    ) -> None:
        self._spec = spec or VehicleSpec(id=vid, url="tcpout://127.0.0.1:5760", name=vid.upper())
        self.state = state
        self.is_simulator = True
        #: the origin the distance limit counts from (None: the home stands in)
        self.fixed_origin: tuple[float, float, float] | None = None
        self.speed = speed
        self.sent: list[tuple[Any, ...]] = []
        self.log: list[tuple[float, str, tuple[Any, ...]]] = []
        self.latency_s = 0.0
        self.arm_delay_s = 0.0
        self.barrier: asyncio.Barrier | None = None
        self.fail: dict[str, str] = {}
        self.params: dict[str, float | int] = {"WPNAV_SPEED": 1000.0, "RTL_ALT": 1500.0, "FENCE_ENABLE": 0.0}
        self.params.update({f"SR0_P{i:03d}": float(i) for i in range(300)})
        self.mission: list[MissionItem] = []
        self.mission_done = False
        #: what the autopilot says it flies to (lat, lon, monotonic), set by a test; None: not said
        self.target: tuple[float, float, float] | None = None
        # earlier reports a late watch may not have seen as the latest (`position_targets`)
        self.target_history: list[tuple[float, float, float]] = []
        #: when its last HEARTBEAT was heard (monotonic), set by a test; None: one heard just now, always
        self.heartbeat_at: float | None = None
        #: the last position target the gateway sent (goto, hold): lat, lon, monotonic
        self.commanded: tuple[float, float, float] | None = None
        #: what a ground station on the relay sent that acts on the drone (set by a test)
        self.ground_commands: list[GroundCommand] = []
        lat, lon = geo.offset_position(HOME[0], HOME[1], 0.0, east_m)
        self.home_ll = (lat, lon)
        self.telemetry = TelemetryCache(stale_after_s=stale_after_s)
        self.set(
            position=position_value(lat, lon, 0.0),
            home=position_value(lat, lon, 0.0),
            armed=False,
            in_air=False,
            heading_deg=0.0,
            velocity_ned=VelocityNedValue(0.0, 0.0, 0.0),
            battery=BatteryValue(remaining_pct=87.0, voltage_v=12.3),
            attitude=AttitudeValue(0.1, -0.2, 0.0),
            gps_info=GpsInfoValue(num_satellites=12, fix_type="FIX_3D"),
            flight_mode="STABILIZE",
            landed_state="ON_GROUND",
            health=HealthValue(True, True, True, True, True, True, True),
            rc_status=RcStatusValue(False, False, None),
            mission_progress=MissionProgressValue(0, 0),
        )
        self.telemetry.add_status_text("info", "ArduCopter V4.7")
        self.telemetry.add_status_text("warning", "PreArm: ok")
        self._flight: asyncio.Task[None] | None = None
        self._stream: asyncio.Task[None] | None = None

    # --- identity and state (VehicleView) -------------------------------------------------------------
    @property
    def id(self) -> str:
        return self._spec.id

    @property
    def spec(self) -> VehicleSpec:
        return self._spec

    @spec.setter
    def spec(self, spec: VehicleSpec) -> None:
        self._spec = spec

    last_error: str | None = None
    autopilot: str | None = "ardupilot"

    def status(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "state": self.state.value,
            "is_simulator": self.is_simulator,
            "last_error": None,
            "sidecar": {"state": "stopped", "pid": None, "grpc_port": None, "restarts": 0},
        }

    def require_ready(self) -> None:
        if self.state != ConnectionState.READY:
            raise VehicleNotReady(
                f"drone '{self.id}' is {self.state.value}, not ready", state=self.state.value
            )

    def initialising(self) -> str | None:
        return None

    async def wait_for_state(self, *states: ConnectionState | str, within_s: float = 60.0) -> ConnectionState:
        return await wait_for_state(self, *states, within_s=within_s)

    async def wait_initialised(self, within_s: float = 60.0, notify: Notify | None = None) -> bool:
        waiting = self.initialising()  # a fake is ready at once; a test may make it say what it waits for
        if waiting is not None and notify is not None:
            await notify(f"{self.id}: {waiting}")
        self.require_ready()
        return True

    def resolve_mode(self, name: str) -> ModeChoice:
        return require_mode(name, ARDUPILOT, self.id)

    def heartbeat_mode(self) -> tuple[str, bool] | None:
        mode, armed = self.telemetry.flight_mode, self.telemetry.armed
        if mode is None or armed is None:
            return None
        return str(mode.value), bool(armed.value)

    def heartbeat_heard_at(self) -> float | None:
        return time.monotonic() if self.heartbeat_at is None else self.heartbeat_at

    def position_target(self) -> tuple[float, float, float] | None:
        return self.target

    def position_targets(self, since: float) -> list[tuple[float, float, float]]:
        reports = [*self.target_history, *([self.target] if self.target is not None else [])]
        return [t for t in reports if t[2] >= since]

    def commanded_target(self) -> tuple[float, float, float] | None:
        return self.commanded

    def ground_station_commands(self, since: float) -> list[GroundCommand]:
        return [c for c in self.ground_commands if c.at >= since]

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        return ARDUPILOT.commanded_modes(kind, done=done)

    def recent_texts(self, within_s: float) -> list[str]:
        return refusals.said_since(self.telemetry.status_texts, time.time() - within_s)

    def on_ground(self, fresh: bool = True) -> bool | None:
        return ARDUPILOT.on_ground(self.telemetry, fresh=fresh)

    def return_altitude_param(self) -> tuple[str, float]:
        return "RTL_ALT", 100.0  # an ArduPilot before 4.7

    async def set_return_altitude(self, alt_m: float) -> tuple[str, float | int]:
        stored, _kind = await self.set_param("RTL_ALT", round(alt_m * 100))
        return "RTL_ALT", stored

    @property
    def protected_params(self) -> tuple[str, ...]:
        return ARDUPILOT.protected_params

    @property
    def origin(self) -> tuple[float, float, float] | None:
        return self.fixed_origin

    @property
    def current_flight_id(self) -> int | None:
        return None  # the fake records no flights

    def flown_here(self) -> FlyingVehicle:
        return self  # every fake drone is flown here (mypy checks the fake against FlyingVehicle here)

    @property
    def limit_params(self) -> Mapping[str, ParamLimit]:
        return ARDUPILOT.limit_params

    # --- telemetry ---------------------------------------------------------------------------------------
    def set(self, **parts: Any) -> None:
        """Put values into the telemetry cache, as a telemetry stream would."""
        for name, val in parts.items():
            self.telemetry.put(name, val)

    def pos(self) -> tuple[float, float, float]:
        p = self.telemetry.position
        assert p is not None
        return p.value.lat_deg, p.value.lon_deg, p.value.rel_alt_m

    def start_streaming(self) -> None:
        if self._stream is None:
            self._stream = asyncio.get_running_loop().create_task(self._streaming(), name=f"fake-{self.id}")

    async def stop_streaming(self) -> None:
        for task in (self._stream, self._flight):
            if task is not None:
                task.cancel()
                with contextlib.suppress(asyncio.CancelledError):
                    await task
        self._stream = self._flight = None

    async def _streaming(self) -> None:
        """Re-send every reading each STREAM_S, the first time at once: a gateway set up slowly on a busy
        machine (longer than the cache's staleness) must not find the readings of __init__ stale."""
        while True:
            if self.telemetry.live:
                for name in TelemetryCache.FIELDS:
                    sample = getattr(self.telemetry, name)
                    if sample is not None:
                        self.telemetry.put(name, sample.value)
            await asyncio.sleep(STREAM_S)

    def _fly(self, lat: float, lon: float, alt: float, then: Callable[[], None] | None = None) -> None:
        if self._flight is not None:
            self._flight.cancel()

        async def run() -> None:
            while True:
                la, lo, al = self.pos()
                n, e = geo.ned_offset(la, lo, lat, lon)
                d = (n * n + e * e + (alt - al) ** 2) ** 0.5
                step = self.speed * 0.05
                if d <= step:
                    self.set(position=position_value(lat, lon, alt))
                    break
                f = step / d
                la2, lo2 = geo.offset_position(la, lo, n * f, e * f)
                self.set(position=position_value(la2, lo2, al + (alt - al) * f))
                await asyncio.sleep(0.05)
            if then is not None:
                then()

        self._flight = asyncio.get_running_loop().create_task(run())

    def _landed(self) -> None:
        self.set(in_air=False, armed=False)

    async def _command(self, name: str, *args: Any) -> None:
        """Every command: recorded, then the hooks (barrier, latency, failure), like a real link."""
        if self.state in NO_SESSION:
            raise VehicleNotReady(
                f"drone '{self.id}' is {self.state.value}: no session", state=self.state.value
            )
        self.log.append((time.monotonic(), name, args))
        if self.barrier is not None:
            await asyncio.wait_for(self.barrier.wait(), scaled(5.0))
        if self.latency_s:
            await asyncio.sleep(self.latency_s)
        if name in self.fail:
            raise CommandFailed(f"{name} on drone '{self.id}' failed: {self.fail[name]}", vehicle_id=self.id)
        self.sent.append((name, *args))

    # --- actions (FlyingVehicle) -------------------------------------------------------------------------

    def __getattr__(self, name: str) -> Callable[..., Coroutine[Any, Any, None]]:
        """An action of `VehicleActions` the fake does not model itself (a new command's, which returns
        nothing): sent like any command (recorded in ``sent`` and ``log`` under its own name, with its
        arguments; ``fail``, ``latency_s`` and ``barrier`` apply). A new action that returns something
        must be modelled here: mypy names it (the fake is checked against `FlyingVehicle`)."""
        if name not in ACTIONS:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

        async def send(*args: Any, **kwargs: Any) -> None:
            await self._command(name, *args, *kwargs.values())

        return send

    async def arm(self, within_s: float = 60.0, notify: Notify | None = None) -> None:
        await self._command("arm")
        self.set(armed=True, flight_mode="GUIDED")

    async def disarm(self) -> None:
        await self._command("disarm")
        self.set(armed=False)

    async def kill(self) -> None:
        await self._command("kill")
        if self._flight is not None:
            self._flight.cancel()
        self.set(armed=False, in_air=False, position=position_value(*self.pos()[:2], 0.0))

    async def takeoff(self, alt_rel_m: float, within_s: float = 60.0, notify: Notify | None = None) -> None:
        await asyncio.sleep(self.arm_delay_s)  # arming takes a while on a real vehicle
        await self._command("takeoff", alt_rel_m)
        self.set(armed=True, in_air=True, flight_mode="GUIDED")
        self._fly(*self.pos()[:2], alt_rel_m)

    async def goto(self, lat: float, lon: float, alt_rel_m: float, yaw_deg: float | None = None) -> None:
        self.commanded = (lat, lon, time.monotonic())
        await self._command("goto", lat, lon, alt_rel_m)
        self._fly(lat, lon, alt_rel_m)

    async def hold(self) -> None:
        lat, lon, _ = self.pos()
        flying = self.telemetry.in_air is not None and self.telemetry.in_air.value
        self.commanded = (lat, lon, time.monotonic()) if flying else None
        await self._command("hold")
        if self._flight is not None:
            self._flight.cancel()

    async def land(self) -> None:
        await self._command("land")
        self.set(flight_mode="LAND")
        self._fly(*self.pos()[:2], 0.0, then=self._landed)

    async def return_to_launch(self) -> None:
        await self._command("rtl")
        self.set(flight_mode="RTL")
        self._fly(self.home_ll[0], self.home_ll[1], 0.0, then=self._landed)

    async def set_yaw(self, heading_deg: float) -> None:
        await self._command("yaw", heading_deg)
        self.set(heading_deg=heading_deg)

    async def set_max_speed(self, mps: float) -> None:
        await self._command("speed", mps)

    async def set_flight_mode(self, name: str) -> None:
        native = self.resolve_mode(name).native
        await self._command("mode", name)
        self.set(flight_mode=native)

    async def upload_mission(self, items: Sequence[MissionItem]) -> int:
        await self._command("upload", len(items))
        self.mission = list(items)
        self.mission_done = False
        self.set(mission_progress=MissionProgressValue(0, len(items)))
        return len(items)

    async def download_mission(self) -> list[MissionItem]:
        return list(self.mission)

    async def clear_mission(self) -> None:
        await self._command("clear")
        self.mission = []

    async def start_mission(self) -> None:
        await self._command("start_mission")
        self.set(
            in_air=True,
            armed=True,
            flight_mode="AUTO",
            mission_progress=MissionProgressValue(1, len(self.mission)),
        )
        last = self.mission[-1]
        self._fly(last.lat, last.lon, max(last.alt_rel_m, 5.0), then=self._mission_finished)

    def _mission_finished(self) -> None:
        total = len(self.mission)
        self.set(mission_progress=MissionProgressValue(total, total, finished=True))
        self.mission_done = True

    async def set_current_mission_item(self, user_index: int) -> None:
        await self._command("set_current", user_index)

    async def is_mission_finished(self) -> bool:
        return self.mission_done

    async def get_param(self, name: str) -> tuple[float | int, str]:
        if name not in self.params:
            raise CommandFailed(
                f"unknown parameter '{name}' on drone '{self.id}'",
                vehicle_id=self.id,
                result="UNKNOWN_PARAMETER",
            )
        return self.params[name], "float"

    async def set_param(self, name: str, value: float | int) -> tuple[float | int, str]:
        await self._command("param", name, value)
        self.params[name] = value
        return value, "float"

    async def list_params(self) -> dict[str, float | int]:
        return dict(self.params)


class FakeRegistry:
    """The registry contract over fake drones: registrations persist through the real Store; drones
    given up front (``vehicles``) are there from the start, as if restored."""

    def __init__(self, settings: Settings, store: Store, vehicles: Sequence[FakeVehicle] = ()) -> None:
        self.settings = settings
        self.store = store
        self.vehicles: dict[str, FakeVehicle] = {v.id: v for v in vehicles}

    async def start(self) -> None:
        for record in await self.store.list_vehicles():
            if record.id not in self.vehicles:
                state = ConnectionState.CONNECTING if record.auto_connect else ConnectionState.REGISTERED
                self.vehicles[record.id] = FakeVehicle(record.id, spec=record.spec, state=state)
        for vehicle in self.vehicles.values():
            vehicle.start_streaming()

    async def stop(self) -> None:
        for vehicle in self.vehicles.values():
            await vehicle.stop_streaming()

    async def move_origin(
        self, vehicle_id: str, lat: object, lon: object, alt_amsl_m: object, by: str
    ) -> Origin:
        vehicle = self.get(vehicle_id)
        origin = Origin(vehicle_id, *checked_point(lat, lon, alt_amsl_m), "operator", by, utcnow())
        vehicle.fixed_origin = origin.point
        return await self.store.save_origin(origin)

    async def add(self, spec: VehicleSpec, connect: bool = True) -> FakeVehicle:
        await self.store.add_vehicle(spec, auto_connect=connect)
        state = ConnectionState.CONNECTING if connect else ConnectionState.REGISTERED
        vehicle = FakeVehicle(spec.id, spec=spec, state=state)
        self.vehicles[spec.id] = vehicle
        vehicle.start_streaming()
        return vehicle

    async def update(self, vehicle_id: str, **changes: Unpack[VehicleChanges]) -> FakeVehicle:
        vehicle = self.get(vehicle_id)
        record = await self.store.update_vehicle(vehicle_id, **changes)
        vehicle.spec = record.spec
        return vehicle

    async def remove(self, vehicle_id: str) -> None:
        vehicle = self.get(vehicle_id)
        await self.store.remove_vehicle(vehicle_id)
        await vehicle.stop_streaming()
        del self.vehicles[vehicle_id]

    def get(self, vehicle_id: str) -> FakeVehicle:
        if vehicle_id not in self.vehicles:
            raise UnknownVehicle(vehicle_id, list(self.vehicles))
        return self.vehicles[vehicle_id]

    def flown(self, vehicle_id: str) -> FakeVehicle:
        return self.get(vehicle_id)  # every fake drone is flown here, as ArduPilot

    def all(self) -> list[FakeVehicle]:
        return list(self.vehicles.values())

    async def connect(self, vehicle_id: str) -> FakeVehicle:
        vehicle = self.get(vehicle_id)
        vehicle.state = ConnectionState.CONNECTING
        return vehicle

    async def disconnect(self, vehicle_id: str) -> FakeVehicle:
        vehicle = self.get(vehicle_id)
        vehicle.state = ConnectionState.REGISTERED
        return vehicle


def spread(n: int, spacing_m: float = 10.0, speed: float = 150.0) -> list[FakeVehicle]:
    """``n`` drones d1..dn, each on its own home ``spacing_m`` east of the previous one."""
    return [FakeVehicle(f"d{i + 1}", east_m=i * spacing_m, speed=speed) for i in range(n)]


def unit_settings(tmp: Path, **overrides: Any) -> Settings:
    """A gateway's settings with its database and its spool file in ``tmp`` (the spool's default is the
    working directory: a slow write under load would leave its file in the checkout)."""
    base: dict[str, Any] = {
        "database_url": f"sqlite+aiosqlite:///{tmp / 'gateway.db'}",
        "spool_path": str(tmp / "spool.jsonl"),
    }
    return Settings(_env_file=None, **{**base, **overrides})


@contextlib.asynccontextmanager
async def fake_gateway(settings: Settings, vehicles: Sequence[FakeVehicle]) -> AsyncIterator[Gateway]:
    """The real runtime Gateway (store, policy, operations, Commander) over fake drones, started."""

    def registry(s: Settings, store: Store) -> VehicleRegistry:
        return FakeRegistry(s, store, vehicles)

    gateway = Gateway(settings, registry_factory=registry)
    await gateway.start()
    try:
        yield gateway
    finally:
        await gateway.stop()


def fake(gateway: Gateway, drone_id: str) -> FakeVehicle:
    """The fake drone behind ``drone_id``."""
    vehicle = gateway.require_registry().get(drone_id)
    assert isinstance(vehicle, FakeVehicle)
    return vehicle


if __debug__:  # the fake keeps the same contract as the real vehicle and registry (mypy checks these)
    _vehicle: type[FlyingVehicle] = FakeVehicle
    _registry: Callable[[Settings, Store], VehicleRegistry] = FakeRegistry
