"""What the MCP tools need from the gateway: vehicles, safety checks, operations, and the waiting logic."""

from __future__ import annotations

import contextlib
from collections.abc import Awaitable, Callable
from typing import Any

from mcp.server.mcpserver import Context

from gateway.errors import SafetyRefusal, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.operations import Operation, OperationManager, Tracker, position, value
from gateway.mcp.results import OperationOut
from gateway.mcp.scopes import ScopedRegistry, current_scope, scopes_by_principal
from gateway.mcp.toolkit import current_call


class FleetAccess:
    """A thin view of the runtime ``Gateway`` (settings, registry, store, operations, safety)."""

    def __init__(self, gateway: Any) -> None:
        self.gateway = gateway
        self.settings = gateway.settings
        operations = getattr(gateway, "operations", None)
        if operations is None:
            operations = OperationManager(self.settings, store_getter=lambda: getattr(gateway, "store", None))
            gateway.operations = operations
        self.operations: OperationManager = operations
        self._scopes = scopes_by_principal(self.settings)

    # -- vehicles ----------------------------------------------------------------------------------
    @property
    def registry(self) -> Any:
        """The registry, as the calling agent may see it (GATEWAY_AGENT_SCOPES)."""
        registry = self.gateway.registry
        scope = current_scope(self._scopes)
        return registry if scope is None or registry is None else ScopedRegistry(registry, scope)

    @property
    def store(self) -> Any:
        return getattr(self.gateway, "store", None)

    @property
    def safety(self) -> Any:
        policy = getattr(self.gateway, "safety", None)
        if policy is None:
            from gateway.fleet.safety import SafetyPolicy

            locks = getattr(self.gateway, "locks", None)
            if locks is not None and hasattr(locks, "view"):
                locks = locks.view()
            policy = SafetyPolicy.from_settings(self.settings, locks)
            self.gateway.safety = policy
        return policy

    def vehicle(self, drone_id: str) -> Any:
        """The registered vehicle (raises UnknownVehicle listing the known ids)."""
        return self.registry.get(drone_id)

    def ready(self, drone_id: str) -> Any:
        vehicle = self.vehicle(drone_id)
        vehicle.require_ready()
        return vehicle

    async def ready_to_arm(self, drone_id: str, ctx: Any | None = None) -> Any:
        """The vehicle once it can be armed: one that is still initialising is waited for (capped),
        and the client is told what it waits for."""
        vehicle = self.vehicle(drone_id)
        waiting = vehicle.initialising()
        if waiting is not None and ctx is not None:
            with contextlib.suppress(Exception):  # progress is a courtesy; the wait happens regardless
                await ctx.report_progress(0.0, 1.0, f"{drone_id}: {waiting}")
        await vehicle.wait_initialised()
        return vehicle

    def session_key(self) -> str | None:
        call = current_call.get()
        return None if call is None else call.session_key

    # -- safety ------------------------------------------------------------------------------------
    def context(self, vehicle: Any) -> Any:
        from gateway.fleet.safety import VehicleContext

        battery = value(vehicle, "battery")
        h = value(vehicle, "home")
        status = vehicle.status()
        return VehicleContext(
            vehicle_id=vehicle.id,
            is_simulator=bool(status.get("is_simulator")),
            armed=bool(value(vehicle, "armed")),
            in_air=bool(value(vehicle, "in_air")),
            battery_pct=None if battery is None else battery.remaining_pct,
            home=None if h is None else (h.lat_deg, h.lon_deg, h.abs_alt_m),
            position=position(vehicle),
        )

    def target(self, lat: float, lon: float, alt_rel_m: float) -> Any:
        from gateway.fleet.safety import Target

        return Target(lat=lat, lon=lon, alt_rel_m=alt_rel_m)

    def check_motion(self, vehicle: Any, lat: float, lon: float, alt_rel_m: float) -> None:
        ctx = self.context(vehicle)
        self.safety.check_actuation(ctx)
        self.safety.check_motion(ctx, self.target(lat, lon, alt_rel_m))

    def guard_takeoff(self, vehicle: Any, action: str) -> None:
        """Refuse motion while a takeoff has not reached its altitude (the paper's crash)."""
        op = self.operations.takeoff_in_progress(vehicle.id)
        if op is None:
            return
        pos = position(vehicle)
        alt = f"{pos[2]:.1f}" if pos else "?"
        target = op.params.get("altitude_m")
        raise SafetyRefusal(
            "takeoff_in_progress",
            f"takeoff_in_progress: {vehicle.id} is still taking off ({alt} of {target} m above home); "
            f"{action} was not sent. Wait for takeoff to finish: call "
            f"monitor_flight(drone_id='{vehicle.id}'), then send {action} again.",
            operation_id=op.id,
        )

    def require_airborne(self, vehicle: Any, action: str) -> None:
        if value(vehicle, "in_air") is not True or value(vehicle, "armed") is not True:
            raise VehicleNotReady(
                f"{vehicle.id} is on the ground; {action} needs a flying drone. Call takeoff first."
            )

    def relative_alt(self, vehicle: Any, altitude_m: float, alt_frame: str) -> float:
        """Tool altitude -> metres above home (the frame conversion lives in geo)."""
        geo.check_finite("altitude_m", altitude_m)
        if alt_frame == "home":
            return altitude_m
        h = value(vehicle, "home")
        if h is None:
            raise VehicleNotReady(f"{vehicle.id} has no home position yet; cannot convert an AMSL altitude")
        return geo.amsl_to_relative(altitude_m, h.abs_alt_m)

    # -- operations --------------------------------------------------------------------------------
    async def run(
        self,
        ctx: Context,
        vehicle: Any,
        tracker: Tracker,
        send: Callable[[], Awaitable[Any]],
        params: dict[str, Any],
        wait: bool,
        action: str,
    ) -> OperationOut:
        def precheck() -> None:
            if tracker.kind not in ("land", "return_to_launch"):
                self.guard_takeoff(vehicle, action)

        op = await self.operations.start(vehicle, tracker, send, params, self.session_key(), precheck)
        if wait:
            await self.wait(ctx, op)
        return self.out(op, vehicle, action)

    async def wait(self, ctx: Context, op: Operation, cap_s: float | None = None) -> Operation:
        async def on_progress(o: Operation) -> None:
            await ctx.report_progress(round(o.progress, 3), 1.0, o.message)

        return await self.operations.wait(op, cap_s, on_progress)

    def out(self, op: Operation, vehicle: Any, action: str | None = None) -> OperationOut:
        pos = position(vehicle)
        name = action or op.kind
        if op.status == "running":
            eta = f", ETA {op.eta_s:.0f} s" if op.eta_s is not None else ""
            text = (
                f"{name} on {op.vehicle_id} still running ({op.progress:.0%}{eta}): {op.message}. "
                f"Call monitor_flight(drone_id='{op.vehicle_id}') to keep waiting."
            )
        else:
            text = f"{name} on {op.vehicle_id} {op.status}: {op.message}"
        return OperationOut(
            drone_id=op.vehicle_id,
            operation_id=op.id,
            kind=op.kind,
            status=op.status.value,
            progress=round(op.progress, 3),
            message=op.message,
            eta_s=None if op.eta_s is None else round(op.eta_s, 1),
            elapsed_s=round(op.elapsed_s(), 1),
            lat_deg=None if pos is None else pos[0],
            lon_deg=None if pos is None else pos[1],
            alt_m=None if pos is None else round(pos[2], 2),
        ).say(text)
