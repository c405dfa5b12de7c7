"""The gateway's tables, as SQLAlchemy Core ``Table`` objects on one ``MetaData``.

Alembic owns the schema (``migrations/``, installed as ``gateway.migrations``); these tables describe it
for the store's queries and for ``alembic revision --autogenerate`` (tests/persist/test_store.py checks
that they match the migrations). The store reads and writes them with Core statements on the async
engine's connections, without the ORM (its mappers and sessions cost a serving gateway about 7.5 MiB of
memory: docs/benchmarks.md). Types are portable (SQLite and PostgreSQL): JSON through
``sqlalchemy.JSON``, datetimes always timezone-aware UTC through :class:`UTCDateTime`.
"""

from __future__ import annotations

from datetime import UTC, datetime
from typing import Any

from sqlalchemy import (
    JSON,
    BigInteger,
    Boolean,
    Column,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    MetaData,
    String,
    Table,
    Text,
)
from sqlalchemy.engine import Dialect
from sqlalchemy.types import TypeDecorator

# Constraint names are fixed so later migrations can alter them on every backend.
NAMING_CONVENTION = {
    "ix": "ix_%(column_0_label)s",
    "uq": "uq_%(table_name)s_%(column_0_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}

# An autoincrementing 64-bit key on PostgreSQL; SQLite only autoincrements INTEGER PRIMARY KEY.
BigId = BigInteger().with_variant(Integer(), "sqlite")


class UTCDateTime(TypeDecorator[datetime]):
    """A datetime stored in UTC and always returned timezone-aware (SQLite drops the zone)."""

    impl = DateTime(timezone=True)
    cache_ok = True

    def process_bind_param(self, value: datetime | None, dialect: Dialect) -> datetime | None:
        if value is None:
            return None
        if value.tzinfo is None:
            raise ValueError("naive datetime given to the store; use timezone-aware UTC datetimes")
        return value.astimezone(UTC)

    def process_result_value(self, value: datetime | None, dialect: Dialect) -> datetime | None:
        if value is None:
            return None
        if value.tzinfo is None:
            return value.replace(tzinfo=UTC)
        return value.astimezone(UTC)


metadata = MetaData(naming_convention=NAMING_CONVENTION)

#: a vehicle's id (`gateway.registry.records.VehicleSpec`), in every table that names one
VehicleIdText = String(32)
#: who did something (a principal: an operator, agent or viewer's name), in every table that says who
PrincipalText = String(200)

# Columns are NOT NULL unless written ``nullable=True``: what a row must have is said once, here.


#: what a Column takes after its name: its type, constraints, keys, defaults
ColumnArgument = Any  # Any: sqlalchemy, Column's arguments (types, constraints, defaults of many kinds)


def _required(name: str, *args: ColumnArgument, **kwargs: ColumnArgument) -> Column[object]:
    """A column that must have a value (NOT NULL)."""
    return Column(name, *args, nullable=False, **kwargs)


def _optional(name: str, *args: ColumnArgument, **kwargs: ColumnArgument) -> Column[object]:
    """A column that may be NULL."""
    return Column(name, *args, nullable=True, **kwargs)


def _keyed(name: str, key: str, text: String, *columns: ColumnArgument) -> Table:
    """A table whose rows are keyed by a name: ``key`` (of type ``text``) first."""
    return Table(name, metadata, Column(key, text, primary_key=True), *columns)


def _per_vehicle(name: str, *columns: ColumnArgument) -> Table:
    """A table of at most one row per vehicle, keyed by its id and removed with it."""
    vehicle = ForeignKey("vehicles.id", ondelete="CASCADE")
    return Table(name, metadata, Column("vehicle_id", VehicleIdText, vehicle, primary_key=True), *columns)


def _numbered(name: str, *columns: ColumnArgument) -> Table:
    """A table of history whose rows the database numbers: a 64-bit autoincrementing ``id`` first."""
    return Table(name, metadata, Column("id", BigId, primary_key=True, autoincrement=True), *columns)


def _required_each(kind: ColumnArgument, *names: str) -> list[Column[object]]:
    """Columns of one type that must each have a value, in the order named."""
    return [_required(name, kind) for name in names]


def _optional_each(kind: ColumnArgument, *names: str) -> list[Column[object]]:
    """Columns of one type that may each be NULL (the figures a row may lack), in the order named."""
    return [_optional(name, kind) for name in names]


vehicles = _keyed(
    "vehicles",
    "id",
    VehicleIdText,
    _required("url", String(256)),
    _optional("name", String(100)),
    _required("tags", JSON, default=list),
    _optional("expected_sysid", Integer),
    _optional("node_tag", String(32)),
    _required("gcs_endpoints", JSON, default=list, server_default="[]"),
    _required("auto_connect", Boolean, default=True),
    *_required_each(UTCDateTime, "created_at", "updated_at"),
)

sessions = _keyed(
    "sessions",
    "key",
    String(200),
    _required("kind", String(16)),
    _optional("principal", PrincipalText),
    _optional("client_name", String(200)),
    _optional("client_version", String(100)),
    _required("first_seen", UTCDateTime()),
    _required("last_seen", UTCDateTime(), index=True),
    _required("request_count", Integer, default=1),
)

audit = _numbered(
    "audit",
    _required("t", UTCDateTime(), index=True),
    _optional("session_key", String(200), index=True),
    _optional("principal", PrincipalText),
    _required("source", String(8)),
    _optional("vehicle_id", VehicleIdText),
    _required("action", String(100)),
    _required("arguments", JSON, default=dict),
    _required("outcome", String(16)),
    _optional("error", Text),
    _optional("duration_ms", Float),
    # the operation a call left running (wait:false): its end finishes the row, on whichever node
    _optional("operation_id", String(64), index=True),
    # a row written before its call's command was sent (outcome running): the call finishes it by this
    _optional("call_id", String(32), index=True, unique=True),
    Index("ix_audit_vehicle_id_t", "vehicle_id", "t"),
)

#: One flight: arm to disarm. Kept after its vehicle is removed (history).
flights = _numbered(
    "flights",
    _required("vehicle_id", VehicleIdText),
    _required("started_at", UTCDateTime(), index=True),
    _optional("ended_at", UTCDateTime()),
    *_optional_each(Float, "home_lat", "home_lon", "home_alt_amsl"),
    *_optional_each(Float, "duration_s", "distance_m", "max_alt_rel_m", "battery_used_pct"),
    Index("ix_flights_vehicle_id_started_at", "vehicle_id", "started_at"),
)

track_samples = _numbered(
    "track_samples",
    _required(
        "flight_id",
        BigId,
        ForeignKey("flights.id", ondelete="CASCADE"),
    ),
    _required("t", UTCDateTime()),
    *_required_each(Float, "lat", "lon"),
    *_optional_each(Float, "alt_rel_m", "heading_deg", "ground_speed_mps", "battery_pct"),
    # the autopilot's HEARTBEAT (MAV_TYPE, custom mode) and GPS fix (GPS_FIX_TYPE, satellites) at the sample
    *_optional_each(BigInteger, "mav_type", "custom_mode", "gps_fix_type", "satellites"),
    Index("ix_track_samples_flight_id_t", "flight_id", "t"),
)

status_texts = _numbered(
    "status_texts",
    _required("vehicle_id", VehicleIdText),
    _optional(
        "flight_id",
        BigId,
        ForeignKey("flights.id", ondelete="SET NULL"),
        index=True,
    ),
    _required("t", UTCDateTime()),
    _required("severity", String(16)),
    _required("text", String(255)),
    Index("ix_status_texts_vehicle_id_t", "vehicle_id", "t"),
)

operations = _keyed(
    "operations",
    "id",
    String(64),
    _required("vehicle_id", VehicleIdText),
    _required("kind", String(64)),
    _required("params", JSON, default=dict),
    _required("status", String(16), index=True),
    _required("progress", Float, default=0.0),
    _optional("message", Text),
    _optional("result", JSON),
    _optional("session_key", String(200)),
    *_required_each(UTCDateTime, "created_at", "updated_at"),
    _optional("finished_at", UTCDateTime()),
    Index("ix_operations_vehicle_id_created_at", "vehicle_id", "created_at"),
)


def _lock_table(name: str, key: str) -> Table:
    """A table of locks that survive restarts, keyed by ``key``: why, by whom and when each was set."""
    return _keyed(
        name,
        key,
        VehicleIdText,
        _required("reason", Text),
        _required("locked_by", PrincipalText),
        _required("locked_at", UTCDateTime()),
    )


#: An operator lock on one vehicle, or on the whole fleet (scope "*").
locks = _lock_table("locks", "scope")
#: A drone taken over by a pilot, another ground station or a failsafe (`gateway.fleet.policy.takeover`):
#: agents are refused until an operator releases it.
takeovers = _lock_table("takeovers", "vehicle_id")

#: A gateway node of a cluster; alive while ``expires_at`` is in the future (renewed with its leases).
cluster_nodes = _keyed(
    "cluster_nodes",
    "node_id",
    String(32),
    _required("tags", JSON, default=list),
    _optional("api_url", String(256)),
    *_required_each(UTCDateTime, "started_at", "last_seen"),
    _required("expires_at", UTCDateTime(), index=True),
)

#: Which node owns (runs the sidecar of) a vehicle, until when. ``epoch`` grows at every change of owner:
#: a fencing number that tells a late message of the previous owner from the current one.
vehicle_leases = _per_vehicle(
    "vehicle_leases",
    _required("node_id", String(32), index=True),
    _required("epoch", BigInteger, default=1),
    *_required_each(UTCDateTime, "acquired_at", "renewed_at", "expires_at"),
)

#: The point a vehicle's distance limit and geofence checks count from: the first home it reported, or
#: where an operator moved it (`gateway.fleet.policy.origin`). The autopilot cannot move it.
vehicle_origins = _per_vehicle(
    "vehicle_origins",
    *_required_each(Float, "lat", "lon", "alt_amsl_m"),
    _required("source", String(16)),  # first_home | operator
    _required("set_by", PrincipalText),
    _required("set_at", UTCDateTime()),
)

#: What a drone's last ``.plan`` carried beside its items and its zones
#: (`gateway.fleet.missions.plan_extras`): its rally points ([[lat, lon, alt above home], ...]), and the
#: circles its geofence was drawn as ({zone name: [centre lat, centre lon, radius m], ...}; the zones
#: themselves are polygons), written back when the drone's mission is exported as a .plan.
vehicle_plan_extras = _per_vehicle(
    "vehicle_plan_extras",
    _required("rally", JSON, default=list),
    _required("circles", JSON, default=dict),
    _required("set_by", PrincipalText),
    _required("set_at", UTCDateTime()),
)
