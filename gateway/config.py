"""Gateway settings, read from the environment (prefix GATEWAY_) or a .env file."""

from __future__ import annotations

import math
import re
import socket
from functools import lru_cache
from pathlib import Path
from typing import Annotated

from pydantic import Field, field_validator, model_validator
from pydantic_settings import BaseSettings, SettingsConfigDict

from gateway.principals import PRINCIPAL_PREFIX, principal_of, split_tokens

ALL_TOOLSETS = ("flight", "navigation", "mission", "telemetry", "params", "fleet")

# ArduPilot (4.x and 4.7 names) then PX4: arming checks, fences, failsafes, battery failsafe thresholds,
# system ids, circuit breakers, failure detector.
DEFAULT_PARAM_DENY_PATTERNS = ",".join(
    (
        "ARMING_*", "FENCE_*", "FS_*", "BATT*_FS_*", "BATT*_LOW_*", "BATT*_CRT_*", "SYSID_*",
        "MAV_SYSID", "MAV_GCS_SYSID", "BRD_SAFETY*", "FLTMODE_GCSBLOCK", "RC_FS_*", "THR_FS*",
        "COM_*", "GF_*", "NAV_DLL_*", "NAV_RCL_*", "CBRK_*", "MAV_SYS_ID", "MAV_COMP_ID",
        "BAT*_LOW_THR", "BAT*_CRIT_THR", "BAT*_EMERGEN_THR", "FD_*",
    )
)  # fmt: skip
#: tuning an agent may change without reaching around a limit: accelerations, jerk, waypoint radius, yaw
#: behaviour, orbit rate (ArduPilot and PX4 names)
DEFAULT_AGENT_PARAM_ALLOW = ",".join(
    (
        "WPNAV_ACCEL", "WPNAV_ACCEL_Z", "WPNAV_ACCEL_C", "WPNAV_JERK", "WPNAV_RADIUS", "WP_YAW_BEHAVIOR",
        "LOIT_ACC_MAX*", "LOIT_BRK_*", "CIRCLE_RATE", "MPC_ACC_HOR", "MPC_ACC_HOR_MAX", "MPC_ACC_UP_MAX",
        "MPC_ACC_DOWN_MAX", "MPC_JERK_AUTO", "MPC_JERK_MAX", "NAV_ACC_RAD", "MPC_YAWRAUTO_MAX",
    )
)  # fmt: skip
DEFAULT_MODE_DENY_IN_AIR = ",".join(
    (
        "STABILIZE", "ACRO", "ALT_HOLD", "LOITER", "POSHOLD", "SPORT", "DRIFT", "FLIP", "THROW",
        "TURTLE", "AUTOTUNE", "FLOWHOLD", "MANUAL", "ALTCTL", "POSCTL", "STABILIZED", "RATTITUDE",
    )
)  # fmt: skip

#: the kinds of number the settings hold, each with the bound all its fields share (a field adds its own
#: upper limit where it has one)
Seconds = Annotated[float, Field(gt=0)]
Metres = Annotated[float, Field(gt=0)]
Speed = Annotated[float, Field(gt=0)]  # m/s
Hertz = Annotated[float, Field(gt=0)]
Percent = Annotated[float, Field(ge=0, le=100)]
AtLeastOne = Annotated[int, Field(ge=1)]  # a count or size that cannot be zero
ZeroOrMore = Annotated[int, Field(ge=0)]  # a count, or seconds where 0 turns a check off
#: a MAVLink system id the gateway may take as a ground station: not 0 (broadcast), 1 (an autopilot's
#: default) or 255 (the usual ground station's default)
GcsSystemId = Annotated[int, Field(ge=2, le=254)]


class Settings(BaseSettings):
    """Everything an operator can configure. Each field's description is the documentation."""

    model_config = SettingsConfigDict(env_prefix="GATEWAY_", env_file=".env", extra="ignore")

    # --- server -------------------------------------------------------------------------------
    host: str = Field("127.0.0.1", description="Address the HTTP server (REST + /mcp) binds to.")
    port: AtLeastOne = Field(8765, le=65535, description="HTTP port of the REST API and /mcp.")
    database_url: str = Field(
        "sqlite+aiosqlite:///./fleet-gateway.db",
        description="SQLAlchemy async URL; SQLite (aiosqlite) by default, PostgreSQL (asyncpg) works too.",
    )
    log_level: str = Field("INFO", description="Python log level of the gateway.")
    max_request_body_bytes: int = Field(
        1_048_576,
        ge=1024,
        description="Largest HTTP request body accepted (REST and /mcp); larger ones are refused with 413.",
    )

    # --- MAVLink / sidecars --------------------------------------------------------------------
    gcs_sysid: GcsSystemId = Field(
        245,
        description="MAVLink system id the gateway uses as a ground station (mavsdk_server --sysid). "
        "Set the autopilot's MAV_GCS_SYSID (SYSID_MYGCS) to it for GCS-loss failsafes to watch it.",
    )
    mavsdk_server_path: str | None = Field(
        None, description="Path of the mavsdk_server binary; default: the one bundled with mavsdk-grpc."
    )
    sidecar_confinement: str = Field(
        "socket",
        pattern="^(socket|loopback|none)$",
        description="'socket': sidecars run from a copy of mavsdk_server that serves gRPC on a unix socket "
        "in a private directory, removed once the gateway is connected, so no other process can reach it; "
        "'loopback': a copy whose gRPC port listens on 127.0.0.1 only (any local process can reach it); "
        "'none': the binary as shipped (gRPC on every interface).",
    )
    sidecar_cache_dir: str | None = Field(
        None, description="Where the confined sidecar binary is kept; default ~/.cache/fleet-gateway."
    )
    sidecar_max_restarts: ZeroOrMore = Field(
        5, description="Consecutive sidecar crashes before a vehicle is marked failed."
    )
    sidecar_backoff_initial_s: Seconds = Field(0.5, description="First restart delay of a sidecar.")
    sidecar_backoff_max_s: Seconds = Field(10.0, description="Longest restart delay of a sidecar.")
    sidecar_heartbeat_watchdog_s: ZeroOrMore = Field(
        0,
        description="mavsdk_server --heartbeat-watchdog-timeout; 0 disables. When set, a hung gateway stops "
        "the GCS heartbeat so the autopilot's own GCS failsafe takes over.",
    )
    link_lost_after_s: Seconds = Field(
        3.0, description="Seconds without a heartbeat/telemetry before a vehicle is link_lost."
    )

    # --- MCP ------------------------------------------------------------------------------------
    mcp_toolsets: str = Field(
        ",".join(ALL_TOOLSETS),
        description="Comma-separated MCP toolsets to expose: " + ", ".join(ALL_TOOLSETS) + ".",
    )
    mcp_wait_cap_s: Seconds = Field(
        45.0, le=600, description="Longest a tool waits for its operation before answering 'running'."
    )
    mcp_sessions_per_caller: AtLeastOne = Field(
        64,
        le=10_000,
        description="Most 2025-era MCP sessions (Mcp-Session-Id) one token keeps open; a new one beyond "
        "this closes that token's session idle the longest.",
    )
    mcp_session_idle_s: Seconds = Field(
        1800.0, le=86_400, description="A 2025-era MCP session with no request for this long is closed."
    )
    allowed_hosts: str = Field(
        "",
        description="Comma-separated extra Host names (and browser Origin hosts) that /mcp and the REST "
        "API answer, e.g. the name of a proxy in front of the gateway; loopback names are always "
        "allowed; '*' allows any (when a proxy checks them). A foreign Host or Origin is refused: a web "
        "page cannot command drones through DNS rebinding or a cross-site form.",
    )
    mcp_allowed_hosts: str = Field(
        "", description="Older name of GATEWAY_ALLOWED_HOSTS, still read (both lists are merged)."
    )
    arrival_tolerance_m: Metres = Field(2.0, description="Horizontal distance counted as arrived.")

    # --- safety -----------------------------------------------------------------------------------
    max_altitude_m: Metres = Field(120.0, description="Highest altitude above home an agent may command.")
    max_distance_m: Metres = Field(1000.0, description="Farthest distance from home an agent may command.")
    min_battery_takeoff_pct: Percent = Field(30.0, description="Battery needed to take off.")
    min_battery_leg_pct: Percent = Field(25.0, description="Battery needed to start a new leg.")
    max_speed_mps: Speed = Field(15.0, description="Highest horizontal speed an agent may set.")
    max_vertical_speed_mps: Speed = Field(
        5.0,
        description="Highest climb, descent or landing speed an agent may set through an autopilot "
        "parameter (WPNAV_SPEED_UP, LAND_SPEED, MPC_Z_VEL_MAX_UP, ...).",
    )
    min_separation_m: Metres = Field(5.0, description="Minimum distance kept between fleet drones.")
    agents_may_kill: bool = Field(False, description="Whether MCP agents may kill motors in the air.")
    simulators_only: bool = Field(False, description="Refuse every actuating MCP tool on real vehicles.")
    min_altitude_m: float = Field(
        2.0,
        ge=0,
        description="Lowest altitude above home a takeoff, goto or mission waypoint may target "
        "(land and RTL go lower).",
    )
    param_deny_patterns: str = Field(
        DEFAULT_PARAM_DENY_PATTERNS,
        description="Comma-separated glob patterns (case-insensitive) of autopilot parameters MCP agents "
        "may not write: arming checks, fences, failsafes, system ids (ArduPilot and PX4 names).",
    )
    agent_param_allow: str = Field(
        DEFAULT_AGENT_PARAM_ALLOW,
        description="Comma-separated glob patterns of autopilot parameters MCP agents may write besides "
        "those governed by a limit (speeds, return altitude: checked against the limits). Every other "
        "parameter is refused for agents; operators write any parameter over REST.",
    )
    mode_deny_in_air: str = Field(
        DEFAULT_MODE_DENY_IN_AIR,
        description="Comma-separated flight modes MCP agents may not select while airborne: modes that "
        "need a pilot's sticks, in which a copter without RC input descends or drifts.",
    )
    geofence_file: str | None = Field(
        None,
        description="GeoJSON FeatureCollection of geofence zones: Polygon/MultiPolygon features with "
        "properties.kind keep_in|keep_out, optional properties.name and properties.vehicle_id.",
    )
    vehicle_limits: dict[str, dict[str, float]] = Field(
        {},
        description="Per-vehicle overrides as JSON: {vehicle_id: {max_altitude_m, max_distance_m, "
        "min_battery_takeoff_pct, min_battery_leg_pct, max_speed_mps, min_altitude_m, "
        "max_vertical_speed_mps}}.",
    )

    # --- auth -------------------------------------------------------------------------------------
    operator_tokens: str = Field("", description="Comma-separated bearer tokens with the operator role.")
    viewer_tokens: str = Field("", description="Comma-separated bearer tokens with the viewer role.")
    agent_tokens: str = Field("", description="Comma-separated bearer tokens for MCP agents.")
    agent_scopes: dict[str, list[str]] = Field(
        {},
        description="Agents limited to some vehicles, as JSON: {token or agent-<8 hex> principal: [vehicle "
        "ids and 'tag:<tag>' entries]}. Such an agent sees and commands only those; others see all.",
    )

    # --- operator console ---------------------------------------------------------------------------
    console_tiles_url: str | None = Field(
        None,
        description="Map tile URL template of the /console map, e.g. "
        "https://tile.example.org/{z}/{x}/{y}.png (the browser fetches the tiles); unset: the map is "
        "drawn without tiles, in metres around the fleet's home (works offline).",
    )
    console_tiles_attribution: str = Field(
        "", description="Attribution the tile server's licence asks for, shown in a corner of the map."
    )

    # --- flight log -------------------------------------------------------------------------------
    track_sample_hz: Hertz = Field(1.0, le=10, description="Track samples recorded per second in flight.")
    track_flush_s: Seconds = Field(2.0, description="Seconds between batched track writes.")
    flight_tlog_dir: str = Field(
        "",
        description="Folder where each flight's raw MAVLink from the drone is written as it is received "
        "(its .tlog export); default: '<database file>-tlogs' next to a SQLite database, "
        "fleet-gateway-tlogs in the working directory for PostgreSQL; 'none': not recorded (the .tlog "
        "is then reconstructed from the 1 Hz track). While recorded, every drone's link runs through "
        "the gateway's relay (as one with gcs_endpoints does).",
    )
    flight_tlog_max_mib: AtLeastOne = Field(
        64,
        le=4096,
        description="Largest raw MAVLink log kept per flight, in MiB; the frames after it are not "
        "written (the export says the log was cut).",
    )
    spool_path: str = Field(
        "",
        description="File (JSON lines) where the history writes the database could not take wait until "
        "it is back, so a gateway killed meanwhile writes them after its restart; default: "
        "fleet-gateway-spool-<node id>.jsonl in the working directory; 'none': memory only.",
    )

    # --- cluster (several `serve` nodes on one PostgreSQL and NATS; docs/cluster.md) --------------
    cluster_nats_url: str = Field(
        "",
        description="NATS server URL(s), comma-separated (e.g. nats://10.0.0.2:4222). Set, with a "
        "PostgreSQL database_url, every `serve` is a cluster node; empty: one gateway on its own.",
    )
    cluster_node_id: str = Field(
        "",
        pattern=r"^([a-z0-9][a-z0-9-]{0,31})?$",
        description="This node's id (1-32 of a-z, 0-9, '-'); default: the host name and HTTP port.",
    )
    cluster_node_tags: str = Field(
        "",
        description="Comma-separated tags of this node (e.g. site-north): a drone registered with "
        "node_tag is only ever owned by nodes that carry that tag.",
    )
    cluster_lease_ttl_s: Seconds = Field(
        10.0,
        ge=1.0,
        le=300.0,
        description="How long a node's lease on a drone lasts without renewal (renewed every third of "
        "it): a dead node's drones are taken over after at most this long.",
    )
    cluster_telemetry_hz: Hertz = Field(
        2.0, le=20, description="Telemetry snapshots per second each owner publishes per drone."
    )
    cluster_forward_timeout_s: Seconds = Field(
        15.0,
        le=600,
        description="Longest a forwarded call waits for the owning node beyond the MCP wait cap.",
    )
    cluster_accept_timeout_s: Seconds = Field(
        3.0,
        le=60,
        description="How long a forwarded call waits for the owning node to accept it; the owner "
        "refuses to start a call it receives later, so the caller's 'not run' is true.",
    )

    @field_validator("mcp_toolsets")
    @classmethod
    def _known_toolsets(cls, value: str) -> str:
        names = [n.strip() for n in value.split(",") if n.strip()]
        unknown = [n for n in names if n not in ALL_TOOLSETS]
        if unknown:
            raise ValueError(f"unknown toolset(s) {unknown}; known: {list(ALL_TOOLSETS)}")
        return ",".join(names)

    @field_validator("cluster_node_tags")
    @classmethod
    def _node_tags(cls, value: str) -> str:
        tags = [t.strip() for t in value.split(",") if t.strip()]
        bad = [t for t in tags if not re.match(r"^[A-Za-z0-9_.\-]{1,32}$", t)]
        if bad:
            raise ValueError(f"node tag(s) {bad} must be 1-32 of letters, digits, '_', '.', '-'")
        return ",".join(tags)

    @field_validator("console_tiles_url")
    @classmethod
    def _tile_template(cls, value: str | None) -> str | None:
        if value is None or not value.strip():
            return None
        missing = [p for p in ("{z}", "{x}", "{y}") if p not in value]
        if missing or not value.startswith(("http://", "https://", "/")):
            raise ValueError(
                f"must be an http(s) URL (or a path on this server) with {{z}}, {{x}} and {{y}} in it, "
                f"e.g. https://tile.example.org/{{z}}/{{x}}/{{y}}.png; got {value!r}"
            )
        return value.strip()

    @model_validator(mode="after")
    def _numbers_are_finite(self) -> Settings:
        """A limit of inf or nan would hold nothing (every comparison with nan is false): refused at
        start, naming the variable."""
        for name, value in self:
            if isinstance(value, float) and not math.isfinite(value):
                raise ValueError(f"GATEWAY_{name.upper()} must be a finite number; got {value}")
        return self

    @model_validator(mode="after")
    def _scopes_name_configured_agents(self) -> Settings:
        """Scopes fail closed: a key that is neither a configured agent token nor the principal name of
        one would confine nobody (the agent it was meant for would see the whole fleet)."""
        tokens = split_tokens(self.agent_tokens)
        principals = {principal_of(t) for t in tokens}
        for key in self.agent_scopes:
            if key not in tokens and key not in principals:
                shown = key if key.startswith(PRINCIPAL_PREFIX) else f"{key[:4]}... ({len(key)} characters)"
                raise ValueError(
                    f"GATEWAY_AGENT_SCOPES key {shown} is neither one of GATEWAY_AGENT_TOKENS nor the "
                    "principal name (agent-<8 hex>) of one, so it would confine no agent; add the token to "
                    "GATEWAY_AGENT_TOKENS or correct the key"
                )
        return self

    @property
    def toolsets(self) -> list[str]:
        return [n for n in self.mcp_toolsets.split(",") if n]

    @property
    def clustered(self) -> bool:
        """True when this gateway is a node of a cluster (a NATS URL is set)."""
        return bool(self.cluster_nats_url.strip())

    @property
    def node_id(self) -> str:
        """This node's id: the setting, else ``<host name>-<port>`` made a valid id."""
        if self.cluster_node_id:
            return self.cluster_node_id
        host = re.sub(r"[^a-z0-9-]+", "-", socket.gethostname().lower()).strip("-") or "node"
        return f"{host[:26]}-{self.port}"[:32]

    @property
    def records_flight_frames(self) -> bool:
        """Whether each flight's raw MAVLink is written (``flight_tlog_dir`` is not 'none')."""
        return self.flight_tlog_dir.strip().lower() != "none"

    @property
    def spool_file(self) -> Path | None:
        """Where the writes the database could not take are kept (None: memory only)."""
        given = self.spool_path.strip()
        if given.lower() == "none":
            return None
        return Path(given) if given else Path(f"fleet-gateway-spool-{self.node_id}.jsonl")

    @property
    def node_tags(self) -> list[str]:
        return [t for t in self.cluster_node_tags.split(",") if t]


@lru_cache
def get_settings() -> Settings:
    return Settings()
