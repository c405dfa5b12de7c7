"""JSON as the project passes it around.

`JsonValue` is pydantic's recursive alias (a list or object of JSON values, a string, number, bool or
None): mypy reads it as that union and pydantic validates it, so a model field or a NATS body typed with
it holds what `json.dumps` writes and nothing else. `JsonObject` is a JSON object; a parameter that only
reads one takes `JsonMapping` (a ``dict[str, float]`` is one too).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Annotated

from pydantic import JsonValue, WithJsonSchema

__all__ = [
    "DocumentedJsonObject",
    "JsonMapping",
    "JsonObject",
    "JsonValue",
    "json_float",
    "json_list",
    "json_object",
]

JsonObject = dict[str, JsonValue]
JsonMapping = Mapping[str, JsonValue]
#: a JsonObject field of a model the REST API documents: its schema an object with any members (JsonValue's
#: own schema says no type, which the OpenAPI document must)
DocumentedJsonObject = Annotated[JsonObject, WithJsonSchema({"type": "object", "additionalProperties": True})]


def json_list(items: Iterable[JsonValue]) -> list[JsonValue]:
    """A copy of ``items`` as a JSON array (a ``list[str]`` is not a ``list[JsonValue]`` to mypy: lists
    are invariant)."""
    return list(items)


def json_object(items: JsonMapping) -> JsonObject:
    """A copy of ``items`` as a JSON object (a ``dict[str, float]`` is not a ``JsonObject`` to mypy)."""
    return dict(items)


def json_float(value: JsonValue, name: str) -> float:
    """A JSON number as a float; ValueError naming ``name`` when it is not one."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    raise ValueError(f"{name} must be a number; got {value!r}")
