"""A stand-in vehicle registry for unit tests of the REST layer (no sidecars, no vehicles).

It keeps the Registry contract (persisting through the real Store) so the REST mapping of results
and errors can be tested fast; the integration tests use the real Registry with simulated drones.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from gateway.config import Settings
from gateway.errors import UnknownVehicle, VehicleNotReady
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store


@dataclass
class FakeTelemetry:
    in_air: bool | None = None

    def fresh(self, name: str) -> object:
        return self.in_air if name == "in_air" else None

    def snapshot(self) -> dict[str, Any]:
        return {"position": None, "battery": {"remaining_pct": 87.0, "age_s": 0.4, "stale": False}}

    def message_counts(self) -> dict[str, int]:
        return {"position": 42}


@dataclass
class FakeVehicle:
    spec: VehicleSpec
    state: str = "registered"
    restarts: int = 0
    telemetry: FakeTelemetry = field(default_factory=FakeTelemetry)

    @property
    def id(self) -> str:
        return self.spec.id

    actions: list[str] = field(default_factory=list)

    async def hold(self) -> None:
        self.actions.append("hold")

    async def land(self) -> None:
        self.actions.append("land")

    async def return_to_launch(self) -> None:
        if self.state != "ready":
            raise VehicleNotReady(f"drone '{self.id}' is {self.state}, not ready", state=self.state)
        self.actions.append("rtl")

    async def kill(self) -> None:
        self.actions.append("kill")

    def status(self) -> dict[str, Any]:
        return {"state": self.state, "last_error": None, "sidecar": {"pid": None, "restarts": self.restarts}}


class FakeRegistry:
    def __init__(self, settings: Settings, store: Store) -> None:
        self.store = store
        self.vehicles: dict[str, FakeVehicle] = {}
        self.started = False

    async def start(self) -> None:
        for record in await self.store.list_vehicles():
            self.vehicles[record.id] = FakeVehicle(
                record.spec, "connecting" if record.auto_connect else "registered"
            )
        self.started = True

    async def stop(self) -> None:
        self.started = False

    async def add(self, spec: VehicleSpec, connect: bool = True) -> FakeVehicle:
        await self.store.add_vehicle(spec, auto_connect=connect)
        vehicle = FakeVehicle(spec, "connecting" if connect else "registered")
        self.vehicles[spec.id] = vehicle
        return vehicle

    async def update(self, vehicle_id: str, **changes: Any) -> FakeVehicle:
        vehicle = self.get(vehicle_id)
        record = await self.store.update_vehicle(vehicle_id, **changes)
        vehicle.spec = record.spec
        return vehicle

    async def remove(self, vehicle_id: str) -> None:
        self.get(vehicle_id)
        await self.store.remove_vehicle(vehicle_id)
        del self.vehicles[vehicle_id]

    def get(self, vehicle_id: str) -> FakeVehicle:
        if vehicle_id not in self.vehicles:
            raise UnknownVehicle(vehicle_id, list(self.vehicles))
        return self.vehicles[vehicle_id]

    def all(self) -> list[FakeVehicle]:
        return list(self.vehicles.values())

    async def connect(self, vehicle_id: str) -> None:
        self.get(vehicle_id).state = "connecting"

    async def disconnect(self, vehicle_id: str) -> None:
        self.get(vehicle_id).state = "registered"
