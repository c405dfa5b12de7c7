"""The host's own checks of a model's call before it is sent, and the words of the request they read.

None of them is a safety rule (the gateway keeps those): each holds back a call that a small model sends
by mistake (measured with the 1.5B coder model): a call that repeats one which just succeeded, one that
would fly a finished part of the request again, a tool or an argument that does not exist, the same
refused call a third time, a call of a plan that a later call of the same plan supersedes.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Mapping, Sequence

from gateway.agent import wording
from gateway.agent.answer import ANSWER_TOOL, finish_hint
from gateway.agent.chat import call_arguments
from gateway.agent.intent import superseded
from gateway.agent.repair import (
    AXIS_ARGUMENTS,
    LAT_LON_PAIRS,
    direction_mismatch,
    horizontal_legs_left,
    null_island,
    request_points,
    swap_hint,
)
from gateway.agent.roster import Roster, drones_named
from gateway.agent.toolbox import (
    Arguments,
    ToolInfo,
    ToolOutcome,
    closest_tool,
    only_beyond_limits,
    signature,
    validate_arguments,
)
from gateway.agent.turns import ModelCall, ToolCallRecord, TurnMemory, TurnResult, moves_of, relative_moves

# Tools that only wait for or report on an action already running: calling one between two identical
# calls does not make the second one new.
WAIT_TOOLS = frozenset({"monitor_flight", "monitor_fleet", "check_arrival"})

# "settles back on the ground", "back on the ground": a landing in other words
BACK_ON_THE_GROUND = r"settl(?:e|es|ing)(?: back)? (?:on|onto|to) the ground|back (?:on|onto) the ground"
# Words of a request that ask for a landing or a return home.
LAND_WORDS = re.compile(
    r"\b(?:land|lands|landing|rtl|return(?:s|ing)? (?:to (?:launch|home)|home)|(?:bring|come|go|fly|get) "
    rf"(?:\w+ )?(?:back )?home|{BACK_ON_THE_GROUND}|back down(?! to| by| \d))\b",
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
    rf"{LAND_WORDS.pattern}|\b(?:set|put|bring) (?:it|them|\w+) (?:back )?down\b|\btouch(?:es)? down\b",
    re.IGNORECASE,
)
# Words of a request that ask for a step more than once.
_AGAIN_WORDS = re.compile(
    r"\b(?:again|twice|thrice|repeat\w*|\d+ times|two times|three times|back and forth|laps?|loops?)\b",
    re.IGNORECASE,
)


# A drone a request tells to stay ("Bravo stays down for now", "leave charlie on the ground") in a clause
# with no number: nothing is to be done with it, and it is no part of the request left undone
_STAY_RE = re.compile(
    r"\b(?:stays?|remains?|waits?|should stay|(?:do not|don'?t) (?:fly|launch|move|touch)|"
    r"leave \w+ (?:on the ground|on the pad|where|be|alone|down))\b",
    re.IGNORECASE,
)
_CLAUSE_RE = re.compile(r"[.;!?]|\bbut\b", re.IGNORECASE)
# a landing said of several drones at once ("land them", "land both")
_PLURAL_RE = re.compile(r"\b(?:them|both|all|each|every\w*|pair|they|the two)\b", re.IGNORECASE)


def _mentions(request: str, drone: str) -> list[re.Match[str]]:
    return list(re.finditer(rf"\b{re.escape(drone)}\b", request, re.IGNORECASE))


def told_to_stay(request: str, drone: str) -> bool:
    """The request tells this drone to stay where it is (a clause naming it, with a stay word and no
    number)."""
    return any(
        _mentions(clause, drone) and _STAY_RE.search(clause) and not re.search(r"\d", clause)
        for clause in _CLAUSE_RE.split(request)
    )


def to_land(request: str, named: Sequence[str]) -> list[str]:
    """The named drones the request asks to land or bring home: all of them when it names one or speaks
    of the landing in the plural, else those whose own part of the request (from the drone's name to the
    next drone's) speaks of it. Measured on the corpus's dev half: "Take alpha up to 14 m and land it, and
    send charlie to 22 m" had the host ask for charlie's landing."""
    if not LAND_WORDS.search(request):
        return []
    if len(named) <= 1 or _PLURAL_RE.search(request):
        return list(named)
    starts = sorted((m.start(), d) for d in named for m in _mentions(request, d))
    landing = set()
    for i, (start, drone) in enumerate(starts):
        end = next((s for s, other in starts[i + 1 :] if other != drone), len(request))
        if LAND_WORDS.search(request[start:end]):
            landing.add(drone)
    return [d for d in named if d in landing]


def ends_landed(request: str) -> bool:
    """The request's last step brings the drones down: a landing or return, with no motion asked after it."""
    ends = [m.end() for m in _DOWN_WORDS.finditer(request)]
    return bool(ends) and not _MOTION_WORDS.search(request[ends[-1] :])


def acts(tools: Mapping[str, ToolInfo], name: str) -> bool:
    """The tool acts on drones (not a read, not a wait)."""
    tool = tools.get(name)
    return name not in WAIT_TOOLS and name != ANSWER_TOOL and not (tool is not None and tool.read_only)


def repeat_of(
    tools: Mapping[str, ToolInfo], name: str, args: Arguments, turn: TurnResult | None
) -> ToolCallRecord | None:
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
        other = tools.get(earlier.name)
        acting = other is None or not (other.read_only or earlier.name in WAIT_TOOLS)
        theirs = drones_named(earlier.arguments)
        if acting and (drones is None or theirs is None or drones & theirs):
            return None
    return None


def refly_of(
    tools: Mapping[str, ToolInfo],
    name: str,
    args: Arguments,
    turn: TurnResult | None,
    memory: TurnMemory,
    on_ground: Callable[[str], bool],
) -> str | None:
    """Why this action would fly a finished part of the request again, or None. Measured: "fly out,
    then bring it back and land where it took off" flew out, returned and landed, then took off and
    flew out again. Two cases, unless the request asks for something more than once: the same call
    (tool and arguments) already succeeded, with other actions since (so `repeat_of` lets it
    through); or the drone is back on the ground after the landing or return the request ends with,
    and this call would take it up. Held back once: the same call sent again goes through."""
    if turn is None or not acts(tools, name) or _AGAIN_WORDS.search(memory.request):
        return None
    key = json.dumps([name, args], sort_keys=True, default=str)
    if key in memory.refly_held:
        return None
    why = None
    same = next(
        (c for c in turn.tool_calls if c.ok and not c.running and c.name == name and c.arguments == args),
        None,
    )
    if same is not None:
        why = f"this {name} call already ran earlier in this request and succeeded ({same.summary})."
    elif name not in _DOWN_TOOLS and ends_landed(memory.request):
        drones = drones_named(args) or frozenset()
        for c in reversed(turn.tool_calls):
            down = drones_named(c.arguments)
            landed = [d for d in drones if on_ground(d) and (down is None or d in down)]
            if c.ok and c.name in _DOWN_TOOLS - {"fleet_hold", "hold_position"} and landed:
                why = (
                    f"{', '.join(landed)} already came down as the request's last step asks "
                    f"({c.name}: {c.summary}); {name} would take it up again."
                )
                break
    if why is not None:
        memory.refly_held.add(key)
    return why


def same_invalid_again(
    name: str,
    args: Arguments | None,
    turn: TurnResult | None,
    statuses: tuple[str, ...] = ("invalid", "error"),
) -> bool:
    """This call was already refused (or, with ``statuses=("repeat",)``, sent back as done) twice in this
    turn, identically."""
    if turn is None:
        return False
    same = [c for c in turn.tool_calls if c.name == name and c.arguments == args and c.status in statuses]
    return len(same) >= 2


MAX_SAME_REPEATS = 5


def _stuck_on(turn: TurnResult, statuses: tuple[str, ...]) -> bool:
    """The last call sent came back with one of ``statuses``, as the same call did MAX_SAME_REPEATS times in
    this turn in all."""
    sent = [c for c in turn.tool_calls if c.status not in ("skipped", "left_out")]
    if not sent or sent[-1].status not in statuses:
        return False
    last = sent[-1]
    same = [c for c in sent if c.status in statuses and c.name == last.name and c.arguments == last.arguments]
    return len(same) >= MAX_SAME_REPEATS


def stuck_on_a_repeat(turn: TurnResult) -> bool:
    """The same call, already done, came back MAX_SAME_REPEATS times in this turn, the last call among
    them: the model is told at the third that it will not be sent, and a model that still sends it will not
    get out (measured on the corpus's dev half, cond-fuller-north: a takeoff sent back 19 times, to the
    step limit, about 500 s)."""
    return _stuck_on(turn, ("repeat",))


def stuck_on_a_refusal(turn: TurnResult) -> bool:
    """The same call was refused MAX_SAME_REPEATS times in this turn, the last call among them: the model is
    told at the third that it will not work, and a model that still sends it will not get out (dev half
    with the 0.5B model: a leg 20 m north for a drained drone refused 31 times, about 220 s, before the
    step limit; a move with north and east swapped, 11 times)."""
    return _stuck_on(turn, ("invalid", "error"))


def _refusal_reason(text: str) -> str | None:
    """A rule's refusal without the host's note after it ("Refused: max_altitude: target altitude 150 m
    ..."), or None for any other text."""
    reason = re.sub(r"^(?:error[^:]*:\s*)+", "", text.strip(), flags=re.IGNORECASE).split(" (Host note")[0]
    return reason if reason.lower().startswith("refused") else None


def same_refusal_again(text: str, turn: TurnResult | None) -> bool:
    """The gateway refused this call with the same words twice before in this turn (another drone, or the
    same target by another tool). Measured on the corpus's dev half (refuse-all-150m): the 1.5B model
    asked for 150 m five times, for three drones and by two tools, after the first refusal."""
    reason = _refusal_reason(text)
    if turn is None or reason is None:
        return False
    return sum(1 for c in turn.tool_calls if c.status == "error" and _refusal_reason(c.text) == reason) >= 2


def unknown_tool_text(tools: Mapping[str, ToolInfo], name: str, turn: TurnResult | None) -> str:
    """Unknown tool: the closest offered tool with its arguments, firmer when the name is repeated."""
    near = closest_tool(name, list(tools.values()))
    calls = turn.tool_calls if turn is not None else []
    again = any(c.name == name and c.status == "unknown_tool" for c in calls)
    parts = [f"{name!r} does not exist; you called it again." if again else f"unknown tool {name!r}."]
    if near is not None:
        hint = f"Use {signature(near)} instead." if again else f"The closest tool is {signature(near)}."
        parts.append(hint)
    parts.append(f"Available tools: {', '.join(sorted(tools))}. Nothing was executed.")
    return " ".join(parts)


def unknown_arguments(base_tools: Sequence[ToolInfo], tool: ToolInfo, args: Arguments) -> str | None:
    """Arguments the tool does not have (in the gateway's own schema, hidden ones included) are refused
    rather than silently dropped: a model that adds lat_deg to takeoff has misread the tool."""
    base = next((t for t in base_tools if t.name == tool.name), tool)
    known = set((base.input_schema or {}).get("properties") or {}) | base.hidden
    extra = sorted(set(args) - known)
    if not known or not extra:
        return None
    names = ", ".join(extra)
    # "10 m lower" written as down_m=10: say the argument it is, with its value (the gateway takes
    # west_m and south_m as said; down_m is retired, gateway/mcp/naming.py)
    opposite = [
        f"{n}={v:g} is {_OPPOSITES[n]}={-v:g}"
        for n in extra
        if n in _OPPOSITES and _OPPOSITES[n] in known and isinstance(v := args[n], int | float)
    ]
    hint = f" ({'; '.join(opposite)})" if opposite else ""
    return f"{tool.name} has no argument {names}{hint}; it takes {signature(tool)}. Nothing was executed."


# Arguments a model writes for the other direction of one the tool has.
_OPPOSITES = {"down_m": "up_m"}


def twice_in_plan(tools: Mapping[str, ToolInfo], call: ModelCall, earlier: Sequence[ModelCall]) -> bool:
    """The action ``call`` is written earlier in the same reply, with the same arguments: the plan has the
    same step twice, so one of its steps is not the one the request asks for."""
    args = call_arguments(call)
    return (
        args is not None
        and acts(tools, call["name"])
        and any(c["name"] == call["name"] and call_arguments(c) == args for c in earlier)
    )


def left_out(call: ModelCall, later: list[ModelCall], request: str) -> str | None:
    """Why this call of a plan is left out because the calls after it supersede it, or None."""
    args = call_arguments(call)
    if args is None:
        return None
    planned = [(c["name"], a) for c in later if (a := call_arguments(c)) is not None]
    return superseded(call["name"], args, request, planned)


def held_back(
    name: str,
    tool: ToolInfo | None,
    args: Arguments | None,
    problem: str | None,
    turn: TurnResult | None,
    memory: TurnMemory,
    *,
    tools: Mapping[str, ToolInfo],
    base_tools: Sequence[ToolInfo],
    answer_tool: bool,
    on_ground: Callable[[object], bool],
) -> tuple[str, ToolOutcome | None]:
    """The status of a call that is not sent and what the model is told instead, or ("", None) for a
    call to send. ``problem`` says why its arguments could not be read; ``tools`` are as offered (with
    the fleet's ids), ``base_tools`` as the gateway declares them; the host's notes go to ``memory``."""

    def note(text: str) -> str:
        memory.host_notes.append(text)
        return text

    request = memory.request
    earlier = repeat_of(tools, name, args, turn) if tool is not None and args is not None else None
    if tool is None:
        return "unknown_tool", ToolOutcome(unknown_tool_text(tools, name, turn), is_error=True)
    if problem is not None:
        return "invalid", ToolOutcome(text=f"{problem} for {name}. Nothing was executed.", is_error=True)
    assert args is not None  # arguments that do not parse come with a problem
    if earlier is None and (refly := refly_of(tools, name, args, turn, memory, on_ground)):
        so_far = wording.in_words(c for c in (turn.tool_calls if turn else []) if c.ok)
        text = (
            f"Not sent: {refly} The request: {request} Done so far: {so_far}. If every part is done, "
            f"{finish_hint(answer_tool)}; else call the tool for the next step."
        )
        return "repeat", ToolOutcome(note(text), is_error=False)
    if earlier is not None:
        text = (
            f"Not sent again: this {name} call already succeeded in this request ({earlier.summary}). It "
            f"is done; do not repeat it. The request: {request} Call the tool for the next step, or "
            f"{finish_hint(answer_tool)} if every part is done."
        )
        return "repeat", ToolOutcome(note(text), is_error=False)
    island = null_island(args, request, on_ground=on_ground(args.get("drone_id")))
    if island is not None:
        note(island)
    # a number beyond an advertised limit is sent: the gateway refuses it naming its rule
    schema_problem = None if only_beyond_limits(tool, args) else validate_arguments(tool, args)
    invalid = (
        unknown_arguments(base_tools, tool, args)
        or schema_problem
        or island
        or direction_mismatch(
            args, request, moves_of(relative_moves(turn.tool_calls) if turn else [], args.get("drone_id"))
        )
    )
    if invalid is not None:
        hint = swap_hint(args)
        return "invalid", ToolOutcome(text=f"{invalid} {hint}" if hint else invalid, is_error=True)
    return "", None


def untouched(
    result: TurnResult,
    request: str,
    roster: Roster | None,
    tools: Mapping[str, ToolInfo],
    answering: bool = False,
) -> str:
    """Facts about parts of the request no successful call has used yet: drones it names, coordinates
    it gives (measured: after alpha's part, the 1.5B model forgot bravo; after two of three waypoints,
    it stopped)."""
    ok = [c.arguments for c in result.tool_calls if c.ok and c.arguments]
    acted = [c.arguments for c in result.tool_calls if c.ok and c.arguments and acts(tools, c.name)]
    facts = []
    ids = roster.ids if roster is not None else []
    # Only actions count: reading or waiting on a drone (monitor_flight answered with the drone's
    # last, older operation) did nothing with it (measured: bravo was read, then forgotten).
    touched = {d for args in acted for d in drones_named(args) or ()}
    named = [i for i in ids if re.search(rf"\b{re.escape(i)}\b", request, re.IGNORECASE)]
    idle = [i for i in named if i not in touched and not told_to_stay(request, i)]
    if idle and touched:
        facts.append(f"The request names {', '.join(idle)}, and nothing has been done with it yet.")
    flying = [d.drone_id for d in (roster.drones if roster else ()) if d.flying]
    aloft = [i for i in to_land(request, named or sorted(touched)) if i in flying]
    # Only against an answer: in the middle of a plan a drone still flies before its last step.
    if answering and aloft:
        # Measured: "take off alpha to 10 m, then land it" answered "climbed and landed" after the
        # takeoff alone.
        facts.append(f"The request asks to land or come home, and {', '.join(aloft)} is still flying.")
    # measured on the corpus's dev half (form-line-south): "25 m south of where they are" formed up in
    # place, north_m=0, and the answer said done
    # (only where the calls speak in north_m/east_m: another server's tools may not)
    attempted = [c.arguments for c in result.tool_calls if c.arguments and (c.ok or wording.refused(c))]
    legs = horizontal_legs_left(request, [a for a in attempted if a is not None])
    if legs and acted and any(set(a) & set(AXIS_ARGUMENTS) for a in attempted if a):
        facts.append(f"Distances the request names that no call has flown yet: {', '.join(legs)}.")
    used = [
        (float(args[lat]), float(args[lon]))
        for args in ok
        for lat, lon in LAT_LON_PAIRS
        if isinstance(args.get(lat), int | float) and isinstance(args.get(lon), int | float)
    ]
    left = [
        p
        for p in request_points(request)
        if not any(abs(p[0] - a) < 1e-5 and abs(p[1] - b) < 1e-5 for a, b in used)
    ]
    if left and used:
        points = "; ".join(f"{a:g}, {b:g}" for a, b in left)
        facts.append(f"Points in the request not flown to yet: {points}.")
    return " ".join(facts)


def beside_a_finished_plan(last: ToolCallRecord) -> bool:
    """A call that does nothing more once every step of the plan is done: a finished call sent again, a
    call the host refused (an unknown tool, a drone the request does not name), or arguments the tool does
    not take. The host then answers from the results instead of asking again."""
    if last.status in ("repeat", "invalid", "unknown_tool"):
        return True
    return last.status == "error" and "invalid arguments for" in (last.text or "")
