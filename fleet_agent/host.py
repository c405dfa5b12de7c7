"""A turn: the model writes a plan, the host compiles each step and sends its calls through the checks. The
loop knows no drone, tool or word (`fleet_agent.compiler`, `fleet_agent.checks`, `fleet_agent.sensors` do)."""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

from fleet_agent.checks import Check, TurnState, default_checks, run_checks
from fleet_agent.compiler import Call, CompileError, Compiler, Said
from fleet_agent.decoding import Planner
from fleet_agent.mcp_link import ToolInfo
from fleet_agent.records import (
    AgentEvent,
    Arguments,
    EventSink,
    ModelConfig,
    ToolCaller,
    ToolCallRecord,
    ToolOutcome,
    TurnResult,
)
from fleet_agent.sensors import McpSensors, ReadFn

#: capped waits the host adds to an action the gateway reports still running (each up to its cap)
MAX_FOLLOW_WAITS = 20
WAIT_TOOL = "monitor_flight"


class AgentHost:
    """One chat model, one gateway (and optionally a server of named places)."""

    def __init__(self, model: ModelConfig, caller: ToolCaller, tools: Sequence[ToolInfo], *,
                 on_event: EventSink | None = None, checks: list[Check] | None = None,
                 planner: Planner | None = None,
                 places: tuple[ToolCaller, str] | None = None) -> None:  # fmt: skip
        self.caller = caller
        self.tools = {t.name: t for t in tools}
        self.on_event = on_event
        self.checks = default_checks() if checks is None else checks
        self.planner = planner or Planner(model)
        self.places = places
        self._ids = itertools.count(1)

    def emit(self, kind: str, **data: Any) -> None:
        if self.on_event is not None:
            self.on_event(AgentEvent(kind, data))

    async def run_turn(self, request: str) -> TurnResult:
        turn = TurnResult(outcome="answered", final_text=None)
        sensors = self._sensors(turn)
        fleet = await sensors.drone_ids()
        attempt = await self.planner.plan(request, fleet, [self.places[1]] if self.places else None)
        turn.usage, turn.steps = attempt.usage, len(attempt.replies)
        for reply in attempt.replies:
            self.emit("model_reply", content=reply)
        if attempt.plan is None:
            turn.outcome = "model_error" if attempt.model_error else "invalid_plan"
            turn.final_text = f"No plan could be made: {attempt.model_error or attempt.errors[-1]}"
            self.emit("final", text=turn.final_text, outcome=turn.outcome)
            return turn
        turn.plan = attempt.plan
        self.emit("plan", plan=attempt.plan.model_dump(mode="json"))
        lines = await self._run_plan(attempt.plan.steps, Compiler(sensors), sensors, turn)
        turn.final_text = " ".join(lines) if lines else "Nothing was asked that the fleet could do."
        self.emit("final", text=turn.final_text, outcome=turn.outcome)
        return turn

    def _sensors(self, turn: TurnResult) -> McpSensors:
        def reader(caller: ToolCaller) -> ReadFn:
            async def read(name: str, args: Arguments) -> ToolOutcome:
                return await self._send(turn, caller, Call(name, args))

            return read

        if self.places is None:
            return McpSensors(reader(self.caller))
        return McpSensors(reader(self.caller), self.places[1], reader(self.places[0]))

    async def _run_plan(
        self, steps: Sequence[Any], compiler: Compiler, sensors: McpSensors, turn: TurnResult
    ) -> list[str]:
        """Each step compiled when its turn comes (the fleet read after the calls before it), its calls and
        lines in order; the steps an ``if`` or a ``choose`` selects take their turns next."""
        state = TurnState(tools=self.tools)
        lines: list[str] = []
        queue = list(steps)
        while queue:
            step = queue.pop(0)
            try:
                selected = await compiler.branch(step)
                if selected is not None:
                    lines += [said.text for said in selected[0]]
                    queue[0:0] = selected[1]
                    continue
                compiled = await compiler.compile(step)
            except CompileError as exc:
                lines.append(f"Not done: {exc}.")
                continue
            for item in compiled:
                if isinstance(item, Said):
                    lines.append(item.text)
                elif await self._checked_send(item, state, sensors, turn, lines):
                    return lines
        return lines

    async def _checked_send(
        self, call: Call, state: TurnState, sensors: McpSensors, turn: TurnResult, lines: list[str]
    ) -> bool:
        """Send one call that the checks let through; True when the turn stops."""
        sent, notes, stop = run_checks(self.checks, call, state)
        lines += notes
        if sent is None:
            self._record(turn, call, ToolOutcome(text="; ".join(notes), is_error=True), status="skipped")
            return stop
        outcome = await self._send(turn, self.caller, sent)
        sensors.invalidate()
        refusal = outcome.refusal
        if refusal is None:
            lines.append(done_line(sent))
        else:
            state.refused.update({d: refusal for d in sent.drones})
            state.link_failed = state.link_failed or refusal.code == "mcp_error"
            lines.append(f"Refused: {refusal.message}")
        return False

    async def _send(self, turn: TurnResult, caller: ToolCaller, call: Call) -> ToolOutcome:
        call_id = f"call_{next(self._ids)}"
        self.emit("tool_call", id=call_id, name=call.tool, arguments=call.args)

        async def progress(p: float, total: float | None, message: str | None) -> None:
            self.emit("progress", id=call_id, name=call.tool, progress=p, total=total, message=message)

        outcome = await caller.call_tool(call.tool, call.args, progress)
        outcome = await self._follow(caller, call, outcome)
        self._record(turn, call, outcome, call_id=call_id)
        return outcome

    async def _follow(self, caller: ToolCaller, call: Call, outcome: ToolOutcome) -> ToolOutcome:
        """An action still running after the gateway's capped wait, waited for to its end."""
        for _ in range(MAX_FOLLOW_WAITS):
            running = (outcome.structured or {}).get("status") == "running"
            if outcome.is_error or not running or call.drone is None:
                return outcome
            outcome = await caller.call_tool(WAIT_TOOL, {"drone_id": call.drone})
        return outcome

    def _record(self, turn: TurnResult, call: Call, outcome: ToolOutcome, *, status: str | None = None,
                call_id: str | None = None) -> None:  # fmt: skip
        call_id = call_id or f"call_{next(self._ids)}"
        status = status or ("error" if outcome.is_error else "ok")
        record = ToolCallRecord(call_id, call.tool, call.args, status, outcome.text, outcome.refusal)
        turn.tool_calls.append(record)
        self.emit("tool_result", id=call_id, name=call.tool, status=status, text=outcome.text,
                  refusal=None if outcome.refusal is None else vars(outcome.refusal))  # fmt: skip


def done_line(call: Call) -> str:
    """What a sent call did, in the answer: the tool and its numbers."""
    args = ", ".join(
        f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in call.args.items() if k != "drone_id"
    )
    who = ", ".join(call.drones)
    return f"{who}: {call.tool}({args}) done." if args else f"{who}: {call.tool} done."
