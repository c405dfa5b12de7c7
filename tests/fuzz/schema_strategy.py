"""Hypothesis strategies for the JSON schemas pydantic writes for MCP tool inputs (a small subset of JSON
Schema: $ref/$defs, anyOf/oneOf, enum/const, the basic types with bounds, patterns and sizes).

Sizes are kept small: the point is to reach every tool with plausible arguments, not to stress memory
(the mutations in the test do that on purpose)."""

from __future__ import annotations

from typing import Any

from hypothesis import strategies as st

MAX_ITEMS = 4
MAX_TEXT = 40
INT_SPAN = 10**6
FLOAT_SPAN = 1e6


def from_schema(schema: dict[str, Any]) -> st.SearchStrategy[Any]:
    return _strategy(schema, schema.get("$defs", {}), 0)


def _strategy(schema: dict[str, Any], defs: dict[str, Any], depth: int) -> st.SearchStrategy[Any]:
    if "$ref" in schema:
        name = schema["$ref"].rsplit("/", 1)[-1]
        return _strategy({**defs[name], **{k: v for k, v in schema.items() if k != "$ref"}}, defs, depth)
    if "const" in schema:
        return st.just(schema["const"])
    if "enum" in schema:
        return st.sampled_from(schema["enum"])
    for key in ("anyOf", "oneOf"):
        if key in schema:
            return st.one_of([_strategy(s, defs, depth) for s in schema[key]])
    if "allOf" in schema and len(schema["allOf"]) == 1:
        return _strategy(schema["allOf"][0], defs, depth)
    kind = schema.get("type")
    if isinstance(kind, list):
        return st.one_of([_strategy({**schema, "type": k}, defs, depth) for k in kind])
    if kind == "null":
        return st.none()
    if kind == "boolean":
        return st.booleans()
    if kind == "integer":
        low = schema.get("minimum", schema.get("exclusiveMinimum", -INT_SPAN - 1) + 1)
        high = schema.get("maximum", schema.get("exclusiveMaximum", INT_SPAN + 1) - 1)
        return st.integers(int(low), int(high))
    if kind == "number":
        low = schema.get("minimum", schema.get("exclusiveMinimum", -FLOAT_SPAN))
        high = schema.get("maximum", schema.get("exclusiveMaximum", FLOAT_SPAN))
        return st.floats(
            low,
            high,
            exclude_min="exclusiveMinimum" in schema,
            exclude_max="exclusiveMaximum" in schema,
            allow_nan=False,
            allow_infinity=False,
        )
    if kind == "string":
        if "pattern" in schema:
            return st.from_regex(schema["pattern"], fullmatch=True).filter(
                lambda s: len(s) <= schema.get("maxLength", 10**9)
            )
        low = schema.get("minLength", 0)
        return st.text(min_size=low, max_size=max(low, min(schema.get("maxLength", MAX_TEXT), MAX_TEXT)))
    if kind == "array":
        items = schema.get("items", {})
        low = schema.get("minItems", 0)
        high = max(low, min(schema.get("maxItems", MAX_ITEMS), MAX_ITEMS))
        if depth > 3:
            return st.just([])
        return st.lists(_strategy(items, defs, depth + 1), min_size=low, max_size=high)
    if kind == "object" or "properties" in schema:
        props = schema.get("properties", {})
        required = set(schema.get("required", []))
        if depth > 3:
            return st.just({})
        return st.fixed_dictionaries(
            {k: _strategy(v, defs, depth + 1) for k, v in props.items() if k in required},
            optional={k: _strategy(v, defs, depth + 1) for k, v in props.items() if k not in required},
        )
    # no type: any small JSON value
    return st.one_of(st.none(), st.booleans(), st.integers(-100, 100), st.text(max_size=8))
