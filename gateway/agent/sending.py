"""Sending a call the host let through to the gateway (`gateway.agent.checks` held back the others):
its progress told as events, an action the gateway reports still running after its capped wait
followed to its end (``follow_running``), and a refused move of a drone on the ground completed with
the takeoff to call first."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

from gateway.agent import wording
from gateway.agent.intent import Reading
from gateway.agent.roster import FleetView
from gateway.agent.toolbox import Arguments, ToolInfo, ToolOutcome
from gateway.agent.turns import Progress, ToolCaller

# With ``follow_running``: how many capped waits the host itself adds to an action still running (each
# monitor call waits up to the gateway's cap, 45 s by default) before it hands "running" to the model.
MAX_FOLLOW_WAITS = 20


class Emit(Protocol):
    """The host's event sink: an event of ``kind`` with its data."""

    def __call__(self, kind: str, **data: Any) -> None: ...


class ToolSender:
    """Sends one tool call to the gateway for the agent host (`gateway.agent.host`)."""

    def __init__(
        self,
        caller: ToolCaller,
        fleet: FleetView,
        emit: Emit,
        note: Callable[[str], str],
        *,
        follow_running: bool = False,
    ) -> None:
        self._caller = caller
        self._fleet = fleet
        self._emit = emit
        self._note = note  # what the host tells the model is remembered (a reply copying it is no answer)
        self._follow_running = follow_running

    async def send(
        self, step: int, call_id: str, tool: ToolInfo, args: Arguments, reading: Reading | None
    ) -> tuple[str, ToolOutcome]:
        """Send the call to the gateway (and, with ``follow_running``, wait for it to end)."""
        name = tool.name

        async def progress(p: float, total: float | None, message: str | None) -> None:
            self._emit("progress", id=call_id, name=name, progress=p, total=total, message=message)

        outcome = await self._caller.call_tool(name, args, progress)
        if self._follow_running:
            outcome = await self._follow(step, call_id, name, args, outcome, progress)
        status = "error" if outcome.is_error else "ok"
        if reading is not None:  # the model learns what its call was read as, after the result
            # (measured: with the note first, the 1.5B model answered a refusal by copying the note)
            outcome = ToolOutcome(
                f"{outcome.text} (Host note: {reading.note}.)", outcome.is_error, outcome.structured
            )
        if outcome.is_error and "take off first" in outcome.text.lower().replace("takeoff", "take off"):
            # only where the gateway says the drone must take off first: a relative move from the ground
            # refused for its distance would otherwise be answered "take off first, then this call
            # again" (the issue's grounded far leg: takeoff, then the same refusal)
            note = await self.takeoff_first(name, args)
            if note:
                self._note(note)
            outcome = ToolOutcome(outcome.text + note, True, outcome.structured)
        return status, outcome

    async def takeoff_first(self, name: str, args: Arguments) -> str:
        """After a refused move of a drone on the ground: the takeoff to call, with the altitude of the
        refused call (the gateway's own text says "Call takeoff first" without numbers). The fleet is read
        again first: measured, a roster read before the reply still showed bravo on the ground after the
        reply's own takeoff, and the note sent the model to take off again instead of reporting the
        gateway's distance refusal."""
        drone, alt = args.get("drone_id"), args.get("alt_m")
        if name == "takeoff" or not isinstance(alt, int | float):
            return ""
        entry = await self._fleet.fresh_entry(drone) if self._fleet.enabled else self._fleet.entry(drone)
        if entry is None or entry.flying is not False:
            return ""
        return wording.takeoff_first(drone, alt)

    async def _follow(
        self, step: int, call_id: str, name: str, args: Arguments, outcome: ToolOutcome, progress: Progress
    ) -> ToolOutcome:
        """Wait for an action the gateway reported still running after its capped wait (not one the model
        sent with ``wait: false``): monitor_fleet for a fleet operation, monitor_flight for one drone."""
        if args.get("wait") is False:
            return outcome
        for _ in range(MAX_FOLLOW_WAITS):
            data = outcome.structured if isinstance(outcome.structured, dict) else {}
            if outcome.is_error or data.get("status") != "running":
                return outcome
            if isinstance(data.get("drones"), list) and isinstance(data.get("operation_id"), str):
                tool, targs = "monitor_fleet", {"operation_id": data["operation_id"]}
            elif isinstance(data.get("drone_id"), str):
                tool, targs = "monitor_flight", {"drone_id": data["drone_id"]}
            else:
                return outcome
            self._emit("following", step=step, id=call_id, name=name, tool=tool, arguments=targs)
            followed = await self._caller.call_tool(tool, targs, progress)
            if followed.is_error:  # e.g. a server that does not offer the monitor tool: keep "running"
                return outcome
            outcome = followed
        return outcome
