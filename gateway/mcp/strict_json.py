"""Strict JSON at the MCP door: an argument is the JSON type its schema says, before the SDK's lax
validation could turn it into one. A number is a JSON number (never the string "10", never true), an
integer an integral number, true/false a JSON boolean, and an object carries only the fields its schema
names (a waypoint's unknown field is refused, not dropped). `strict_problems` walks the arguments with
the tool's own JSON schema and names each argument that breaks this; an empty list: all is well.

Lists and objects may come as a JSON string holding them (the SDK parses such strings: some clients
send them), so a string is let through where a list or object is wanted, to the SDK's own check.
"""

from __future__ import annotations

import json
from collections.abc import Callable

from gateway.mcp.sdk_types import SdkArguments, SdkSchema

_KIND_NAMES = {
    "number": "a JSON number",
    "integer": "a JSON integer",
    "boolean": "true or false",
    "string": "a string",
    "array": "a list",
    "object": "an object",
    "null": "null",
}


Describe = Callable[[str, SdkSchema], str | None]
"""What an argument's schema accepts, in words (`gateway.mcp.arguments`' wording), or None."""


_GIVEN_NAMES = {
    "number": "a fractional number",
    "integral": "a number",
    "integer": "a number",
    "boolean": "true or false",
    "string": "a string",
    "array": "a list",
    "object": "an object",
    "null": "null",
}


def strict_problems(
    arguments: SdkArguments, schema: SdkSchema, describe: Describe | None = None
) -> list[str]:
    """One line per argument (or nested field) whose JSON type is not its schema's."""
    problems: list[str] = []
    say: Describe = describe or (lambda _name, _node: None)
    properties = schema.get("properties", {})
    for name, value in arguments.items():
        prop = properties.get(name)
        if isinstance(prop, dict):
            _walk(schema, prop, value, name, problems, say)
    return problems


def _kind(value: object) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "number" if not value.is_integer() else "integral"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list):
        return "array"
    if isinstance(value, dict):
        return "object"
    return "unknown"


def _fits(wanted: str, kind: str) -> bool:
    if wanted == "number":
        return kind in ("integer", "number", "integral")
    if wanted == "integer":
        return kind in ("integer", "integral")
    if wanted in ("array", "object"):
        return kind in (wanted, "string")  # a JSON string holding it: the SDK parses it
    return kind == wanted


def _resolve(schema: SdkSchema, node: SdkSchema) -> SdkSchema:
    ref = node.get("$ref")
    if isinstance(ref, str):
        found = schema.get("$defs", {}).get(ref.rsplit("/", 1)[-1])
        return found if isinstance(found, dict) else {}
    return node


def _walk(
    schema: SdkSchema, node: SdkSchema, value: object, path: str, problems: list[str], say: Describe
) -> None:
    node = _resolve(schema, node)
    options = [_resolve(schema, o) for o in node.get("anyOf", []) if isinstance(o, dict)] or [node]
    kind = _kind(value)
    typed = [o for o in options if isinstance(o.get("type"), str)]
    if not typed or len(typed) < len(options):
        return  # an option without a type (any value): the SDK's validation decides
    matching = [o for o in typed if _fits(o["type"], kind)]
    if not matching:
        described = [say(path.rsplit(".", 1)[-1], {**node, **o}) for o in typed if o["type"] != "null"]
        kinds = [str(o["type"]) for o in typed]
        words = [d for d in described if d] or [_KIND_NAMES.get(k, k) for k in kinds]
        wanted = " or ".join(dict.fromkeys(words))
        given = _GIVEN_NAMES.get(kind, kind)
        problems.append(
            f"{path} must be {wanted} (got {shown_value(value)}): "
            f"send a JSON {_json_word(typed)}, not {given}"
        )
        return
    chosen = next((o for o in matching if o["type"] not in ("array", "object") or kind != "string"), None)
    if chosen is None:
        return  # a JSON string holding a list or object: checked once the SDK has parsed it
    if chosen["type"] == "array" and isinstance(value, list):
        items = chosen.get("items")
        if isinstance(items, dict):
            for index, element in enumerate(value):
                _walk(schema, items, element, f"{path}[{index}]", problems, say)
    elif chosen["type"] == "object" and isinstance(value, dict):
        fields = chosen.get("properties", {})
        if chosen.get("additionalProperties") is False:
            unknown = [key for key in value if key not in fields]
            for key in unknown:
                problems.append(
                    f"{path}.{key} is not a field of {path}; its fields: {', '.join(fields) or 'none'}"
                )
        for key, element in value.items():
            sub = fields.get(key)
            if isinstance(sub, dict):
                _walk(schema, sub, element, f"{path}.{key}", problems, say)


def _json_word(typed: list[SdkSchema]) -> str:
    kinds = [o["type"] for o in typed if o["type"] != "null"]
    return {"integer": "number"}.get(kinds[0], kinds[0]) if kinds else "value"


def shown_value(value: object) -> str:
    """A value a client sent, as JSON (its repr when it is not JSON), cut to 60 characters to echo."""
    try:
        text = json.dumps(value)
    except (TypeError, ValueError):
        text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."
