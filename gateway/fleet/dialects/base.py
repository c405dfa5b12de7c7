"""The seam between the flight verbs and an autopilot: the ``Dialect`` Protocol (``DialectReads``, what is
read through it, and what sending commands needs), and what a dialect may use of the vehicle's link
(``LinkOps``).

A dialect owns what differs between autopilots: its flight modes and the mapping of the common mode
names onto them, how a mission is laid out on the wire (ArduPilot's home slot 0; PX4 none) and how its
progress is counted, how the autopilot says it rejects a mission, the RTL altitude parameter and its
units, the arming rules, the parameters agents may not write, how to tell the vehicle is on the ground,
and the link facts (refused streams, mode names in HEARTBEAT, position estimate, EVENT messages).
Everything else (the verbs, the operations, the policy) is the same for every autopilot.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Mapping, Sequence
from typing import Protocol, TypeVar

from gateway.fleet.dialects.modes import ModeChoice
from gateway.fleet.missions.mission import DownloadedItem, MissionItem, WirePlan
from gateway.fleet.policy.mission_check import MissionSemantics
from gateway.fleet.policy.param_limits import ParamLimit
from gateway.link.mavsdk_system import System
from gateway.link.telemetry import HealthValue, MissionProgressValue, TelemetryCache

T = TypeVar("T")


class LinkOps(Protocol):
    """What a dialect may use of the vehicle's link (``gateway.link.session.Link`` has all of it)."""

    @property
    def id(self) -> str: ...

    @property
    def system(self) -> System: ...

    @property
    def telemetry(self) -> TelemetryCache: ...

    async def call(self, what: str, aw: Awaitable[T], timeout_s: float = ...) -> T: ...

    async def command_long(self, command: int, *params: float, what: str) -> None: ...


class DialectReads(Protocol):
    """What the gateway reads through an autopilot's dialect: link facts, the names of its modes, the
    landed state, mission progress and its parameters. Every autopilot has this much, even one the
    gateway has no dialect for (``unsupported.Unsupported``)."""

    @property
    def name(self) -> str:
        """The autopilot as a person names it, for messages ("ArduCopter", "PX4")."""
        ...

    # --- link facts (gateway.link.contract.LinkRules) --------------------------------------------------
    @property
    def skipped_streams(self) -> frozenset[str]: ...

    @property
    def follows_events(self) -> bool: ...

    def mode_name(self, custom_mode: int, mav_type: int) -> str | None: ...

    @property
    def estimate_from_ekf_report(self) -> bool: ...

    def position_estimate_ok(self, health: HealthValue, ekf_flags: int | None) -> bool: ...

    @property
    def ready_after_prearm_pass(self) -> bool: ...

    # --- flight modes --------------------------------------------------------------------------------
    def mode_names(self) -> list[str]:
        """Every name set_flight_mode accepts on this autopilot: the common ones, then its own."""
        ...

    def resolve_mode(self, name: str) -> ModeChoice | None:
        """The mode ``name`` (common or native, any case) means here, or None if there is none."""
        ...

    def native_mode(self, custom_mode: int) -> str:
        """The autopilot's own name of a HEARTBEAT custom mode (e.g. GUIDED, AUTO.LOITER)."""
        ...

    def commanded_modes(self, kind: str, *, done: bool = False) -> frozenset[str]:
        """The native modes the vehicle may be in while it does what the gateway commanded: an
        operation of ``kind`` (takeoff, goto, reposition, move_to_relative, set_yaw, hold, land,
        return_to_launch, mission, formation, fleet_climb), or ``done`` once that operation succeeded
        (PX4 holds after a takeoff or a mission). Every other mode is one the gateway did not command: a
        pilot, another ground station or a failsafe chose it (`gateway.fleet.policy.takeover`). Empty for a
        kind the dialect does not fly in a known mode (then nothing is judged)."""
        ...

    # --- the ground ----------------------------------------------------------------------------------
    def on_ground(self, telemetry: TelemetryCache, *, fresh: bool = True) -> bool | None:
        """Whether the vehicle is on the ground: None when no fresh telemetry says (``fresh=False``:
        from the cached values however old, for trackers that judge staleness themselves)."""
        ...

    # --- missions ------------------------------------------------------------------------------------
    @property
    def first_user_seq(self) -> int:
        """The wire seq of the user's item 1: 1 behind ArduPilot's home slot, else 0 (progress is
        counted from it: `mission_progress`)."""
        ...

    # --- parameters ----------------------------------------------------------------------------------
    @property
    def return_altitude_params(self) -> tuple[tuple[str, float], ...]:
        """The parameter RTL climbs to before flying home and its units per metre; several when
        versions of the autopilot name it differently (the first the vehicle has is used). Empty when
        the gateway does not know it."""
        ...

    @property
    def protected_params(self) -> tuple[str, ...]:
        """Glob patterns of parameters agents may not write (arming checks, fences, failsafes, ids)."""
        ...

    @property
    def mission_semantics(self) -> MissionSemantics:
        """The mission commands and frames whose effect the gateway models on this autopilot
        (`gateway.fleet.dialects.mission_semantics`); any other item is unchecked."""
        ...

    @property
    def limit_params(self) -> Mapping[str, ParamLimit]:
        """The parameters that set what the autopilot flies at, by name, each with the policy limit it
        could walk around (checked on an agent's write)."""
        ...


class Dialect(DialectReads, Protocol):
    """One autopilot's way of doing what the verbs need: its reads, and how commands are sent to it.
    Implementations: ``ardupilot.ArduPilot``, ``px4.PX4``; ``gateway.fleet.dialects`` finds them in its
    registry by the autopilot the HEARTBEAT names."""

    # --- arming ----------------------------------------------------------------------------------------
    @property
    def arming_mode(self) -> str | None:
        """The mode to switch to before arming (ArduPilot: GUIDED), None to arm in the current one."""
        ...

    def arming_will_pass(self, complaint: str) -> bool:
        """Whether an arming refusal is one the autopilot lifts by itself while it initialises."""
        ...

    async def set_yaw(self, link: LinkOps, heading_deg: float) -> None:
        """Turn in place to ``heading_deg`` (0-360, from true north)."""
        ...

    # --- missions ------------------------------------------------------------------------------------
    def encode_mission(self, items: list[MissionItem], home: tuple[float, float, float] | None) -> WirePlan:
        """The wire mission for the user's items (1..N)."""
        ...

    def decode_mission(self, wire: Sequence[DownloadedItem]) -> tuple[list[MissionItem], WirePlan]:
        """The user's items from a downloaded wire mission."""
        ...

    @property
    def mission_verdict_s(self) -> float:
        """How long after the upload's ACK the autopilot may still reject the mission (0: never)."""
        ...

    def mission_rejection(self, text: str) -> bool:
        """Whether a status text is the autopilot rejecting the uploaded mission."""
        ...

    async def start_mission_on_ground(self, link: LinkOps, arm: Callable[[], Awaitable[None]]) -> None:
        """Arm and start the uploaded (accepted) mission from the ground; the vehicle takes off."""
        ...


def mission_progress(
    dialect: DialectReads,
    current_seq: int,
    total: int,
    plan: WirePlan | None,
    finished: bool,
    *,
    from_mission_current: bool,
) -> MissionProgressValue:
    """Wire progress in the user's item numbers. ``total`` is MAVSDK's wire count or, with
    ``from_mission_current``, MISSION_CURRENT.total (which leaves ArduPilot's home out); ``plan`` (when
    known) maps DO_CHANGE_SPEED items to the item they belong to."""
    first_user_seq = dialect.first_user_seq
    wire_total = total + first_user_seq if from_mission_current else total
    if plan is None:
        user_total = max(0, wire_total - first_user_seq)
        user = min(max(0, current_seq - first_user_seq + 1), user_total)
    else:
        user_total = len(plan.user_to_wire)
        user = plan.user_index(current_seq) if current_seq >= first_user_seq and user_total else 0
    return MissionProgressValue(user_total if finished else user, user_total, finished)


def reader(telemetry: TelemetryCache, fresh: bool) -> Callable[[str], object]:
    """How a dialect reads a telemetry value: fresh only, or the cached one however old."""
    if fresh:
        return telemetry.fresh
    return lambda name: None if (sample := getattr(telemetry, name)) is None else sample.value


def matches_any(text: str, words: tuple[str, ...]) -> bool:
    lowered = text.lower()
    return any(word in lowered for word in words)
