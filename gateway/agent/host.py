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

This module is the loop; the records of a turn are in turns.py, the model side in chat.py, the host's
checks of a call in checks.py, sending a call that passed them (and following it) in sending.py, the
readings of what a small model meant in intent.py and repair.py, and what the host says to the model
and the user in wording.py.
"""

from __future__ import annotations

import asyncio
import json
import time
from collections.abc import Sequence
from typing import Any

import openai

from gateway.agent import checks, claims, held_answers, planning, readings, wording
from gateway.agent.answer import ANSWER_TOOL, ANSWER_TOOL_INFO, answer_text, bare_answer, finish_hint
from gateway.agent.chat import (
    ChatModel,
    Message,
    ModelReply,
    assistant_message,
    call_arguments,
    close_open_calls,
)
from gateway.agent.claims import Claim
from gateway.agent.intent import Reading, read_call
from gateway.agent.parsing import RESULT_FOLLOWS, ArgumentsError, parse_arguments, strip_thinking
from gateway.agent.repair import extras_of_a_drone_only_tool, unplaced_optional_point
from gateway.agent.roster import FleetView, Roster, drones_named
from gateway.agent.sending import ToolSender
from gateway.agent.step_calls import leg_without_height
from gateway.agent.toolbox import Arguments, ToolInfo, ToolOutcome
from gateway.agent.turns import (
    MAX_EMPTY_REPROMPTS,
    AgentEvent,
    EventSink,
    ModelCall,
    ModelConfig,
    ModelReplyError,
    ToolCaller,
    ToolCallRecord,
    TurnMemory,
    TurnResult,
    Usage,
    relative_moves,
)
from gateway.agent.wording import DEFAULT_SYSTEM_PROMPT

# DEFAULT_SYSTEM_PROMPT (wording.py), AgentEvent, ModelConfig, ToolCallRecord and TurnResult (turns.py)
# are imported from here too.


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
        plan_first: bool = False,
    ) -> None:
        if max_steps < 1:
            raise ValueError(f"max_steps must be at least 1, got {max_steps}")
        self.model = model
        self.caller = caller
        # answer_tool: offer the host's own answer_user tool, the way a small model ends a turn (answer.py)
        self.answer_tool = answer_tool
        base_tools = list(tools) + ([ANSWER_TOOL_INFO] if answer_tool else [])
        self._truncated = False  # the model's last reply stopped at the token limit
        self.fleet = FleetView(caller, base_tools, roster, self._roster_read)
        # follow_running: an action whose capped wait ended while it still runs is waited for by the host
        # (monitor_flight / monitor_fleet), so the model sees how it ended, as if the call had waited.
        self.sender = ToolSender(caller, self.fleet, self._emit, self._note, follow_running=follow_running)
        self.max_steps = max_steps
        # plan_first: the model first writes the request as numbered steps, without tools (planning.py)
        self.plan_first = plan_first
        self.system_prompt = system_prompt
        self.on_event = on_event or (lambda _e: None)
        self._chat = ChatModel(model, chat_client)
        self.messages: list[Message] = []
        self.total_usage = Usage()
        self.turns = 0
        self._memory = TurnMemory()  # what this turn has said and done, to judge the next reply
        self._turn_start = 0
        self._turn_plan: planning.Plan | None = None  # this turn's steps and where the turn is in them
        self._plan_made: set[str] = set()  # the calls the host made for this turn's steps
        self.reset()

    def reset(self) -> None:
        """Forget the conversation (the tool list stays)."""
        self.messages = [{"role": "system", "content": self.system_prompt}] if self.system_prompt else []

    # the fleet and the tools as offered (the fleet's ids as an ``enum``): see roster.FleetView
    @property
    def tools(self) -> dict[str, ToolInfo]:
        return self.fleet.tools

    def _roster_read(self, roster: Roster | None) -> None:
        if roster is None:
            self._emit("roster", available=False, message="no fleet roster: the server offers no list_drones")
        else:
            self._emit("roster", available=True, text=roster.text(), ids=roster.ids)

    def _emit(self, kind: str, **data: Any) -> None:
        self.on_event(AgentEvent(kind, data))

    def _note(self, text: str) -> str:
        """Remember what the host tells the model (a reply that only copies it is no answer)."""
        self._memory.host_notes.append(text)
        return text

    async def run_turn(self, user_text: str) -> TurnResult:
        """Send one user message and run the tool loop until the model answers or the step limit hits."""
        self.turns += 1
        started = time.monotonic()
        self._memory = TurnMemory(request=user_text)
        self._emit("turn_start", turn=self.turns, user=user_text)
        roster = await self.fleet.refresh()
        result = TurnResult(outcome="step_limit", final_text=None, steps=0)
        content = f"{roster.text()}\n\n{user_text}" if roster is not None else user_text
        self._turn_plan = None
        self._plan_made = set()
        if self.plan_first and roster is not None:
            steps = await self._plan(roster.ids, user_text, result.usage)
            if steps:
                content = f"{content}\n\n{self._note(planning.steps_text(steps))}"
                asked = planning.asked_drones(user_text, roster.ids)
                self._turn_plan = planning.Plan(steps, roster.ids, asked, user_text)
        self._turn_start = len(self.messages)  # where this turn's messages begin (a plan rewrites them)
        self.messages.append({"role": "user", "content": content})
        try:
            await self._loop(result)
        except asyncio.CancelledError:
            # The user interrupted (Ctrl-C): keep the conversation valid for the next turn and say that
            # an action already sent goes on in the gateway (a cancelled wait does not stop a drone).
            close_open_calls(self.messages, wording.INTERRUPTED)
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

    async def _plan(self, fleet_ids: list[str], request: str, usage: Usage) -> list[str]:
        """The request as numbered steps (planning.py); none when the model gives none or fails."""
        try:
            steps = await planning.plan_steps(self._chat, fleet_ids, request, usage)
        except (openai.OpenAIError, ModelReplyError) as exc:
            self._emit("plan", steps=[], error=f"{type(exc).__name__}: {exc}")
            return []
        self._emit("plan", steps=steps)
        return steps

    async def _loop(self, result: TurnResult) -> None:
        while result.steps < self.max_steps:
            result.steps += 1
            if await self._plan_calls(result):
                plan = self._turn_plan
                assert plan is not None
                # read again: the host's calls moved drones, and the answer's checks read this roster
                roster_now = await self.fleet.refresh() if self.fleet.enabled else None
                prompt = plan.prompt(self._memory.request, result.tool_calls, roster_now)
                self.messages[self._turn_start :] = [{"role": "user", "content": self._note(prompt)}]
            try:
                reply = await self._ask_model(result.steps, result.usage, result)
            except (openai.OpenAIError, ModelReplyError) as exc:
                result.outcome, result.error = "model_error", f"{type(exc).__name__}: {exc}"
                self._emit("model_error", step=result.steps, error=result.error)
                break
            content, calls, parsed = reply.content, reply.calls, reply.parsed
            copied = False
            if parsed:
                calls = self._without_copied_records(calls, result)
                copied = len(calls) < len(reply.calls)
            if not calls:
                said = strip_thinking(content or "").strip()
                echo = bool(said) and (copied or wording.echoes_host(said, self._memory))
                if (
                    said
                    and not echo
                    and not self._truncated
                    and (
                        held := held_answers.nothing_ran(result, self._memory, self.answer_tool)
                        or held_answers.claims_unbacked(
                            self._memory, self._unbacked(result, said), set(self.tools)
                        )
                        or held_answers.pick_unsaid(self._memory, result, self.fleet.ids, said)
                    )
                ):
                    self.messages.append({"role": "assistant", "content": content or ""})
                    self.messages.append({"role": "user", "content": self._note(held)})
                    self._emit("answer_held", step=result.steps, text=said, reason=held)
                    continue
                if said and not echo and not self._truncated:
                    result.outcome = "answered"
                    believed = self._believed(result, content or "")
                    result.final_text = wording.with_refusals(believed, result)
                    self.messages.append({"role": "assistant", "content": content or ""})
                    self._emit("final", step=result.steps, text=result.final_text)
                    break
                # An empty reply is not an answer, nor is one that only repeats the request or the host's
                # own words (measured: the 1.5B model answered with the "done so far" re-prompt, the
                # request, or the host's "call takeoff ... first" note): ask again.
                result.empty_replies += 1
                result.empty_streak += 1
                if echo:
                    self._emit("echo_reply", step=result.steps, text=said)
                plan = self._turn_plan
                if result.empty_streak > MAX_EMPTY_REPROMPTS or (
                    plan is not None and plan.finished(result.tool_calls)
                ):
                    # with every step of the plan done, an empty reply is the model's end: the host
                    # answers from the results (measured with the 1.5B model: asked twice more after
                    # "every step is done", it replied with nothing twice more)
                    self._end_without_answer(result)
                    break
                self._emit("empty_reply", step=result.steps, attempt=result.empty_streak)
                reprompt = await self._reprompt(result, echo)
                if self._truncated:
                    reprompt = f"{wording.CUT_BEFORE_CALL}\n{reprompt}"
                self.messages.append({"role": "user", "content": self._note(reprompt)})
                continue
            if parsed:
                result.parsed_from_text += len(calls)
            self.messages.append(assistant_message(content, calls, parsed))
            failed: ToolCallRecord | None = None
            answer: str | None = None
            gave_up = False
            reply_start = len(result.tool_calls)
            for i, call in enumerate(calls):
                left_out = (
                    checks.left_out(call, calls[i + 1 :], self._memory.request)
                    if failed is None and answer is None
                    else None
                )
                if left_out is not None:
                    record = self._skip(result.steps, call, parsed, left_out, status="left_out")
                elif failed is not None:  # the calls of one reply are a plan: later steps need the earlier
                    why = (
                        f"the earlier call {failed.name} in the same reply repeats a step it already did, so "
                        "that step of your plan is wrong. Send the request's next step."
                        if failed.status == "repeat"
                        else f"the earlier call {failed.name} in the same reply failed. Fix that first."
                    )
                    record = self._skip(result.steps, call, parsed, why)
                elif answer is not None or gave_up:
                    record = self._skip(result.steps, call, parsed, "the turn ended with answer_user.")
                elif call["name"] == ANSWER_TOOL and self.answer_tool:
                    reads = [
                        c
                        for c in result.tool_calls[reply_start:]
                        if c.ok and not checks.acts(self.tools, c.name)
                    ]
                    answer, gave_up = await self._answer_call(result.steps, call, parsed, result, reads)
                    continue
                else:
                    record = await self._execute(result.steps, call, parsed, result)
                    if record.status in ("error", "invalid", "unknown_tool"):
                        failed = record
                    elif record.status == "repeat" and checks.twice_in_plan(self.tools, call, calls[:i]):
                        # measured on the corpus's dev half (compound-two-climbs): "up to 10 m, then
                        # another 10 m higher, then land" planned as takeoff(10), takeoff(10), land; the
                        # second takeoff was held back and the landing flew, the climb never did
                        failed = record
                    elif record.ok and checks.acts(self.tools, record.name):
                        # the model acted again after being asked: a later empty reply starts a new count
                        result.empty_streak = 0
                result.tool_calls.append(record)
            if answer is not None:
                result.outcome, result.final_text = "answered", wording.with_refusals(answer, result)
                self._emit("final", step=result.steps, text=result.final_text, via=ANSWER_TOOL)
                break
            if gave_up:
                self._end_without_answer(result)
                break
            pending = wording.pending_text(result)
            if pending:
                self.messages[-1]["content"] += f"\n\n{self._note(pending)}"
            if self._truncated:
                self.messages[-1]["content"] += f"\n\n{self._note(wording.CUT_AFTER_CALL)}"
            if self.fleet.enabled and result.steps < self.max_steps:
                roster = await self.fleet.refresh()
                if roster is not None:
                    last = self.messages[-1]
                    last["content"] = f"{last['content']}\n\n{roster.text()}"
            plan = self._turn_plan
            sent = [c for c in result.tool_calls if c.status not in ("skipped", "left_out")]
            if (
                plan is not None
                and sent
                and checks.beside_a_finished_plan(sent[-1])
                and plan.finished(result.tool_calls)
            ):
                # only the answer is left and the model sent a finished call again, or a call that is no
                # call: the host answers from the results (dev half: a battery read sent again 19 times, to
                # the step limit; with the 0.5B model, fleet_status with made-up arguments, 9 times)
                self._end_without_answer(result)
                break
            if checks.stuck_on_a_refusal(result):
                # the host answers with what was done and what was refused, and why
                self._end_without_answer(
                    result, f"the same call was refused {checks.MAX_SAME_REPEATS} times; the host answers"
                )
                break
            if checks.stuck_on_a_repeat(result):
                if self._request_done(result):
                    # every part of the request is done and the model only sends a done call again: the
                    # host answers from the results (dev half with the 0.5B model, without a plan: "arrange
                    # all three drones in a circle ... here" flown right, then sent again to the limit)
                    self._end_without_answer(
                        result,
                        f"the same call came back {checks.MAX_SAME_REPEATS} times, already done, the request "
                        "done; the host answers",
                    )
                    break
                self._emit(
                    "step_limit",
                    max_steps=self.max_steps,
                    message=f"stopped: the same call came back {checks.MAX_SAME_REPEATS} times, already done",
                )
                break
            if (
                plan is not None
                and not pending
                and sent
                and (lead := self._plan_lead(plan, sent[-1], result))
            ):
                # the turn so far, rewritten as one user message ending with the step whose turn it is:
                # measured with the 1.5B model, after a tool result it often ends its reply at once (one
                # token), whatever the result or a note after it says; a first reply never came back empty
                roster_now = self.fleet.roster if self.fleet.enabled else None
                prompt = plan.prompt(self._memory.request, result.tool_calls, roster_now, lead.strip())
                self.messages[self._turn_start :] = [{"role": "user", "content": self._note(prompt)}]
        else:
            self._emit(
                "step_limit",
                max_steps=self.max_steps,
                message=f"stopped after {self.max_steps} model steps without a final answer",
            )

    async def _plan_calls(self, result: TurnResult) -> bool:
        """Make the calls the plan's next steps are, as the model would have, and say whether any ran:
        the readings a step needs, and a step whose words say its call exactly (step_calls.py). Their
        arguments are fixed by the steps, so the host makes them instead of asking for them, through the
        same checks as the model's calls (dev half: asked for "alpha: read battery", the 1.5B model
        answered that alpha had the lowest battery without a read; "fly over 20 m north while climbing
        another 6 m" was called with alt_m=6). A call that failed is not made again: the model is asked,
        with the failure in what it reads."""
        plan, ran = self._turn_plan, False
        for _ in range(len(plan.steps) + len(self.fleet.ids) if plan is not None else 0):
            assert plan is not None
            due = plan.call_due(result.tool_calls)
            made = json.dumps(due, sort_keys=True)
            if due is None or due[0] not in self.tools or made in self._plan_made:
                break  # nothing the host can make (a tool not offered), or made already: the model is asked
            self._plan_made.add(made)
            if leg_without_height(due) and await self._on_the_ground(due[1].get("drone_id")):
                break  # the gateway refuses a leg from the ground with no height: the model is asked
            name, args = due
            call: ModelCall = {
                "id": f"call_plan_{len(result.tool_calls) + 1}",
                "name": name,
                "raw_args": args,
            }
            self._emit("plan_call", step=result.steps, name=name, arguments=args)
            record = await self._execute(result.steps, call, False, result)
            result.tool_calls.append(record)
            ran = True
            if not record.ok:
                break
        return ran

    async def _on_the_ground(self, drone_id: object) -> bool:
        drone = await self.fleet.fresh_entry(drone_id)
        return drone is not None and drone.flying is False

    def _off_request(self, name: str, args: Arguments, turn: TurnResult | None) -> str | None:
        """Why an acting call is not sent because its drone is not the request's: one the request does not
        name (when it names some and does not speak of the whole fleet), or, in a plan, one a choice
        between drones passed over. Measured on the corpus's dev half with the 1.5B model: "of bravo and
        charlie, launch the better charged one" took off alpha, the only drone at 100 %."""
        if not checks.acts(self.tools, name) or not self.fleet.ids:
            return None
        if turn is not None and self._only_the_answer_left(turn):
            return (
                "Not sent: every step of the request is done, and the request asks for nothing more. Nothing "
                "was executed. Call answer_user with one sentence saying what was done."
            )
        drones: frozenset[str] = drones_named(args) or frozenset()
        asked = planning.asked_drones(self._memory.request, self.fleet.ids)
        plan = self._turn_plan
        if off := sorted(d for d in drones if d not in asked):
            return (
                f"Not sent: the request does not name {', '.join(off)}; it names {', '.join(asked)}. Nothing "
                "was executed. Call the tool for the request's next step."
            )
        where = plan.where(turn.tool_calls if turn is not None else []) if plan is not None else None
        if where is not None and (passed := sorted(drones & set(where.passed_over))):
            return (
                f"Not sent: {', '.join(passed)} is not the drone this step is for. Nothing was executed. "
                f"{where.note}"
            )
        return None

    @staticmethod
    def _plan_lead(plan: planning.Plan, last: ToolCallRecord, result: TurnResult) -> str | None:
        """What the plan's rewritten prompt says first about the model's last call, or None when the turn
        is not rewritten (a failed call: its error says how to fix it). A repeat and an answer held back
        with steps left are said, since the rewrite drops the note that came with them (dev half: after
        two battery reads and an answer held back, the next reply read a third battery and landed the
        drone that was to stay)."""
        if last.status == "ok":
            return " "
        if last.status == "repeat":
            return f"Your last {last.name} call was not sent again: it already ran in this request."
        if last.name == ANSWER_TOOL and last.status == "invalid" and not plan.finished(result.tool_calls):
            return "Not answered yet: a step of the request is left."
        return None

    async def _answer_for_the_model(self, result: TurnResult) -> None:
        """The model gave no answer (empty replies, the step limit, a model error): the host answers from
        the gateway's own results (wording.answer_from_results). A model that stopped replying after some
        call ran or was refused considered the request finished: the turn counts as answered. One stopped
        by the step limit or a model error, or in which nothing ran, keeps its outcome (and exit status)."""
        roster = await self.fleet.refresh() if self.fleet.enabled else None
        text = wording.answer_from_results(result, self._memory.request, roster)
        if result.outcome == "empty_answer" and any(
            (c.ok and c.name != ANSWER_TOOL) or c.status == "error" for c in result.tool_calls
        ):
            result.outcome = "answered"
        result.final_text, result.answered_by = text, "host"
        self.messages.append({"role": "assistant", "content": text})
        self._emit("final", step=result.steps, text=text, via="host")

    def _without_copied_records(self, calls: list[ModelCall], result: TurnResult) -> list[ModelCall]:
        """The calls of a text reply without the copies of the plan's "done so far" lines: a call written
        with "-> result" after it that repeats one that succeeded this turn. Measured on the corpus's dev
        half with the 1.5B model: read as calls, the copies flew finished steps again; a new call written
        with a result it made up is still sent."""
        ran = [(c.name, c.arguments) for c in result.tool_calls if c.ok]
        kept: list[ModelCall] = []
        for call in calls:
            if RESULT_FOLLOWS in call.get("notes", []) and (call["name"], call_arguments(call)) in ran:
                self._emit("copied_record", step=result.steps, name=call["name"], arguments=call["raw_args"])
                continue
            kept.append(call)
        return kept

    def _end_without_answer(self, result: TurnResult, why: str = "") -> None:
        """The turn ends as ``empty_answer``: the model gave no answer too many times (or ``why``)."""
        result.outcome = "empty_answer"
        self._emit(
            "empty_answer",
            step=result.steps,
            message=why or f"no answer {result.empty_streak} times in a row; the request may be unfinished",
        )

    async def _reprompt(self, result: TurnResult, echo: bool = False) -> str:
        """What the model is told after an empty reply (wording.reprompt_text), with the fleet read now."""
        roster = await self.fleet.refresh()
        plan = self._turn_plan
        if plan is not None:
            # the step whose turn it is, short: measured with the 1.5B model, the long re-prompt below
            # after a step-by-step turn got nothing again, the step alone its call
            said = "Your reply only repeated my note." if echo else "Your reply was empty."
            return f"{said} {plan.next_note(result.tool_calls)}"
        # an empty reply is the model stopping, so a drone still flying that the request lands is said
        # (measured on the corpus's dev half, compound-two-climbs: after the second climb the model
        # replied with nothing twice, and the landing the request ends with was never sent)
        untouched = checks.untouched(
            result, self._memory.request, self.fleet.roster, self.tools, answering=True
        )
        return wording.reprompt_text(result, self._memory.request, echo, untouched, roster, self.answer_tool)

    def _request_done(self, result: TurnResult) -> bool:
        """The request's own checks find nothing left: every drone it names acted on, every distance it
        names flown, every drone it lands down (checks.untouched)."""
        return any(
            c.ok and checks.acts(self.tools, c.name) for c in result.tool_calls
        ) and not checks.untouched(
            result, self._memory.request, self.fleet.roster, self.tools, answering=True
        )

    def _only_the_answer_left(self, result: TurnResult) -> bool:
        """Every step of the plan is done and the request's own checks find nothing left: the next reply
        can only be the answer (dev half with the 0.5B model: "alpha just goes up to 8 m and lands again",
        every step made by the host, then alpha flown 30 m south by the model's next call)."""
        plan = self._turn_plan
        return (
            plan is not None
            and bool(self.answer_tool)
            and plan.finished(result.tool_calls)
            and self._request_done(result)
        )

    def _offered(self, result: TurnResult) -> list[dict[str, Any]]:
        """The tool specs of the next reply: only the answer's when nothing else is left (fewer tokens to
        read, and no call to make again); the names for reading calls written as text stay all the tools',
        so such a call is refused (``_off_request``), not taken for an answer."""
        specs = self.fleet.specs
        if not self._only_the_answer_left(result):
            return specs
        return [s for s in specs if s.get("function", {}).get("name") == ANSWER_TOOL] or specs

    async def _ask_model(self, step: int, usage: Usage, result: TurnResult) -> ModelReply:
        reply = await self._chat.ask(self.messages, self._offered(result), self.fleet.parameters, usage)
        self._truncated = reply.truncated
        self._emit(
            "model_reply",
            step=step,
            content=reply.content,
            tool_calls=len(reply.calls),
            parsed_from_text=reply.parsed,
            prompt_tokens=reply.prompt_tokens,
            completion_tokens=reply.completion_tokens,
            finish_reason=reply.finish_reason,
        )
        if reply.parsed:
            count = len(reply.calls)
            message = f"parsed {count} tool call(s) from text"
            self._emit("parsed_from_text", step=step, count=count, message=message, notes=reply.notes)
        return reply

    # --- tool side -------------------------------------------------------------------------------

    async def _execute(
        self, step: int, call: ModelCall, parsed: bool, turn: TurnResult | None = None
    ) -> ToolCallRecord:
        call_id, name = call["id"], call["name"]
        args: Arguments | None = None
        problem: str | None = call.get("parse_error")
        notes: list[str] = []
        if problem is None:
            try:
                args = parse_arguments(call["raw_args"])
            except ArgumentsError as exc:
                problem = str(exc)
        reading: Reading | None = None
        if args is not None:
            flown = relative_moves(turn.tool_calls) if turn is not None else []
            name, args, reading, notes = await read_call(
                name, args, self._memory.request, self.fleet.ids, self.fleet.fresh_entry, flown
            )
            if (offered := self.tools.get(name)) is not None:
                schema = offered.input_schema or {}
                notes += unplaced_optional_point(args, self._memory.request, schema.get("required") or [])
                notes += extras_of_a_drone_only_tool(args, schema.get("properties") or {})
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
        status, outcome = checks.held_back(
            name, tool, args, problem, turn, self._memory, tools=self.tools, base_tools=self.fleet.base_tools,
            answer_tool=self.answer_tool, on_ground=self.fleet.on_ground,
        )  # fmt: skip
        if outcome is None and args is not None and (off := self._off_request(name, args, turn)) is not None:
            status, outcome = "invalid", ToolOutcome(text=self._note(off), is_error=True)
        if outcome is None:
            assert tool is not None and args is not None
            status, outcome = await self.sender.send(step, call_id, tool, args, reading)
        request, roster = self._memory.request, self.fleet.roster
        if (
            status == "repeat"
            and turn is not None
            and (left := checks.untouched(turn, request, roster, self.tools, answering=True))
        ):
            # measured on the corpus's dev half (compound-two-climbs): the climb already done sent again
            # three times, the landing the request ends with never
            outcome = ToolOutcome(f"{outcome.text} Still to do: {left}", is_error=False)
        if status in ("invalid", "error") and checks.same_invalid_again(name, args, turn):
            outcome = ToolOutcome(
                f"{outcome.text} This is the third time this same call was refused; it will not work. Stop "
                f"calling it: {finish_hint(self.answer_tool)}, saying what was done and what was refused.",
                is_error=True,
            )
        elif status == "repeat" and checks.same_invalid_again(name, args, turn, ("repeat",)):
            # measured on the corpus's dev half (compound-two-climbs): the same move, already done, sent
            # eight times in a row, each answered "not sent again", until the step limit
            outcome = ToolOutcome(
                f"{outcome.text} This is the third time this same call came back; it will not be sent. Stop "
                f"calling it: send a different call for what the request still asks, or "
                f"{finish_hint(self.answer_tool)}.",
                is_error=False,
            )
        elif status == "error" and checks.same_refusal_again(outcome.text, turn):
            outcome = ToolOutcome(
                f"{outcome.text} This is the third time the gateway refused this, for the same reason; it "
                f"will not allow it. Stop asking: {finish_hint(self.answer_tool)}, saying what was done and "
                "what was refused.",
                is_error=True,
            )
        model_text = outcome.text
        if status in ("invalid", "unknown_tool"):
            # the host's own refusals are instructions to the model, no answer for the user; a gateway
            # refusal copied as the answer ("refused by rule max_altitude ...", "already on the ground")
            # does tell the user what happened (measured: an answer copying "alpha is already on the
            # ground" after a finished survey was sent back three times)
            self._memory.error_texts.append(outcome.text)
        elif status == "error":
            self._memory.gateway_errors.append(outcome.text)
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

    def _skip(
        self, step: int, call: ModelCall, parsed: bool, why: str, status: str = "skipped"
    ) -> ToolCallRecord:
        """A call of a reply that is not sent (an earlier call failed, the turn ended, or a later call
        supersedes it: ``left_out``): the model is told why."""
        text = self._note(wording.skip_text(why, status))  # measured: copied back as the answer
        self.messages.append({"role": "tool", "tool_call_id": call["id"], "content": text})
        self._emit("tool_result", step=step, id=call["id"], name=call["name"], status=status, summary=text,
                   text=text)  # fmt: skip
        return ToolCallRecord(call["id"], call["name"], call_arguments(call), status, text, parsed, text)

    # --- the end of a turn: answer_user ----------------------------------------------------------

    async def _answer_call(
        self,
        step: int,
        call: ModelCall,
        parsed: bool,
        result: TurnResult,
        reads: Sequence[ToolCallRecord] = (),
    ) -> tuple[str | None, bool]:
        """An ``answer_user`` call: the answer that ends the turn, or None when it is sent back (empty, an
        echo, or premature once); the flag says the model has now given no answer too often. ``reads``:
        the reads of the same reply, whose results the answer was written without."""
        args = call_arguments(call)
        text = answer_text(args) if args is not None else bare_answer(call["raw_args"])
        shown = args if args is not None else call["raw_args"]
        self._emit(
            "tool_call", step=step, id=call["id"], name=ANSWER_TOOL, arguments=shown, parsed_from_text=parsed
        )
        answer: str | None = None
        stale = wording.written_before_results(text, result)
        empty = not text or stale or wording.echoes_host(text, self._memory)
        # An answer is held back first (once per reason): a model that gives up with an echo after its
        # own invalid call is told how to go on, not only that the echo is no answer.
        held = await self._hold_answer(result, empty, text)
        if not held and not empty:
            held = held_answers.written_blind(self._memory, reads, text)
        if held or empty:
            reply = held or wording.not_an_answer(text, stale, result)
            if empty:
                result.empty_replies += 1
                result.empty_streak += 1
        else:
            answer = self._believed(result, text)
            reply = "Delivered to the user."
        gave_up = answer is None and result.empty_streak > MAX_EMPTY_REPROMPTS
        self.messages.append({"role": "tool", "tool_call_id": call["id"], "content": self._note(reply)})
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

    def _believed(self, result: TurnResult, text: str) -> str:
        """An answer taken after the host sent it back once, with the host's marked lines on what it gets
        wrong: drones it says acted that no call moved, a drone it picks that the readings do not."""
        pick = readings.pick_unsaid(self._memory.request, result.tool_calls, self.fleet.ids, text)
        return wording.with_pick(wording.with_unbacked(text, self._unbacked(result, text)), pick)

    def _unbacked(self, result: TurnResult, text: str) -> list[Claim]:
        """The drones the answer says acted that no call of this turn acted on (claims.py), by the roster
        read after the last step (none when the host keeps no roster)."""
        if not self.fleet.enabled or not text:
            return []
        acting = lambda name: checks.acts(self.tools, name)  # noqa: E731
        return claims.unbacked(text, self._memory.request, result, self.fleet.roster, acting)

    async def _hold_answer(self, result: TurnResult, empty: bool = False, text: str = "") -> str | None:
        """Why an answer is sent back instead of ending the turn, or None; each reason at most once a turn,
        so a model that answers again is believed."""
        held = self._memory.held
        # the last call that ran (calls skipped after it in the same reply do not count)
        last = next((c for c in reversed(result.tool_calls) if c.status not in ("skipped", "left_out")), None)
        if last is not None and last.status in ("invalid", "unknown_tool") and "invalid" not in held:
            held.add("invalid")
            return wording.invalid_last_call(last.name)
        # a gateway error that is no refusal by a rule is a mistake in the call, not an outcome to report
        # (measured on the corpus's dev half, multi-two-heights: "alpha is on the ground; say how high to
        # fly: ..." came back word for word as the answer, and nothing had flown)
        if (
            last is not None
            and last.status == "error"
            and not wording.refused(last)
            and not wording.already_so(last)
            and "invalid" not in held
        ):
            held.add("invalid")
            return wording.failed_last_call(last.name)
        if (
            not empty
            and (nothing := held_answers.nothing_ran(result, self._memory, self.answer_tool)) is not None
        ):
            return nothing
        if not empty and (unsaid := held_answers.refusal_unsaid(result, self._memory, text)) is not None:
            return unsaid
        if self.fleet.enabled:
            # where the drones are is read now, not a step ago: the answer may share a reply with the call
            # that flew them, and whether a drone still flies decides what is left (checks.untouched)
            await self.fleet.refresh()
        if not empty and (
            claimed := held_answers.claims_unbacked(
                self._memory, self._unbacked(result, text), set(self.tools)
            )
        ):
            return claimed
        if not empty and (picked := held_answers.pick_unsaid(self._memory, result, self.fleet.ids, text)):
            return picked
        if "untouched" in held:
            return None
        untouched = checks.untouched(
            result, self._memory.request, self.fleet.roster, self.tools, answering=True
        )
        if not untouched:
            return None
        held.add("untouched")
        return wording.unfinished(untouched)
