"""What a vehicle's link shows its owner and what the owner gives it: the connection states, the
autopilot's rules (``LinkRules``, implemented by ``gateway.fleet.dialects``), the other links seen for
duplicate system ids (``Peer``) and the notice of what a vehicle still initialising waits for
(``OnWait``). The link itself is ``gateway.link.session.Link``."""

from __future__ import annotations

import enum
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Protocol

from gateway.link.telemetry import HealthValue, TelemetryCache

OnWait = Callable[[str], Awaitable[None]]
"""Told, in words, what a vehicle still initialising is waiting for (each time that changes)."""


class ConnectionState(enum.StrEnum):
    REGISTERED = "registered"
    CONNECTING = "connecting"
    CONNECTED = "connected"
    READY = "ready"
    LINK_LOST = "link_lost"
    FAILED = "failed"


#: the states in which a drone is heard: enough for a stop (land, return, hold), which never waits for ready
#: to fly (an ArduPilot drone is ready only with its first EKF report, up to half a minute later)
HEARD = frozenset({ConnectionState.CONNECTED, ConnectionState.READY})


class LinkRules(Protocol):
    """What the link needs to know about the vehicle's autopilot (``gateway.fleet.dialects`` has them)."""

    @property
    def skipped_streams(self) -> frozenset[str]:
        """Telemetry streams not to request (the autopilot refuses them)."""
        ...

    @property
    def follows_events(self) -> bool:
        """Whether the autopilot explains refusals in EVENT messages (kept with the status texts)."""
        ...

    def mode_name(self, custom_mode: int, mav_type: int) -> str | None:
        """The flight mode a HEARTBEAT reports, or None to use MAVSDK's name for it."""
        ...

    @property
    def estimate_from_ekf_report(self) -> bool:
        """Whether the position estimate is read from EKF_STATUS_REPORT (then a drone is not ready before
        the first report, unless the autopilot refused the stream)."""
        ...

    def position_estimate_ok(self, health: HealthValue, ekf_flags: int | None) -> bool:
        """Whether the autopilot's position estimate is good enough to arm and fly."""
        ...

    @property
    def ready_after_prearm_pass(self) -> bool:
        """Whether a disarmed drone is still initialising until the autopilot's own pre-arm bit
        (SYS_STATUS, MAV_SYS_STATUS_PREARM_CHECK) has said "armable" once in the session."""
        ...

    def on_ground(self, telemetry: TelemetryCache) -> bool | None:
        """Whether the vehicle is on the ground (None: no fresh telemetry says)."""
        ...


class Peer(Protocol):
    """Another vehicle's link, as seen for duplicate system ids."""

    @property
    def id(self) -> str: ...

    @property
    def sysid(self) -> int | None: ...

    @property
    def state(self) -> ConnectionState: ...


@dataclass(frozen=True)
class GroundCommand:
    """A frame from a ground station on the gateway's relay that acts on the drone
    (`gateway.link.ground_commands`)."""

    sysid: int
    what: str  # "SET_POSITION_TARGET_GLOBAL_INT", "COMMAND_LONG MAV_CMD_DO_REPOSITION"...
    at: float  # monotonic, when the relay passed it on
