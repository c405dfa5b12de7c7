"""What the flight logic needs of a vehicle and of the registry that holds the vehicles.

`gateway.fleet.vehicle.Vehicle` satisfies `FlyingVehicle`, and so does the one fake vehicle of the unit
tests (`tests/fakes.py`): the Commander, the operation trackers and the fleet operations are written
against these Protocols, never against the MAVSDK-backed class.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Protocol

from gateway.fleet.mission import MissionItem
from gateway.fleet.modes import ModeChoice
from gateway.fleet.param_limits import ParamLimit
from gateway.link.telemetry import TelemetryCache
from gateway.registry.spec import VehicleSpec

if TYPE_CHECKING:
    from gateway.fleet.vehicle import ConnectionState

Notify = Callable[[str], Awaitable[None]]
"""Told, in words, what a command waits for before it can be sent (e.g. a drone still initialising)."""


class FlyingVehicle(Protocol):
    """One drone: identity, connection state, telemetry cache, and the commands it takes."""

    @property
    def telemetry(self) -> TelemetryCache: ...

    @property
    def is_simulator(self) -> bool: ...

    @property
    def id(self) -> str: ...

    @property
    def spec(self) -> VehicleSpec: ...

    @property
    def state(self) -> ConnectionState: ...

    def status(self) -> dict[str, Any]: ...

    def require_ready(self) -> None:
        """Raise VehicleNotReady (naming the state and why) unless the vehicle can fly."""

    def initialising(self) -> str | None:
        """While connected but not ready: what the vehicle still waits for."""

    async def wait_initialised(self, within_s: float = ..., notify: Notify | None = None) -> bool:
        """Wait up to ``within_s`` for a vehicle still initialising (``notify`` hears what it waits
        for): True once ready; False when the time ran out while it still initialises and its
        autopilot can judge an arming attempt; VehicleNotReady naming why in any other state."""

    def resolve_mode(self, name: str) -> ModeChoice: ...

    def heartbeat_mode(self) -> tuple[str, bool] | None:
        """The autopilot's name of the mode its HEARTBEAT shows and whether it is armed (None: no
        fresh HEARTBEAT)."""

    def position_target(self) -> tuple[float, float, float] | None:
        """Where the autopilot says it flies to (POSITION_TARGET_GLOBAL_INT): lat, lon and when it said
        so (monotonic); None when it has not said."""

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        """The modes the autopilot may show while it does what the gateway commanded (an operation of
        ``kind``; ``done``: once it succeeded), in its own names (`Dialect.commanded_modes`)."""

    def recent_texts(self, within_s: float) -> list[str]:
        """The autopilot's status texts (notice or worse) of the last ``within_s`` seconds, oldest first."""

    def on_ground(self, fresh: bool = True) -> bool | None:
        """On the ground as the autopilot's dialect tells (None: unknown; ``fresh=False`` reads cached
        values however old)."""

    def return_altitude_param(self) -> tuple[str, float]:
        """The parameter holding the RTL altitude and its units per metre."""

    async def set_return_altitude(self, alt_m: float) -> tuple[str, float | int]:
        """Write the RTL altitude (m above home) in the autopilot's parameter and units."""

    @property
    def protected_params(self) -> tuple[str, ...]:
        """Patterns of the parameters the vehicle's autopilot protects from agents."""

    @property
    def limit_params(self) -> Mapping[str, ParamLimit]:
        """The parameters that could walk around a policy limit, each with the limit it governs."""

    async def arm(self, within_s: float = ..., notify: Notify | None = None) -> None:
        """Arm, waiting (all within ``within_s``) for a drone still initialising and for refusals the
        autopilot lifts by itself; the refusal says why in the autopilot's words."""

    async def disarm(self) -> None: ...

    async def kill(self) -> None: ...

    async def takeoff(self, alt_rel_m: float, within_s: float = ..., notify: Notify | None = None) -> None:
        """Arm as ``arm`` does (within ``within_s``), then take off; returns once accepted."""

    async def goto(self, lat: float, lon: float, alt_rel_m: float, yaw_deg: float | None = None) -> None: ...

    async def hold(self) -> None: ...

    async def land(self) -> None: ...

    async def return_to_launch(self) -> None: ...

    async def set_yaw(self, heading_deg: float) -> None: ...

    async def set_max_speed(self, mps: float) -> None: ...

    async def set_flight_mode(self, name: str) -> None: ...

    async def upload_mission(self, items: Sequence[MissionItem]) -> int: ...

    async def download_mission(self) -> list[MissionItem]: ...

    async def clear_mission(self) -> None: ...

    async def start_mission(self) -> None: ...

    async def set_current_mission_item(self, user_index: int) -> None: ...

    async def is_mission_finished(self) -> bool: ...

    async def get_param(self, name: str) -> tuple[float | int, str]: ...

    async def set_param(self, name: str, value: float | int) -> tuple[float | int, str]: ...

    async def list_params(self) -> dict[str, float | int]: ...


class VehicleDirectory(Protocol):
    """Finding vehicles: what the Commander needs of the registry."""

    def get(self, vehicle_id: str) -> FlyingVehicle:
        """The vehicle; UnknownVehicle (listing the known ids) otherwise."""

    def all(self) -> Sequence[FlyingVehicle]: ...


class VehicleRegistry(VehicleDirectory, Protocol):
    """The whole registry as the runtime and the REST API use it (the real one is
    `gateway.fleet.registry.Registry`)."""

    async def start(self) -> None: ...

    async def stop(self) -> None: ...

    async def add(self, spec: VehicleSpec, connect: bool = True) -> FlyingVehicle: ...

    async def update(self, vehicle_id: str, **changes: Any) -> FlyingVehicle: ...

    async def remove(self, vehicle_id: str) -> None: ...

    async def connect(self, vehicle_id: str) -> FlyingVehicle: ...

    async def disconnect(self, vehicle_id: str) -> FlyingVehicle: ...
