"""What the safety policy reads: a vehicle's context, a motion target, a running operation, and the
shapes of a mission item and a formation plan it judges (Protocols, so the policy imports neither)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

from gateway.errors import SafetyRefusal


class PlannedSlot(Protocol):
    """One drone's part of a formation plan (`gateway.fleet.formation.formation.SlotAssignment`)."""

    @property
    def drone_id(self) -> str: ...
    @property
    def legs(self) -> Sequence[Target]: ...


class PlannedFormation(Protocol):
    """What the policy reads of a formation plan (`gateway.fleet.formation.formation.FormationPlan`), so that
    the
    policy does not import the planner, which raises the policy's refusals."""

    @property
    def min_separation_m(self) -> float: ...
    @property
    def slots(self) -> Sequence[PlannedSlot]: ...


@dataclass(frozen=True)
class VehicleContext:
    """What the policy needs to know about one vehicle, taken from its telemetry cache.

    ``home`` is (lat, lon, alt_amsl_m); ``position`` is (lat, lon, alt_rel_m, metres above home).
    None means unknown (never received, or stale).
    """

    vehicle_id: str
    is_simulator: bool
    armed: bool
    in_air: bool
    battery_pct: float | None
    home: tuple[float, float, float] | None
    position: tuple[float, float, float] | None
    #: (lat, lon, alt_amsl_m) the distance limit and the zones count from: fixed per vehicle (the first
    #: home it reported, moved only by an operator); None until known, then the home stands in
    origin: tuple[float, float, float] | None = None

    def refuse(self, rule: str, text: str, **numbers: object) -> SafetyRefusal:
        """A refusal of a command to this drone by ``rule`` (a `safety_rules.Rule`): as
        `safety_rules.refuse` words it, with the drone named in its details."""
        return SafetyRefusal(str(rule), f"{rule}: {text}", vehicle_id=self.vehicle_id, **numbers)

    @property
    def distance_origin(self) -> tuple[float, float, float] | None:
        """Where the distance limit counts from: the vehicle's origin, else (not yet known) its home."""
        return self.origin if self.origin is not None else self.home

    @property
    def airborne(self) -> bool:
        """In the air as far as the policy is concerned: in_air, or armed and more than 1 m above home
        (a landed-state report can lag behind)."""
        if self.in_air:
            return True
        return bool(self.armed and self.position is not None and self.position[2] > 1.0)


@dataclass(frozen=True)
class Target:
    """A motion target: latitude, longitude (degrees), altitude in metres above home. Where a drone is
    commanded to, not where it reports it is (`gateway.link.telemetry.PositionValue`, both altitudes)."""

    lat: float
    lon: float
    alt_rel_m: float


@dataclass(frozen=True)
class RunningOperation:
    """What the policy needs to know of a drone's running operation (the takeoff and busy rules)."""

    operation_id: str
    kind: str
    message: str
    target_alt_m: float | None = None


class MissionItemLike(Protocol):
    """The fields of `gateway.fleet.missions.mission.MissionItem` the policy reads (mypy checks the model
    against them where the policy is handed its items)."""

    lat: float
    lon: float
    alt_rel_m: float
    speed_mps: float | None
    command: int | None

    @property
    def kind(self) -> str: ...
