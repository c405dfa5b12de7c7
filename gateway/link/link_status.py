"""A link's status: its state and what it knows of the vehicle, in one JSON-ready dict (the vehicle's
status, as the REST API, the console and the MCP tools show it)."""

from __future__ import annotations

from datetime import UTC, datetime

from gateway.link.session import Link
from gateway.util.json_types import JsonObject, json_list


def link_status(link: Link) -> JsonObject:
    """The link's state and what it knows of the vehicle (the vehicle's status)."""
    car = link.sidecar
    age = link.last_heartbeat_age_s
    return {
        "id": link.id,
        "name": link.spec.name,
        "url": link.spec.url,
        "tags": json_list(link.spec.tags),
        "state": link.state.value,
        "state_age_s": round(link.state_age_s, 3),
        "last_heartbeat_age_s": None if age is None else round(age, 3),
        "last_heartbeat_at": _iso(link.facts.last_heartbeat_wall),
        "last_error": link.describe_error(),
        "sysid": link.facts.sysid,
        "expected_sysid": link.spec.expected_sysid,
        "sysid_mismatch": link.sysid_mismatch,
        "duplicate_sysid": json_list(link.duplicate_sysid),
        # other autopilots heard on this vehicle's link (mavsdk_server follows only the first)
        "other_sysids_on_link": json_list(sorted(link.facts.sysids_seen - {link.facts.sysid})),
        "is_simulator": link.is_simulator,
        "autopilot": link.autopilot,
        "autopilot_version": link.autopilot_version,
        "flight_mode": link.telemetry.fresh("flight_mode"),
        "armed": link.telemetry.fresh("armed"),
        "initialising": link.initialising(),
        "unsupported_streams": json_list(link.unsupported_streams),
        "sidecar": {
            "state": car.state.value if car else "stopped",
            "pid": car.pid if car else None,
            "grpc_port": car.grpc_port if car else None,
            "restarts": car.info.restarts if car else 0,
        },
        # each ground station endpoint the drone's MAVLink is relayed to, and what passed
        "ground_stations": link.relay.status() if link.relay is not None else [],
        # what the relay carried between the drone and its sidecar (None: the sidecar holds the link)
        "relay": link.relay.carried() if link.relay is not None else None,
    }


def _iso(epoch_s: float | None) -> str | None:
    return None if epoch_s is None else datetime.fromtimestamp(epoch_s, UTC).isoformat()
