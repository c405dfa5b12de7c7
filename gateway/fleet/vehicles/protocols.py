"""What the flight logic needs of a vehicle and of the registry that holds the vehicles.

A vehicle has two sides. `VehicleView` is what every door reads: identity, connection state, the
telemetry snapshot and what its autopilot's dialect says about it (modes, landed state, protected
parameters). That is all a cluster node has of a drone another node flies
(`gateway.cluster.remote.RemoteVehicle`). `VehicleActions` is what only the node that flies the drone
can do: the commands its dialect sends. `FlyingVehicle` is both: `gateway.fleet.vehicles.vehicle.Vehicle` and
the
one fake vehicle of the unit tests (`tests/fakes.py`).

Code that reads asks the directory for the view (`VehicleDirectory.get`); code that acts asks for the
flying vehicle (`VehicleDirectory.flown`, or `flying(view)` for a view in hand), which refuses in words
when this node cannot fly it (another node owns it; `flown` also when the gateway has no dialect for its
autopilot, which every action refuses anyway). The Commander, the operation trackers
and the fleet operations are written against these Protocols, never against the MAVSDK-backed class.

A new autopilot call is a member of `VehicleActions` here and its body in `gateway.fleet.vehicles.vehicle`
(which
asks `require_dialect()` first); only when autopilots do it differently, a `Dialect` method too
(`gateway.fleet.dialects.base`, with each dialect's body). Nothing else on this side: a remote view has
no actions to stub, and the registry hands out whatever `FlyingVehicle` has.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Protocol, Unpack

from gateway.errors import OwnedElsewhere
from gateway.fleet.dialects.modes import ModeChoice
from gateway.fleet.missions.mission import MissionItem
from gateway.fleet.policy.origin import Origin
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.link.contract import GroundCommand
from gateway.link.telemetry import TelemetryCache
from gateway.registry.spec import VehicleChanges, VehicleSpec
from gateway.util.json_types import JsonObject

if TYPE_CHECKING:
    from gateway.link.contract import ConnectionState

Notify = Callable[[str], Awaitable[None]]
"""Told, in words, what a command waits for before it can be sent (e.g. a drone still initialising)."""


class VehicleView(Protocol):
    """What every door reads of one drone: identity, connection state, telemetry snapshot and its
    autopilot's dialect's answers. A remote node's view of a drone has all of it."""

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

    @property
    def last_error(self) -> str | None:
        """Why the drone is not ready (None when nothing is wrong)."""

    @property
    def autopilot(self) -> str | None:
        """ "ardupilot", "px4" or "mav_autopilot_<n>" as its HEARTBEAT names it; None before one came."""

    @property
    def current_flight_id(self) -> int | None:
        """The flight being recorded here (armed now); None on the ground, or when another node records it."""

    def status(self) -> JsonObject: ...

    def require_ready(self) -> None:
        """Raise VehicleNotReady (naming the state and why) unless the vehicle can fly."""

    def initialising(self) -> str | None:
        """While connected but not ready: what the vehicle still waits for."""

    async def wait_for_state(self, *states: ConnectionState | str, within_s: float = ...) -> ConnectionState:
        """Wait until the state is one of ``states``; VehicleNotReady naming the state otherwise."""

    async def wait_initialised(self, within_s: float = ..., notify: Notify | None = None) -> bool:
        """Wait up to ``within_s`` for a vehicle still initialising (``notify`` hears what it waits
        for): True once ready; False when the time ran out while it still initialises and its
        autopilot can judge an arming attempt; VehicleNotReady naming why in any other state."""

    def resolve_mode(self, name: str) -> ModeChoice: ...

    def heartbeat_mode(self) -> tuple[str, bool] | None:
        """The autopilot's name of the mode its HEARTBEAT shows and whether it is armed (None: no
        fresh HEARTBEAT)."""

    def heartbeat_heard_at(self) -> float | None:
        """When (monotonic) the last HEARTBEAT was heard; None before the first one of the session."""

    def position_target(self) -> tuple[float, float, float] | None:
        """Where the autopilot says it flies to (POSITION_TARGET_GLOBAL_INT): lat, lon and when it said
        so (monotonic); None when it has not said."""

    def position_targets(self, since: float) -> list[tuple[float, float, float]]:
        """The targets the autopilot reported at or after ``since`` (monotonic), oldest first, as far
        back as the last few seconds: a target it flew only briefly still shows here."""

    def ground_station_commands(self, since: float) -> list[GroundCommand]:
        """What ground stations on the gateway's relay sent that acts on the drone, at or after ``since``
        (monotonic), oldest first (`gateway.link.ground_commands`); none without a relay."""

    def commanded_target(self) -> tuple[float, float, float] | None:
        """The last position target the gateway sent this drone (a goto or a hold): lat, lon and when
        it was sent (monotonic); None when it sent none (or a hold on the ground sent nothing)."""

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

    @property
    def protected_params(self) -> tuple[str, ...]:
        """Patterns of the parameters the vehicle's autopilot protects from agents."""

    @property
    def limit_params(self) -> Mapping[str, ParamLimit]:
        """The parameters that could walk around a policy limit, each with the limit it governs."""

    @property
    def origin(self) -> tuple[float, float, float] | None:
        """(lat, lon, alt_amsl_m) the distance limit and the zones count from: the first home the vehicle
        reported or where an operator moved it (None: not known here; its home stands in)."""

    def flown_here(self) -> FlyingVehicle | None:
        """The drone with its actions when this node flies it (the vehicle itself), None when another
        cluster node flies it. Who flies a drone is this explicit fact of the vehicle, never read from
        the shape of the object: a class that flies drones returns ``self`` here, which mypy checks
        against `FlyingVehicle` member by member."""


class VehicleActions(Protocol):
    """What only the node that flies a drone can do: the commands its autopilot's dialect sends. Each
    refuses (naming the autopilot) when the gateway has no dialect for the drone's autopilot."""

    async def set_return_altitude(self, alt_m: float) -> tuple[str, float | int]:
        """Write the RTL altitude (m above home) in the autopilot's parameter and units."""

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


class FlyingVehicle(VehicleView, VehicleActions, Protocol):
    """A drone this node flies: its view and its actions."""


def flying(view: VehicleView) -> FlyingVehicle:
    """``view`` as a drone this node flies, to send it a command; OwnedElsewhere (naming the node that
    flies it, as its view reports) for a view of a drone another cluster node flies."""
    vehicle = view.flown_here()
    if vehicle is not None:
        return vehicle
    owner = view.status().get("owner_node")
    raise OwnedElsewhere.of(view.id, owner if isinstance(owner, str) else None)


class VehicleDirectory(Protocol):
    """Finding vehicles: what the Commander needs of the registry."""

    def get(self, vehicle_id: str) -> VehicleView:
        """The vehicle, to read; UnknownVehicle (listing the known ids) otherwise."""

    def flown(self, vehicle_id: str) -> FlyingVehicle:
        """The vehicle, to act on: `get`'s, when this node flies it. Refused in words otherwise:
        OwnedElsewhere (another cluster node flies it) or NoDialect (the gateway has no dialect for
        its autopilot: it is shown, never commanded)."""

    def all(self) -> Sequence[VehicleView]: ...


class VehicleRegistry(VehicleDirectory, Protocol):
    """The whole registry as the runtime and the REST API use it (the real one is
    `gateway.fleet.vehicles.registry.Registry`)."""

    async def start(self) -> None: ...

    async def stop(self) -> None: ...

    async def move_origin(
        self, vehicle_id: str, lat: object, lon: object, alt_amsl_m: object, by: str
    ) -> Origin:
        """An operator's new origin for the vehicle's distance limit and zones (checked, stored), on the
        node that flies it (OwnedElsewhere otherwise)."""

    async def add(self, spec: VehicleSpec, connect: bool = True) -> VehicleView: ...

    async def update(self, vehicle_id: str, **changes: Unpack[VehicleChanges]) -> VehicleView: ...

    async def remove(self, vehicle_id: str) -> None: ...

    async def connect(self, vehicle_id: str) -> VehicleView: ...

    async def disconnect(self, vehicle_id: str) -> VehicleView: ...
