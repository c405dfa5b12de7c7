"""What the host says: its system prompt, its notes to the model (asked again, held back, not sent),
and its own answer to the user when the model gave none.

Results are put in words, never in call syntax: a model may echo this text, and an echoed call must not
read as a new one. Each text carries the measurement that shaped it.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Sequence

from gateway.agent.answer import ANSWER_TOOL, answer_text
from gateway.agent.claims import REFUSAL_WORDS, Claim
from gateway.agent.roster import Roster, drones_named
from gateway.agent.turns import ToolCallRecord, TurnMemory, TurnResult

# The system prompt of the full profile (profiles.py has the small model's).
DEFAULT_SYSTEM_PROMPT = (
    "You are the pilot assistant of a drone fleet. You act only through the tools you are given; never "
    "claim an action that no tool result confirmed. Altitudes are metres above each drone's home unless a "
    "tool says otherwise. When a tool reports an operation still running, keep checking with the tools "
    "until it is done before the next step of a plan. If a tool refuses a request, do not try to work "
    "around the safety rule: tell the user which rule refused it. When the task is done, answer briefly "
    "with what was done and the final state."
)
INTERRUPTED = (
    "Interrupted by the user before the result arrived; an action already sent may still be running on "
    "the drone."
)
# Measured: a 6-step plan written as text stopped at 200 tokens inside the 4th call; the 4th waypoint
# and the return home were never read, and the model did not notice.
CUT_AFTER_CALL = (
    "(Your reply was cut off at the length limit after this call; whatever came after it was not read. "
    "Send the remaining steps, one call at a time.)"
)
CUT_BEFORE_CALL = (
    "Your reply was cut off at the length limit before a complete tool call. Write only the next tool call."
)

_REFUSAL_RE = re.compile(r"^(?:error[^:]*:\s*)*refused\b", re.IGNORECASE)


def first_line(text: str) -> str:
    return next((s.strip() for s in text.splitlines() if s.strip()), "")


def norm(text: str) -> str:
    return " ".join(re.sub(r"[^\w.,:=-]+", " ", text.lower()).split())


def refused(record: ToolCallRecord) -> bool:
    """The gateway refused the call by a rule ("Refused: max_distance: ..."): an outcome to report. Other
    errors ("alt_m 0 is not above home") are mistakes the model can correct (measured: an alt_m=0 error
    labelled "cannot be done" was passed on to the user instead of corrected)."""
    return record.status == "error" and bool(_REFUSAL_RE.match(record.text))


_ALREADY_RE = re.compile(r"\balready\b[^.:]*: nothing to do\b", re.IGNORECASE)


def already_so(record: ToolCallRecord) -> bool:
    """The call failed because the drone already is as it asks ("charlie is already on the ground and
    disarmed: nothing to do"): nothing to correct."""
    return record.status == "error" and bool(_ALREADY_RE.search(record.text))


def in_words(records: Iterable[ToolCallRecord]) -> str:
    """Calls and their results in words, never in call syntax."""
    return "; ".join(f"{c.name}: {c.summary}" for c in records)


def outcomes_text(result: TurnResult) -> str:
    """What the calls of the turn did, in words: the done ones and the refused ones."""
    done = in_words(c for c in result.tool_calls if c.ok)
    refusals = in_words(c for c in result.tool_calls if refused(c))
    return (f"done: {done}." if done else "nothing done.") + (f" refused: {refusals}." if refusals else "")


def pending_text(result: TurnResult) -> str:
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


def skip_text(why: str, status: str) -> str:
    """What the model is told of a call of its reply that was not sent."""
    if status == "skipped":
        return f"Not executed: {why}"
    return f"Left out: {why}; the rest of your reply goes on."


def takeoff_first(drone: object, alt: float) -> str:
    """Added to the gateway's "take off first" refusal of a move of a drone on the ground: the takeoff
    to call, with the altitude of the refused call (the gateway's own text gives no numbers)."""
    return (
        f' (Host note: {drone} is on the ground. Call takeoff with drone_id "{drone}" and alt_m '
        f"{alt:g} first, then this call again.)"
    )


def echoes_host(said: str, memory: TurnMemory) -> bool:
    """The reply only repeats the request, or copies what the host told the model or an error a tool
    gave this turn (measured: an answer that was the host's note on an invalid call). A copied read
    ("alpha battery 73 %") is a fine answer."""
    text = norm(said)
    text = re.sub(r"^error(?: executing tool \w+)?:\s*", "", text)
    if text.startswith("fleet now:"):
        # the host's roster line, label and all (measured on the corpus's dev half, cond-above-forty-hop:
        # sent back once as a guess, the 1.5B model answered with the roster line itself)
        return True
    told = [*memory.host_notes, *memory.error_texts]
    if len(text) < 20:
        # a short reply that is a whole phrase of the host's note (measured: "Nothing yet.", from
        # "Already done: nothing yet", was taken as the answer)
        short = text.strip(" .,:;-")
        return bool(short) and any(
            short == phrase.strip() for note in told for phrase in re.split(r"[.,:;]", norm(note))
        )
    if text in norm(memory.request):
        return True
    if any(text[:60] in norm(error) or norm(error)[:50] in text for error in memory.gateway_errors):
        return False  # it tells the user what the gateway refused, whatever else it copies
    return any(text[:60] in norm(note) for note in told)


def written_before_results(text: str, result: TurnResult) -> bool:
    """The answer is one the model wrote into a plan that then failed (skipped with the rest of it),
    sent again unchanged after a refusal. Measured: "Bravo has taken off and is flying to the farm",
    written beside the go_to_location the gateway refused, came back word for word as the answer."""
    failed = any(c.status in ("error", "invalid") for c in result.tool_calls)
    return failed and any(
        c.name == ANSWER_TOOL and c.status == "skipped" and answer_text(c.arguments) == text
        for c in result.tool_calls
    )


def not_an_answer(text: str, stale: bool, result: TurnResult) -> str:
    """Why an ``answer_user`` call is sent back: no text, written before the results, or an echo."""
    if not text:
        return (
            "Not an answer: answer_user needs text, one sentence for the user saying what was done and where "
            "the drones are now."
        )
    if stale:
        return (
            "Not an answer: you wrote it with your plan, before the results; it was not sent. Since then: "
            f"{outcomes_text(result)} Say in one sentence what really happened."
        )
    if not any(c.status in ("ok", "error") for c in result.tool_calls):
        # measured on the corpus's dev half (cond-bravo-seventy, cond-charlie-sixty): a conditional request
        # restated as the answer; told to say "what was done", the model restated it again
        return (
            "Not an answer: that only repeats the request, and nothing has been read or done in this turn. "
            "Call the tool for the request's first step now (get_battery, fleet_status or get_position "
            "when it depends on a reading)."
        )
    return (
        "Not an answer: that only repeats the request or my note. Say in one sentence what was done and "
        "where the drones are now."
    )


# An answer before any call ran (held_answers.nothing_ran): what the model is told, once a turn.
NOTHING_RAN = (
    "Not sent to the user yet: no tool has run in this turn, so nothing was checked or done. Read what the "
    "request depends on with a tool (fleet_status, get_battery, get_position), or call the tool for its "
    "first step; if the request needs no tool at all, give the same answer again."
)


def invalid_last_call(name: str) -> str:
    """An answer held back because the last call was the model's own mistake. Measured: after the host's
    note on go_to_location(0, 0) the 1.5B model answered with the note itself; nothing had been done."""
    return (
        f"Not finished yet: your {name} call was not valid, so nothing was sent; my note above says how to "
        "fix it. Send the corrected call, then the rest of the request."
    )


# Words of an answer that tell the user something was refused or is not possible.
_SAYS_REFUSED_RE = re.compile(REFUSAL_WORDS, re.IGNORECASE)


def says_refused(text: str) -> bool:
    """The answer tells the user that something was refused or is not possible."""
    return bool(_SAYS_REFUSED_RE.search(text))


def with_refusals(answer: str, result: TurnResult) -> str:
    """The model's answer, followed by the host's marked line naming the gateway's refusals of this turn
    when the answer says nothing of them: every turn ends with a true answer, refusals reported. Measured
    on the corpus's dev half (refuse-all-150m): sent back once quoting the refusal, the 1.5B model gave the
    same answer, silent about it, again."""
    refusals = [c for c in result.tool_calls if refused(c)]
    if not refusals or says_refused(answer):
        return answer
    why = "; ".join(f"{c.name}: {_reason(c)}" for c in refusals[-2:])
    return f"{answer} (Host: the gateway refused {why}.)"


def _next_tool(claim: Claim, offered: set[str]) -> str:
    """The tool that would do what a claim says, for the note that sends the answer back."""
    if claim.now is not None and claim.now.flying is False and "takeoff" in offered:
        return f" ({claim.drone_id} is on the ground: takeoff first)"
    return ""


def claims_unbacked(claims: list[Claim], offered: set[str]) -> str:
    """An answer held back because it says drones acted that no call of this turn moved."""
    said = "; ".join(
        f"{c.drone_id} '{c.words}', but "
        + (
            f"{c.drone_id} is not there"
            if c.acted
            else f"no call has done anything with {c.drone_id} in this turn"
        )
        + (f" (now: {c.now.text()})" if c.now is not None else "")
        for c in claims
    )
    tools = "".join(_next_tool(c, offered) for c in claims)
    return (
        f"Not sent to the user yet: your answer says {said}. If the request asks for it, call the tool for "
        f"it now{tools}; if it must not be done, answer again saying that it was not done and why."
    )


def with_unbacked(answer: str, claims: list[Claim]) -> str:
    """The model's answer, believed after it was sent back once, followed by the host's marked line on
    the drones it claims acted with no call this turn: the user is not left with a false answer."""
    if not claims:
        return answer
    now = "; ".join(c.now.text() for c in claims if c.now is not None)
    idle = ", ".join(c.drone_id for c in claims if not c.acted)
    said = f"no call in this turn acted on {idle}; " if idle else ""
    return f"{answer} (Host: {said}now: {now}.)" if now else f"{answer} (Host: {said.rstrip('; ')}.)"


def pick_unsaid(pick: str) -> str:
    """An answer held back because it does not name the drone the readings pick."""
    return (
        f"Not sent to the user yet: by this turn's readings {pick}, and your answer does not name it. "
        "Answer again in one sentence from the readings."
    )


def with_pick(answer: str, pick: str | None) -> str:
    """The model's answer, believed after it was sent back once, followed by the host's marked pick."""
    return answer if pick is None else f"{answer} (Host: by this turn's readings {pick}.)"


def _reason(record: ToolCallRecord) -> str:
    """The first line of a call's error, without the "Error ...:" prefixes."""
    return re.sub(r"^(?:error[^:]*:\s*)+", "", first_line(record.text), flags=re.IGNORECASE)


def refusal_unsaid(record: ToolCallRecord) -> str:
    """An answer held back because it does not mention the gateway's refusal."""
    why = _reason(record)
    return (
        f"Not sent to the user yet: the gateway refused part of the request ({record.name}: {why}), and "
        "your answer does not say so. Answer again in one sentence with what was done and what was refused, "
        "and why."
    )


def written_blind(reads: Sequence[ToolCallRecord]) -> str:
    """An answer held back because it was written beside the reads it depends on, before their results."""
    results = "; ".join(f"{c.name}: {first_line(c.text) or c.summary}" for c in reads)
    return (
        "Not sent to the user yet: you wrote the answer in the same reply as the reading, before it came "
        f"back. It returned: {results}. Answer again from that, with the numbers."
    )


def failed_last_call(name: str) -> str:
    """An answer held back because the last call failed with an error that is no refusal by a rule."""
    return (
        f"Not finished yet: your {name} call failed and nothing was done; the error says how to fix it. Send "
        "the corrected call, then the rest of the request. If it cannot be done, say why in your answer."
    )


def unfinished(untouched_facts: str) -> str:
    """An answer held back because the request names something no call has done yet."""
    return (
        f"Not finished yet: {untouched_facts} Call the tool for the next step; call answer_user when every "
        "part is done, or to say why it cannot be done."
    )


def reprompt_text(
    result: TurnResult,
    request: str,
    echo: bool,
    untouched_facts: str,
    roster: Roster | None,
    answer_tool: bool,
) -> str:
    """What the model is told after an empty reply: the request, what is done, what the request names
    that nothing has touched yet, the fleet now."""
    done = in_words(c for c in result.tool_calls if c.ok)
    parts = [
        "Your reply only repeated the request or my note; that is not an answer."
        if echo
        else "Your reply was empty.",
        f"The request: {request}",
        f"Already done (do not repeat): {done or 'nothing yet'}.",
    ]
    refusals = [c for c in result.tool_calls if refused(c)]
    if refusals:
        # Measured: after "Refused: max_distance ..." the 1.5B model replied with nothing twice; a
        # refusal is an outcome to report, not a step still to do.
        parts.append(f"Refused (cannot be done, do not retry): {in_words(refusals[-2:])}.")
    if untouched_facts:
        parts.append(untouched_facts)
    pending = pending_text(result)
    if pending:
        parts.append(pending)
    if roster is not None:
        parts.append(roster.text())
    said = "what was done and what was refused" if refusals else "what was done"
    finish = (
        f"call answer_user with one sentence for the user saying {said}"
        if answer_tool
        else f"reply with one sentence for the user saying {said}"
    )
    what = "done or refused" if refusals else "done"
    parts.append(
        f"If every part of the request is {what}, {finish}. Otherwise reply with only the tool call for the "
        "next step."
    )
    return "\n".join(parts)


def _without_error_prefix(text: str) -> str:
    return re.sub(r"^error:\s*", "", text, flags=re.IGNORECASE)


def answer_from_results(result: TurnResult, request: str, roster: Roster | None) -> str:
    """The host's answer when the model gave none, marked as the host's: what each call did or why the
    gateway refused it, and where the drones named are now."""
    done = [c for c in result.tool_calls if c.ok and c.name != ANSWER_TOOL]
    errors = [c for c in result.tool_calls if c.status == "error"]
    parts = []
    if done:
        parts.append("Done: " + "; ".join(f"{c.name} ({c.summary})" for c in done) + ".")
    # a rule's refusal is said as one; another error is a call that failed (measured on the corpus's dev
    # half, multi-two-heights: "alpha is on the ground; say how high to fly" was called a refusal)
    refusals = [c for c in errors if refused(c)]
    failures = [c for c in errors if not refused(c)]
    if refusals:
        why = "; ".join(f"{c.name}: {_without_error_prefix(first_line(c.text))}" for c in refusals[-3:])
        parts.append(f"Not done, the gateway refused: {why}.")
    if failures:
        why = "; ".join(f"{c.name}: {_without_error_prefix(first_line(c.text))}" for c in failures[-3:])
        parts.append(f"Not done, the call failed: {why}.")
    if not done and not errors:
        reason = result.error or f"the model gave no usable reply ({result.outcome})"
        parts.append(f"Nothing was done: {reason}.")
    if roster is not None:
        touched = {d for c in [*done, *errors] for d in drones_named(c.arguments) or ()}
        named = {d for d in roster.ids if re.search(rf"\b{re.escape(d)}\b", request, re.IGNORECASE)}
        drones = [e.text() for e in roster.drones if e.drone_id in touched | named]
        if drones:
            parts.append("Now: " + "; ".join(drones) + ".")
    return "(Answer from the host, from the gateway's results: the model gave none.) " + " ".join(parts)
