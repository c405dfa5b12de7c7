"""The agent loop: model -> tool calls -> MCP calls -> results back to the model, until it answers.

The host adds no safety logic of its own and none that bypasses the gateway: it only refuses to *send*
a call whose arguments do not validate against the tool's input schema (with the fleet's current ids as
an ``enum``) or that repeats a call which has just succeeded, and it hands every tool error (the
gateway's refusals included) back to the model verbatim so the model can correct itself.

What keeps a small model on track: the fleet roster after each step, an empty reply never taken as the
answer (asked again, at most twice, with the request and what was done so far), a repeated call
answered "already done" instead of being sent, and a mistaken tool name answered with the closest one.
The system prompt and the tool list stay the same between steps (a local server then reuses the cached
prompt prefix); what changes (the roster) goes at the end of the conversation.
"""

from __future__ import annotations

import asyncio
import itertools
import json
import re
import time
from collections.abc import Awaitable, Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import openai

from gateway.agent.answer import ANSWER_TOOL, ANSWER_TOOL_INFO, answer_text, finish_hint
from gateway.agent.intent import (
    Reading,
    coordinates_as_metres,
    superseded,
    swapped_request_point,
    zero_zero_as_here,
)
from gateway.agent.parsing import (
    ArgumentsError,
    extract_tool_calls,
    known_case,
    parse_arguments,
    strip_thinking,
)
from gateway.agent.repair import (
    LAT_LON_PAIRS,
    altitude_not_a_climb,
    direction_mismatch,
    null_island,
    request_points,
    restore_request_directions,
    restore_request_numbers,
    swap_hint,
)
from gateway.agent.roster import (
    DroneEntry,
    Roster,
    drones_named,
    fetch_roster,
    normalise_drone_ids,
    with_drone_enum,
)
from gateway.agent.toolbox import (
    ToolInfo,
    ToolOutcome,
    closest_tool,
    only_beyond_limits,
    signature,
    validate_arguments,
)

DEFAULT_SYSTEM_PROMPT = (
    "You are the pilot assistant of a drone fleet. You act only through the tools you are given; never "
    "claim an action that no tool result confirmed. Altitudes are metres above each drone's home unless a "
    "tool says otherwise. When a tool reports an operation still running, keep checking with the tools "
    "until it is done before the next step of a plan. If a tool refuses a request, do not try to work "
    "around the safety rule: tell the user which rule refused it. When the task is done, answer briefly "
    "with what was done and the final state."
)

# An empty reply is asked again at most this many times before the turn ends as ``empty_answer``.
MAX_EMPTY_REPROMPTS = 2
# Tools that only wait for or report on an action already running: calling one between two identical
# calls does not make the second one new.
WAIT_TOOLS = frozenset({"monitor_flight", "monitor_fleet", "check_arrival"})
# With ``follow_running``: how many capped waits the host itself adds to an action still running (each
# monitor call waits up to the gateway's cap, 45 s by default) before it hands "running" to the model.
MAX_FOLLOW_WAITS = 20


class ModelReplyError(RuntimeError):
    """The model endpoint answered with something that is not a usable chat completion."""


@dataclass
class AgentEvent:
    """One thing that happened in a turn; displays render these, ``--json`` prints them as lines."""

    kind: str
    data: dict[str, Any]

    def to_json(self) -> dict[str, Any]:
        return {"event": self.kind, **self.data}


EventSink = Callable[[AgentEvent], None]


class ToolCaller(Protocol):
    """What the host needs from an MCP connection (``McpLink`` implements it)."""

    async def call_tool(
        self,
        name: str,
        arguments: dict[str, Any],
        progress: Callable[[float, float | None, str | None], Awaitable[None]] | None = None,
    ) -> ToolOutcome: ...


@dataclass
class ModelConfig:
    """Where and how to reach the chat model (any OpenAI-compatible Chat Completions endpoint)."""

    endpoint: str
    model: str
    api_key: str = "not-needed"
    temperature: float | None = 0.0
    timeout_s: float = 300.0
    max_retries: int = 1
    max_tokens: int | None = None  # cap on one reply (a small model on a CPU can ramble for minutes)


@dataclass
class ToolCallRecord:
    """One tool call of a turn, as executed (or not)."""

    id: str
    name: str
    arguments: dict[str, Any] | None
    status: str  # ok | error | invalid | unknown_tool | repeat | skipped | left_out
    summary: str
    parsed_from_text: bool = False
    text: str = ""  # what the model was told
    running: bool = False  # the result says the action is still going (a repeat of it is expected)

    @property
    def ok(self) -> bool:
        return self.status == "ok"


@dataclass
class Usage:
    """Token counts as reported by the API (None where the endpoint gave no usage)."""

    prompt_tokens: int | None = None
    completion_tokens: int | None = None
    model_calls: int = 0
    calls_without_usage: int = 0

    def add(self, prompt: int | None, completion: int | None) -> None:
        self.model_calls += 1
        if prompt is None and completion is None:
            self.calls_without_usage += 1
            return
        self.prompt_tokens = (self.prompt_tokens or 0) + (prompt or 0)
        self.completion_tokens = (self.completion_tokens or 0) + (completion or 0)

    def merge(self, other: Usage) -> None:
        """Add another turn's counts (a side nobody reported stays None)."""
        if other.prompt_tokens is not None or other.completion_tokens is not None:
            self.prompt_tokens = (self.prompt_tokens or 0) + (other.prompt_tokens or 0)
            self.completion_tokens = (self.completion_tokens or 0) + (other.completion_tokens or 0)
        self.model_calls += other.model_calls
        self.calls_without_usage += other.calls_without_usage


@dataclass
class TurnResult:
    """How one user turn ended."""

    outcome: str  # answered | empty_answer | step_limit | model_error
    final_text: str | None
    steps: int
    tool_calls: list[ToolCallRecord] = field(default_factory=list)
    usage: Usage = field(default_factory=Usage)
    wall_s: float = 0.0
    error: str | None = None
    parsed_from_text: int = 0
    empty_replies: int = 0
    # empty replies since the model last acted; the turn ends when it passes MAX_EMPTY_REPROMPTS
    empty_streak: int = 0
    # who wrote final_text: the model, or the host from the gateway's results when the model gave none
    answered_by: str = "model"


class AgentHost:
    """A conversation between one chat model and one MCP server's tools."""

    def __init__(
        self,
        model: ModelConfig,
        caller: ToolCaller,
        tools: Sequence[ToolInfo],
        *,
        max_steps: int = 12,
        system_prompt: str | None = DEFAULT_SYSTEM_PROMPT,
        on_event: EventSink | None = None,
        chat_client: openai.AsyncOpenAI | None = None,
        roster: bool = True,
        answer_tool: bool = False,
        follow_running: bool = False,
    ) -> None:
        if max_steps < 1:
            raise ValueError(f"max_steps must be at least 1, got {max_steps}")
        self.model = model
        self.caller = caller
        # answer_tool: offer the host's own answer_user tool, the way a small model ends a turn (answer.py)
        self.answer_tool = answer_tool
        self.base_tools = list(tools) + ([ANSWER_TOOL_INFO] if answer_tool else [])
        # follow_running: an action whose capped wait ended while it still runs is waited for by the host
        # (monitor_flight / monitor_fleet), so the model sees how it ended, as if the call had waited.
        self.follow_running = follow_running
        self._truncated = False  # the model's last reply stopped at the token limit
        self.use_roster = roster
        self.roster: Roster | None = None
        self._enum_ids: list[str] = []
        self._set_tools(self.base_tools)
        self.max_steps = max_steps
        self.system_prompt = system_prompt
        self.on_event = on_event or (lambda _e: None)
        self.chat = chat_client or openai.AsyncOpenAI(
            base_url=model.endpoint,
            api_key=model.api_key or "not-needed",
            timeout=model.timeout_s,
            max_retries=model.max_retries,
        )
        self.messages: list[dict[str, Any]] = []
        self.total_usage = Usage()
        self.turns = 0
        self._request = ""
        self._host_notes: list[str] = []  # what the host itself told the model this turn (echo detection)
        self._held: set[str] = set()  # why answers were sent back this turn (each reason once)
        # the host's own refusals of calls this turn (an answer copying one is no answer)
        self._error_texts: list[str] = []
        # the gateway's errors this turn (its refusals among them): an answer copying one tells the user
        # what happened, even when a host note quoted it first
        self._gateway_errors: list[str] = []
        self._refly_held: set[str] = set()  # calls held back once as flying a finished step again
        self._ids = itertools.count(1)
        self.reset()

    def reset(self) -> None:
        """Forget the conversation (the tool list stays)."""
        self.messages = [{"role": "system", "content": self.system_prompt}] if self.system_prompt else []

    def _set_tools(self, tools: Sequence[ToolInfo]) -> None:
        self.tools = {t.name: t for t in tools}
        self.tool_specs = [t.openai_spec() for t in tools]
        self._parameters = {t.name: list((t.input_schema or {}).get("properties") or {}) for t in tools}

    async def refresh_roster(self) -> Roster | None:
        """Read the fleet from the gateway; when its ids changed, the tool schemas get the new ``enum``
        (the tool list changes only then, so a server's prompt cache survives ordinary steps)."""
        if not self.use_roster:
            return None
        roster = await fetch_roster(self.caller)
        if roster is None:
            self.use_roster = False  # a server without list_drones: no roster, no enum, no retries
            self._emit("roster", available=False, message="no fleet roster: the server offers no list_drones")
            return None
        self.roster = roster
        if roster.ids != self._enum_ids:
            self._enum_ids = roster.ids
            self._set_tools([with_drone_enum(t, roster.ids) for t in self.base_tools])
        self._emit("roster", available=True, text=roster.text(), ids=roster.ids)
        return roster

    def _emit(self, kind: str, **data: Any) -> None:
        self.on_event(AgentEvent(kind, data))

    async def run_turn(self, user_text: str) -> TurnResult:
        """Send one user message and run the tool loop until the model answers or the step limit hits."""
        self.turns += 1
        started = time.monotonic()
        self._request = user_text
        self._host_notes = []
        self._held = set()
        self._error_texts = []
        self._gateway_errors = []
        self._refly_held = set()
        self._emit("turn_start", turn=self.turns, user=user_text)
        roster = await self.refresh_roster()
        content = f"{roster.text()}\n\n{user_text}" if roster is not None else user_text
        self.messages.append({"role": "user", "content": content})
        result = TurnResult(outcome="step_limit", final_text=None, steps=0)
        try:
            await self._loop(result)
        except asyncio.CancelledError:
            # The user interrupted (Ctrl-C): keep the conversation valid for the next turn and say that
            # an action already sent goes on in the gateway (a cancelled wait does not stop a drone).
            self._close_open_calls()
            self._emit("interrupted", message="turn interrupted; actions already sent continue on the drones")
            raise
        if result.outcome != "answered":
            await self._answer_for_the_model(result)
        result.wall_s = time.monotonic() - started
        self.total_usage.merge(result.usage)
        self._emit(
            "turn_end",
            turn=self.turns,
            outcome=result.outcome,
            steps=result.steps,
            tool_calls=len(result.tool_calls),
            empty_replies=result.empty_replies,
            prompt_tokens=result.usage.prompt_tokens,
            completion_tokens=result.usage.completion_tokens,
            wall_s=round(result.wall_s, 3),
        )
        return result

    async def _loop(self, result: TurnResult) -> None:
        while result.steps < self.max_steps:
            result.steps += 1
            try:
                reply = await self._ask_model(result.steps, result.usage)
            except (openai.OpenAIError, ModelReplyError) as exc:
                result.outcome, result.error = "model_error", f"{type(exc).__name__}: {exc}"
                self._emit("model_error", step=result.steps, error=result.error)
                break
            content, calls, parsed = reply
            if not calls:
                said = strip_thinking(content or "").strip()
                echo = bool(said) and self._echoes_host(said)
                if said and not echo and not self._truncated:
                    result.outcome, result.final_text = "answered", content or ""
                    self.messages.append({"role": "assistant", "content": content or ""})
                    self._emit("final", step=result.steps, text=content or "")
                    break
                # An empty reply is not an answer, nor is one that only repeats the request or the host's
                # own words (measured: the 1.5B model answered with the "done so far" re-prompt, the
                # request, or the host's "call takeoff ... first" note): ask again.
                result.empty_replies += 1
                result.empty_streak += 1
                if echo:
                    self._emit("echo_reply", step=result.steps, text=said)
                if result.empty_streak > MAX_EMPTY_REPROMPTS:
                    self._end_without_answer(result)
                    break
                self._emit("empty_reply", step=result.steps, attempt=result.empty_streak)
                reprompt = await self._reprompt(result, echo)
                if self._truncated:
                    reprompt = (
                        "Your reply was cut off at the length limit before a complete tool call. Write only "
                        f"the next tool call.\n{reprompt}"
                    )
                self._host_notes.append(reprompt)
                self.messages.append({"role": "user", "content": reprompt})
                continue
            if parsed:
                result.parsed_from_text += len(calls)
            self.messages.append(_assistant_message(content, calls, parsed))
            failed: ToolCallRecord | None = None
            answer: str | None = None
            gave_up = False
            for i, call in enumerate(calls):
                left_out = self._left_out(call, calls[i + 1 :]) if failed is None and answer is None else None
                if left_out is not None:
                    record = self._skip(result.steps, call, parsed, left_out, status="left_out")
                elif failed is not None:  # the calls of one reply are a plan: later steps need the earlier
                    why = f"the earlier call {failed.name} in the same reply failed. Fix that first."
                    record = self._skip(result.steps, call, parsed, why)
                elif answer is not None or gave_up:
                    record = self._skip(result.steps, call, parsed, "the turn ended with answer_user.")
                elif call["name"] == ANSWER_TOOL and self.answer_tool:
                    answer, gave_up = await self._answer_call(result.steps, call, parsed, result)
                    continue
                else:
                    record = await self._execute(result.steps, call, parsed, result)
                    if record.status in ("error", "invalid", "unknown_tool"):
                        failed = record
                    elif record.ok and self._acts(record.name):
                        # the model acted again after being asked: a later empty reply starts a new count
                        result.empty_streak = 0
                result.tool_calls.append(record)
            if answer is not None:
                result.outcome, result.final_text = "answered", answer
                self._emit("final", step=result.steps, text=answer, via=ANSWER_TOOL)
                break
            if gave_up:
                self._end_without_answer(result)
                break
            pending = _pending_text(result)
            if pending:
                self._host_notes.append(pending)
                self.messages[-1]["content"] += f"\n\n{pending}"
            if self._truncated:
                # Measured: a 6-step plan written as text stopped at 200 tokens inside the 4th call; the
                # 4th waypoint and the return home were never read, and the model did not notice.
                cut = (
                    "(Your reply was cut off at the length limit after this call; whatever came after it was "
                    "not read. Send the remaining steps, one call at a time.)"
                )
                self._host_notes.append(cut)
                self.messages[-1]["content"] += f"\n\n{cut}"
            if self.use_roster and result.steps < self.max_steps:
                roster = await self.refresh_roster()
                if roster is not None:
                    last = self.messages[-1]
                    last["content"] = f"{last['content']}\n\n{roster.text()}"
        else:
            self._emit(
                "step_limit",
                max_steps=self.max_steps,
                message=f"stopped after {self.max_steps} model steps without a final answer",
            )

    async def _answer_for_the_model(self, result: TurnResult) -> None:
        """The model gave no answer (empty replies, the step limit, a model error): the host answers from
        the gateway's own results, marked as the host's: what each call did or why the gateway refused
        it, and where the drones named are now. A model that stopped replying after some call ran or was
        refused considered the request finished: the turn counts as answered. One stopped by the step
        limit or a model error, or in which nothing ran, keeps its outcome (and its exit status)."""
        done = [c for c in result.tool_calls if c.ok and c.name != ANSWER_TOOL]
        refused = [c for c in result.tool_calls if c.status == "error"]
        parts = []
        if done:
            parts.append("Done: " + "; ".join(f"{c.name} ({c.summary})" for c in done) + ".")
        if refused:
            why = "; ".join(f"{c.name}: {_first_line(c.text)}" for c in refused[-3:])
            parts.append(f"Not done, the gateway refused: {why}.")
        if not done and not refused:
            reason = result.error or f"the model gave no usable reply ({result.outcome})"
            parts.append(f"Nothing was done: {reason}.")
        roster = await self.refresh_roster() if self.use_roster else None
        if roster is not None:
            touched = {d for c in [*done, *refused] for d in drones_named(c.arguments) or ()}
            named = {d for d in roster.ids if re.search(rf"\b{re.escape(d)}\b", self._request, re.IGNORECASE)}
            drones = [e.text() for e in roster.drones if e.drone_id in touched | named]
            if drones:
                parts.append("Now: " + "; ".join(drones) + ".")
        text = "(Answer from the host, from the gateway's results: the model gave none.) " + " ".join(parts)
        if (done or refused) and result.outcome == "empty_answer":
            result.outcome = "answered"
        result.final_text, result.answered_by = text, "host"
        self.messages.append({"role": "assistant", "content": text})
        self._emit("final", step=result.steps, text=text, via="host")

    def _end_without_answer(self, result: TurnResult) -> None:
        """The turn ends as ``empty_answer``: the model gave no answer too many times."""
        result.outcome = "empty_answer"
        self._emit(
            "empty_answer",
            step=result.steps,
            message=f"no answer {result.empty_streak} times in a row; the request may be unfinished",
        )

    async def _reprompt(self, result: TurnResult, echo: bool = False) -> str:
        """What the model is told after an empty reply: the request, what is done, what the request names
        that nothing has touched yet, the fleet now."""
        # Results in words, never in call syntax: a model may echo this text, and an echoed call must not
        # read as a new one.
        done = _in_words(c for c in result.tool_calls if c.ok)
        roster = await self.refresh_roster()
        parts = [
            "Your reply only repeated the request or my note; that is not an answer."
            if echo
            else "Your reply was empty.",
            f"The request: {self._request}",
            f"Already done (do not repeat): {done or 'nothing yet'}.",
        ]
        refused = [c for c in result.tool_calls if _refused(c)]
        if refused:
            # Measured: after "Refused: max_distance ..." the 1.5B model replied with nothing twice; a
            # refusal is an outcome to report, not a step still to do.
            parts.append(f"Refused (cannot be done, do not retry): {_in_words(refused[-2:])}.")
        untouched = self._untouched(result)
        if untouched:
            parts.append(untouched)
        pending = _pending_text(result)
        if pending:
            parts.append(pending)
        if roster is not None:
            parts.append(roster.text())
        said = "what was done and what was refused" if refused else "what was done"
        finish = (
            f"call answer_user with one sentence for the user saying {said}"
            if self.answer_tool
            else f"reply with one sentence for the user saying {said}"
        )
        what = "done or refused" if refused else "done"
        parts.append(
            f"If every part of the request is {what}, {finish}. Otherwise reply with only the tool call for "
            "the next step."
        )
        return "\n".join(parts)

    def _untouched(self, result: TurnResult, answering: bool = False) -> str:
        """Facts about parts of the request no successful call has used yet: drones it names, coordinates
        it gives (measured: after alpha's part, the 1.5B model forgot bravo; after two of three waypoints,
        it stopped)."""
        ok = [c.arguments for c in result.tool_calls if c.ok and c.arguments]
        acted = [c.arguments for c in result.tool_calls if c.ok and c.arguments and self._acts(c.name)]
        facts = []
        ids = self.roster.ids if self.roster is not None else []
        # Only actions count: reading or waiting on a drone (monitor_flight answered with the drone's
        # last, older operation) did nothing with it (measured: bravo was read, then forgotten).
        touched = {d for args in acted for d in drones_named(args) or ()}
        named = [i for i in ids if re.search(rf"\b{re.escape(i)}\b", self._request, re.IGNORECASE)]
        idle = [i for i in named if i not in touched]
        if idle and touched:
            facts.append(f"The request names {', '.join(idle)}, and nothing has been done with it yet.")
        flying = [d.drone_id for d in (self.roster.drones if self.roster else ()) if d.flying]
        aloft = [i for i in (named or sorted(touched)) if i in flying]
        # Only against an answer: in the middle of a plan a drone still flies before its last step.
        if answering and aloft and _LAND_WORDS.search(self._request):
            # Measured: "take off alpha to 10 m, then land it" answered "climbed and landed" after the
            # takeoff alone.
            facts.append(f"The request asks to land or come home, and {', '.join(aloft)} is still flying.")
        used = [
            (float(args[lat]), float(args[lon]))
            for args in ok
            for lat, lon in LAT_LON_PAIRS
            if isinstance(args.get(lat), int | float) and isinstance(args.get(lon), int | float)
        ]
        left = [
            p
            for p in request_points(self._request)
            if not any(abs(p[0] - a) < 1e-5 and abs(p[1] - b) < 1e-5 for a, b in used)
        ]
        if left and used:
            points = "; ".join(f"{a:g}, {b:g}" for a, b in left)
            facts.append(f"Points in the request not flown to yet: {points}.")
        return " ".join(facts)

    def _close_open_calls(self) -> None:
        """Answer every tool call of the last assistant message that has no result yet (the API rejects
        a conversation with unanswered tool calls)."""
        for i in range(len(self.messages) - 1, -1, -1):
            msg = self.messages[i]
            if msg.get("role") == "assistant" and msg.get("tool_calls"):
                answered = {m.get("tool_call_id") for m in self.messages[i + 1 :] if m.get("role") == "tool"}
                for tc in msg["tool_calls"]:
                    if tc["id"] not in answered:
                        self.messages.append({
                            "role": "tool",
                            "tool_call_id": tc["id"],
                            "content": "Interrupted by the user before the result arrived; an action already "
                            "sent may still be running on the drone.",
                        })  # fmt: skip
                return
            if msg.get("role") == "user":
                return

    # --- model side ------------------------------------------------------------------------------

    async def _ask_model(self, step: int, usage: Usage) -> tuple[str | None, list[dict[str, Any]], bool]:
        kwargs: dict[str, Any] = {"model": self.model.model, "messages": self.messages}
        if self.tool_specs:
            kwargs["tools"] = self.tool_specs
        if self.model.temperature is not None:
            kwargs["temperature"] = self.model.temperature
        if self.model.max_tokens is not None:
            kwargs["max_tokens"] = self.model.max_tokens
        response = await self.chat.chat.completions.create(**kwargs)
        u = getattr(response, "usage", None)
        prompt = getattr(u, "prompt_tokens", None) if u is not None else None
        completion = getattr(u, "completion_tokens", None) if u is not None else None
        usage.add(prompt, completion)
        if not response.choices:
            raise ModelReplyError("the model endpoint returned no choices")
        message = response.choices[0].message
        content = message.content
        self._truncated = response.choices[0].finish_reason == "length"
        calls = [
            {
                "id": tc.id or self._new_id(),
                "name": known_case(_clean_name(tc.function.name), self.tools),
                "raw_args": tc.function.arguments,
            }
            for tc in (message.tool_calls or [])
            if getattr(tc, "function", None) is not None
        ]
        parsed = False
        if not calls and content:
            found = extract_tool_calls(content, self._parameters)
            if found:
                parsed = True
                calls = [
                    {
                        "id": self._new_id(),
                        "name": c.name,
                        "raw_args": c.arguments,
                        "parse_error": c.error,
                        "notes": c.notes,
                    }
                    for c in found
                ]
        self._emit(
            "model_reply",
            step=step,
            content=content,
            tool_calls=len(calls),
            parsed_from_text=parsed,
            prompt_tokens=prompt,
            completion_tokens=completion,
            finish_reason=response.choices[0].finish_reason,
        )
        if parsed:
            self._emit(
                "parsed_from_text",
                step=step,
                count=len(calls),
                message=f"parsed {len(calls)} tool call(s) from text",
                notes=sorted({n for c in calls for n in c.get("notes", [])}),
            )
        return content, calls, parsed

    def _new_id(self) -> str:
        return f"call_host_{next(self._ids)}"

    # --- tool side -------------------------------------------------------------------------------

    async def _execute(
        self, step: int, call: dict[str, Any], parsed: bool, turn: TurnResult | None = None
    ) -> ToolCallRecord:
        call_id, name = call["id"], call["name"]
        args: dict[str, Any] | None = None
        problem: str | None = call.get("parse_error")
        notes: list[str] = []
        if problem is None:
            try:
                args = parse_arguments(call["raw_args"])
            except ArgumentsError as exc:
                problem = str(exc)
        reading: Reading | None = None
        if args is not None:
            notes = normalise_drone_ids(args, self._enum_ids) if self._enum_ids else []
            notes += restore_request_numbers(args, self._request)
            notes += swapped_request_point(args, self._request)
            reading = await self._read_as_meant(name, args)
            if reading is not None:
                name, args = reading.name, reading.arguments
                notes.append(reading.note)
            if name in ("move_to_relative",):
                notes += restore_request_directions(args, self._request)
                if args.get("up_m"):  # the fleet is read only when there is a climb to judge
                    drone = await self._fresh_entry(args.get("drone_id"))
                    alt_now = drone.alt_m if drone is not None and drone.flying else None
                    notes += altitude_not_a_climb(args, self._request, alt_now)
        self._emit(
            "tool_call",
            step=step,
            id=call_id,
            name=name,
            arguments=args if args is not None else call["raw_args"],
            parsed_from_text=parsed,
        )
        if notes:
            self._emit("arguments_corrected", step=step, id=call_id, name=name, notes=notes)
        tool = self.tools.get(name)
        earlier = self._repeat_of(name, args, turn) if tool is not None and args is not None else None
        if tool is None:
            status = "unknown_tool"
            outcome = ToolOutcome(text=self._unknown_tool_text(name, turn), is_error=True)
        elif problem is not None:
            status = "invalid"
            outcome = ToolOutcome(text=f"{problem} for {name}. Nothing was executed.", is_error=True)
        elif earlier is None and args is not None and (refly := self._refly_of(name, args, turn)):
            status = "repeat"
            so_far = _in_words(c for c in (turn.tool_calls if turn else []) if c.ok)
            outcome = self._host_note(
                text=f"Not sent: {refly} The request: {self._request} Done so far: {so_far}. If every part "
                f"is done, {finish_hint(self.answer_tool)}; else call the tool for the next step.",
                is_error=False,
            )
        elif earlier is not None:
            status = "repeat"
            outcome = self._host_note(
                text=f"Not sent again: this {name} call already succeeded in this request "
                f"({earlier.summary}). It is done; do not repeat it. The request: {self._request} "
                f"Call the tool for the next step, or {finish_hint(self.answer_tool)} if every part is "
                "done.",
                is_error=False,
            )
        else:
            assert args is not None
            island = null_island(args, self._request, on_ground=self._on_ground(args.get("drone_id")))
            if island is not None:
                self._host_notes.append(island)
            # a number beyond an advertised limit is sent: the gateway refuses it naming its rule
            schema_problem = None if only_beyond_limits(tool, args) else validate_arguments(tool, args)
            invalid = (
                self._unknown_arguments(tool, args)
                or schema_problem
                or island
                or direction_mismatch(args, self._request)
            )
            if invalid is not None:
                hint = swap_hint(args)
                text = f"{invalid} {hint}" if hint else invalid
                status, outcome = "invalid", ToolOutcome(text=text, is_error=True)
            else:

                async def progress(p: float, total: float | None, message: str | None) -> None:
                    self._emit("progress", id=call_id, name=name, progress=p, total=total, message=message)

                outcome = await self.caller.call_tool(name, args, progress)
                if self.follow_running:
                    outcome = await self._follow(step, call_id, name, args, outcome, progress)
                status = "error" if outcome.is_error else "ok"
                if reading is not None:  # the model learns what its call was read as, after the result
                    # (measured: with the note first, the 1.5B model answered a refusal by copying the note)
                    outcome = ToolOutcome(
                        f"{outcome.text} (Host note: {reading.note}.)", outcome.is_error, outcome.structured
                    )
                if outcome.is_error and "take off first" in outcome.text.lower().replace(
                    "takeoff", "take off"
                ):
                    # only where the gateway says the drone must take off first: a relative move from
                    # the ground refused for its distance would otherwise be answered "take off first,
                    # then this call again" (the issue's grounded far leg: takeoff, then the same refusal)
                    note = await self._takeoff_first(name, args)
                    if note:
                        self._host_notes.append(note)
                    outcome = ToolOutcome(outcome.text + note, True, outcome.structured)
        if status in ("invalid", "error") and self._same_invalid_again(name, args, turn):
            outcome = ToolOutcome(
                f"{outcome.text} This is the third time this same call was refused; it will not work. Stop "
                f"calling it: {finish_hint(self.answer_tool)}, saying what was done and what was refused.",
                is_error=True,
            )
        model_text = outcome.text
        if status in ("invalid", "unknown_tool"):
            # the host's own refusals are instructions to the model, no answer for the user; a gateway
            # refusal copied as the answer ("refused by rule max_altitude ...", "already on the ground")
            # does tell the user what happened (measured: an answer copying "alpha is already on the
            # ground" after a finished survey was sent back three times)
            self._error_texts.append(outcome.text)
        elif status == "error":
            self._gateway_errors.append(outcome.text)
        if outcome.is_error and not outcome.text.lower().startswith("error"):
            model_text = f"Error: {outcome.text}"  # the text itself stays verbatim
        self.messages.append({"role": "tool", "tool_call_id": call_id, "content": model_text})
        summary = outcome.summary()
        self._emit(
            "tool_result", step=step, id=call_id, name=name, status=status, summary=summary, text=outcome.text
        )
        structured = outcome.structured if isinstance(outcome.structured, dict) else {}
        return ToolCallRecord(
            id=call_id,
            name=name,
            arguments=args,
            status=status,
            summary=summary,
            parsed_from_text=parsed,
            text=model_text,
            running=structured.get("status") == "running",
        )

    async def _read_as_meant(self, name: str, args: dict[str, Any]) -> Reading | None:
        """The call a small model meant by this one (gateway/agent/intent.py), read against the fleet as it
        is now (in a plan, the takeoff before this call has changed it since the last roster)."""
        zero = name == "go_to_location" and args.get("lat_deg") == 0 and args.get("lon_deg") == 0
        metres = name == "move_to_relative" and len(request_points(self._request)) > 0
        if not (zero or metres):
            return None
        drone = await self._fresh_entry(args.get("drone_id"))
        return zero_zero_as_here(name, args, self._request, drone) or coordinates_as_metres(
            name, args, self._request, drone
        )

    async def _fresh_entry(self, drone_id: Any) -> DroneEntry | None:
        """The drone as the gateway reports it now: in a plan, the roster read before the reply is out of
        date once the reply's own takeoff has run. None without a roster."""
        if not self.use_roster:
            return None
        await self.refresh_roster()
        return self._entry(drone_id)

    def _entry(self, drone_id: Any) -> DroneEntry | None:
        drones = self.roster.drones if self.roster is not None else ()
        return next((d for d in drones if d.drone_id == drone_id), None)

    def _host_note(self, text: str, is_error: bool) -> ToolOutcome:
        self._host_notes.append(text)
        return ToolOutcome(text=text, is_error=is_error)

    def _echoes_host(self, said: str) -> bool:
        """The reply only repeats the request, or copies what the host told the model or an error a tool
        gave this turn (measured: an answer that was the host's note on an invalid call). A copied read
        ("alpha battery 73 %") is a fine answer."""
        text = _norm(said)
        text = re.sub(r"^error(?: executing tool \w+)?:\s*", "", text)
        if len(text) < 20:
            # a short reply that is a whole phrase of the host's note (measured: "Nothing yet.", from
            # "Already done: nothing yet", was taken as the answer)
            short = text.strip(" .,:;-")
            told = [*self._host_notes, *self._error_texts]
            return bool(short) and any(
                short == phrase.strip() for note in told for phrase in re.split(r"[.,:;]", _norm(note))
            )
        if text in _norm(self._request):
            return True
        if any(text[:60] in _norm(error) or _norm(error)[:50] in text for error in self._gateway_errors):
            return False  # it tells the user what the gateway refused, whatever else it copies
        told = [*self._host_notes, *self._error_texts]
        return any(text[:60] in _norm(note) for note in told)

    async def _takeoff_first(self, name: str, args: dict[str, Any]) -> str:
        """After a refused move of a drone on the ground: the takeoff to call, with the altitude of the
        refused call (the gateway's own text says "Call takeoff first" without numbers). The fleet is read
        again first: measured, a roster read before the reply still showed bravo on the ground after the
        reply's own takeoff, and the note sent the model to take off again instead of reporting the
        gateway's distance refusal."""
        drone, alt = args.get("drone_id"), args.get("alt_m")
        if name == "takeoff" or not isinstance(alt, int | float):
            return ""
        entry = await self._fresh_entry(drone) if self.use_roster else self._entry(drone)
        if entry is None or entry.flying is not False:
            return ""
        return (
            f' (Host note: {drone} is on the ground. Call takeoff with drone_id "{drone}" and alt_m '
            f"{alt:g} first, then this call again.)"
        )

    def _same_invalid_again(self, name: str, args: dict[str, Any] | None, turn: TurnResult | None) -> bool:
        """This refused call was already refused twice in this turn, identically."""
        if turn is None:
            return False
        refused = ("invalid", "error")
        same = [c for c in turn.tool_calls if c.name == name and c.arguments == args and c.status in refused]
        return len(same) >= 2

    def _on_ground(self, drone_id: Any) -> bool:
        entry = self._entry(drone_id)
        return entry is not None and entry.flying is False

    def _unknown_arguments(self, tool: ToolInfo, args: dict[str, Any]) -> str | None:
        """Arguments the tool does not have (in the gateway's own schema, hidden ones included) are refused
        rather than silently dropped: a model that adds lat_deg to takeoff has misread the tool."""
        base = next((t for t in self.base_tools if t.name == tool.name), tool)
        known = set((base.input_schema or {}).get("properties") or {})
        extra = sorted(set(args) - known)
        if not known or not extra:
            return None
        names = ", ".join(extra)
        return f"{tool.name} has no argument {names}; it takes {signature(tool)}. Nothing was executed."

    def _skip(
        self, step: int, call: dict[str, Any], parsed: bool, why: str, status: str = "skipped"
    ) -> ToolCallRecord:
        """A call of a reply that is not sent (an earlier call failed, the turn ended, or a later call
        supersedes it: ``left_out``): the model is told why."""
        text = (
            f"Not executed: {why}"
            if status == "skipped"
            else f"Left out: {why}; the rest of your reply goes on."
        )
        self._host_notes.append(text)  # measured: copied back as the answer
        self.messages.append({"role": "tool", "tool_call_id": call["id"], "content": text})
        self._emit("tool_result", step=step, id=call["id"], name=call["name"], status=status, summary=text,
                   text=text)  # fmt: skip
        return ToolCallRecord(call["id"], call["name"], _call_arguments(call), status, text, parsed, text)

    def _left_out(self, call: dict[str, Any], later: list[dict[str, Any]]) -> str | None:
        """Why this call of a plan is left out because the calls after it supersede it, or None."""
        args = _call_arguments(call)
        if args is None:
            return None
        planned = [(c["name"], a) for c in later if (a := _call_arguments(c)) is not None]
        return superseded(call["name"], args, self._request, planned)

    async def _answer_call(
        self, step: int, call: dict[str, Any], parsed: bool, result: TurnResult
    ) -> tuple[str | None, bool]:
        """An ``answer_user`` call: the answer that ends the turn, or None when it is sent back (empty, an
        echo, or premature once); the flag says the model has now given no answer too often."""
        try:
            args = parse_arguments(call["raw_args"]) if call.get("parse_error") is None else None
        except ArgumentsError:
            args = None
        text = answer_text(args)
        shown = args if args is not None else call["raw_args"]
        self._emit(
            "tool_call", step=step, id=call["id"], name=ANSWER_TOOL, arguments=shown, parsed_from_text=parsed
        )
        reply: str
        answer: str | None = None
        stale = self._written_before_results(text, result)
        empty = not text or stale or self._echoes_host(text)
        # An answer is held back first (once per reason): a model that gives up with an echo after its
        # own invalid call is told how to go on, not only that the echo is no answer.
        held = await self._hold_answer(result)
        if held:
            reply = held
            if empty:
                result.empty_replies += 1
                result.empty_streak += 1
        elif empty:
            result.empty_replies += 1
            result.empty_streak += 1
            if not text:
                reply = (
                    "Not an answer: answer_user needs text, one sentence for the user saying what was done "
                    "and where the drones are now."
                )
            elif stale:
                reply = (
                    "Not an answer: you wrote it with your plan, before the results; it was not sent. Since "
                    f"then: {_outcomes_text(result)} Say in one sentence what really happened."
                )
            else:
                reply = (
                    "Not an answer: that only repeats the request or my note. Say in one sentence what was "
                    "done and where the drones are now."
                )
        else:
            answer, reply = text, "Delivered to the user."
        gave_up = answer is None and result.empty_streak > MAX_EMPTY_REPROMPTS
        self._host_notes.append(reply)
        self.messages.append({"role": "tool", "tool_call_id": call["id"], "content": reply})
        status = "ok" if answer is not None else "invalid"
        self._emit(
            "tool_result",
            step=step,
            id=call["id"],
            name=ANSWER_TOOL,
            status=status,
            summary=reply,
            text=reply,
        )
        return answer, gave_up

    def _written_before_results(self, text: str, result: TurnResult) -> bool:
        """The answer is one the model wrote into a plan that then failed (skipped with the rest of it),
        sent again unchanged after a refusal. Measured: "Bravo has taken off and is flying to the farm",
        written beside the go_to_location the gateway refused, came back word for word as the answer."""
        refused = any(c.status in ("error", "invalid") for c in result.tool_calls)
        return refused and any(
            c.name == ANSWER_TOOL and c.status == "skipped" and answer_text(c.arguments) == text
            for c in result.tool_calls
        )

    async def _hold_answer(self, result: TurnResult) -> str | None:
        """Why an answer is sent back instead of ending the turn, or None; each reason at most once a turn,
        so a model that answers again is believed."""
        # the last call that ran (calls skipped after it in the same reply do not count)
        last = next((c for c in reversed(result.tool_calls) if c.status not in ("skipped", "left_out")), None)
        if last is not None and last.status in ("invalid", "unknown_tool") and "invalid" not in self._held:
            # Measured: after the host's note on go_to_location(0, 0) the 1.5B model answered with the note
            # itself; the call was the model's own mistake and nothing had been done.
            self._held.add("invalid")
            return (
                f"Not finished yet: your {last.name} call was not valid, so nothing was sent; my note above "
                "says how to fix it. Send the corrected call, then the rest of the request."
            )
        if "untouched" in self._held:
            return None
        if self.use_roster:
            await self.refresh_roster()  # whether a drone still flies is read now, not a step ago
        untouched = self._untouched(result, answering=True)
        if not untouched:
            return None
        self._held.add("untouched")
        return (
            f"Not finished yet: {untouched} Call the tool for the next step; call answer_user when every "
            "part is done, or to say why it cannot be done."
        )

    def _acts(self, name: str) -> bool:
        """The tool acts on drones (not a read, not a wait)."""
        tool = self.tools.get(name)
        return name not in WAIT_TOOLS and name != ANSWER_TOOL and not (tool is not None and tool.read_only)

    async def _follow(
        self,
        step: int,
        call_id: str,
        name: str,
        args: dict[str, Any],
        outcome: ToolOutcome,
        progress: Callable[[float, float | None, str | None], Awaitable[None]],
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
            followed = await self.caller.call_tool(tool, targs, progress)
            if followed.is_error:  # e.g. a server that does not offer the monitor tool: keep "running"
                return outcome
            outcome = followed
        return outcome

    def _repeat_of(self, name: str, args: dict[str, Any], turn: TurnResult | None) -> ToolCallRecord | None:
        """The earlier call of this turn that this one repeats: same tool, same arguments, it succeeded
        and finished, and no other action has been sent to the same drones since (waiting and reading
        in between do not count). A call repeated while its action still runs is not a repeat."""
        if turn is None:
            return None
        drones = drones_named(args)
        for earlier in reversed(turn.tool_calls):
            if earlier.status != "ok":
                continue
            if earlier.name == name and earlier.arguments == args:
                return None if earlier.running else earlier
            other = self.tools.get(earlier.name)
            acts = other is None or not (other.read_only or earlier.name in WAIT_TOOLS)
            theirs = drones_named(earlier.arguments)
            if acts and (drones is None or theirs is None or drones & theirs):
                return None
        return None

    def _refly_of(self, name: str, args: dict[str, Any], turn: TurnResult | None) -> str | None:
        """Why this action would fly a finished part of the request again, or None. Measured: "fly out,
        then bring it back and land where it took off" flew out, returned and landed, then took off and
        flew out again. Two cases, unless the request asks for something more than once: the same call
        (tool and arguments) already succeeded, with other actions since (so `_repeat_of` lets it
        through); or the drone is back on the ground after the landing or return the request ends with,
        and this call would take it up. Held back once: the same call sent again goes through."""
        if turn is None or not self._acts(name) or _AGAIN_WORDS.search(self._request):
            return None
        key = json.dumps([name, args], sort_keys=True, default=str)
        if key in self._refly_held:
            return None
        why = None
        same = next(
            (c for c in turn.tool_calls if c.ok and not c.running and c.name == name and c.arguments == args),
            None,
        )
        if same is not None:
            why = f"this {name} call already ran earlier in this request and succeeded ({same.summary})."
        elif name not in _DOWN_TOOLS and _ends_landed(self._request):
            drones = drones_named(args) or frozenset()
            for c in reversed(turn.tool_calls):
                down = drones_named(c.arguments)
                landed = [d for d in drones if self._on_ground(d) and (down is None or d in down)]
                if c.ok and c.name in _DOWN_TOOLS - {"fleet_hold", "hold_position"} and landed:
                    why = (
                        f"{', '.join(landed)} already came down as the request's last step asks "
                        f"({c.name}: {c.summary}); {name} would take it up again."
                    )
                    break
        if why is not None:
            self._refly_held.add(key)
        return why

    def _unknown_tool_text(self, name: str, turn: TurnResult | None) -> str:
        """Unknown tool: the closest offered tool with its arguments, firmer when the name is repeated."""
        near = closest_tool(name, list(self.tools.values()))
        calls = turn.tool_calls if turn is not None else []
        again = any(c.name == name and c.status == "unknown_tool" for c in calls)
        parts = [f"{name!r} does not exist; you called it again." if again else f"unknown tool {name!r}."]
        if near is not None:
            hint = f"Use {signature(near)} instead." if again else f"The closest tool is {signature(near)}."
            parts.append(hint)
        parts.append(f"Available tools: {', '.join(sorted(self.tools))}. Nothing was executed.")
        return " ".join(parts)


# Words of a request that ask for a landing or a return home.
_LAND_WORDS = re.compile(
    r"\b(?:land|lands|landing|rtl|return(?:s|ing)? (?:to (?:launch|home)|home)|(?:bring|come|go|fly|get) "
    r"(?:\w+ )?(?:back )?home)\b",
    re.IGNORECASE,
)


# Tools that bring drones down or stop them.
_DOWN_TOOLS = frozenset(
    {"land", "return_to_launch", "fleet_land", "fleet_return_to_launch", "fleet_hold", "hold_position"}
)
# Words after a request's last landing that ask for more flying.
_MOTION_WORDS = re.compile(
    r"\b(?:take (?:it |them )?off|takeoff|fly|go|move|climb|head|send|up|raise|hover|formation)\b",
    re.IGNORECASE,
)
_DOWN_WORDS = re.compile(
    rf"{_LAND_WORDS.pattern}|\b(?:set|put|bring) (?:it|them|\w+) (?:back )?down\b|\btouch(?:es)? down\b",
    re.IGNORECASE,
)


def _ends_landed(request: str) -> bool:
    """The request's last step brings the drones down: a landing or return, with no motion asked after it."""
    ends = [m.end() for m in _DOWN_WORDS.finditer(request)]
    return bool(ends) and not _MOTION_WORDS.search(request[ends[-1] :])


# Words of a request that ask for a step more than once.
_AGAIN_WORDS = re.compile(
    r"\b(?:again|twice|thrice|repeat\w*|\d+ times|two times|three times|back and forth|laps?|loops?)\b",
    re.IGNORECASE,
)


def _first_line(text: str) -> str:
    return next((s.strip() for s in text.splitlines() if s.strip()), "")


def _pending_text(result: TurnResult) -> str:
    """The calls of the model's own plan that were not sent because an earlier one failed, and have not
    succeeded since: once the failure is fixed, they are still the next steps (measured: after a refused
    go_to_location and a takeoff, the 1.5B model forgot the skipped move and landing)."""
    pending: list[ToolCallRecord] = []
    for i, c in enumerate(result.tool_calls):
        if c.status != "skipped" or c.arguments is None or c.name == ANSWER_TOOL:
            continue
        later = result.tool_calls[i + 1 :]
        if any(d.ok and d.name == c.name and d.arguments == c.arguments for d in later):
            continue
        if any(p.name == c.name and p.arguments == c.arguments for p in pending):
            continue
        pending.append(c)
    if not pending or result.tool_calls[-1].status == "skipped":
        return ""  # nothing left, or the failure that skipped them is the latest news
    calls = "\n".join(json.dumps({"name": c.name, "arguments": c.arguments}) for c in pending)
    return f"Not sent yet from your earlier reply (their turn comes after the call that failed):\n{calls}"


_REFUSAL_RE = re.compile(r"^(?:error[^:]*:\s*)*refused\b", re.IGNORECASE)


def _refused(record: ToolCallRecord) -> bool:
    """The gateway refused the call by a rule ("Refused: max_distance: ..."): an outcome to report. Other
    errors ("alt_m 0 is not above home") are mistakes the model can correct (measured: an alt_m=0 error
    labelled "cannot be done" was passed on to the user instead of corrected)."""
    return record.status == "error" and bool(_REFUSAL_RE.match(record.text))


def _in_words(records: Iterable[ToolCallRecord]) -> str:
    """Calls and their results in words, never in call syntax (a model may echo it: an echoed call must
    not read as a new one)."""
    return "; ".join(f"{c.name}: {c.summary}" for c in records)


def _outcomes_text(result: TurnResult) -> str:
    """What the calls of the turn did, in words: the done ones and the refused ones."""
    done = _in_words(c for c in result.tool_calls if c.ok)
    refused = _in_words(c for c in result.tool_calls if _refused(c))
    return (f"done: {done}." if done else "nothing done.") + (f" refused: {refused}." if refused else "")


def _call_arguments(call: dict[str, Any]) -> dict[str, Any] | None:
    """A call's arguments as a dict, or None when they do not parse."""
    if call.get("parse_error") is not None:
        return None
    try:
        return parse_arguments(call["raw_args"])
    except ArgumentsError:
        return None


def _norm(text: str) -> str:
    return " ".join(re.sub(r"[^\w.,:=-]+", " ", text.lower()).split())


def _args_text(args: dict[str, Any] | None) -> str:
    return ", ".join(f"{k}={json.dumps(v, default=str)}" for k, v in (args or {}).items())


def _clean_name(name: str | None) -> str:
    name = (name or "").strip()
    return name[len("functions.") :] if name.startswith("functions.") else name


def _assistant_message(content: str | None, calls: list[dict[str, Any]], parsed: bool) -> dict[str, Any]:
    """The assistant turn as it goes back into the conversation. A call recovered from text is given the
    structured form, so that the tool results that follow refer to a call the API knows about."""
    tool_calls = []
    for c in calls:
        raw = c["raw_args"]
        if isinstance(raw, str):
            args_text = raw
        else:
            args_text = json.dumps(raw if raw is not None else {})
        tool_calls.append(
            {"id": c["id"], "type": "function", "function": {"name": c["name"], "arguments": args_text}}
        )
    return {"role": "assistant", "content": None if parsed else content, "tool_calls": tool_calls}
