"""Checks of a call before it is sent, in order: ``Allow``, ``Reject`` (not sent, its note in the answer),
``Replace`` (another call) or ``Stop`` (no more this turn); none loosens or repeats the gateway's rules."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

from fleet_agent.compiler import Call
from fleet_agent.mcp_link import ToolInfo
from fleet_agent.records import Refusal


@dataclass(frozen=True)
class Allow:
    pass


@dataclass(frozen=True)
class Reject:
    note: str


@dataclass(frozen=True)
class Replace:
    call: Call
    note: str


@dataclass(frozen=True)
class Stop:
    note: str


Verdict = Allow | Reject | Replace | Stop


@dataclass
class TurnState:
    """What the checks may read: the tools offered and what the turn's calls met so far."""

    tools: dict[str, ToolInfo]
    refused: dict[str, Refusal] = field(default_factory=dict)  # drone -> the gateway's refusal
    link_failed: bool = False


class Check(Protocol):
    name: str

    def __call__(self, call: Call, turn: TurnState) -> Verdict: ...


class OfferedTool:
    """The gateway must offer the tool (a selection of toolsets may leave it out)."""

    name = "offered_tool"

    def __call__(self, call: Call, turn: TurnState) -> Verdict:
        if call.tool in turn.tools:
            return Allow()
        return Reject(f"the gateway offers no {call.tool} here, so it was not sent")


class NothingToFly:
    """A relative move of 0 m that changes no height is no step."""

    name = "nothing_to_fly"

    def __call__(self, call: Call, turn: TurnState) -> Verdict:
        if call.tool != "move_to_relative":
            return Allow()
        if any(call.args.get(k) for k in ("north_m", "east_m", "up_m")) or call.args.get("alt_m") is not None:
            return Allow()
        return Reject(f"{call.drone}: a move of 0 m was not sent")


class AfterRefusal:
    """Once the gateway refused a drone's call, that drone's later moves are not sent (they built on it);
    a landing, a return or a hold still is."""

    name = "after_refusal"
    still_sent = frozenset(
        "land return_to_launch hold_position fleet_land fleet_return_to_launch fleet_hold".split()
    )

    def __call__(self, call: Call, turn: TurnState) -> Verdict:
        if call.tool in self.still_sent:
            return Allow()
        refused = [d for d in call.drones if d in turn.refused]
        if refused:
            return Reject(f"{', '.join(refused)}: the rest was not sent after the refusal")
        return Allow()


class LinkLost:
    """When the MCP link to the gateway failed, nothing more is sent."""

    name = "link_lost"

    def __call__(self, call: Call, turn: TurnState) -> Verdict:
        return Stop("the link to the gateway failed; nothing more was sent") if turn.link_failed else Allow()


def default_checks() -> list[Check]:
    return [LinkLost(), AfterRefusal(), OfferedTool(), NothingToFly()]


def run_checks(checks: list[Check], call: Call, turn: TurnState) -> tuple[Call | None, list[str], bool]:
    """The call to send (None: none), the notes the checks left, and whether the turn stops."""
    notes: list[str] = []
    for check in checks:
        verdict = check(call, turn)
        if isinstance(verdict, Stop):
            return None, [*notes, verdict.note], True
        if isinstance(verdict, Reject):
            return None, [*notes, verdict.note], False
        if isinstance(verdict, Replace):
            call = verdict.call
            notes.append(verdict.note)
    return call, notes, False
