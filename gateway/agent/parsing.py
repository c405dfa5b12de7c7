"""Lenient recovery of tool calls that a model wrote as text instead of structured ``tool_calls``.

Small local models (qwen2.5-7b, llama 3.x, mistral in LM Studio / Ollama / llama.cpp) often put their tool
call into the message content: JSON in a code fence, ``<tool_call>`` tags (closed or not), doubled braces
from a template that escaped them, the arguments as a JSON string inside the JSON, trailing commas, Python
literals (``True``, single quotes), or a call written like ``takeoff(drone_id="alpha", ...)``.

This module only *recovers the intent* (tool name + argument object). It never decides whether a call is
acceptable: the caller validates the arguments against the tool's input schema before anything runs.
"""

from __future__ import annotations

import ast
import json
import re
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from gateway.agent.answer import ANSWER_TOOL, bare_answer
from gateway.agent.toolbox import Arguments

_NAME_KEYS = ("name", "tool", "tool_name", "function_name", "function", "recipient_name")
_ARG_KEYS = ("arguments", "parameters", "args", "input", "params", "kwargs")

_FENCE_RE = re.compile(r"```[ \t]*([A-Za-z0-9_+-]*)[ \t]*\n?(.*?)(?:```|\Z)", re.DOTALL)
_TAG_NAMES = r"(?:tool_call|tool_calls|function_call|functioncall)"
_TAG_RE = re.compile(  # <tool_call>...</tool_call>, also unclosed (ends at the next tag or the text's end)
    rf"<\|?{_TAG_NAMES}\|?>(.*?)(?:<\|?/{_TAG_NAMES}\|?>|(?=<\|?{_TAG_NAMES}\|?>)|\Z)",
    re.DOTALL | re.IGNORECASE,
)
_FUNCTION_TAG_RE = re.compile(r"<function=([A-Za-z0-9_.-]+)>(.*?)(?:</function>|\Z)", re.DOTALL)
_MISTRAL_RE = re.compile(r"\[TOOL_CALLS\]\s*(.*)", re.DOTALL)
_TRAILING_COMMA_RE = re.compile(r",(\s*[}\]])")
# Reasoning models (qwen3, deepseek-r1) think aloud first; a call drafted while thinking is not a call.
_THINK_RE = re.compile(r"<think>.*?(?:</think>|\Z)", re.DOTALL | re.IGNORECASE)
# An answer whose text quotes JSON without escaping it: {"name": "answer_user", "arguments": {"text": "..."}}
# read up to its last closing braces (the answer comes last in a plan).
_BROKEN_ANSWER_RE = re.compile(
    rf'\{{\{{?\s*"name"\s*:\s*"({ANSWER_TOOL})"\s*,\s*"arguments"\s*:\s*\{{\s*"text"\s*:\s*"(.*)"\s*\}}\s*\}}',
    re.DOTALL,
)


class ArgumentsError(ValueError):
    """The arguments of a tool call are not a JSON object (after lenient repair)."""


@dataclass
class TextToolCall:
    """A tool call recovered from message text. ``arguments`` is None when they could not be decoded."""

    name: str
    arguments: Arguments | None
    raw: str
    error: str | None = None
    notes: list[str] = field(default_factory=list)


def loads_lenient(text: str) -> Any:
    """Decode JSON-ish text: strict JSON first, then with trailing commas removed, doubled braces
    collapsed, and finally as a Python literal (single quotes, True/False/None). Raises ValueError."""
    text = text.strip()
    if not text:
        raise ValueError("empty text")
    candidates = [text]
    no_commas = _TRAILING_COMMA_RE.sub(r"\1", text)
    candidates.append(no_commas)
    if "{{" in text or "}}" in text:
        for repaired in _undoubled_braces(text):
            candidates += [repaired, _TRAILING_COMMA_RE.sub(r"\1", repaired)]
    for cand in candidates:
        try:
            return json.loads(cand)
        except (json.JSONDecodeError, RecursionError):
            continue
    for cand in candidates:
        try:
            value = ast.literal_eval(cand)
        except (ValueError, SyntaxError, MemoryError, RecursionError, TypeError):
            continue
        if isinstance(value, (dict, list, str, int, float, bool)) or value is None:
            return value
    raise ValueError(f"not valid JSON: {_shorten(text)}")


def strip_thinking(content: str) -> str:
    """The text without ``<think>`` blocks (what is left is what the model said)."""
    return _THINK_RE.sub("", content)


def parse_arguments(raw: Any) -> Arguments:
    """Turn a tool call's ``arguments`` (string, doubly encoded string, dict, None) into a dict.

    Raises ArgumentsError naming the problem when the result is not a JSON object."""
    value = raw
    for _ in range(3):  # a string of JSON inside JSON, possibly twice
        if value is None:
            return {}
        if isinstance(value, str):
            if not value.strip():
                return {}
            try:
                value = loads_lenient(value)
            except ValueError as exc:
                raise ArgumentsError(f"arguments are not valid JSON ({exc})") from None
            continue
        break
    if not isinstance(value, dict):
        raise ArgumentsError(f"arguments must be a JSON object, got {type(value).__name__}")
    return value


# The note on a call written with "-> result" after it (parsing's reading; the host drops copies).
RESULT_FOLLOWS = "written with a result after it"


def extract_tool_calls(content: str | None, known_tools: Collection[str] = ()) -> list[TextToolCall]:
    """Find the tool calls written in ``content``; an empty list when there are none.

    Calls in explicit markup (tool-call tags, code fences, a message that is only JSON) are returned even
    for unknown tool names, so the model can be told the name is wrong; in free prose only objects naming
    a known tool count, so that ordinary JSON in an answer is not mistaken for a call."""
    if not content or not content.strip():
        return []
    text = _THINK_RE.sub("", content).strip()
    if not text:
        return []
    known = set(known_tools)
    # With a mapping of tool -> parameter names (in order), calls written with positional arguments
    # (``takeoff(bravo, 20)``) are read too.
    params = {k: list(v) for k, v in known_tools.items()} if isinstance(known_tools, Mapping) else {}

    blocks = [m.group(1) for m in _TAG_RE.finditer(text) if m.group(1).strip()]
    if blocks:
        calls = [
            c for b in blocks for c in _calls_in_block(_strip_fence(b), known, explicit=True, params=params)
        ]
        if calls:
            return calls
    fn_tags = list(_FUNCTION_TAG_RE.finditer(text))
    if fn_tags:
        calls = [
            _call_from_parts(m.group(1), m.group(2), m.group(0), ["<function=...> tag"]) for m in fn_tags
        ]
        return calls
    mistral = _MISTRAL_RE.search(text)
    if mistral:
        calls = _calls_in_block(mistral.group(1), known, explicit=True, params=params)
        if calls:
            return calls
    fences = [m.group(2) for m in _FENCE_RE.finditer(text) if m.group(2).strip()]
    if fences:
        calls = [c for b in fences for c in _calls_in_block(b, known, explicit=True, params=params)]
        if calls:
            return calls
    # The whole message is one JSON value (object or list of calls)?
    whole = _calls_in_block(text, known, explicit=True, whole_only=True, params=params)
    if whole:
        return whole
    # Free prose: scan for embedded objects / python-style calls naming a known tool.
    return _calls_in_block(text, known, explicit=False, params=params)


# --- internals ---------------------------------------------------------------------------------------


def _calls_in_block(
    block: str,
    known: set[str],
    *,
    explicit: bool,
    whole_only: bool = False,
    params: Mapping[str, Sequence[str]] | None = None,
) -> list[TextToolCall]:
    block = block.strip()
    if not block:
        return []
    try:
        value = loads_lenient(block)
    except ValueError:
        value = None
    if value is not None:
        calls = _calls_from_value(value, block, known, explicit=explicit)
        if calls or whole_only:
            return calls
    elif whole_only:
        return []
    calls = _embedded_calls(block, known, explicit=explicit)
    if calls:
        return calls
    return _python_style_calls(block, known, params or {})


def _calls_from_value(value: Any, raw: str, known: set[str], *, explicit: bool) -> list[TextToolCall]:
    if isinstance(value, list):
        out: list[TextToolCall] = []
        for item in value:
            out += _calls_from_value(
                item, json.dumps(item) if not isinstance(item, str) else item, known, explicit=explicit
            )
        return out
    if not isinstance(value, dict):
        return []
    if isinstance(value.get("tool_calls"), list):
        return _calls_from_value(value["tool_calls"], raw, known, explicit=explicit)
    if isinstance(value.get("function"), dict):  # OpenAI shape {"type": "function", "function": {...}}
        inner = value["function"]
        return _calls_from_value(inner, raw, known, explicit=explicit)
    name = next((value[k] for k in _NAME_KEYS if isinstance(value.get(k), str) and value[k].strip()), None)
    if name is None:
        return []
    name = name.strip()
    if name.startswith("functions."):
        name = name[len("functions.") :]
    name = known_case(name, known)
    if not explicit and name not in known:
        return []
    arg_key = next((k for k in _ARG_KEYS if k in value), None)
    notes: list[str] = []
    if arg_key is not None:
        raw_args = value[arg_key]
        if isinstance(raw_args, str):
            notes.append("arguments given as a JSON string")
    else:
        # {"name": "land", "drone_id": "alpha"}: arguments written flat beside the name
        raw_args = {k: v for k, v in value.items() if k not in _NAME_KEYS and k not in ("type", "id")}
        if raw_args:
            notes.append("arguments written beside the name")
    return [_finish(name, raw_args, raw, notes)]


def known_case(name: str, known: Collection[str]) -> str:
    """The known tool name that ``name`` spells in another case (``Takeoff``), else ``name``."""
    if name in known:
        return name
    matches = [k for k in known if k.lower() == name.lower()]
    return matches[0] if len(matches) == 1 else name


def _call_from_parts(name: str, args_text: str, raw: str, notes: list[str]) -> TextToolCall:
    return _finish(name.strip(), args_text, raw, notes)


def _finish(name: str, raw_args: Any, raw: str, notes: list[str]) -> TextToolCall:
    if name == ANSWER_TOOL and (text := bare_answer(raw_args)):
        # measured on the corpus's dev half (cond-above-forty-hop): "arguments": "Charlie is above ..."
        return TextToolCall(
            name=name, arguments={"text": text}, raw=raw, notes=[*notes, "answer as a bare string"]
        )
    try:
        args = parse_arguments(raw_args)
        return TextToolCall(name=name, arguments=args, raw=raw, notes=notes)
    except ArgumentsError as exc:
        return TextToolCall(name=name, arguments=None, raw=raw, error=str(exc), notes=notes)


def _embedded_calls(text: str, known: set[str], *, explicit: bool) -> list[TextToolCall]:
    """Calls in balanced ``{...}`` / ``[...]`` spans (string-aware) found left to right. A span that does
    not decode to a call is not skipped over: a stray brace or quote in prose must not hide a real call."""
    calls: list[TextToolCall] = []
    i, n = 0, len(text)
    while i < n:
        if text[i] in "{[":
            end = _matching_close(text, i)
            if end is not None:
                span = text[i : end + 1]
                try:
                    found = _calls_from_value(loads_lenient(span), span, known, explicit=explicit)
                except ValueError:
                    found = []
                if found and text[end + 1 :].lstrip().startswith("->"):
                    # "{call} -> what came of it": the host's record of a call that ran (the plan's "done so
                    # far" lines) copied back, or a result the model made up for a new call; the host tells
                    # which (a copy repeats a call that ran)
                    for c in found:
                        c.notes.append(RESULT_FOLLOWS)
                if found:
                    calls += found
                    i = end + 1
                    continue
            broken = _BROKEN_ANSWER_RE.match(text, i)
            if broken is not None and broken.group(1) in known:
                # Measured: an answer copying the host's note with a call in it as raw JSON; read as calls,
                # the quoted land landed a drone the user wanted hovering. The quote is the answer's text.
                calls.append(TextToolCall(broken.group(1), {"text": broken.group(2)}, broken.group(0),
                                          notes=["answer text with unescaped quotes"]))  # fmt: skip
                break
        i += 1
    return calls


def _matching_close(text: str, start: int) -> int | None:
    stack: list[str] = []
    quote: str | None = None
    escaped = False
    pairs = {"{": "}", "[": "]"}
    for j in range(start, len(text)):
        ch = text[j]
        if quote:
            if escaped:
                escaped = False
            elif ch == "\\":
                escaped = True
            elif ch == quote:
                quote = None
            continue
        if ch in ('"', "'"):
            quote = ch
        elif ch in pairs:
            stack.append(pairs[ch])
        elif ch in "}]":
            if not stack or stack.pop() != ch:
                return None
            if not stack:
                return j
    return None


def _python_style_calls(
    text: str, known: set[str], params: Mapping[str, Sequence[str]]
) -> list[TextToolCall]:
    """``takeoff(drone_id="alpha", alt_m=15)`` for a known tool name, literal values; positional
    arguments (``takeoff(bravo, 20)``, a bare word read as text) when the tool's parameters are known."""
    calls: list[TextToolCall] = []
    for name in sorted(known, key=len, reverse=True):
        # any case: the 1.5B model began a line with "Formation_goto(...)"
        for m in re.finditer(rf"(?<![A-Za-z0-9_.]){re.escape(name)}\s*\(", text, re.IGNORECASE):
            end = _matching_paren(text, m.end() - 1)
            if end is None:
                continue
            snippet = text[m.start() : end + 1]
            if not _stands_alone(text, m.start(), end + 1):
                continue
            try:
                node = ast.parse(snippet, mode="eval").body
            except SyntaxError:
                continue
            if not isinstance(node, ast.Call):
                continue
            names = list(params.get(name, []))
            if node.args and len(node.args) > len(names):
                continue
            try:
                args = {names[i]: _literal(a) for i, a in enumerate(node.args)}
                args |= {kw.arg: _literal(kw.value) for kw in node.keywords if kw.arg}
            except (ValueError, SyntaxError):
                continue
            notes = ["python-style call"] + (["positional arguments"] if node.args else [])
            calls.append(TextToolCall(name=name, arguments=args, raw=snippet, notes=notes))
    calls.sort(key=lambda c: text.find(c.raw))
    return calls


_LIST_MARK_RE = re.compile(r"^\s*(?:[-*]|\d+[.)])?\s*$")
_LINE_END_RE = re.compile(r"^\s*[;,.]?\s*$")
_JOIN = r"\s*(?:[,;]|(?:,\s*)?(?:and\s+)?then)\s*"
_AFTER_CALL_RE = re.compile(rf"^\s*(?:[-*]|\d+[.)])?\s*[A-Za-z_][\w.]*\s*\(.*\){_JOIN}$")
_BEFORE_CALL_RE = re.compile(rf"^{_JOIN}[A-Za-z_][\w.]*\s*\(")


def _stands_alone(text: str, start: int, end: int) -> bool:
    """A python-style call counts only on a line of its own (a list marker before it, ``;`` after it):
    in a sentence it is the model describing, or echoing, what was done. Measured: a 1.5B model echoed
    "Done so far: takeoff(drone_id='alpha', ...)" and the drone took off again."""
    line_start = text.rfind("\n", 0, start) + 1
    line_end = text.find("\n", end)
    line_end = len(text) if line_end < 0 else line_end
    before, after = text[line_start:start], text[end:line_end]
    # Several calls on one line, joined by "," ";" or "then", count too (measured: the 1.5B model wrote
    # 'takeoff(drone_id="alpha", alt_m=5), land(drone_id="alpha")' as its whole reply).
    first = bool(_LIST_MARK_RE.match(before)) or bool(_AFTER_CALL_RE.match(before))
    last = bool(_LINE_END_RE.match(after)) or bool(_BEFORE_CALL_RE.match(after))
    return first and last


def _literal(node: ast.expr) -> Any:
    """A literal value; a bare name (``bravo``) is read as the text it spells."""
    if isinstance(node, ast.Name):
        return node.id
    return ast.literal_eval(node)


def _matching_paren(text: str, start: int) -> int | None:
    depth = 0
    quote: str | None = None
    for j in range(start, len(text)):
        ch = text[j]
        if quote:
            if ch == quote and text[j - 1] != "\\":
                quote = None
            continue
        if ch in ('"', "'"):
            quote = ch
        elif ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                return j
    return None


def _undoubled_braces(text: str) -> list[str]:
    """Repairs for braces doubled by a template that escaped them: every pair halved once (the exact
    inverse of the escaping), or just one outer pair removed (only the outer braces were doubled)."""
    out = [text.replace("{{", "{").replace("}}", "}")]
    if text.startswith("{{") and text.endswith("}}"):
        out.append(text[1:-1])
    return out


def _strip_fence(block: str) -> str:
    m = _FENCE_RE.search(block)
    return m.group(2) if m else block


def _shorten(text: str, limit: int = 80) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 1] + "…"
