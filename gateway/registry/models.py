"""SQLAlchemy 2.x ORM tables of the gateway.

Alembic owns the schema (``migrations/``, installed as ``gateway.migrations``); these classes describe it
for the store's queries and for ``alembic revision --autogenerate``. Types are portable (SQLite and
PostgreSQL): JSON through ``sqlalchemy.JSON``, datetimes always timezone-aware UTC through
:class:`UTCDateTime`.
"""

from __future__ import annotations

from datetime import UTC, datetime

from sqlalchemy import (
    JSON,
    BigInteger,
    Boolean,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    MetaData,
    String,
    Text,
)
from sqlalchemy.engine import Dialect
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column
from sqlalchemy.types import TypeDecorator

from gateway.util.json_types import JsonObject

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


class Base(DeclarativeBase):
    metadata = MetaData(naming_convention=NAMING_CONVENTION)


class VehicleRow(Base):
    __tablename__ = "vehicles"

    id: Mapped[str] = mapped_column(String(32), primary_key=True)
    url: Mapped[str] = mapped_column(String(256))
    name: Mapped[str | None] = mapped_column(String(100))
    tags: Mapped[list[str]] = mapped_column(JSON, default=list)
    expected_sysid: Mapped[int | None] = mapped_column(Integer)
    node_tag: Mapped[str | None] = mapped_column(String(32))
    gcs_endpoints: Mapped[list[str]] = mapped_column(JSON, default=list, server_default="[]")
    auto_connect: Mapped[bool] = mapped_column(Boolean, default=True)
    created_at: Mapped[datetime] = mapped_column(UTCDateTime())
    updated_at: Mapped[datetime] = mapped_column(UTCDateTime())


class SessionRow(Base):
    __tablename__ = "sessions"

    key: Mapped[str] = mapped_column(String(200), primary_key=True)
    kind: Mapped[str] = mapped_column(String(16))
    principal: Mapped[str | None] = mapped_column(String(200))
    client_name: Mapped[str | None] = mapped_column(String(200))
    client_version: Mapped[str | None] = mapped_column(String(100))
    first_seen: Mapped[datetime] = mapped_column(UTCDateTime())
    last_seen: Mapped[datetime] = mapped_column(UTCDateTime(), index=True)
    request_count: Mapped[int] = mapped_column(Integer, default=1)


class AuditRow(Base):
    __tablename__ = "audit"
    __table_args__ = (Index("ix_audit_vehicle_id_t", "vehicle_id", "t"),)

    id: Mapped[int] = mapped_column(BigId, primary_key=True, autoincrement=True)
    t: Mapped[datetime] = mapped_column(UTCDateTime(), index=True)
    session_key: Mapped[str | None] = mapped_column(String(200), index=True)
    principal: Mapped[str | None] = mapped_column(String(200))
    source: Mapped[str] = mapped_column(String(8))
    vehicle_id: Mapped[str | None] = mapped_column(String(32))
    action: Mapped[str] = mapped_column(String(100))
    arguments: Mapped[JsonObject] = mapped_column(JSON, default=dict)
    outcome: Mapped[str] = mapped_column(String(16))
    error: Mapped[str | None] = mapped_column(Text)
    duration_ms: Mapped[float | None] = mapped_column(Float)
    # the operation a call left running (wait:false): its end finishes the row, on whichever node
    operation_id: Mapped[str | None] = mapped_column(String(64), index=True)
    # a row written before its call's command was sent (outcome running): the call finishes it by this
    call_id: Mapped[str | None] = mapped_column(String(32), index=True, unique=True)


class FlightRow(Base):
    """One flight: arm to disarm. Kept after its vehicle is removed (history)."""

    __tablename__ = "flights"
    __table_args__ = (Index("ix_flights_vehicle_id_started_at", "vehicle_id", "started_at"),)

    id: Mapped[int] = mapped_column(BigId, primary_key=True, autoincrement=True)
    vehicle_id: Mapped[str] = mapped_column(String(32))
    started_at: Mapped[datetime] = mapped_column(UTCDateTime(), index=True)
    ended_at: Mapped[datetime | None] = mapped_column(UTCDateTime())
    home_lat: Mapped[float | None] = mapped_column(Float)
    home_lon: Mapped[float | None] = mapped_column(Float)
    home_alt_amsl: Mapped[float | None] = mapped_column(Float)
    duration_s: Mapped[float | None] = mapped_column(Float)
    distance_m: Mapped[float | None] = mapped_column(Float)
    max_alt_rel_m: Mapped[float | None] = mapped_column(Float)
    battery_used_pct: Mapped[float | None] = mapped_column(Float)


class TrackSampleRow(Base):
    __tablename__ = "track_samples"
    __table_args__ = (Index("ix_track_samples_flight_id_t", "flight_id", "t"),)

    id: Mapped[int] = mapped_column(BigId, primary_key=True, autoincrement=True)
    flight_id: Mapped[int] = mapped_column(
        BigInteger().with_variant(Integer(), "sqlite"), ForeignKey("flights.id", ondelete="CASCADE")
    )
    t: Mapped[datetime] = mapped_column(UTCDateTime())
    lat: Mapped[float] = mapped_column(Float)
    lon: Mapped[float] = mapped_column(Float)
    alt_rel_m: Mapped[float | None] = mapped_column(Float)
    heading_deg: Mapped[float | None] = mapped_column(Float)
    ground_speed_mps: Mapped[float | None] = mapped_column(Float)
    battery_pct: Mapped[float | None] = mapped_column(Float)
    # the autopilot's HEARTBEAT (MAV_TYPE, custom mode) and GPS fix (GPS_FIX_TYPE, satellites) at the sample
    mav_type: Mapped[int | None] = mapped_column(BigInteger)
    custom_mode: Mapped[int | None] = mapped_column(BigInteger)
    gps_fix_type: Mapped[int | None] = mapped_column(BigInteger)
    satellites: Mapped[int | None] = mapped_column(BigInteger)


class StatusTextRow(Base):
    __tablename__ = "status_texts"
    __table_args__ = (Index("ix_status_texts_vehicle_id_t", "vehicle_id", "t"),)

    id: Mapped[int] = mapped_column(BigId, primary_key=True, autoincrement=True)
    vehicle_id: Mapped[str] = mapped_column(String(32))
    flight_id: Mapped[int | None] = mapped_column(
        BigInteger().with_variant(Integer(), "sqlite"),
        ForeignKey("flights.id", ondelete="SET NULL"),
        index=True,
    )
    t: Mapped[datetime] = mapped_column(UTCDateTime())
    severity: Mapped[str] = mapped_column(String(16))
    text: Mapped[str] = mapped_column(String(255))


class OperationRow(Base):
    __tablename__ = "operations"
    __table_args__ = (Index("ix_operations_vehicle_id_created_at", "vehicle_id", "created_at"),)

    id: Mapped[str] = mapped_column(String(64), primary_key=True)
    vehicle_id: Mapped[str] = mapped_column(String(32))
    kind: Mapped[str] = mapped_column(String(64))
    params: Mapped[JsonObject] = mapped_column(JSON, default=dict)
    status: Mapped[str] = mapped_column(String(16), index=True)
    progress: Mapped[float] = mapped_column(Float, default=0.0)
    message: Mapped[str | None] = mapped_column(Text)
    result: Mapped[JsonObject | None] = mapped_column(JSON)
    session_key: Mapped[str | None] = mapped_column(String(200))
    created_at: Mapped[datetime] = mapped_column(UTCDateTime())
    updated_at: Mapped[datetime] = mapped_column(UTCDateTime())
    finished_at: Mapped[datetime | None] = mapped_column(UTCDateTime())


class LockRow(Base):
    """An operator lock on one vehicle, or on the whole fleet (scope "*"); survives restarts."""

    __tablename__ = "locks"

    scope: Mapped[str] = mapped_column(String(32), primary_key=True)
    reason: Mapped[str] = mapped_column(Text)
    locked_by: Mapped[str] = mapped_column(String(200))
    locked_at: Mapped[datetime] = mapped_column(UTCDateTime())


class TakeoverRow(Base):
    """A drone taken over by a pilot, another ground station or a failsafe (`gateway.fleet.policy.takeover`):
    agents are refused until an operator releases it; survives restarts."""

    __tablename__ = "takeovers"

    vehicle_id: Mapped[str] = mapped_column(String(32), primary_key=True)
    reason: Mapped[str] = mapped_column(Text)
    locked_by: Mapped[str] = mapped_column(String(200))
    locked_at: Mapped[datetime] = mapped_column(UTCDateTime())


class ClusterNodeRow(Base):
    """A gateway node of a cluster; alive while ``expires_at`` is in the future (renewed with its leases)."""

    __tablename__ = "cluster_nodes"

    node_id: Mapped[str] = mapped_column(String(32), primary_key=True)
    tags: Mapped[list[str]] = mapped_column(JSON, default=list)
    api_url: Mapped[str | None] = mapped_column(String(256))
    started_at: Mapped[datetime] = mapped_column(UTCDateTime())
    last_seen: Mapped[datetime] = mapped_column(UTCDateTime())
    expires_at: Mapped[datetime] = mapped_column(UTCDateTime(), index=True)


class VehicleLeaseRow(Base):
    """Which node owns (runs the sidecar of) a vehicle, until when. ``epoch`` grows at every change of
    owner: a fencing number that tells a late message of the previous owner from the current one."""

    __tablename__ = "vehicle_leases"

    vehicle_id: Mapped[str] = mapped_column(
        String(32), ForeignKey("vehicles.id", ondelete="CASCADE"), primary_key=True
    )
    node_id: Mapped[str] = mapped_column(String(32), index=True)
    epoch: Mapped[int] = mapped_column(BigInteger, default=1)
    acquired_at: Mapped[datetime] = mapped_column(UTCDateTime())
    renewed_at: Mapped[datetime] = mapped_column(UTCDateTime())
    expires_at: Mapped[datetime] = mapped_column(UTCDateTime())


class OriginRow(Base):
    """The point a vehicle's distance limit and geofence checks count from: the first home it reported,
    or where an operator moved it (`gateway.fleet.policy.origin`). The autopilot cannot move it."""

    __tablename__ = "vehicle_origins"

    vehicle_id: Mapped[str] = mapped_column(
        String(32), ForeignKey("vehicles.id", ondelete="CASCADE"), primary_key=True
    )
    lat: Mapped[float] = mapped_column(Float)
    lon: Mapped[float] = mapped_column(Float)
    alt_amsl_m: Mapped[float] = mapped_column(Float)
    source: Mapped[str] = mapped_column(String(16))  # first_home | operator
    set_by: Mapped[str] = mapped_column(String(200))
    set_at: Mapped[datetime] = mapped_column(UTCDateTime())


class PlanExtrasRow(Base):
    """What a drone's last ``.plan`` carried beside its items and its zones
    (`gateway.fleet.missions.plan_extras`): its rally points, and the circles its geofence was drawn as
    (the zones themselves are polygons), written back when the drone's mission is exported as a .plan."""

    __tablename__ = "vehicle_plan_extras"

    vehicle_id: Mapped[str] = mapped_column(
        String(32), ForeignKey("vehicles.id", ondelete="CASCADE"), primary_key=True
    )
    #: [[lat, lon, alt above home], ...]
    rally: Mapped[list[list[float]]] = mapped_column(JSON, default=list)
    #: {zone name: [centre lat, centre lon, radius m], ...}
    circles: Mapped[dict[str, list[float]]] = mapped_column(JSON, default=dict)
    set_by: Mapped[str] = mapped_column(String(200))
    set_at: Mapped[datetime] = mapped_column(UTCDateTime())
