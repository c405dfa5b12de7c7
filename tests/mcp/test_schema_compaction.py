"""What clients are shown of a tool's arguments: short, but never looser than what the model must know."""

from __future__ import annotations

import copy

import pytest

from gateway.mcp.toolkit import _advertise, collapse_optional_nulls


def test_optional_null_collapses_to_the_type_keeping_its_description() -> None:
    schema = {
        "type": "object",
        "properties": {
            "heading_deg": {
                "anyOf": [{"type": "number", "minimum": 0}, {"type": "null"}],
                "default": None,
                "description": "Facing",
            },
            "mode": {"anyOf": [{"type": "string"}, {"type": "null"}], "default": "x"},  # not a None default
            "spacing_m": {"type": "number", "default": 10.0},
        },
    }
    original_mode = copy.deepcopy(schema["properties"]["mode"])
    collapse_optional_nulls(schema)
    assert schema["properties"]["heading_deg"] == {"type": "number", "minimum": 0, "description": "Facing"}
    assert schema["properties"]["mode"] == original_mode
    assert schema["properties"]["spacing_m"] == {"type": "number", "default": 10.0}


def test_nested_definitions_are_collapsed_too() -> None:
    schema = {
        "$defs": {
            "Waypoint": {
                "properties": {
                    "speed_mps": {"anyOf": [{"type": "number"}, {"type": "null"}], "default": None}
                }
            }
        },
        "properties": {},
    }
    collapse_optional_nulls(schema)
    assert schema["$defs"]["Waypoint"]["properties"]["speed_mps"] == {"type": "number"}


def test_advertise_replaces_a_parameter_and_drops_unused_definitions() -> None:
    schema = {
        "$defs": {"Waypoint": {"type": "object"}, "Other": {"type": "string"}},
        "properties": {
            "waypoints": {"type": "array", "items": {"$ref": "#/$defs/Waypoint"}},
            "note": {"$ref": "#/$defs/Other"},
        },
    }
    _advertise(schema, {"waypoints": {"type": "array", "items": {"type": "object"}}})
    assert schema["properties"]["waypoints"] == {"type": "array", "items": {"type": "object"}}
    assert schema["$defs"] == {"Other": {"type": "string"}}
    with pytest.raises(ValueError, match="unknown parameter 'nope'"):
        _advertise(schema, {"nope": {}})


def test_output_schemas_write_nullable_fields_as_type_lists_accepting_the_same_values() -> None:
    import jsonschema

    from gateway.mcp.toolkit import nullable_type_lists

    schema = {
        "type": "object",
        "properties": {
            "battery_pct": {"anyOf": [{"type": "number"}, {"type": "null"}], "description": "%"},
            "mode": {"anyOf": [{"type": "string", "enum": ["a"]}, {"type": "null"}]},  # more than a type
            "row": {"anyOf": [{"$ref": "#/$defs/Row"}, {"type": "null"}]},
        },
        "$defs": {"Row": {"type": "object"}},
    }
    compact = nullable_type_lists(schema)
    assert compact["properties"]["battery_pct"] == {"type": ["number", "null"], "description": "%"}
    assert compact["properties"]["mode"] == schema["properties"]["mode"]
    assert compact["properties"]["row"] == schema["properties"]["row"]
    for value, ok in ((1.5, True), (None, True), ("x", False)):
        for s in (schema, compact):
            valid = jsonschema.Draft202012Validator(s).is_valid({"battery_pct": value})
            assert valid is ok, (s, value)
