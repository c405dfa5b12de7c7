"""The Registry: which vehicles exist (persisted through the Store) and their live Vehicle objects.

    store = await Store.open(settings.database_url)
    registry = Registry(settings, store)
    await registry.start()                      # restore registrations, connect the auto_connect ones
    v = await registry.add(VehicleSpec(id="alpha", url="tcpout://127.0.0.1:5760", expected_sysid=1))
    await v.wait_for_state("ready", within_s=60)
    await v.takeoff(10)                         # returns once accepted; poll v.telemetry for progress
    ...
    await registry.stop()                       # no mavsdk_server process remains

Each Vehicle owns one mavsdk_server sidecar (gateway.link.sidecar), its telemetry cache
(gateway.link.telemetry) and its flight recorder (gateway.fleet.flightlog).
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any

from pydantic import ValidationError

from gateway.config import Settings
from gateway.errors import InvalidArgument, UnknownVehicle
from gateway.fleet.vehicle import ConnectionState, Vehicle
from gateway.link.sidecar import Confine
from gateway.registry.spec import VehicleSpec
from gateway.registry.store import Store

log = logging.getLogger("gateway.registry")

StateListener = Callable[[Vehicle, ConnectionState, ConnectionState], None]


class Registry:
    """Owns one Vehicle (and through it one sidecar) per registered drone."""

    def __init__(self, settings: Settings, store: Store, *, confine: Confine | None = None) -> None:
        self.settings = settings
        self.store = store
        self._confine = confine
        self._vehicles: dict[str, Vehicle] = {}
        self._listeners: list[StateListener] = []
        self._lock = asyncio.Lock()
        self._started = False

    # --- lifecycle --------------------------------------------------------------------------------------
    async def start(self) -> None:
        """Restore every registered vehicle; connect those with auto_connect."""
        async with self._lock:
            if self._started:
                return
            self._started = True
            for record in await self.store.list_vehicles():
                try:
                    spec = VehicleSpec.model_validate(
                        record.model_dump(include={"id", "url", "name", "tags", "expected_sysid"})
                    )
                except ValidationError as exc:  # a row edited by hand must not keep the others down
                    log.error("not restoring vehicle %r: invalid registration: %s", record.id, exc)
                    continue
                vehicle = self._make(spec)
                if record.auto_connect:
                    await vehicle.connect()
            log.info("registry started with %d vehicle(s)", len(self._vehicles))

    async def stop(self) -> None:
        """Disconnect every vehicle; no mavsdk_server process remains afterwards."""
        async with self._lock:
            vehicles = list(self._vehicles.values())
            results = await asyncio.gather(*(v.disconnect() for v in vehicles), return_exceptions=True)
            for vehicle, result in zip(vehicles, results, strict=True):
                if isinstance(result, BaseException):
                    log.error("stopping %s failed: %r", vehicle.id, result)
            self._vehicles.clear()
            self._started = False

    # --- registrations ----------------------------------------------------------------------------------
    async def add(self, spec: VehicleSpec | dict[str, Any], connect: bool = True) -> Vehicle:
        """Register (persist) a vehicle and, by default, connect it. Raises DuplicateVehicle."""
        spec = _validate_spec(spec)
        async with self._lock:
            await self.store.add_vehicle(spec, auto_connect=connect)
            vehicle = self._make(spec)
        if connect:
            await vehicle.connect()
        return vehicle

    async def update(self, vehicle_id: str, **changes: Any) -> Vehicle:
        """Change name, tags, expected_sysid, url or auto_connect; a new URL reconnects the vehicle."""
        old = self.get(vehicle_id)
        record = await self.store.update_vehicle(vehicle_id, **changes)
        spec = VehicleSpec.model_validate(
            record.model_dump(include={"id", "url", "name", "tags", "expected_sysid"})
        )
        was_connected = old.sidecar is not None
        if spec.url != old.spec.url and was_connected:
            await old.disconnect()
            old.spec = spec
            await old.connect()
        else:
            old.spec = spec
        return old

    async def remove(self, vehicle_id: str) -> None:
        vehicle = self.get(vehicle_id)
        await vehicle.disconnect()
        await self.store.remove_vehicle(vehicle_id)
        self._vehicles.pop(vehicle_id, None)

    def get(self, vehicle_id: str) -> Vehicle:
        vehicle = self._vehicles.get(vehicle_id) if isinstance(vehicle_id, str) else None
        if vehicle is None:
            raise UnknownVehicle(str(vehicle_id)[:64], list(self._vehicles))
        return vehicle

    def all(self) -> list[Vehicle]:
        return [self._vehicles[k] for k in sorted(self._vehicles)]

    async def connect(self, vehicle_id: str) -> Vehicle:
        vehicle = self.get(vehicle_id)
        await vehicle.connect()
        await self.store.update_vehicle(vehicle_id, auto_connect=True)
        return vehicle

    async def disconnect(self, vehicle_id: str) -> Vehicle:
        vehicle = self.get(vehicle_id)
        await vehicle.disconnect()
        await self.store.update_vehicle(vehicle_id, auto_connect=False)
        return vehicle

    def on_state_change(self, listener: StateListener) -> None:
        """``listener(vehicle, old, new)`` on every connection state change (e.g. MCP resource updates)."""
        self._listeners.append(listener)

    # --- internals --------------------------------------------------------------------------------------
    def _make(self, spec: VehicleSpec) -> Vehicle:
        vehicle = Vehicle(
            spec,
            self.settings,
            store=self.store,
            peers=self.all,
            confine=self._confine,
            on_state=self._state_changed,
        )
        self._vehicles[spec.id] = vehicle
        return vehicle

    def _state_changed(self, vehicle: Vehicle, old: ConnectionState, new: ConnectionState) -> None:
        for listener in list(self._listeners):
            try:
                listener(vehicle, old, new)
            except Exception:
                log.exception("state listener failed")


def _validate_spec(spec: VehicleSpec | dict[str, Any]) -> VehicleSpec:
    try:
        return VehicleSpec.model_validate(spec.model_dump() if isinstance(spec, VehicleSpec) else spec)
    except ValidationError as exc:
        problems = "; ".join(f"{'.'.join(map(str, e['loc'])) or 'spec'}: {e['msg']}" for e in exc.errors())
        raise InvalidArgument(f"invalid vehicle registration: {problems}") from None
