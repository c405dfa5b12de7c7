"""/metrics: Prometheus text exposition from a CollectorRegistry of this app (several apps can coexist)."""

from __future__ import annotations

import time
from collections import Counter as Tally
from collections.abc import AsyncIterator, Iterator
from contextlib import asynccontextmanager
from typing import TYPE_CHECKING

from fastapi import APIRouter, Depends, FastAPI, Request, Response
from prometheus_client import CONTENT_TYPE_LATEST, CollectorRegistry, Counter, Histogram, generate_latest
from prometheus_client.core import CounterMetricFamily, GaugeMetricFamily, Metric
from prometheus_client.registry import Collector
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from gateway.api.deps import authorize
from gateway.errors import SafetyRefusal
from gateway.fleet.vehicles.protocols import VehicleView
from gateway.registry.records import AuditRecord

if TYPE_CHECKING:
    from gateway.runtime import Gateway

CONNECTION_STATES = ("registered", "connecting", "connected", "ready", "link_lost", "failed")

router = APIRouter(tags=["health"])


def _state_name(vehicle: VehicleView) -> str:
    return str(vehicle.state)


class FleetCollector(Collector):
    """Reads the fleet at scrape time: vehicles by state, sidecar restarts, telemetry message counts."""

    def __init__(self, gateway: Gateway) -> None:
        self.gateway = gateway

    def collect(self) -> Iterator[Metric]:
        registry = self.gateway.registry if self.gateway.ready else None
        vehicles = list(registry.all()) if registry is not None else []
        up = GaugeMetricFamily("fleet_gateway_ready", "1 when the database is open and the registry runs")
        up.add_metric([], 1.0 if self.gateway.ready else 0.0)
        yield up

        by_state = GaugeMetricFamily(
            "fleet_gateway_vehicles", "Registered vehicles by connection state", labels=["state"]
        )
        tally = Tally(_state_name(v) for v in vehicles)
        for state in sorted(set(CONNECTION_STATES) | set(tally)):
            by_state.add_metric([state], tally.get(state, 0))
        yield by_state

        restarts = CounterMetricFamily(
            "fleet_gateway_sidecar_restarts", "mavsdk_server sidecar restarts per vehicle", labels=["vehicle"]
        )
        messages = CounterMetricFamily(
            "fleet_gateway_telemetry_messages",
            "Telemetry updates received per vehicle and stream (use rate() for messages per second)",
            labels=["vehicle", "stream"],
        )
        heartbeat = GaugeMetricFamily(
            "fleet_gateway_heartbeat_age_seconds",
            "Seconds since the vehicle's last HEARTBEAT",
            labels=["vehicle"],
        )
        ages = GaugeMetricFamily(
            "fleet_gateway_telemetry_age_seconds",
            "Age of the newest cached sample per vehicle and stream",
            labels=["vehicle", "stream"],
        )
        for vehicle in vehicles:
            status = vehicle.status()
            sidecar = status.get("sidecar")
            count = sidecar.get("restarts") if isinstance(sidecar, dict) else None
            restarts.add_metric([vehicle.id], float(count) if isinstance(count, int) else 0.0)
            age = status.get("last_heartbeat_age_s")
            if isinstance(age, int | float):
                heartbeat.add_metric([vehicle.id], float(age))
            for stream, count in _message_counts(vehicle).items():
                messages.add_metric([vehicle.id, stream], float(count))
            for stream, age in _sample_ages(vehicle).items():
                ages.add_metric([vehicle.id, stream], age)
        yield restarts
        yield messages
        yield heartbeat
        yield ages


def _sample_ages(vehicle: VehicleView) -> dict[str, float]:
    """Age of each telemetry part the cache holds (parts never received are left out)."""
    cache = vehicle.telemetry
    ages: dict[str, float] = {}
    for name in cache.FIELDS:
        sample = getattr(cache, name)
        if sample is not None:
            ages[name] = float(sample.age_s)
    return ages


def _message_counts(vehicle: VehicleView) -> dict[str, int]:
    """Per-stream update counts of the vehicle's telemetry cache."""
    return dict(vehicle.telemetry.message_counts)


def route_template(scope: Scope) -> str:
    """The matched route's full path template (``/api/v1/vehicles/{vehicle_id}``), for low-cardinality labels.

    Included routers keep their routes' own (relative) templates, so the prefix is taken from the
    request path: its leading segments that the relative template does not cover.
    """
    relative = getattr(scope.get("route"), "path", None)
    if not relative:
        return "<unmatched>"
    segments = scope.get("path", "").rstrip("/").split("/")
    covered = relative.rstrip("/").count("/")
    prefix = "/".join(segments[: len(segments) - covered]) if covered else "/".join(segments)
    return (prefix + relative) or "/"


class RequestMetricsMiddleware:
    """Pure ASGI middleware (no body buffering, safe for streamed /mcp responses, which it skips)."""

    def __init__(self, app: ASGIApp, requests: Counter, latency: Histogram) -> None:
        self.app = app
        self.requests = requests
        self.latency = latency

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http" or scope.get("path", "").startswith("/mcp"):
            await self.app(scope, receive, send)
            return
        started = time.perf_counter()
        status = 500

        async def send_wrapper(message: Message) -> None:
            nonlocal status
            if message["type"] == "http.response.start":
                status = message["status"]
            await send(message)

        try:
            await self.app(scope, receive, send_wrapper)
        finally:
            template = route_template(scope)
            self.requests.labels(scope.get("method", ""), template, str(status)).inc()
            self.latency.labels(template).observe(time.perf_counter() - started)


class AuditMetrics:
    """Counts every audited call once its outcome is known (a call left running counts when its
    operation ends): calls by door, action and outcome; refusals by rule (a refusal's message begins
    with its rule); how calls that ran an operation ended."""

    def __init__(self, registry: CollectorRegistry) -> None:
        self.calls = Counter(
            "fleet_gateway_calls",
            "Audited calls (MCP tools, REST and console actions) by door, action and outcome",
            ["source", "action", "outcome"],
            registry=registry,
        )
        self.refusals = Counter(
            "fleet_gateway_refusals",
            "Calls refused by the safety policy, by rule",
            ["rule"],
            registry=registry,
        )
        self.operations = Counter(
            "fleet_gateway_operation_outcomes",
            "Calls that started a tracked operation, by how the operation ended",
            ["outcome"],
            registry=registry,
        )

    def record(self, row: AuditRecord) -> None:
        if row.outcome == "running":
            return
        self.calls.labels(row.source, row.action, row.outcome).inc()
        if row.outcome == "refused":
            text = (row.error or "").removeprefix(f"{SafetyRefusal.code}: ")  # REST rows name the code first
            rule = text.split(":", 1)[0].strip()
            self.refusals.labels(rule if rule.replace("_", "").isalnum() else "other").inc()
        if row.operation_id is not None:
            self.operations.labels(row.outcome).inc()


def install_metrics(app: FastAPI, gateway: Gateway) -> CollectorRegistry:
    """Create the app's registry, its HTTP request metrics and the fleet collector."""
    registry = CollectorRegistry(auto_describe=True)
    registry.register(FleetCollector(gateway))
    requests = Counter(
        "fleet_gateway_http_requests",
        "HTTP requests by method, route template and status",
        ["method", "route", "status"],
        registry=registry,
    )
    latency = Histogram(
        "fleet_gateway_http_request_duration_seconds",
        "HTTP request handling time by route template",
        ["route"],
        registry=registry,
    )

    app.add_middleware(RequestMetricsMiddleware, requests=requests, latency=latency)
    app.state.metrics_registry = registry
    audit = AuditMetrics(registry)

    @asynccontextmanager
    async def count_audit() -> AsyncIterator[None]:  # runs once the gateway (and its store) started
        stop = gateway.require_store().on_audit(audit.record)
        try:
            yield
        finally:
            stop()

    app.state.lifespan_hooks.append(count_audit)
    return registry


@router.get(
    "/metrics",
    summary="Prometheus metrics (a viewer or operator token when tokens are configured)",
    response_class=Response,
    dependencies=[Depends(authorize)],  # the fleet's state and positions are not for anyone who asks
)
async def metrics(request: Request) -> Response:
    return Response(generate_latest(request.app.state.metrics_registry), media_type=CONTENT_TYPE_LATEST)
