"""Property-based test of the MCP surface: arguments generated from every tool's input schema, and
mutations of them (wrong types, NaN, inf, huge numbers, huge strings, missing fields).

Properties, over a real gateway and a simulated drone on the ground:
- every call ends in a result or a clear error (a tool error, or a JSON-RPC error for arguments that are
  not JSON), within a bound; never a crashed session or a hang; the session answers afterwards;
- arguments that break the tool's schema or carry a non-finite number are refused;
- no invalid command reaches the drone: the simulator's true state (armed, mode, position) is unchanged.
  Schema-valid arguments run while the operator has locked the fleet (so a valid takeoff is refused by
  the lock instead of flying); invalid ones run unlocked, so the validation alone must stop them.

Hypothesis runs in a worker thread (its engine is synchronous); each call is scheduled on the test's
event loop, where the MCP client lives.
"""

from __future__ import annotations

import asyncio
import json
import math
from collections import Counter
from typing import Any

import httpx
import jsonschema
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from mcp.shared.exceptions import MCPError

from tests.fuzz.schema_strategy import from_schema
from tests.helpers.timing import scaled
from tests.mcp.conftest import Stack

pytestmark = pytest.mark.asyncio(loop_scope="module")
DRONES = 1
DRONE = "d1"
CALL_TIMEOUT_S = scaled(90.0)  # a hang bound, generous (2 shared cores); not a duration assertion
VALID_EXAMPLES = 300
MUTATED_EXAMPLES = 500

HUGE_STRING = "x" * 100_000
BAD_VALUES: list[Any] = [
    float("nan"), float("inf"), float("-inf"), 1e308, -1e308, 10**30, -(10**30), HUGE_STRING, "",
    "not-a-number", None, [], {}, True, [1, 2, 3], {"a": 1},
]  # fmt: skip


def as_sent(value: Any) -> Any:
    """What the MCP client puts on the wire: pydantic's JSON writes NaN and infinities as null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: as_sent(v) for k, v in value.items()}
    if isinstance(value, list):
        return [as_sent(v) for v in value]
    return value


def as_received(schema: dict[str, Any], args: dict[str, Any]) -> dict[str, Any]:
    """The arguments as the server reads them: null for an optional argument with no default is the
    same as leaving it out (the advertised schema shows such arguments as their plain type)."""
    sent = as_sent(args)
    required = set(schema.get("required", []))
    props = schema.get("properties", {})
    return {
        k: v
        for k, v in sent.items()
        if not (v is None and k not in required and "default" not in props.get(k, {"default": 0}))
    }


def with_our_drone(schema: dict[str, Any], args: st.SearchStrategy[dict[str, Any]]) -> st.SearchStrategy:
    """Half the time aim at the real drone (else mostly unknown ids, which test little)."""
    props = schema.get("properties", {})

    def aim(data: dict[str, Any], ours: bool) -> dict[str, Any]:
        if ours and "drone_id" in props:
            data = {**data, "drone_id": DRONE}
        if ours and "drone_ids" in props:
            data = {**data, "drone_ids": [DRONE]}
        return data

    return st.builds(aim, args, st.booleans())


def mutate(schema: dict[str, Any]) -> st.SearchStrategy[dict[str, Any]]:
    """A valid example with one field broken: removed (if required), or replaced by a bad value."""
    props = sorted(schema.get("properties", {}))
    required = list(schema.get("required", []))
    valid = with_our_drone(schema, from_schema(schema))

    @st.composite
    def one(draw: st.DrawFn) -> dict[str, Any]:
        args = dict(draw(valid))
        if not props:
            args["unexpected"] = draw(st.sampled_from(BAD_VALUES))
            return args
        field = draw(st.sampled_from(props))
        if field in required and draw(st.booleans()):
            args.pop(field, None)
        else:
            args[field] = draw(st.sampled_from(BAD_VALUES))
        return args

    return one()


async def true_state(stack: Stack) -> tuple[Any, ...]:
    s = await stack.true_state(DRONE)
    return (s["armed"], s["mode"], round(s["lat"], 6), round(s["lon"], 6), round(s["rel_alt_m"], 1))


async def test_tools_survive_generated_and_mutated_arguments(stack: Stack) -> None:
    loop = asyncio.get_running_loop()
    outcomes: Counter[str] = Counter()
    async with stack.client("auto", name="fuzz") as c:
        tools = {t.name: t.input_schema for t in (await c.list_tools()).tools}
        assert len(tools) >= 45
        validators = {name: jsonschema.Draft202012Validator(schema) for name, schema in tools.items()}
        before = await true_state(stack)

        async def one_call(name: str, args: dict[str, Any]) -> tuple[str, str]:
            try:
                r = await asyncio.wait_for(c.call_tool(name, args), CALL_TIMEOUT_S)
            except MCPError as exc:  # a JSON-RPC error (e.g. NaN is not JSON): clear, session intact
                return "protocol_error", str(exc)
            text = " ".join(getattr(p, "text", "") for p in r.content)
            return ("tool_error" if r.is_error else "ok"), text

        def run(name: str, args: dict[str, Any], must_refuse: bool) -> None:
            future = asyncio.run_coroutine_threadsafe(one_call(name, args), loop)
            kind, text = future.result(CALL_TIMEOUT_S + 30)
            outcomes[kind] += 1
            shown = {k: f"{v[:40]}..." if isinstance(v, str) and len(v) > 40 else v for k, v in args.items()}
            if kind != "ok":
                assert text.strip(), f"{name}{shown}: an error without a message"
            if must_refuse:
                assert kind != "ok", f"{name}{shown} was accepted: {text[:300]}"
            after = asyncio.run_coroutine_threadsafe(true_state(stack), loop).result(30)
            assert after == before, f"{name}{shown} changed the drone: {before} -> {after} ({text[:300]})"

        tool_names = sorted(tools)
        common: dict[str, Any] = {
            "deadline": None,
            "database": None,
            "derandomize": True,
            "suppress_health_check": list(HealthCheck),
        }

        @settings(max_examples=VALID_EXAMPLES, **common)
        @given(st.data())
        def valid_arguments(data: st.DataObject) -> None:
            name = data.draw(st.sampled_from(tool_names), label="tool")
            args = data.draw(with_our_drone(tools[name], from_schema(tools[name])), label="args")
            run(name, args, must_refuse=False)

        @settings(max_examples=MUTATED_EXAMPLES, **common)
        @given(st.data())
        def mutated_arguments(data: st.DataObject) -> None:
            name = data.draw(st.sampled_from(tool_names), label="tool")
            args = data.draw(mutate(tools[name]), label="args")
            invalid = not validators[name].is_valid(as_received(tools[name], args))
            run(name, args, must_refuse=invalid)

        # The fleet lock stays on in both phases: a mutation can still be valid (a takeoff below the
        # altitude limit with another 'wait'), and a valid takeoff would fly. Invalid arguments are
        # refused before any tool body runs, so the lock hides no validation hole.
        async with httpx.AsyncClient(base_url=stack.base_url, timeout=scaled(30)) as http:
            r = await http.post("/api/v1/fleet/lock", json={"reason": "fuzzing tool arguments"})
            assert r.status_code == 200, r.text
            try:
                await asyncio.to_thread(valid_arguments)
                await asyncio.to_thread(mutated_arguments)
            finally:
                r = await http.delete("/api/v1/fleet/lock")
                assert r.status_code == 200, r.text

        # the session still answers, and the drone is where it was
        r = await c.call_tool("get_position", {"drone_id": DRONE})
        assert not r.is_error
    assert await true_state(stack) == before
    print(f"\nMCP fuzz: {sum(outcomes.values())} calls over {len(tools)} tools: {dict(outcomes)}")


def _resolve(schema: dict[str, Any], defs: dict[str, Any]) -> dict[str, Any]:
    if "$ref" in schema:
        return _resolve(defs[schema["$ref"].rsplit("/", 1)[-1]], defs)
    for key in ("anyOf", "oneOf"):
        for option in schema.get(key, []):
            resolved = _resolve(option, defs)
            if resolved.get("type") != "null":
                return resolved
    return schema


def _filler(name: str, schema: dict[str, Any], defs: dict[str, Any]) -> Any:
    """A plain value of the right type for a required field."""
    s = _resolve(schema, defs)
    kind = s.get("type")
    if "enum" in s:
        return s["enum"][0]
    if name == "drone_id":
        return DRONE
    if name == "drone_ids":
        return [DRONE]
    return {"number": 10.0, "integer": 1, "boolean": False, "string": "x", "array": [], "object": {}}.get(
        str(kind), None
    )


def numeric_fields(schema: dict[str, Any]) -> list[tuple[str, ...]]:
    """Paths of number fields, at top level and one level inside arrays of objects (waypoints)."""
    defs = schema.get("$defs", {})
    paths: list[tuple[str, ...]] = []
    for name, prop in schema.get("properties", {}).items():
        s = _resolve(prop, defs)
        if s.get("type") in ("number", "integer"):
            paths.append((name,))
        elif s.get("type") == "array":
            item = _resolve(s.get("items", {}), defs)
            for sub, sub_schema in item.get("properties", {}).items():
                if _resolve(sub_schema, defs).get("type") in ("number", "integer"):
                    paths.append((name, sub))
    return paths


def nan_arguments(schema: dict[str, Any], path: tuple[str, ...], bad: float) -> dict[str, Any]:
    defs = schema.get("$defs", {})
    props = schema.get("properties", {})
    args = {name: _filler(name, props[name], defs) for name in schema.get("required", [])}
    if len(path) == 1:
        args[path[0]] = bad
    else:
        item_schema = _resolve(_resolve(props[path[0]], defs).get("items", {}), defs)
        item = {n: _filler(n, item_schema["properties"][n], defs) for n in item_schema.get("required", [])}
        args[path[0]] = [{**item, path[1]: bad}]
    return args


async def test_nan_and_infinity_on_the_wire_are_refused(stack: Stack) -> None:
    """JSON has no NaN, but a client can still send the literals NaN / Infinity (Python's json does).
    Every numeric field of every tool, given those raw, gets an error and sends nothing."""
    headers = {
        "accept": "application/json, text/event-stream",
        "content-type": "application/json",
        "mcp-protocol-version": "2026-07-28",
    }
    async with stack.client("auto", name="nan-list") as c:
        tools = {t.name: t.input_schema for t in (await c.list_tools()).tools}
    before = await true_state(stack)
    checked = 0
    meta = {
        "io.modelcontextprotocol/clientInfo": {"name": "nan", "version": "1"},
        "io.modelcontextprotocol/protocolVersion": "2026-07-28",
        "io.modelcontextprotocol/clientCapabilities": {},
    }
    async with httpx.AsyncClient(base_url=stack.base_url, timeout=CALL_TIMEOUT_S) as http:
        # control: the same kind of raw request with ordinary numbers is answered
        control = {"name": "get_position", "arguments": {"drone_id": DRONE}, "_meta": meta}
        r = await http.post(
            "/mcp",
            content=json.dumps({"jsonrpc": "2.0", "id": -1, "method": "tools/call", "params": control}),
            headers={**headers, "mcp-method": "tools/call", "mcp-name": "get_position"},
        )
        answer = _rpc_answer(r)
        assert answer is not None and not answer.get("result", {}).get("isError", True), (
            r.status_code,
            r.text,
        )
        for name, schema in sorted(tools.items()):
            for path in numeric_fields(schema):
                for bad in (float("nan"), float("inf"), float("-inf")):
                    args = nan_arguments(schema, path, bad)
                    body = {
                        "jsonrpc": "2.0",
                        "id": checked,
                        "method": "tools/call",
                        "params": {
                            "name": name,
                            "arguments": args,
                            "_meta": meta,
                        },
                    }
                    raw = json.dumps(body, allow_nan=True)  # writes the NaN / Infinity literals
                    routing = {"mcp-method": "tools/call", "mcp-name": name}
                    r = await http.post("/mcp", content=raw, headers={**headers, **routing})
                    checked += 1
                    answer = _rpc_answer(r)
                    where = f"{name} {'.'.join(path)}={bad}"
                    assert r.status_code < 500, f"{where}: HTTP {r.status_code} {r.text[:300]}"
                    refused = answer is None or "error" in answer or answer.get("result", {}).get("isError")
                    assert refused, f"{where} was accepted: {json.dumps(answer)[:300]}"
                    assert await true_state(stack) == before, f"{where} changed the drone"
                    if checked == 1:
                        print(f"\nfirst raw NaN refusal ({where}): {json.dumps(answer)[:200]}")
    assert checked >= 30, checked
    print(f"\nraw NaN/Infinity: {checked} calls, all refused")


def _rpc_answer(r: httpx.Response) -> dict[str, Any] | None:
    """The JSON-RPC message of a JSON or SSE response; None when the HTTP layer refused it."""
    if r.status_code >= 400:
        return None
    if r.headers.get("content-type", "").startswith("text/event-stream"):
        for line in r.text.splitlines():
            if line.startswith("data:") and line[5:].strip():
                message = json.loads(line[5:])
                if "result" in message or "error" in message:
                    return message
        raise AssertionError(f"no JSON-RPC answer in the stream: {r.text[:300]}")
    return r.json()
