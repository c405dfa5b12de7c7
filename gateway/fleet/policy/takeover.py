"""A pilot or another ground station always wins: what the gateway commanded, and how it tells that
someone else took the drone.

Every command the gateway sends puts the autopilot in a mode its dialect names (`Dialect.commanded_modes`:
GUIDED for an ArduCopter goto, AUTO.MISSION for a PX4 mission...). The `OperationManager` keeps one
`ModeExpectation` per drone and watches the HEARTBEAT's mode: once the drone has been seen in a mode the
gateway commanded, a switch to any other mode that the gateway did not send (its own commands are sent
under the drone's command lock, and the watch looks away meanwhile) is a *takeover*: a pilot's RC mode
switch, another ground station, or the autopilot's own failsafe. The running operation then ends as
``interrupted`` with `Takeover.message`, and the drone is locked for agents (`Takeover.lock_reason`,
`gateway.fleet.policy.operator_locks.LockBook.take_over`) until an operator releases it. The gateway sends
that drone
nothing on its own meanwhile. The same holds when the mode stays but the autopilot's own target leaves
the gateway's (`ModeExpectation.target`), and when a ground station on the gateway's relay sends the
drone a command (`gateway.link.ground_commands`).

Pure logic: no I/O, no clocks but the times handed in.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from datetime import datetime

#: how far back a status text may explain a mode change (the autopilot says why just before it switches)
CAUSE_WINDOW_S = 5.0
#: what the autopilot says when a failsafe (or a fence, or the EKF) changes its mode, by cause
FAILSAFE_WORDS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("battery failsafe", ("battery", "batt ", "low voltage", "critical battery", "emergency battery")),
    ("radio (RC) failsafe", ("radio failsafe", "rc failsafe", "manual control lost", "rc lost", "no rc")),
    ("ground station (GCS) failsafe", ("gcs failsafe", "data link lost", "datalink", "gcs lost")),
    ("EKF / navigation failsafe", ("ekf", "navigation", "position estimate", "gps glitch", "no gps")),
    ("geofence breach", ("fence", "geofence")),
    ("crash or vibration check", ("crash", "vibration")),
    ("terrain failsafe", ("terrain",)),
    ("failsafe", ("failsafe", "fail safe")),
)
#: modes a failsafe (rather than a pilot) usually picks, in either autopilot's names
FAILSAFE_MODES = frozenset({"RTL", "SMART_RTL", "LAND", "AUTO_RTL", "BRAKE", "AUTO.RTL", "AUTO.LAND"})
_SPACE = re.compile(r"\s+")


@dataclass
class ModeExpectation:
    """What the gateway last commanded a drone to do, and the modes that doing it may show."""

    kind: str  # the operation kind, or "set_flight_mode X", "hold"
    modes: frozenset[str]
    settled: frozenset[str]  # the modes allowed once the operation succeeded
    operation_id: str | None = None
    #: the drone has been seen (armed) in one of ``modes`` since the command: only then is a change
    #: judged (the HEARTBEAT that follows a command can still show the mode before it)
    seen: bool = False
    #: when the drone was first seen outside the commanded modes in a mode it settles in (a mission
    #: that may have just finished), monotonic
    outside_since: float | None = None
    last_mode: str | None = None
    #: the gateway's target the autopilot should report (lat, lon, monotonic time sent): the running
    #: goto's leg, or where a hold or a goto that arrived left the drone; None: nothing to compare
    target: tuple[float, float, float] | None = None
    #: the autopilot has reported ``target`` since it was sent: from then on a move away is someone else's
    target_adopted: bool = False
    #: how far (m) the reported target may be from ``target``
    target_near_m: float = 10.0
    #: when the autopilot's reported target was first seen away from ``target`` (monotonic)
    target_off_since: float | None = None
    #: when the gateway commanded it (monotonic): a ground station's command on the relay after that is
    #: a takeover
    since: float = 0.0


@dataclass(frozen=True)
class Takeover:
    """A mode change the gateway did not command."""

    vehicle_id: str
    from_mode: str
    to_mode: str
    cause: str  # "a pilot or another ground station took control", "battery failsafe", ...
    said: str | None  # the autopilot's own words, when it said why
    at: datetime
    operation_id: str | None = None
    operation_kind: str | None = None
    #: the mode stayed; the autopilot's target moved away from the gateway's (another ground station)
    retargeted: bool = False
    #: a ground station on the gateway's relay sent the drone a command ("COMMAND_LONG MAV_CMD_...")
    command: str | None = None

    @property
    def failsafe(self) -> bool:
        return self.said is not None or self.to_mode in FAILSAFE_MODES

    def message(self) -> str:
        """How the operation ended, for the caller waiting on it."""
        said = f" (autopilot says: '{self.said}')" if self.said else ""
        if self.command is not None:
            return (
                f"a ground station commanded the drone in {self.to_mode}: {self.cause}. The ground station "
                f"has control now; drone {self.vehicle_id} is locked for agents until an operator releases it"
            )
        if self.retargeted:
            return (
                f"the autopilot left the gateway's target while staying in {self.to_mode}: {self.cause}. "
                f"The ground station has control now; drone {self.vehicle_id} is locked for agents until an "
                "operator releases it"
            )
        return (
            f"the autopilot switched from {self.from_mode} to {self.to_mode}: {self.cause}{said}. The "
            f"{'failsafe' if self.failsafe and self.said else 'pilot or ground station'} has control now; "
            f"drone {self.vehicle_id} is locked for agents until an operator releases it"
        )

    def lock_reason(self) -> str:
        """The takeover lock's reason, shown to agents, operators, list_drones and REST."""
        said = f" (autopilot says: '{self.said}')" if self.said else ""
        if self.command is not None:
            return f"taken over in {self.to_mode} at {self.at.strftime('%H:%M:%S')} UTC: {self.cause}"
        if self.retargeted:
            return (
                f"taken over in {self.to_mode} at {self.at.strftime('%H:%M:%S')} UTC: the autopilot left "
                f"the gateway's target, {self.cause}"
            )
        return (
            f"taken over in {self.to_mode} at {self.at.strftime('%H:%M:%S')} UTC: the autopilot left "
            f"{self.from_mode}, {self.cause}{said}"
        )

    def to_record(self) -> dict[str, str | None]:
        return {
            "vehicle_id": self.vehicle_id,
            "from_mode": self.from_mode,
            "to_mode": self.to_mode,
            "cause": self.cause,
            "said": self.said,
            "at": self.at.isoformat(),
            "operation_id": self.operation_id,
            "operation_kind": self.operation_kind,
            "retargeted": "yes" if self.retargeted else None,
            "command": self.command,
        }


def likely_cause(to_mode: str, texts: Iterable[str]) -> tuple[str, str | None]:
    """Why the mode changed, as far as the autopilot told: (cause, its words or None). ``texts`` are its
    recent status texts, newest last."""
    for text in reversed(list(texts)):
        lowered = text.lower()
        for cause, words in FAILSAFE_WORDS:
            if any(word in lowered for word in words):
                return cause, _SPACE.sub(" ", text).strip()[:200]
    if to_mode in FAILSAFE_MODES:
        return (
            "a pilot, another ground station or an autopilot failsafe chose it "
            "(the autopilot did not say why)",
            None,
        )
    return "a pilot or another ground station took control", None
