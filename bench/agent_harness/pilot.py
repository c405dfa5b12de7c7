"""The scripted "ideal pilot" of the benchmark's harness self-check (not a model).

It answers each chat request by looking at the conversation: while the last tool result says its
operation is still running it asks the wait tool, otherwise it sends the next planned call, and when the
plan is done it answers. It exercises the whole harness (gateway, MCP, host loop, checks, figures)
without a model; its numbers say nothing about any model and are labelled so.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from typing import Any

from bench.agent_harness.missions import PlannedCall
from bench.agent_harness.scripted import ScriptedReply
from gateway.agent.planning import PLAN_SYSTEM_PROMPT

SELF_CHECK_MODEL = "harness-self-check (scripted, not a model)"


@dataclass
class ScriptedPilot:
    """Callable reply source for ``ScriptedModelServer``; set ``plan`` before each mission."""

    wait_tool: str | None = "monitor_flight"
    wait_arg: str = "drone_id"
    max_waits_per_call: int = 40
    # Every n-th planned call is written as text (<tool_call> tags), as small models do, so the
    # self-check also runs the host's lenient parser end to end; 0 = always structured.
    text_every: int = 0
    plan: list[PlannedCall] = field(default_factory=list)
    answer: str = "Done."

    def load(self, plan: list[PlannedCall], answer: str) -> None:
        self.plan, self.answer = list(plan), answer

    def __call__(self, request: dict[str, Any]) -> ScriptedReply:
        messages = request.get("messages", [])
        if messages and messages[0].get("content") == PLAN_SYSTEM_PROMPT:
            # the small profile's plan step (gateway/agent/planning.py): no steps, so the host's notes stay
            # out of the conversation this pilot counts its calls in
            return ScriptedReply(content="")
        last_user = max(i for i, m in enumerate(messages) if m.get("role") == "user")
        turn = messages[last_user + 1 :]
        calls_made = [
            tc["function"]["name"]
            for m in turn
            if m.get("role") == "assistant"
            for tc in m.get("tool_calls") or []
        ]
        results = [m.get("content") or "" for m in turn if m.get("role") == "tool"]
        planned_done = sum(1 for name in calls_made if name != self.wait_tool)
        if results and self.wait_tool:
            op = running_operation(results[-1])
            waits = _trailing_waits(calls_made, self.wait_tool)
            if op is not None and waits < self.max_waits_per_call:
                return ScriptedReply(tool_calls=[(self.wait_tool, {self.wait_arg: op})])
        if planned_done < len(self.plan):
            name, args = self.plan[planned_done]
            if self.text_every and planned_done % self.text_every == self.text_every - 1:
                return ScriptedReply(
                    content=f"<tool_call>{json.dumps({'name': name, 'arguments': args})}</tool_call>"
                )
            return ScriptedReply(tool_calls=[(name, args)])
        answer = self.answer or f"Result: {results[-1] if results else ''}"
        return ScriptedReply(content=answer)


_WAIT_HINT_RE = re.compile(r"still running.*?monitor_flight\(drone_id=['\"]([^'\"]+)['\"]\)", re.DOTALL)


def running_operation(tool_text: str) -> str | None:
    """What to pass to the wait tool when a result says its operation is still running, else None.

    The gateway's text says "... still running (40%, ETA 12 s): ... Call monitor_flight(drone_id='alpha')
    to keep waiting." (the drone id is returned); a JSON result with status "running" gives its
    operation id."""
    m = _WAIT_HINT_RE.search(tool_text or "")
    if m:
        return m.group(1)
    try:
        data = json.loads(tool_text)
    except (json.JSONDecodeError, TypeError):
        return None
    if not isinstance(data, dict) or data.get("status") != "running":
        return None
    op = data.get("operation_id")
    if op is None and isinstance(data.get("operation"), dict):
        op = data["operation"].get("id")
    return str(op) if op else None


def _trailing_waits(calls: list[str], wait_tool: str) -> int:
    n = 0
    for name in reversed(calls):
        if name != wait_tool:
            break
        n += 1
    return n
