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
from typing import Final, Literal

from pydantic import TypeAdapter
from typing_extensions import TypedDict  # pydantic validates it on Python 3.11

from gateway.fleet.vehicles.protocols import VehicleView
from gateway.link.telemetry import VALUE_TYPES, Sample, StatusTextValue, TelemetryCache
from gateway.util.json_types import JsonObject, JsonValue

SNAPSHOT_VERSION: Final = 1

STATUS_TEXTS_SENT = 10


class StatusTextBody(TypedDict):
    """A `StatusTextValue` as a snapshot carries it."""

    t: float
    severity: str
    text: str


class Snapshot(TypedDict):
    """What an owner publishes of one vehicle (`encode`; `decode` checks a received one is this)."""

    v: Literal[1]  # SNAPSHOT_VERSION
    id: str
    node: str
    epoch: int
    seq: int
    sent_at: float
    status: JsonObject  # the owner's ``Vehicle.status()``
    live: bool
    #: stream name -> [its value as JSON, its age at the owner in seconds]
    tele: dict[str, tuple[JsonValue, float]]
    texts: list[StatusTextBody]
    operation: JsonObject | None  # the owner's current operation


_SNAPSHOT = TypeAdapter(Snapshot)


def _plain(value: object) -> JsonValue:
    """A cached value as JSON: a dataclass its fields, an enum its value, anything else of no JSON type
    its text."""
    if is_dataclass(value) and not isinstance(value, type):
        fields_: JsonObject = asdict(value)
        return fields_
    if isinstance(value, enum.Enum):
        return _plain(value.value)
    if value is None or isinstance(value, bool | int | float | str):
        return value
    return str(value)


def encode(
    vehicle: VehicleView, node_id: str, epoch: int, seq: int, operation: JsonObject | None = None
) -> bytes:
    """The snapshot of a local vehicle, as JSON bytes."""
    cache = vehicle.telemetry
    tele: dict[str, tuple[JsonValue, float]] = {}
    for name in TelemetryCache.FIELDS:
        sample: Sample[object] | None = getattr(cache, name)
        if sample is not None:
            tele[name] = (_plain(sample.value), round(sample.age_s, 3))
    body: Snapshot = {
        "v": SNAPSHOT_VERSION,
        "id": vehicle.id,
        "node": node_id,
        "epoch": epoch,
        "seq": seq,
        "sent_at": time.time(),
        "status": vehicle.status(),
        "live": cache.live,
        "tele": tele,
        "texts": [
            {"t": t.t, "severity": t.severity, "text": t.text}
            for t in list(cache.status_texts)[-STATUS_TEXTS_SENT:]
        ],
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


def decode(payload: bytes) -> Snapshot:
    """A received snapshot (raises ValueError on anything that is not one of this version)."""
    return _SNAPSHOT.validate_json(payload)  # its ValidationError is a ValueError


def apply(cache: TelemetryCache, body: Snapshot, now: float | None = None) -> None:
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
    texts = [StatusTextValue(**t) for t in body.get("texts") or []]
    cache.status_texts = deque(texts, maxlen=cache.status_texts.maxlen)
