"""The fleet as the model is told it: ids, on the ground or flying, altitude, battery.

A small model invents ids (``drone1``, ``Alpha``) and forgets what is already flying. The host reads the
roster from the gateway's ``list_drones`` tool before each model request and gives it to the model as a
short line, and it writes the current ids into the tool schemas as an ``enum``, so that its own schema
validation refuses a wrong id before anything is sent.
"""

from __future__ import annotations

import copy
import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

from gateway.agent.toolbox import Arguments, ToolInfo
from gateway.agent.turns import ToolCaller

ROSTER_TOOL = "list_drones"
# Arguments that name one drone / several drones in the gateway's tools.
DRONE_ID_ARGS = ("drone_id",)
DRONE_IDS_ARGS = ("drone_ids",)


@dataclass(frozen=True)
class DroneEntry:
    drone_id: str
    flying: bool | None
    alt_m: float | None
    battery_pct: float | None
    state: str | None = None
    operation: str | None = None
    lat_deg: float | None = None  # where it is; not shown to the model, used to read "0, 0" as "here"
    lon_deg: float | None = None

    def text(self) -> str:
        if self.state not in (None, "ready"):
            where = f"not ready ({self.state})"
        elif self.flying:
            where = "flying" + (f" at {self.alt_m:.0f} m" if self.alt_m is not None else "")
        elif self.flying is False:
            where = "on the ground"
        else:
            where = "state unknown"
        battery = f", battery {self.battery_pct:.0f}%" if self.battery_pct is not None else ""
        busy = f", busy: {self.operation}" if self.operation else ""
        return f"{self.drone_id} {where}{battery}{busy}"


@dataclass(frozen=True)
class Roster:
    drones: tuple[DroneEntry, ...]

    @property
    def ids(self) -> list[str]:
        return [d.drone_id for d in self.drones]

    def text(self) -> str:
        """One line: ``Fleet now: alpha flying at 15 m, battery 97%; bravo on the ground, battery 100%.``"""
        if not self.drones:
            return "Fleet now: no drones."
        return "Fleet now: " + "; ".join(d.text() for d in self.drones) + "."

    @classmethod
    def from_structured(cls, data: object) -> Roster | None:
        """From ``list_drones``' structured result (``{"drones": [{"drone_id", "in_air", ...}]}``)."""
        rows = data.get("drones") if isinstance(data, Mapping) else None
        if not isinstance(rows, list):
            return None
        out = []
        for row in rows:
            if not isinstance(row, Mapping) or not isinstance(row.get("drone_id"), str):
                continue
            out.append(
                DroneEntry(
                    drone_id=row["drone_id"],
                    flying=_bool(row.get("in_air")),
                    alt_m=_num(row.get("alt_m")),
                    battery_pct=_num(row.get("battery_pct")),
                    state=row.get("state") if isinstance(row.get("state"), str) else None,
                    operation=row.get("operation") if isinstance(row.get("operation"), str) else None,
                    lat_deg=_num(row.get("lat_deg")),
                    lon_deg=_num(row.get("lon_deg")),
                )
            )
        return cls(tuple(out))


async def fetch_roster(caller: ToolCaller) -> Roster | None:
    """The roster from the gateway, or None when it cannot be read (the model then goes without it)."""
    outcome = await caller.call_tool(ROSTER_TOOL, {})
    if outcome.is_error:
        return None
    return Roster.from_structured(outcome.structured)


class FleetView:
    """The fleet as the host knows it, and the tools as the model is offered them: the roster is read
    from the gateway's ``list_drones`` (before each model request, and again where a call needs it
    fresh); when its ids change the tool schemas get them as an ``enum`` (the tool list changes only
    then, so a server's prompt cache survives ordinary steps)."""

    def __init__(
        self,
        caller: ToolCaller,
        base_tools: Sequence[ToolInfo],
        enabled: bool,
        on_read: Callable[[Roster | None], None],
    ) -> None:
        self.caller = caller
        self.base_tools = list(base_tools)  # as the gateway declares them
        self.enabled = enabled  # False: no roster, no enum, no retries
        self.roster: Roster | None = None
        self.ids: list[str] = []  # the ids written into the tool schemas
        self._on_read = on_read  # told each roster read (None: the server offers no list_drones)
        self._offer(self.base_tools)

    def _offer(self, tools: Sequence[ToolInfo]) -> None:
        self.tools = {t.name: t for t in tools}
        self.specs = [t.openai_spec() for t in tools]
        # each tool's argument names, to read a call the model wrote as text
        self.parameters = {t.name: list((t.input_schema or {}).get("properties") or {}) for t in tools}

    async def refresh(self) -> Roster | None:
        """Read the fleet from the gateway (None when there is no roster)."""
        if not self.enabled:
            return None
        roster = await fetch_roster(self.caller)
        if roster is None:
            self.enabled = False  # a server without list_drones
            self._on_read(None)
            return None
        self.roster = roster
        if roster.ids != self.ids:
            self.ids = roster.ids
            self._offer([with_drone_enum(t, roster.ids) for t in self.base_tools])
        self._on_read(roster)
        return roster

    async def fresh_entry(self, drone_id: object) -> DroneEntry | None:
        """The drone as the gateway reports it now: in a plan, the roster read before the reply is out of
        date once the reply's own takeoff has run. None without a roster."""
        if not self.enabled:
            return None
        await self.refresh()
        return self.entry(drone_id)

    def entry(self, drone_id: object) -> DroneEntry | None:
        drones = self.roster.drones if self.roster is not None else ()
        return next((d for d in drones if d.drone_id == drone_id), None)

    def on_ground(self, drone_id: object) -> bool:
        entry = self.entry(drone_id)
        return entry is not None and entry.flying is False


def with_drone_enum(tool: ToolInfo, ids: Sequence[str]) -> ToolInfo:
    """The tool with ``drone_id`` / ``drone_ids`` limited to the current ids (a copy; the original stays)."""
    props = (tool.input_schema or {}).get("properties")
    if not ids or not isinstance(props, Mapping):
        return tool
    if not any(name in props for name in (*DRONE_ID_ARGS, *DRONE_IDS_ARGS)):
        return tool
    schema = copy.deepcopy(tool.input_schema)
    for name, prop in schema["properties"].items():
        if not isinstance(prop, dict):
            continue
        if name in DRONE_ID_ARGS:
            prop["enum"] = list(ids)
        elif name in DRONE_IDS_ARGS:
            items = prop.setdefault("items", {})
            if isinstance(items, dict):
                items["enum"] = list(ids)
    return dataclasses.replace(tool, input_schema=schema)


def normalise_drone_ids(arguments: Arguments, ids: Sequence[str]) -> list[str]:
    """Correct the case of drone ids in place where exactly one known id matches (``Alpha`` -> ``alpha``),
    as the gateway itself accepts them; returns notes naming each correction."""
    notes: list[str] = []
    by_lower: dict[str, list[str]] = {}
    for i in ids:
        by_lower.setdefault(i.lower(), []).append(i)

    def fix(value: object) -> object:
        if isinstance(value, str) and value not in ids:
            match = by_lower.get(value.strip().lower(), [])
            if len(match) == 1:
                notes.append(f"drone id {value!r} read as {match[0]!r}")
                return match[0]
        return value

    for name in DRONE_ID_ARGS:
        if name in arguments:
            arguments[name] = fix(arguments[name])
    for name in DRONE_IDS_ARGS:
        if isinstance(arguments.get(name), list):
            arguments[name] = [fix(v) for v in arguments[name]]
    return notes


def drones_named(arguments: Arguments | None) -> frozenset[str] | None:
    """The drones a call names; None when it names none (a fleet call without ids means all drones)."""
    if not arguments:
        return None
    named: set[str] = set()
    for name in DRONE_ID_ARGS:
        if isinstance(arguments.get(name), str):
            named.add(arguments[name])
    for name in DRONE_IDS_ARGS:
        if isinstance(arguments.get(name), list):
            named.update(v for v in arguments[name] if isinstance(v, str))
    return frozenset(named) if named else None


def _bool(v: object) -> bool | None:
    return v if isinstance(v, bool) else None


def _num(v: object) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None
