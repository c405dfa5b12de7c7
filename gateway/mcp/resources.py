"""MCP resources (fleet://drones, drone://{id}/state, drone://{id}/mission), their change notifications,
and the prompts.

Change notifications go out at most once a second per resource: a 1 Hz loop compares a fingerprint of
each resource and, when it changed, publishes ``ResourceUpdated`` on the subscription bus (2026-07-28
``subscriptions/listen``) and sends ``notifications/resources/updated`` to the 2025-era sessions that
subscribed with ``resources/subscribe``.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
from collections.abc import AsyncIterator, Callable
from typing import TypeVar

from mcp.server.mcpserver import AssistantMessage, UserMessage
from mcp.server.mcpserver.exceptions import ResourceError, ResourceNotFoundError
from mcp.server.session import ServerSession
from mcp.server.subscriptions import InMemorySubscriptionBus, ResourceUpdated
from mcp.types import EmptyResult, SubscribeRequestParams, UnsubscribeRequestParams

from gateway.errors import GatewayError, NotFound, UnknownVehicle
from gateway.fleet.commands.commander import Commander
from gateway.fleet.operations.fleet_operation import FleetOperation
from gateway.fleet.vehicles.readings import position, value
from gateway.mcp import sdk_private
from gateway.mcp.results import plain, plain_object, surface_telemetry
from gateway.mcp.sdk_types import AnyServer, RequestContext
from gateway.runtime import Gateway
from gateway.util.json_types import JsonValue

log = logging.getLogger(__name__)
T = TypeVar("T")

NOTIFY_PERIOD_S = 1.0
FORMATION_URI = "fleet://formation"


def drones_json(commander: Commander) -> list[dict[str, object]]:
    out: list[dict[str, object]] = []
    for v in commander.registry.all():
        op = commander.operations.running(v.id)
        out.append(
            {
                "drone_id": v.id,
                "name": v.spec.name,
                "state": str(plain(v.state)),
                "armed": value(v.telemetry.armed),
                "in_air": value(v.telemetry.in_air),
                "operation": None if op is None else op.kind,
            }
        )
    return out


#: what an agent is never told of a sidecar: how to reach it around the gateway (gRPC) and its process
SIDECAR_PRIVATE = ("pid", "grpc_port")


def agent_status(status: dict[str, JsonValue]) -> dict[str, JsonValue]:
    """A vehicle's status as an agent may read it: the sidecar's state, not its process or gRPC port."""
    sidecar = status.get("sidecar")
    if isinstance(sidecar, dict):
        status = {**status, "sidecar": {k: v for k, v in sidecar.items() if k not in SIDECAR_PRIVATE}}
    return status


def state_json(commander: Commander, drone_id: str) -> dict[str, object]:
    v = commander.vehicle(drone_id)
    op = commander.operations.latest(drone_id)
    return {
        "drone_id": drone_id,
        "status": agent_status(plain_object(v.status())),
        "telemetry": surface_telemetry(plain_object(v.telemetry.snapshot())),
        "operation": None if op is None else op.to_dict(),
    }


async def mission_json(commander: Commander, drone_id: str) -> dict[str, object]:
    v = commander.ready(drone_id)
    items = await v.download_mission()
    prog = value(v.telemetry.mission_progress)
    return {
        "drone_id": drone_id,
        "current": None if prog is None else int(prog.current),
        "items": [
            {
                "index": n,
                "kind": i.kind,
                "lat_deg": i.lat,
                "lon_deg": i.lon,
                "alt_m": i.alt_rel_m,
                "hold_s": i.hold_s,
                "speed_mps": i.speed_mps,
            }
            for n, i in enumerate(items, 1)
        ],
    }


def formation_json(commander: Commander) -> dict[str, object]:
    """The last formation: its plan and progress (per drone), or a note that none was flown."""
    fop = commander.fleet.latest("formation_goto")
    if fop is None:
        return {"formation": None, "message": "no formation flown yet"}
    return {**fop.to_dict(), "plan": fop.plan}


class ResourceNotifier:
    """Tracks resource fingerprints and notifies subscribers of changes (1 Hz at most); the formation
    resource is notified when a formation changes phase or a drone's outcome (not on every tick)."""

    def __init__(self, gateway: Gateway, bus: InMemorySubscriptionBus, formation: bool) -> None:
        self.gateway = gateway
        self.bus = bus
        self.formation = formation
        self.legacy: dict[str, set[ServerSession]] = {}
        self._last: dict[str, object] = {}
        self._pending: set[asyncio.Task[None]] = set()

    def install(self, server: AnyServer) -> None:
        """Serve 2025-era ``resources/subscribe`` (the SDK's bus serves only 2026-07-28 listeners)."""

        async def on_subscribe(ctx: RequestContext, p: SubscribeRequestParams) -> EmptyResult:
            self.legacy.setdefault(str(p.uri), set()).add(ctx.session)
            return EmptyResult()

        async def on_unsubscribe(ctx: RequestContext, p: UnsubscribeRequestParams) -> EmptyResult:
            self.legacy.get(str(p.uri), set()).discard(ctx.session)
            return EmptyResult()

        sdk_private.add_request_handler(server, "resources/subscribe", SubscribeRequestParams, on_subscribe)
        sdk_private.add_request_handler(
            server, "resources/unsubscribe", UnsubscribeRequestParams, on_unsubscribe
        )

    def fingerprints(self, commander: Commander) -> dict[str, object]:
        prints: dict[str, object] = {}
        vehicles = list(commander.registry.all())
        prints["fleet://drones"] = json.dumps(drones_json(commander), sort_keys=True, default=str)
        for v in vehicles:
            pos = position(v)
            op = commander.operations.latest(v.id)
            prints[f"drone://{v.id}/state"] = (
                str(v.state),
                value(v.telemetry.armed),
                value(v.telemetry.in_air),
                str(value(v.telemetry.flight_mode)),
                None if pos is None else (round(pos[0], 6), round(pos[1], 6), round(pos[2], 1)),
                None if op is None else (op.id, op.status.value, round(op.progress, 2)),
            )
            prog = value(v.telemetry.mission_progress)
            mission_op = op if op is not None and op.kind == "mission" else None
            prints[f"drone://{v.id}/mission"] = (
                None if prog is None else (int(prog.current), int(prog.total)),
                None if mission_op is None else mission_op.status.value,
            )
        return prints

    async def publish(self, uri: str) -> None:
        await self.bus.publish(ResourceUpdated(uri=uri))
        for session in list(self.legacy.get(uri, ())):
            try:
                await session.send_resource_updated(uri)
            except Exception:  # a session that went away stops being notified
                self.legacy[uri].discard(session)

    async def tick(self, commander: Commander) -> list[str]:
        prints = self.fingerprints(commander)
        changed = [uri for uri, fp in prints.items() if uri in self._last and self._last[uri] != fp]
        self._last = prints
        for uri in changed:
            await self.publish(uri)
        return changed

    async def run(self) -> None:
        while True:
            try:
                if self.gateway.ready:
                    await self.tick(self.gateway.commander)
            except Exception:
                log.exception("resource notifier tick failed")
            await asyncio.sleep(NOTIFY_PERIOD_S)

    def _on_fleet_change(self, fop: FleetOperation) -> None:
        if fop.kind != "formation_goto":
            return
        task = asyncio.get_running_loop().create_task(self._publish_quietly(FORMATION_URI))
        self._pending.add(task)  # keeps the task alive until it ran
        task.add_done_callback(self._pending.discard)

    async def _publish_quietly(self, uri: str) -> None:
        try:
            await self.publish(uri)
        except Exception:  # a notification must never break a flight
            log.exception("could not publish %s", uri)

    @contextlib.asynccontextmanager
    async def running(self) -> AsyncIterator[None]:
        """For the MCP server's lifespan: the 1 Hz loop, and formation notices while the gateway runs."""
        fleet = self.gateway.fleet_operations
        if self.formation and fleet is not None:
            fleet.listeners.append(self._on_fleet_change)
        task = asyncio.create_task(self.run(), name="mcp-resource-notifier")
        try:
            yield
        finally:
            task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await task
            if fleet is not None:
                with contextlib.suppress(ValueError):
                    fleet.listeners.remove(self._on_fleet_change)


def _resource_error(exc: GatewayError) -> ResourceError:
    """Unknown drone -> not found (-32602 with the uri); anything else -> a resource error."""
    if isinstance(exc, UnknownVehicle | NotFound):
        return ResourceNotFoundError(exc.message)
    return ResourceError(exc.message)


def _guard(fn: Callable[[], T]) -> T:
    try:
        return fn()
    except GatewayError as exc:
        raise _resource_error(exc) from None


def register_resources(server: AnyServer, gateway: Gateway, formation: bool) -> None:
    if formation:

        @server.resource(
            FORMATION_URI, mime_type="application/json", description="Last formation: plan+progress"
        )
        def fleet_formation() -> str:
            return json.dumps(_guard(lambda: formation_json(gateway.commander)), default=str)

    @server.resource(
        "fleet://drones", mime_type="application/json", description="All drones: id, state, action"
    )
    def fleet_drones() -> str:
        return json.dumps(_guard(lambda: drones_json(gateway.commander)), default=str)

    @server.resource("drone://{drone_id}/state", mime_type="application/json", description="Status+telemetry")
    def drone_state(drone_id: str) -> str:
        return json.dumps(_guard(lambda: state_json(gateway.commander, drone_id)), default=str)

    @server.resource("drone://{drone_id}/mission", mime_type="application/json", description="Mission items")
    async def drone_mission(drone_id: str) -> str:
        try:
            return json.dumps(await mission_json(gateway.commander, drone_id), default=str)
        except GatewayError as exc:
            raise _resource_error(exc) from None


def register_prompts(server: AnyServer) -> None:
    @server.prompt(title="Preflight check")
    def preflight_check(drone_id: str) -> list[UserMessage | AssistantMessage]:
        """Check a drone is fit to fly before takeoff."""
        return [
            UserMessage(
                f"Run a preflight check of drone '{drone_id}' before we fly. Call get_telemetry, "
                "get_health_all_ok, get_battery, get_gps_info and print_status_text. Report: link state "
                "and data age, health failures, battery %, GPS fix and satellites, home position, and any "
                "warning texts. Conclude GO or NO-GO with the reason. Do not arm or take off."
            ),
            AssistantMessage(f"I'll read drone://{drone_id}/state and run the checks, without arming."),
        ]

    @server.prompt(title="Area survey")
    def survey_area(
        drone_id: str, area: str, alt_m: str = "30", spacing_m: str = "20"
    ) -> list[UserMessage | AssistantMessage]:
        """Plan and fly a lawnmower survey of an area."""
        return [
            UserMessage(
                f"Survey {area} with drone '{drone_id}' at {alt_m} m above home, lanes {spacing_m} m "
                "apart. Steps: preflight check (get_telemetry, get_battery); plan a lawnmower pattern of "
                "waypoints (lat_deg, lon_deg, alt_m above home) covering the area; show me the plan; then "
                "initiate_mission with a takeoff item first and an rtl item last. While it runs, call "
                "monitor_flight until the status is no longer 'running', then report."
            )
        ]
