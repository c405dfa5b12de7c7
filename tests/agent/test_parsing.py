"""The lenient tool-call parser, against the malformed formats small models really produce."""

from __future__ import annotations

import pytest

from gateway.agent.parsing import (
    RESULT_FOLLOWS,
    ArgumentsError,
    extract_tool_calls,
    loads_lenient,
    parse_arguments,
)

KNOWN = ["takeoff", "land", "go_to_location", "get_telemetry"]
TAKEOFF = {"drone_id": "alpha", "alt_m": 15}

# (label, model text, expected [(name, arguments)])
RECOVERABLE = [
    (
        "bare JSON object",
        '{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15}}',
        [("takeoff", TAKEOFF)],
    ),
    (
        "json code fence with prose",
        'I will take off now.\n```json\n{"name": "takeoff", "arguments": '
        '{"drone_id": "alpha", "alt_m": 15}}\n```',
        [("takeoff", TAKEOFF)],
    ),
    (
        "unlabelled fence",
        '```\n{"name": "land", "arguments": {"drone_id": "alpha"}}\n```',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "unclosed fence",
        '```json\n{"name": "land", "arguments": {"drone_id": "alpha"}}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "hermes/qwen tool_call tags",
        '<tool_call>\n{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15}}\n</tool_call>',
        [("takeoff", TAKEOFF)],
    ),
    (
        "unclosed tool_call tag",
        '<tool_call>{"name": "land", "arguments": {"drone_id": "alpha"}}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "two tool_call tags, second unclosed",
        '<tool_call>{"name": "land", "arguments": {"drone_id": "alpha"}}</tool_call>\n'
        '<tool_call>{"name": "land", "arguments": {"drone_id": "bravo"}}',
        [("land", {"drone_id": "alpha"}), ("land", {"drone_id": "bravo"})],
    ),
    (
        "tool_call tag around a fence",
        '<tool_call>\n```json\n{"name": "land", "arguments": {"drone_id": "alpha"}}\n```\n</tool_call>',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "doubled braces everywhere",
        '{{"name": "takeoff", "arguments": {{"drone_id": "alpha", "alt_m": 15}}}}',
        [("takeoff", TAKEOFF)],
    ),
    (
        "doubled outer braces only",
        '{{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15}}}',
        [("takeoff", TAKEOFF)],
    ),
    (
        "arguments as a JSON string",
        '{"name": "takeoff", "arguments": "{\\"drone_id\\": \\"alpha\\", \\"alt_m\\": 15}"}',
        [("takeoff", TAKEOFF)],
    ),
    (
        "arguments doubly encoded",
        '{"name": "land", "arguments": "\\"{\\\\\\"drone_id\\\\\\": \\\\\\"alpha\\\\\\"}\\""}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "trailing commas",
        '{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15,},}',
        [("takeoff", TAKEOFF)],
    ),
    (
        "trailing comma inside string arguments",
        '{"name": "takeoff", "arguments": "{\\"drone_id\\": \\"alpha\\", \\"alt_m\\": 15,}"}',
        [("takeoff", TAKEOFF)],
    ),
    (
        "python literal dict",
        "{'name': 'land', 'arguments': {'drone_id': 'alpha', 'force': True}}",
        [("land", {"drone_id": "alpha", "force": True})],
    ),
    (
        "parameters key",
        '{"name": "land", "parameters": {"drone_id": "alpha"}}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "flat arguments beside the name",
        '{"name": "land", "drone_id": "alpha"}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "openai-shaped function object",
        '{"type": "function", "function": {"name": "land", "arguments": "{\\"drone_id\\": \\"alpha\\"}"}}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "tool_calls wrapper",
        '{"tool_calls": [{"function": {"name": "land", "arguments": {"drone_id": "alpha"}}}]}',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "list of calls",
        '[{"name": "land", "arguments": {"drone_id": "alpha"}}, '
        '{"name": "land", "arguments": {"drone_id": "b"}}]',
        [("land", {"drone_id": "alpha"}), ("land", {"drone_id": "b"})],
    ),
    (
        "mistral TOOL_CALLS marker",
        '[TOOL_CALLS] [{"name": "land", "arguments": {"drone_id": "alpha"}}]',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "llama <function=...> tag",
        '<function=land>{"drone_id": "alpha"}</function>',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "functions. prefix",
        '{"name": "functions.land", "arguments": {"drone_id": "alpha"}}',
        [("land", {"drone_id": "alpha"})],
    ),
    ("no arguments at all", '{"name": "get_telemetry"}', [("get_telemetry", {})]),
    ("null arguments", '{"name": "get_telemetry", "arguments": null}', [("get_telemetry", {})]),
    (
        "object embedded in prose (known tool)",
        'Sure! Calling {"name": "land", "arguments": {"drone_id": "alpha"}} right away.',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "python-style call on a line of its own",
        'Let me do this first:\ntakeoff(drone_id="alpha", alt_m=15)',
        [("takeoff", TAKEOFF)],
    ),
    (
        "unknown tool in explicit markup is still reported",
        '<tool_call>{"name": "fly_to_moon", "arguments": {}}</tool_call>',
        [("fly_to_moon", {})],
    ),
    (
        "call after a reasoning block",
        '<think>maybe {"name": "takeoff", "arguments": {}}? no, land</think>\n'
        '<tool_call>{"name": "land", "arguments": {"drone_id": "alpha"}}</tool_call>',
        [("land", {"drone_id": "alpha"})],
    ),
    (
        "braces inside strings do not confuse the scanner",
        'Note "}{" then {"name": "land", "arguments": {"drone_id": "a}b"}}',
        [("land", {"drone_id": "a}b"})],
    ),
]


@pytest.mark.parametrize(("label", "text", "expected"), RECOVERABLE, ids=[r[0] for r in RECOVERABLE])
def test_recovers_tool_calls(label: str, text: str, expected: list) -> None:
    calls = extract_tool_calls(text, KNOWN)
    assert [(c.name, c.arguments) for c in calls] == expected, label
    assert all(c.error is None for c in calls)


NOT_CALLS = [
    ("plain answer", "Both drones landed and are disarmed."),
    ("empty", ""),
    ("whitespace", "  \n "),
    ("JSON without a tool name", '{"lat": 47.39, "lon": 8.54}'),
    ("prose object naming an unknown tool", 'The log said {"name": "bob", "arguments": {}} earlier.'),
    ("python-style call of an unknown function", "I used print(x=1) to check."),
    # A call inside a sentence describes (or echoes) what was done: reading it again would repeat it.
    (
        "python-style call inside a sentence",
        'Done so far: takeoff(drone_id="alpha", alt_m=15); all good.',
    ),
    ("a number", "42"),
    ("a code fence with python code", "```python\nx = 1\n```"),
    (
        "a call only drafted while thinking",
        '<think>{"name": "land", "arguments": {"drone_id": "a"}}</think>OK.',
    ),
    ("an unfinished reasoning block", '<think>I could call {"name": "land", "arguments": {}}'),
]


@pytest.mark.parametrize(("label", "text"), NOT_CALLS, ids=[r[0] for r in NOT_CALLS])
def test_ordinary_text_is_not_a_call(label: str, text: str) -> None:
    assert extract_tool_calls(text, KNOWN) == [], label


def test_undecodable_arguments_are_reported_not_guessed() -> None:
    calls = extract_tool_calls(
        '<tool_call>{"name": "land", "arguments": "drone alpha please"}</tool_call>', KNOWN
    )
    assert len(calls) == 1
    assert calls[0].name == "land" and calls[0].arguments is None
    assert "not valid JSON" in (calls[0].error or "")


def test_arguments_that_are_not_an_object_are_an_error() -> None:
    calls = extract_tool_calls('{"name": "land", "arguments": [1, 2]}', KNOWN)
    assert calls[0].arguments is None and "JSON object" in (calls[0].error or "")


@pytest.mark.parametrize(
    ("raw", "expected"),
    [
        (None, {}),
        ("", {}),
        ({"a": 1}, {"a": 1}),
        ('{"a": 1}', {"a": 1}),
        ('{"a": 1,}', {"a": 1}),
        ('"{\\"a\\": 1}"', {"a": 1}),
        ('{{"a": 1}}', {"a": 1}),
        ("{'a': None}", {"a": None}),
    ],
)
def test_parse_arguments(raw: object, expected: dict) -> None:
    assert parse_arguments(raw) == expected


@pytest.mark.parametrize("raw", ["[1]", "3", '"just text"', "{not json", 7, ["a"]])
def test_parse_arguments_rejects(raw: object) -> None:
    with pytest.raises(ArgumentsError):
        parse_arguments(raw)


def test_loads_lenient_prefers_strict_json() -> None:
    # Legitimately nested JSON ending in "}}" must not be "repaired".
    assert loads_lenient('{"a": {"b": {"c": 1}}}') == {"a": {"b": {"c": 1}}}
    with pytest.raises(ValueError, match="not valid JSON"):
        loads_lenient("{broken")


def test_positional_python_style_calls_need_the_tools_parameters() -> None:
    params = {"takeoff": ["drone_id", "alt_m"], "land": ["drone_id"]}
    calls = extract_tool_calls("takeoff(bravo, 20)\n- land('bravo');", params)
    assert [(c.name, c.arguments) for c in calls] == [
        ("takeoff", {"drone_id": "bravo", "alt_m": 20}),
        ("land", {"drone_id": "bravo"}),
    ]
    assert "positional arguments" in calls[0].notes
    assert extract_tool_calls("takeoff(bravo, 20)", ["takeoff"]) == []  # names only: keywords only
    assert extract_tool_calls("land(bravo, 20)", params) == []  # more arguments than parameters


def test_a_known_tool_written_in_another_case_is_read_as_that_tool() -> None:
    """The 1.5B model began a reply with ``Formation_goto(...)``: read, not taken as the answer."""
    text = 'Formation_goto(drone_ids=["alpha", "bravo"], formation="line", alt_m=25)'
    calls = extract_tool_calls(text, {"formation_goto": ["drone_ids", "formation", "alt_m"]})
    assert [(c.name, c.arguments) for c in calls] == [
        ("formation_goto", {"drone_ids": ["alpha", "bravo"], "formation": "line", "alt_m": 25})
    ]
    json_calls = extract_tool_calls('{"name": "Takeoff", "arguments": {"alt_m": 5}}', {"takeoff": ["alt_m"]})
    assert [c.name for c in json_calls] == ["takeoff"]


def test_calls_joined_on_one_line_by_commas_or_then_are_all_read() -> None:
    params = {"takeoff": ["drone_id", "alt_m"], "land": ["drone_id"]}
    for text in (
        'takeoff(drone_id="alpha", alt_m=5), land(drone_id="alpha")',
        'takeoff(drone_id="alpha", alt_m=5); land(drone_id="alpha")',
        'takeoff(drone_id="alpha", alt_m=5), then land(drone_id="alpha")',
    ):
        assert [c.name for c in extract_tool_calls(text, params)] == ["takeoff", "land"], text
    # In a sentence they stay a description.
    said = 'Done so far: takeoff(drone_id="alpha", alt_m=5), land(drone_id="alpha")'
    assert extract_tool_calls(said, params) == []


def test_a_call_quoted_inside_an_answer_with_unescaped_quotes_is_the_answers_text_not_a_call() -> None:
    # Measured: the 1.5B model copied the host's note, with a skipped land call as raw JSON, into its
    # answer; read as a call, the land brought down a drone the user wanted hovering.
    quoted = '{"name": "land", "arguments": {"drone_id": "bravo"}}'
    content = (
        '{"name": "answer_user", "arguments": {"text": "Already done: takeoff. Not sent yet: '
        + quoted
        + '"}}'
    )
    known = {"answer_user": ["text"], "land": ["drone_id"]}
    calls = extract_tool_calls(content, known)
    text = f"Already done: takeoff. Not sent yet: {quoted}"
    assert [(c.name, c.arguments) for c in calls] == [("answer_user", {"text": text})]
    # without the answer tool offered, nothing is read as an answer
    assert [c.name for c in extract_tool_calls(content, {"land": ["drone_id"]})] == ["land"]


def test_a_call_followed_by_an_arrow_is_marked_as_written_with_a_result() -> None:
    """Measured on the dev half (multi-west-and-land): the 1.5B model copied the plan's "done so far"
    lines ("{call} -> what came of it"); the host drops the copies of calls that ran (test_planning)."""
    params = {"takeoff": ["drone_id", "alt_m"], "land": ["drone_id"]}
    done = '{"name": "takeoff", "arguments": {"drone_id": "alpha", "alt_m": 15}} -> takeoff succeeded - '
    new = '{"name": "land", "arguments": {"drone_id": "alpha"}}'
    calls = extract_tool_calls(done + new, params)
    assert [(c.name, c.notes) for c in calls] == [("takeoff", [RESULT_FOLLOWS]), ("land", [])]
