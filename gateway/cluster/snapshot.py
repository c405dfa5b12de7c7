"""Telemetry snapshots between nodes: what an owner publishes of one vehicle, and how others rebuild it.

A snapshot carries the vehicle's status (state, sysid, autopilot...), every cached telemetry value with
its age when sent, the last status texts and the owner's current operation. The receiver rebuilds the
same :class:`~gateway.link.telemetry.TelemetryCache` values, each aged by what it was at the owner, so
freshness rules (stale after ``link_lost_after_s``) hold on every node.
"""

from __future__ import annotations

import enum
import json
import time
from collections import deque
from dataclasses import asdict, fields, is_dataclass
from typing import Any

from gateway.fleet.vehicles.protocols import VehicleView
from gateway.link.telemetry import VALUE_TYPES, Sample, StatusTextValue, TelemetryCache

SNAPSHOT_VERSION = 1

STATUS_TEXTS_SENT = 10


def _plain(value: object) -> object:
    if is_dataclass(value) and not isinstance(value, type):
        return asdict(value)
    if isinstance(value, enum.Enum):
        return value.value
    return value


def encode(
    vehicle: VehicleView, node_id: str, epoch: int, seq: int, operation: dict[str, Any] | None = None
) -> bytes:
    """The snapshot of a local vehicle, as JSON bytes."""
    cache = vehicle.telemetry
    tele: dict[str, Any] = {}
    for name in TelemetryCache.FIELDS:
        sample: Sample[object] | None = getattr(cache, name)
        if sample is not None:
            tele[name] = [_plain(sample.value), round(sample.age_s, 3)]
    body = {
        "v": SNAPSHOT_VERSION,
        "id": vehicle.id,
        "node": node_id,
        "epoch": epoch,
        "seq": seq,
        "sent_at": time.time(),
        "status": vehicle.status(),
        "live": cache.live,
        "tele": tele,
        "texts": [asdict(t) for t in list(cache.status_texts)[-STATUS_TEXTS_SENT:]],
        "operation": operation,
    }
    return json.dumps(body, default=str, separators=(",", ":")).encode()


def _rebuild(name: str, raw: object) -> object:
    kind = VALUE_TYPES.get(name)
    if kind is None or not isinstance(raw, dict):
        return raw
    values = {}
    for f in fields(kind):
        v = raw.get(f.name)
        values[f.name] = tuple(v) if isinstance(v, list) else v
    return kind(**values)


def decode(payload: bytes) -> dict[str, Any]:
    """A received snapshot (raises ValueError on anything that is not one)."""
    body = json.loads(payload)
    if not isinstance(body, dict) or body.get("v") != SNAPSHOT_VERSION or not isinstance(body.get("id"), str):
        raise ValueError("not a telemetry snapshot of this version")
    return body


def apply(cache: TelemetryCache, body: dict[str, Any], now: float | None = None) -> None:
    """Replace ``cache``'s values with the snapshot's, each as old as it was at the owner."""
    now = time.monotonic() if now is None else now
    tele = body.get("tele") or {}
    for name in TelemetryCache.FIELDS:
        item = tele.get(name)
        if item is None:
            setattr(cache, name, None)
            continue
        raw, age = item
        setattr(cache, name, Sample(_rebuild(name, raw), now - max(0.0, float(age))))
        cache.message_counts[name] = cache.message_counts.get(name, 0) + 1
    cache.live = bool(body.get("live", True))
    texts = [StatusTextValue(**t) for t in body.get("texts") or [] if isinstance(t, dict)]
    cache.status_texts = deque(texts, maxlen=cache.status_texts.maxlen)
