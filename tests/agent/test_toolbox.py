"""Tool selection, argument validation and result summaries (pure functions)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from gateway.agent.toolbox import (
    ToolInfo,
    ToolSelectionError,
    one_line_summary,
    outcome_from_result,
    select_tools,
    tool_info_from_mcp,
    tool_list_tokens,
    toolset_of,
    validate_arguments,
)

GOTO = ToolInfo(
    name="go_to_location",
    description="Fly to a position.",
    input_schema={
        "type": "object",
        "properties": {
            "drone_id": {"type": "string"},
            "lat_deg": {"type": "number", "minimum": -90, "maximum": 90},
            "lon_deg": {"type": "number"},
            "alt_m": {"type": "number", "exclusiveMinimum": 0},
            "alt_frame": {"enum": ["relative", "amsl"]},
        },
        "required": ["drone_id", "lat_deg", "lon_deg", "alt_m"],
        "additionalProperties": False,
    },
    toolset="navigation",
)
GOOD = {"drone_id": "a", "lat_deg": 47.4, "lon_deg": 8.5, "alt_m": 20}


def test_valid_arguments_pass() -> None:
    assert validate_arguments(GOTO, GOOD) is None


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        ({"lat_deg": 123.0}, "123.0 is greater than the maximum of 90"),
        ({"alt_m": 0}, "0 is less than or equal to the minimum of 0"),
        ({"alt_m": "20"}, "'20' is not of type 'number'"),
        ({"alt_frame": "agl"}, "'agl' is not one of ['relative', 'amsl']"),
        ({"speed": 3}, "Additional properties are not allowed ('speed' was unexpected)"),
        ({"drone_id": None}, "None is not of type 'string'"),
    ],
)
def test_invalid_arguments_name_the_problem(change: dict, needle: str) -> None:
    message = validate_arguments(GOTO, {**GOOD, **change})
    assert message is not None and needle in message
    assert message.startswith("invalid arguments for go_to_location") and "Nothing was executed" in message
    assert "Expected arguments: {drone_id: string" in message


def test_missing_required_argument() -> None:
    message = validate_arguments(GOTO, {"drone_id": "a"})
    assert message is not None and "'lat_deg' is a required property" in message


def test_schema_with_defs_validates_nested_models() -> None:
    tool = ToolInfo(
        "upload",
        "",
        {
            "type": "object",
            "$defs": {
                "Wp": {"type": "object", "properties": {"lat": {"type": "number"}}, "required": ["lat"]}
            },
            "properties": {"items": {"type": "array", "items": {"$ref": "#/$defs/Wp"}}},
            "required": ["items"],
        },
    )
    assert validate_arguments(tool, {"items": [{"lat": 1.0}]}) is None
    assert "'lat' is a required property" in (validate_arguments(tool, {"items": [{}]}) or "")


def test_toolset_meta_keys() -> None:
    assert toolset_of({"fleet-gateway/toolset": "flight"}) == "flight"
    assert toolset_of({"toolset": "params"}) == "params"
    assert toolset_of({"fleet-gateway": {"toolset": "mission"}}) == "mission"
    assert toolset_of({"other": 1}) is None


def test_selection_errors_are_clear() -> None:
    plain = [ToolInfo("hop", "", {}), ToolInfo("skip", "", {})]
    with pytest.raises(ToolSelectionError, match="name no toolset"):
        select_tools(plain, toolsets=["flight"])
    with pytest.raises(ToolSelectionError, match=r"unknown tool\(s\) \['fly'\]"):
        select_tools(plain, names=["fly"])
    with pytest.raises(ToolSelectionError, match=r"unknown toolset\(s\) \['nav'\]"):
        select_tools([GOTO], toolsets=["nav"])
    assert select_tools(plain) == plain
    assert [t.name for t in select_tools(plain, names=["hop"])] == ["hop"]


def test_meta_names_the_toolset() -> None:
    tagged = [ToolInfo("takeoff", "", {}, toolset="navigation"), ToolInfo("land", "", {}, toolset="flight")]
    assert [t.name for t in select_tools(tagged, toolsets=["navigation"])] == ["takeoff"]


def test_openai_spec_shape() -> None:
    spec = GOTO.openai_spec()
    assert spec["type"] == "function"
    assert spec["function"]["name"] == "go_to_location"
    assert spec["function"]["parameters"]["required"][0] == "drone_id"
    assert ToolInfo("x", "d", {}).openai_spec()["function"]["parameters"] == {
        "type": "object",
        "properties": {},
    }


def test_tool_info_from_mcp_tool() -> None:
    tool = SimpleNamespace(
        name="land",
        description=None,
        title="Land",
        input_schema={"type": "object"},
        meta={"fleet-gateway/toolset": "flight"},
        annotations=SimpleNamespace(read_only_hint=False),
    )
    info = tool_info_from_mcp(tool)
    assert (info.name, info.description, info.toolset, info.read_only) == ("land", "Land", "flight", False)


def test_result_conversion_and_summary() -> None:
    result = SimpleNamespace(
        content=[SimpleNamespace(type="text", text='{"status": "running"}')],
        structured_content={"status": "running", "operation_id": "op-1", "progress": 0.4},
        is_error=False,
    )
    out = outcome_from_result(result)
    assert out.text == '{"status": "running"}' and not out.is_error
    assert out.summary() == "status=running"
    prose = SimpleNamespace(
        content=[SimpleNamespace(type="text", text="takeoff on a succeeded: reached 10 m")],
        structured_content={"status": "succeeded"},
        is_error=False,
    )
    assert outcome_from_result(prose).summary() == "takeoff on a succeeded: reached 10 m"
    with_json = outcome_from_result(result, include_structured=True)
    assert (
        with_json.text == '{"status": "running"}\n{"status":"running","operation_id":"op-1","progress":0.4}'
    )
    only_structured = SimpleNamespace(content=[], structured_content={"alt_m": 10.0}, is_error=False)
    assert outcome_from_result(only_structured).text == '{"alt_m":10.0}'
    long = SimpleNamespace(
        content=[SimpleNamespace(type="text", text="x" * 100)], structured_content=None, is_error=True
    )
    bounded = outcome_from_result(long, max_chars=10)
    assert bounded.is_error and bounded.text.startswith("x" * 10) and "truncated, 90 more" in bounded.text


def test_one_line_summary() -> None:
    assert one_line_summary("first line\nsecond") == "first line …"
    assert one_line_summary("", {"lat": 47.123456789, "lon": 8.5}) == "lat=47.1235, lon=8.5"
    assert len(one_line_summary("y" * 500)) == 140


def test_tool_list_tokens_grow_with_the_list() -> None:
    one, method = tool_list_tokens([GOTO])
    two, _ = tool_list_tokens([GOTO, ToolInfo("land", "Land where the drone is.", {"type": "object"})])
    assert 0 < one < two
    assert method in ("cl100k_base", "estimate: characters / 4")


def test_small_profile_keeps_its_tools_and_drops_advanced_optional_arguments() -> None:
    from gateway.agent.profiles import SMALL_MODEL_TOOLS, apply_profile

    props = {"drone_id": {"type": "string"}, "alt_m": {"type": "number"}, "wait": {"type": "boolean"}}
    schema = {"type": "object", "properties": props, "required": ["drone_id", "alt_m"]}
    takeoff = ToolInfo("takeoff", "Take off.", schema)
    must_wait = ToolInfo(
        "land", "Land.", {"type": "object", "properties": {"wait": {"type": "boolean"}}, "required": ["wait"]}
    )
    other = ToolInfo("get_imu", "IMU.", {"type": "object", "properties": {}})
    small = apply_profile([other, GOTO, must_wait, takeoff], "small")
    assert [t.name for t in small] == [
        n for n in SMALL_MODEL_TOOLS if n in {"takeoff", "land", "go_to_location"}
    ]
    by_name = {t.name: t for t in small}
    assert "alt_frame" not in by_name["go_to_location"].input_schema["properties"]
    assert "alt_frame" in GOTO.input_schema["properties"]  # the original is untouched
    assert set(by_name["takeoff"].input_schema["properties"]) == {"drone_id", "alt_m"}
    assert "wait" in by_name["land"].input_schema["properties"]  # required: stays
    # With an explicit selection only the arguments are trimmed.
    assert [t.name for t in apply_profile([other, GOTO], "small", keep_selection=True)] == [
        "get_imu",
        "go_to_location",
    ]
    assert apply_profile([other], "full") == [other]
    with pytest.raises(ToolSelectionError, match="none of the small profile's tools"):
        apply_profile([other], "small")
    with pytest.raises(ToolSelectionError, match="unknown profile 'tiny'"):
        apply_profile([other], "tiny")


def test_small_profile_shows_formation_goto_spacing_before_the_centre_and_offsets() -> None:
    """Measured on the dev half (form-line-here, form-pair-abreast): the "N m apart" went into north_m, the
    first metres argument the 1.5B model read."""
    from gateway.agent.profiles import apply_profile

    names = ["drone_ids", "formation", "center_lat_deg", "center_lon_deg", "alt_m", "north_m", "east_m",
             "spacing_m", "heading_deg", "wait"]  # fmt: skip
    schema = {"type": "object", "properties": {n: {"type": "number"} for n in names}, "required": names[:2]}
    (small,) = apply_profile([ToolInfo("formation_goto", "f", schema)], "small")
    shown = ["drone_ids", "formation", "alt_m", "spacing_m", "center_lat_deg", "center_lon_deg", "north_m",
             "east_m"]  # fmt: skip
    assert list(small.input_schema["properties"]) == shown
    assert list(schema["properties"]) == names  # the gateway's own schema is untouched


def test_closest_tool_by_spelling_or_by_the_words_of_the_name() -> None:
    from gateway.agent.toolbox import closest_tool, signature

    battery = ToolInfo("get_battery", "Battery: remaining %, voltage.", {"type": "object"})
    status = ToolInfo("fleet_status", "All drones: state, battery %, alt m.", {"type": "object"})
    move = ToolInfo(
        "move_to_relative", "Fly north/east/up metres from where the drone is.", {"type": "object"}
    )
    tools = [battery, status, move]
    assert closest_tool("get_battery_status", tools) is battery
    assert closest_tool("fly_north", tools) is move
    assert closest_tool("self_destruct", tools) is None
    assert signature(GOTO) == (
        "go_to_location(drone_id: string, lat_deg: number, lon_deg: number, alt_m: number, alt_frame?: any)"
    )


def test_only_a_number_beyond_an_advertised_limit_is_left_to_the_server() -> None:
    from gateway.agent.toolbox import only_beyond_limits

    tool = ToolInfo(
        "takeoff",
        "t",
        {
            "type": "object",
            "properties": {"drone_id": {"type": "string"}, "alt_m": {"type": "number", "maximum": 120}},
            "required": ["drone_id", "alt_m"],
        },
    )
    assert only_beyond_limits(tool, {"drone_id": "a", "alt_m": 500})
    assert not only_beyond_limits(tool, {"drone_id": "a", "alt_m": 50})  # nothing wrong at all
    assert not only_beyond_limits(tool, {"drone_id": "a", "alt_m": "high"})  # a wrong type
    assert not only_beyond_limits(tool, {"alt_m": 500})  # a missing argument besides the limit
