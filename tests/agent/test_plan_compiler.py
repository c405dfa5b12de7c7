"""The typed plan: its schema, its validation, and its compilation to gateway calls."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest
from pydantic import ValidationError

from fleet_agent import geometry
from fleet_agent.compiler import DEFAULT_TAKEOFF_M, Call, CompileError, Compiler, DroneState, Said
from fleet_agent.plan import parse_plan, plan_schema
from fleet_agent.prompt import EXAMPLES, system_prompt, user_message

FLEET = ["alpha", "bravo", "charlie"]
HOME = (47.3977, 8.5456)


@dataclass
class FakeSensors:
    states: dict[str, DroneState] = field(default_factory=dict)
    places: dict[str, tuple[float, float]] = field(default_factory=dict)
    homes: dict[str, tuple[float, float]] = field(default_factory=dict)

    async def state(self, drone: str) -> DroneState:
        return self.states.get(drone, DroneState(HOME[0], HOME[1], 0.0, False, 80.0))

    async def home(self, drone: str) -> tuple[float, float]:
        return self.homes.get(drone, HOME)

    async def place(self, name: str) -> tuple[float, float]:
        if name not in self.places:
            raise CompileError(f"unknown place {name!r}")
        return self.places[name]


def m(value: float, unit: str = "m") -> dict:
    return {"value": value, "unit": unit}


def leg(value: float, direction: str, unit: str = "m") -> dict:
    return {"distance": m(value, unit), "direction": direction}


async def compiled(step: dict, sensors: FakeSensors | None = None) -> list:
    plan = parse_plan({"steps": [step]}, FLEET)
    compiler = Compiler(sensors or FakeSensors())
    return await compiler.compile(plan.steps[0])


def flying(
    lat: float = HOME[0], lon: float = HOME[1], alt: float = 10.0, battery: float = 80.0
) -> DroneState:
    return DroneState(lat, lon, alt, True, battery)


def test_the_schema_names_the_fleet_in_every_drone_field() -> None:
    schema = plan_schema(FLEET)
    defs = schema["$defs"]
    assert defs["Takeoff"]["properties"]["drone"]["enum"] == FLEET
    assert defs["Formation"]["properties"]["drones"]["items"]["enum"] == FLEET
    assert defs["Choose"]["properties"]["among"]["items"]["enum"] == FLEET
    ref_drone = defs["Reference"]["properties"]["drone"]["anyOf"]
    assert {"type": "string", "enum": FLEET} in ref_drone
    assert defs["Length"]["required"] == ["value", "unit"]
    assert set(defs["Length"]["properties"]["unit"]["$ref"].split("/")[-1:]) == {"Unit"}


def test_every_step_starts_with_its_action() -> None:
    """A schema-guided decoder writes properties in the schema's order: a step whose first property were
    its drone would be a different first token from the examples' (measured with the 0.5B model: every
    step came out as a formation, the steps whose action came first)."""
    for name, definition in plan_schema(FLEET)["$defs"].items():
        if "action" in definition.get("properties", {}):
            assert next(iter(definition["properties"])) == "action", name
            assert definition["required"][0] == "action", name


def test_a_drone_outside_the_fleet_or_a_length_without_unit_does_not_validate() -> None:
    with pytest.raises(ValidationError, match="drone 'delta' is not in the fleet"):
        parse_plan({"steps": [{"action": "land", "drone": "delta"}]}, FLEET)
    with pytest.raises(ValidationError, match="unit"):
        parse_plan({"steps": [{"action": "takeoff", "drone": "alpha", "altitude": {"value": 5}}]}, FLEET)
    assert parse_plan('{"steps": [{"action": "land", "drone": "Alpha"}]}', FLEET).steps[0].drone == "alpha"


def test_a_formation_has_two_drones_and_a_move_its_origin_before_its_legs() -> None:
    """One drone's circle is an orbit: the schema a decoder follows has no formation of one drone. A move
    names where it starts before its legs (a model that wrote the legs first fell back on ``here``)."""
    defs = plan_schema(FLEET)["$defs"]
    assert defs["Formation"]["properties"]["drones"]["minItems"] == 2
    assert list(defs["Move"]["properties"])[:4] == ["action", "drone", "origin", "legs"]
    for step in ("Move", "Pattern"):  # a decoder writes required properties first: all are, in order
        assert defs[step]["required"] == list(defs[step]["properties"]), step
    one = {"action": "formation", "drones": ["alpha"], "shape": "circle", "spacing": m(25), "altitude": m(15)}
    with pytest.raises(ValidationError, match="at least 2 items"):
        parse_plan({"steps": [one]}, FLEET)


def test_the_prompt_examples_are_valid_plans_of_their_own_fleet() -> None:
    for _, plan in EXAMPLES:
        parse_plan(plan, ["delta", "echo"])
    assert "Request:" in system_prompt() and user_message("x", FLEET).startswith(
        "Fleet: alpha, bravo, charlie"
    )


async def test_feet_are_converted_and_a_landing_kept() -> None:
    plan = parse_plan({"steps": [{"action": "takeoff", "drone": "bravo", "altitude": m(50, "ft")},
                                 {"action": "land", "drone": "bravo"}]}, FLEET)  # fmt: skip
    compiler = Compiler(FakeSensors())
    calls = [c for s in plan.steps for c in await compiler.compile(s)]
    assert calls == [Call("takeoff", {"drone_id": "bravo", "alt_m": 15.24}, "bravo"),
                     Call("land", {"drone_id": "bravo"}, "bravo")]  # fmt: skip


async def test_a_move_from_the_ground_takes_off_first_and_flies_its_legs_in_order() -> None:
    step = {"action": "move", "drone": "alpha", "legs": [leg(30, "north"), leg(0.02, "west", "km")],
            "after": "stay", "altitude": m(15), "origin": {"kind": "here"}}  # fmt: skip
    assert await compiled(step) == [
        Call("takeoff", {"drone_id": "alpha", "alt_m": 15.0}, "alpha"),
        Call("move_to_relative", {"drone_id": "alpha", "north_m": 30.0, "east_m": 0.0}, "alpha"),
        Call("move_to_relative", {"drone_id": "alpha", "north_m": 0.0, "east_m": -20.0}, "alpha"),
    ]
    out_and_back = {**step, "legs": [leg(20, "west"), leg(3, "down"), leg(20, "east")]}
    flown = await compiled(out_and_back, FakeSensors({"alpha": flying()}))
    assert [c.args for c in flown] == [
        {"drone_id": "alpha", "north_m": 0.0, "east_m": -20.0, "alt_m": 15.0},
        {"drone_id": "alpha", "north_m": 0.0, "east_m": 20.0},
    ]
    up_only = {"action": "move", "drone": "alpha", "legs": [leg(25, "north"), leg(8, "up")], "altitude": None,
               "after": "stay", "origin": {"kind": "here"}}  # fmt: skip
    assert (await compiled(up_only))[0] == Call("takeoff", {"drone_id": "alpha", "alt_m": 8.0}, "alpha")


async def test_a_move_in_the_air_climbs_by_its_up_legs() -> None:
    sensors = FakeSensors({"alpha": flying()})
    step = {"action": "move", "drone": "alpha", "legs": [leg(20, "south"), leg(5, "up")], "altitude": None,
            "after": "stay", "origin": {"kind": "here"}}  # fmt: skip
    assert await compiled(step, sensors) == [
        Call("move_to_relative", {"drone_id": "alpha", "north_m": -20.0, "east_m": 0.0, "up_m": 5.0}, "alpha")
    ]
    diagonal = {"action": "move", "drone": "alpha", "legs": [leg(10, "northeast")], "altitude": m(12),
                "after": "stay", "origin": {"kind": "here"}}  # fmt: skip
    (call,) = await compiled(diagonal, sensors)
    assert call.args == {"drone_id": "alpha", "north_m": 7.07, "east_m": 7.07, "alt_m": 12.0}


async def test_a_drone_on_the_ground_takes_off_to_its_first_climb_and_flies_the_next_after_it() -> None:
    """ "60 m up, then 70 m more" is two climbs: a ceiling at 120 m refuses the second, not both (one
    takeoff to 130 m was refused whole and the drone never left the ground)."""
    step = {"action": "move", "drone": "charlie", "legs": [leg(60, "up"), leg(70, "up")], "altitude": None,
            "after": "stay", "origin": {"kind": "here"}}  # fmt: skip
    assert await compiled(step) == [
        Call("takeoff", {"drone_id": "charlie", "alt_m": 60.0}, "charlie"),
        Call(
            "move_to_relative",
            {"drone_id": "charlie", "north_m": 0.0, "east_m": 0.0, "up_m": 70.0},
            "charlie",
        ),
    ]
    then_north = {**step, "legs": [leg(10, "up"), leg(20, "north"), leg(5, "up")]}
    assert [c.args for c in await compiled(then_north)] == [
        {"drone_id": "charlie", "alt_m": 10.0},
        {"drone_id": "charlie", "north_m": 20.0, "east_m": 0.0, "up_m": 5.0},
    ]
    one_climb = {**step, "legs": [leg(10, "up"), leg(20, "north")]}
    assert [c.args for c in await compiled(one_climb)] == [
        {"drone_id": "charlie", "alt_m": 10.0},
        {"drone_id": "charlie", "north_m": 20.0, "east_m": 0.0},
    ]


async def test_a_point_north_of_another_drone_is_read_from_its_position() -> None:
    bravo_at = geometry.offset_position(*HOME, 100.0, 50.0)
    sensors = FakeSensors({"bravo": flying(*bravo_at, alt=20.0)})
    step = {"action": "move", "drone": "alpha", "legs": [leg(30, "north")], "altitude": m(12),
            "after": "stay", "origin": {"kind": "drone", "drone": "bravo"}}  # fmt: skip
    takeoff, goto = await compiled(step, sensors)
    assert takeoff == Call("takeoff", {"drone_id": "alpha", "alt_m": 12.0}, "alpha")
    assert goto.tool == "go_to_location" and goto.args["alt_m"] == 12.0
    north, east = geometry.offset_between(*HOME, goto.args["lat_deg"], goto.args["lon_deg"])
    assert abs(north - 130.0) < 0.05 and abs(east - 50.0) < 0.05


async def test_a_named_place_and_home_are_origins() -> None:
    tower = geometry.offset_position(*HOME, 40.0, 0.0)
    sensors = FakeSensors({"alpha": flying(alt=15.0)}, {"water tower": tower})
    step = {"action": "move", "after": "stay", "drone": "alpha", "legs": [], "altitude": None,
            "origin": {"kind": "place", "place": "water tower"}}  # fmt: skip
    (goto,) = await compiled(step, sensors)
    assert (goto.args["lat_deg"], goto.args["lon_deg"], goto.args["alt_m"]) == (
        round(tower[0], 7), round(tower[1], 7), 15.0)  # fmt: skip
    with pytest.raises(CompileError, match="unknown place 'mill'"):
        await compiled({**step, "origin": {"kind": "place", "place": "mill"}}, sensors)
    home = {**step, "legs": [leg(10, "east")], "origin": {"kind": "home"}}
    (goto,) = await compiled(home, sensors)
    assert abs(geometry.offset_between(*HOME, goto.args["lat_deg"], goto.args["lon_deg"])[1] - 10.0) < 0.05
    sensors.homes["bravo"] = geometry.offset_position(*HOME, 30.0, 0.0)
    (goto,) = await compiled({**home, "origin": {"kind": "home", "drone": "bravo"}}, sensors)
    north, east = geometry.offset_between(*HOME, goto.args["lat_deg"], goto.args["lon_deg"])
    assert abs(north - 30.0) < 0.05 and abs(east - 10.0) < 0.05  # from bravo's home, not alpha's


#: a pattern's properties the request may leave out (required, null)
NULLS = dict.fromkeys(("sides", "lines", "spacing", "heading", "turn", "altitude"))


async def test_a_square_for_one_drone_is_four_legs_not_a_formation() -> None:
    step = {
        **NULLS,
        "action": "pattern",
        "after": "stay",
        "drone": "charlie",
        "shape": "square",
        "size": m(66, "ft"),
        "altitude": m(10),
    }
    calls = await compiled(step)
    assert calls[0] == Call("takeoff", {"drone_id": "charlie", "alt_m": 10.0}, "charlie")
    legs = [(c.args["north_m"], c.args["east_m"]) for c in calls[1:]]
    assert legs == [(20.12, 0.0), (0.0, 20.12), (-20.12, 0.0), (0.0, -20.12)]


async def test_a_drone_flying_at_the_height_asked_is_sent_no_move_there() -> None:
    """The gateway refuses a move that goes nowhere, and the host then sends none of the drone's later
    moves: "take off to 12 m, a pentagon at 12 m" flew none of the pentagon's legs."""
    at_12 = FakeSensors({"alpha": flying(alt=11.6)})
    step = {**NULLS, "action": "pattern", "after": "land", "drone": "alpha", "shape": "square", "size": m(20),
            "altitude": m(12)}  # fmt: skip
    calls = await compiled(step, at_12)
    assert calls[0] == Said("alpha flies at 11.6 m already.")
    assert [c.tool for c in calls[1:]] == ["move_to_relative"] * 4 + ["land"]
    assert all("alt_m" not in c.args for c in calls[1:])
    climb = await compiled(step | {"altitude": m(20)}, at_12)
    assert climb[0] == Call("move_to_relative", {"drone_id": "alpha", "alt_m": 20.0}, "alpha")
    hop = await compiled({"action": "takeoff", "drone": "alpha", "altitude": m(12), "after": "land"}, at_12)
    assert hop == [Said("alpha flies at 11.6 m already."), Call("land", {"drone_id": "alpha"}, "alpha")]


async def test_a_formation_carries_its_spacing_and_centre_move() -> None:
    step = {"action": "formation", "drones": ["alpha", "bravo"], "shape": "column", "spacing": m(12),
            "altitude": m(15), "legs": [leg(40, "north")]}  # fmt: skip
    args = {"drone_ids": ["alpha", "bravo"], "formation": "column", "alt_m": 15.0, "spacing_m": 12.0,
            "north_m": 40.0}  # fmt: skip
    assert await compiled(step) == [Call("formation_goto", args)]


async def test_a_formation_ends_as_its_after_says_for_each_drone_and_a_landing_is_flown_once() -> None:
    """The schema requires a formation's ``after`` (a landing asked for after it was left out)."""
    assert plan_schema(FLEET)["$defs"]["Formation"]["required"][-2:] == ["legs", "after"]
    step = {"action": "formation", "drones": ["charlie", "alpha"], "shape": "line", "spacing": m(9),
            "altitude": m(11), "legs": [leg(30, "south")], "after": "land"}  # fmt: skip
    calls = await compiled(step)
    assert [(c.tool, c.drone) for c in calls] == [
        ("formation_goto", None), ("land", "charlie"), ("land", "alpha")
    ]  # fmt: skip
    home = await compiled({**step, "after": "return_home"})
    assert [c.tool for c in home[1:]] == ["return_to_launch", "return_to_launch"]
    again = [{"action": "land", "drone": "alpha"}, {"action": "land", "drone": "bravo"}]
    plan = parse_plan({"steps": [step, *again]}, FLEET)
    assert [getattr(s, "drone", None) for s in plan.steps] == [None, "bravo"]


async def test_a_triangle_or_square_of_drones_is_the_gateways_circle_when_the_corners_match() -> None:
    step = {"action": "formation", "drones": FLEET, "shape": "triangle", "spacing": m(10), "altitude": m(20)}
    assert (await compiled(step))[0].args["formation"] == "circle"
    pair = {**step, "drones": ["alpha", "bravo"]}
    assert (await compiled(pair))[0].args["formation"] == "wedge"
    square = {**step, "shape": "square"}
    assert (await compiled(square))[0].args["formation"] == "grid"


STAY = {"after": "stay"}


async def test_a_move_or_pattern_ends_as_its_after_says_and_a_repeated_ending_is_flown_once() -> None:
    step = {"action": "move", "drone": "alpha", "origin": {"kind": "here"}, "legs": [leg(20, "east")],
            "altitude": None, "after": "land"}  # fmt: skip
    sensors = FakeSensors({"alpha": flying()})
    assert (await compiled(step, sensors))[-1] == Call("land", {"drone_id": "alpha"}, "alpha")
    square = {
        **NULLS,
        "action": "pattern",
        "drone": "alpha",
        "shape": "square",
        "size": m(10),
        "after": "return_home",
    }
    assert (await compiled(square, sensors))[-1] == Call("return_to_launch", {"drone_id": "alpha"}, "alpha")
    lands = [{"action": "land", "drone": "alpha"}, {"action": "land", "drone": "bravo"}]
    plan = parse_plan({"steps": [step, *lands]}, FLEET)
    assert [s.action for s in plan.steps] == ["move", "land"] and plan.steps[1].drone == "bravo"


async def test_a_pattern_at_0_m_flies_at_no_given_height_as_a_move_does() -> None:
    """A 1.5B plan gave its square an altitude of 0 m where the request gave none: read as a height, that
    was a takeoff to 0 m from the ground and a landing before the legs in the air."""
    square = {**NULLS, **STAY, "action": "pattern", "drone": "alpha", "shape": "square", "size": m(10),
              "altitude": m(0)}  # fmt: skip
    in_the_air = await compiled(square, FakeSensors({"alpha": flying()}))
    assert [c.tool for c in in_the_air] == ["move_to_relative"] * 4
    from_the_ground = await compiled(square)
    assert from_the_ground[0] == Call("takeoff", {"drone_id": "alpha", "alt_m": DEFAULT_TAKEOFF_M}, "alpha")
    assert [c.tool for c in from_the_ground[1:]] == ["move_to_relative"] * 4


async def test_a_named_polygon_has_its_sides_and_a_polygon_its_count() -> None:
    hexagon = await compiled(
        {**NULLS, "action": "pattern", "drone": "alpha", "shape": "hexagon", "size": m(12), **STAY}
    )
    assert len(hexagon) == 7 and hexagon[1].args["north_m"] == 12.0  # a takeoff, then six legs
    five = {
        **NULLS,
        **STAY,
        "action": "pattern",
        "drone": "alpha",
        "shape": "polygon",
        "sides": 5,
        "size": m(12),
    }
    assert len(await compiled(five, FakeSensors({"alpha": flying()}))) == 5
    orbit = {
        **NULLS,
        **STAY,
        "action": "pattern",
        "drone": "alpha",
        "shape": "orbit",
        "size": m(25),
        "turn": "left",
    }
    legs = await compiled(orbit, FakeSensors({"alpha": flying()}))
    assert len(legs) == 14 and legs[1].args["east_m"] < 0  # round to the left (west) first
    rectangle = {**NULLS, **STAY, "action": "pattern", "drone": "alpha", "shape": "rectangle", "size": m(40),
                 "spacing": m(20), "heading": "east"}  # fmt: skip
    sides = await compiled(rectangle, FakeSensors({"alpha": flying()}))
    assert [(c.args["north_m"], c.args["east_m"]) for c in sides] == [(0, 40), (-20, 0), (0, -40), (20, 0)]


async def test_a_formation_centred_on_a_point() -> None:
    step = {"action": "formation", "drones": ["alpha", "bravo"], "shape": "line", "spacing": m(10),
            "altitude": m(25), "legs": [{"distance": m(10), "direction": "north"}],
            "origin": {"kind": "point", "lat_deg": HOME[0], "lon_deg": HOME[1]}}  # fmt: skip
    (call,) = await compiled(step)
    north, east = geometry.offset_between(*HOME, call.args["center_lat_deg"], call.args["center_lon_deg"])
    assert abs(north - 10.0) < 0.05 and abs(east) < 0.05 and "north_m" not in call.args


async def test_a_condition_takes_its_branch_from_the_reading() -> None:
    step = {"action": "if", "drone": "bravo", "reading": "battery", "compare": "above", "value": 50,
            "then": [{"action": "takeoff", "drone": "bravo", "altitude": m(15)}],
            "otherwise": [{"action": "report", "drones": ["bravo"], "readings": ["battery"]}]}  # fmt: skip
    low = FakeSensors({"bravo": DroneState(*HOME, 0.0, False, 35.0)})
    said, report = await compiled(step, low)
    assert (
        isinstance(said, Said) and "35" in said.text and report == Said("bravo: battery 35 %, on the ground.")
    )
    high = FakeSensors({"bravo": DroneState(*HOME, 0.0, False, 70.0)})
    assert (await compiled(step, high))[1] == Call("takeoff", {"drone_id": "bravo", "alt_m": 15.0}, "bravo")


async def test_a_condition_on_a_lead_compares_the_difference_of_two_drones_readings() -> None:
    fly = [{"action": "move", "drone": "alpha", "origin": "here", "legs": [leg(25, "east")],
            "altitude": m(10), "after": "stay"}]  # fmt: skip
    step = {"action": "if", "drone": "alpha", "reading": "battery", "than": "charlie", "compare": "at_least",
            "value": 20, "then": fly, "otherwise": [{**fly[0], "drone": "charlie"}]}  # fmt: skip
    batteries = {"alpha": 62.0, "charlie": 48.0}
    sensors = FakeSensors({d: DroneState(*HOME, 0.0, False, b) for d, b in batteries.items()})
    said, takeoff, _ = await compiled(step, sensors)
    assert said == Said("alpha: battery 62 %, charlie 48 %, a lead of 14, at least 20: not.")
    assert takeoff.drone == "charlie"
    sensors.states["alpha"] = DroneState(*HOME, 0.0, False, 70.0)
    assert (await compiled(step, sensors))[1].drone == "alpha"
    sensors.states["charlie"] = DroneState(*HOME, 0.0, False, None)
    assert await compiled(step, sensors) == [Said("alpha or charlie reports no battery: nothing was done.")]
    with pytest.raises(ValidationError, match="'delta' is not in the fleet"):
        parse_plan({"steps": [{**step, "than": "delta"}]}, FLEET)


async def test_choose_flies_the_chosen_drone_whatever_the_steps_name() -> None:
    states = {
        d: DroneState(*HOME, 0.0, False, b) for d, b in (("alpha", 90.0), ("bravo", 40.0), ("charlie", 60.0))
    }
    step = {"action": "choose", "among": FLEET, "reading": "battery", "pick": "lowest",
            "then": [{"action": "takeoff", "drone": "alpha", "altitude": m(6)},
                     {"action": "land", "drone": "alpha"}]}  # fmt: skip
    said, takeoff, land = await compiled(step, FakeSensors(states))
    assert said == Said("bravo has the lowest battery (40 %).")
    assert takeoff.args == {"drone_id": "bravo", "alt_m": 6.0} and land.drone == "bravo"


async def test_a_report_answers_with_readings_and_a_pick() -> None:
    states = {"alpha": DroneState(*HOME, 0.0, False, 88.0), "bravo": flying(alt=12.3, battery=47.0)}
    step = {"action": "report", "drones": ["alpha", "bravo"], "readings": ["battery", "altitude"],
            "pick": "lowest"}  # fmt: skip
    lines = [s.text for s in await compiled(step, FakeSensors(states))]
    assert lines == [
        "alpha: battery 88 %, altitude 0.0 m, on the ground.",
        "bravo: battery 47 %, altitude 12.3 m, flying.",
        "bravo has the lowest battery (47).",
    ]


async def test_a_takeoff_of_a_flying_drone_changes_its_height() -> None:
    sensors = FakeSensors({"alpha": flying()})
    assert await compiled({"action": "altitude", "drone": "alpha", "altitude": m(30)}, sensors) == [
        Call("move_to_relative", {"drone_id": "alpha", "alt_m": 30.0}, "alpha")
    ]
    away = FakeSensors({"alpha": flying(lat=HOME[0] + 0.001)})  # about 111 m north of home
    assert await compiled({"action": "return_home", "drone": "alpha"}, away) == [
        Call("return_to_launch", {"drone_id": "alpha"}, "alpha")
    ]


async def test_a_move_that_only_climbs_to_its_given_height_flies_to_that_height() -> None:
    step = {"action": "move", "drone": "bravo", "legs": [leg(12, "up")], "altitude": m(12), "after": "land",
            "origin": {"kind": "here"}}  # fmt: skip
    assert await compiled(step) == [
        Call("takeoff", {"drone_id": "bravo", "alt_m": 12.0}, "bravo"),
        Call("land", {"drone_id": "bravo"}, "bravo"),
    ]
    in_air = FakeSensors({"bravo": flying(alt=5.0)})
    assert (await compiled({**step, "after": "stay"}, in_air)) == [
        Call("move_to_relative", {"drone_id": "bravo", "alt_m": 12.0}, "bravo")
    ]


def test_a_condition_names_both_branches() -> None:
    step = {"action": "if", "drone": "bravo", "reading": "battery", "compare": "above", "value": 50,
            "then": [{"action": "land", "drone": "bravo"}]}  # fmt: skip
    with pytest.raises(ValidationError, match="otherwise"):
        parse_plan({"steps": [step]}, FLEET)
    assert parse_plan({"steps": [{**step, "otherwise": []}]}, FLEET).steps[0].otherwise == []  # type: ignore[union-attr]
    condition = plan_schema(FLEET)["$defs"]["Condition"]
    assert {"then", "otherwise"} <= set(condition["required"])


def test_a_moves_origin_is_one_word_here_home_or_a_drones_id() -> None:
    step = {"action": "move", "drone": "alpha", "legs": [leg(25, "north")], "altitude": m(15),
            "after": "stay"}  # fmt: skip
    plan = parse_plan({"steps": [{**step, "origin": "Bravo"}, {**step, "origin": "home"}]}, FLEET)
    assert [s.origin.model_dump(exclude_none=True) for s in plan.steps] == [  # type: ignore[union-attr]
        {"kind": "drone", "drone": "bravo"}, {"kind": "home"}]  # fmt: skip
    with pytest.raises(ValidationError, match="not in the fleet"):
        parse_plan({"steps": [{**step, "origin": "zulu"}]}, FLEET)
    origin = plan_schema(FLEET)["$defs"]["Move"]["properties"]["origin"]
    assert origin["anyOf"][0]["enum"] == ["here", "home", *FLEET]


async def test_a_climb_ends_as_its_after_says_and_the_schema_requires_it() -> None:
    hop = {"action": "takeoff", "drone": "bravo", "altitude": m(12), "after": "land"}
    assert await compiled(hop) == [
        Call("takeoff", {"drone_id": "bravo", "alt_m": 12.0}, "bravo"),
        Call("land", {"drone_id": "bravo"}, "bravo"),
    ]
    plan = parse_plan({"steps": [hop, {"action": "land", "drone": "bravo"}]}, FLEET)
    assert len(plan.steps) == 1  # the landing written twice is flown once
    in_air = FakeSensors({"bravo": flying(lat=HOME[0] + 0.001, alt=5.0)})
    assert await compiled({**hop, "action": "altitude", "after": "return_home"}, in_air) == [
        Call("move_to_relative", {"drone_id": "bravo", "alt_m": 12.0}, "bravo"),
        Call("return_to_launch", {"drone_id": "bravo"}, "bravo"),
    ]
    defs = plan_schema(FLEET)["$defs"]
    for name in ("Takeoff", "Altitude"):
        assert "after" in defs[name]["required"] and "default" not in defs[name]["properties"]["after"]


async def test_a_spot_by_a_flying_drone_without_a_height_takes_that_drones_height() -> None:
    bravo = flying(*geometry.offset_position(*HOME, 15.0, 0.0), alt=18.0)
    step = {"action": "move", "drone": "alpha", "origin": "bravo", "legs": [leg(30, "east"), leg(4, "up")],
            "altitude": None, "after": "stay"}  # fmt: skip
    takeoff, goto = await compiled(step, FakeSensors({"bravo": bravo}))
    assert takeoff.args["alt_m"] == goto.args["alt_m"] == 22.0
    (goto,) = await compiled(step, FakeSensors({"alpha": flying(alt=9.0)}))  # bravo on the ground
    assert goto.args["alt_m"] == 13.0


def test_a_plan_and_a_branch_are_bounded_in_the_schema() -> None:
    """A reply that repeats a step ends at the bound instead of running on to the token limit."""
    defs = plan_schema(FLEET)
    assert defs["properties"]["steps"]["maxItems"] == 12
    assert defs["$defs"]["Condition"]["properties"]["otherwise"]["maxItems"] == 4
    assert defs["$defs"]["Move"]["properties"]["legs"]["maxItems"] == 8
    assert defs["$defs"]["Formation"]["properties"]["legs"]["maxItems"] == 8
    shuttle = {"action": "move", "drone": "bravo", "origin": "here", "legs": [leg(30, "north")] * 9,
               "altitude": None, "after": "stay"}  # fmt: skip
    with pytest.raises(ValidationError, match="at most 8 items"):
        parse_plan({"steps": [shuttle]}, FLEET)


async def test_a_leg_with_a_negative_distance_is_flown_the_opposite_way() -> None:
    """ "-20 m north, +15 m east" as the request wrote it: 20 m south, 15 m east (a small model copied the
    signed offset twice, and no plan came); an altitude stays at zero or above."""
    step = {"action": "move", "drone": "charlie", "origin": "here", "altitude": m(12), "after": "stay",
            "legs": [leg(-20, "north"), leg(15, "east"), leg(-3, "down")]}  # fmt: skip
    plan = parse_plan({"steps": [step]}, FLEET)
    assert [(g.distance.value, g.direction) for g in plan.steps[0].legs] == [
        (20, "south"),
        (15, "east"),
        (3, "up"),
    ]
    calls = await compiled(step, FakeSensors({"charlie": flying(alt=12.0)}))
    assert [(c.args["north_m"], c.args["east_m"], c.args.get("up_m")) for c in calls] == [
        (-20.0, 0.0, None),
        (0.0, 15.0, 3.0),
    ]
    below = {"action": "takeoff", "drone": "alpha", "altitude": m(-5), "after": "stay"}
    with pytest.raises(ValidationError, match="greater than or equal to 0"):
        parse_plan({"steps": [below]}, FLEET)


async def test_a_choice_written_once_for_each_candidate_is_flown_once_by_the_chosen_drone() -> None:
    hop = {"action": "takeoff", "altitude": m(6), "after": "land"}
    step = {"action": "choose", "among": FLEET, "reading": "battery", "pick": "lowest",
            "then": [{**hop, "drone": d} for d in FLEET]}  # fmt: skip
    low = FakeSensors({"bravo": DroneState(HOME[0], HOME[1], 0.0, False, 30.0)})
    said, *calls = await compiled(step, low)
    assert isinstance(said, Said) and calls == [
        Call("takeoff", {"drone_id": "bravo", "alt_m": 6.0}, "bravo"),
        Call("land", {"drone_id": "bravo"}, "bravo"),
    ]


async def test_from_the_ground_a_climb_as_high_as_the_height_given_is_that_height() -> None:
    step = {"action": "move", "drone": "bravo", "legs": [leg(40, "west"), leg(10, "up")], "altitude": m(10),
            "after": "stay", "origin": "here"}  # fmt: skip
    assert [c.args for c in await compiled(step)] == [
        {"drone_id": "bravo", "alt_m": 10.0},
        {"drone_id": "bravo", "north_m": 0.0, "east_m": -40.0},
    ]
    more = {**step, "legs": [leg(40, "west"), leg(5, "up")]}  # at 10 m, then 5 m more
    assert (await compiled(more))[1].args["up_m"] == 5.0


def test_a_takeoff_to_a_height_an_earlier_step_flew_at_is_a_repeat_and_a_second_hop_is_not() -> None:
    north = {"action": "move", "drone": "charlie", "origin": "here", "legs": [{"distance": m(30),
             "direction": "north"}], "altitude": m(10), "after": "return_home"}  # fmt: skip
    again = {"action": "takeoff", "drone": "charlie", "altitude": m(10), "after": "land"}
    plan = parse_plan({"steps": [north, again]}, FLEET)
    assert [s.action for s in plan.steps] == ["move"]
    assert len(parse_plan({"steps": [north, {**again, "altitude": m(20)}]}, FLEET).steps) == 2
    hops = parse_plan({"steps": [again, again]}, FLEET)
    assert [s.action for s in hops.steps] == ["takeoff", "takeoff"]


async def test_a_takeoff_repeating_a_climb_that_stays_is_that_climb_and_keeps_its_landing() -> None:
    climb = {"action": "altitude", "drone": "charlie", "altitude": m(8), "after": "stay"}
    again = {"action": "takeoff", "drone": "charlie", "altitude": m(8), "after": "land"}
    plan = parse_plan({"steps": [climb, again]}, FLEET)
    assert [(s.action, s.after) for s in plan.steps] == [("altitude", "land")]
    calls = await Compiler(FakeSensors()).compile(plan.steps[0])
    assert [c.tool for c in calls] == ["takeoff", "land"]
    up_only = {"action": "move", "drone": "charlie", "origin": "here", "legs": [leg(8, "up")],
               "altitude": m(8), "after": "stay"}  # fmt: skip
    plan = parse_plan({"steps": [up_only, {**again, "after": "return_home"}]}, FLEET)
    assert [(s.action, s.after) for s in plan.steps] == [("move", "return_home")]
    # after a flight sideways the takeoff is left out and its landing flown there; after a climb that
    # already lands, both are left out
    north = {**up_only, "legs": [leg(20, "north")]}
    assert [s.action for s in parse_plan({"steps": [north, again]}, FLEET).steps] == ["move", "land"]
    staying = {**again, "after": "stay"}
    assert [s.action for s in parse_plan({"steps": [north, staying]}, FLEET).steps] == ["move"]
    landed = {**climb, "after": "land"}
    assert len(parse_plan({"steps": [landed, again]}, FLEET).steps) == 1


async def test_a_return_home_of_a_drone_over_its_home_is_a_landing() -> None:
    """The autopilot's return climbs to its own return altitude first: over home, the host lands."""
    hop = {"action": "takeoff", "drone": "bravo", "altitude": m(6), "after": "return_home"}
    assert [c.tool for c in await compiled(hop)] == ["takeoff", "land"]
    assert [c.tool for c in await compiled({"action": "return_home", "drone": "bravo"})] == ["land"]
    up_only = {"action": "move", "drone": "bravo", "origin": "here", "legs": [leg(6, "up")],
               "altitude": None, "after": "return_home"}  # fmt: skip
    assert [c.tool for c in await compiled(up_only)][-1] == "land"
    out_and_back = {**up_only, "legs": [leg(20, "north"), leg(20, "south")]}
    assert [c.tool for c in await compiled(out_and_back)][-1] == "land"
    north = {**up_only, "legs": [leg(20, "north")]}
    assert [c.tool for c in await compiled(north)][-1] == "return_to_launch"
    # on the ground away from the home of an earlier flight: it takes off from here, its home once armed
    earlier_home = FakeSensors(homes={"bravo": (HOME[0] + 0.0005, HOME[1])})  # 55 m north
    assert [c.tool for c in await compiled(up_only, earlier_home)][-1] == "land"
    assert [c.tool for c in await compiled(north, earlier_home)][-1] == "return_to_launch"
    back_home = FakeSensors({"bravo": flying(lat=HOME[0] + 0.0002)})  # 22 m north of home
    south = {**up_only, "legs": [leg(22.2, "south")]}
    assert [c.tool for c in await compiled(south, back_home)][-1] == "land"


async def test_a_climb_to_0_m_is_a_landing_or_nothing() -> None:
    down = {"action": "takeoff", "drone": "bravo", "altitude": m(0), "after": "stay"}
    assert await compiled(down) == [Said("bravo stays on the ground (a height of 0 m).")]
    in_air = FakeSensors({"bravo": flying(lat=HOME[0] + 0.001)})
    landing = Call("land", {"drone_id": "bravo"}, "bravo")
    assert await compiled({**down, "action": "altitude"}, in_air) == [landing]


def test_a_repeated_climb_is_read_against_the_same_drone_s_step_before_it() -> None:
    up = {"action": "altitude", "altitude": m(16), "after": "stay"}
    steps = [{**up, "drone": "alpha"}, {**up, "drone": "bravo"},
             {"action": "takeoff", "drone": "alpha", "altitude": m(16), "after": "land"}]  # fmt: skip
    plan = parse_plan({"steps": steps}, FLEET)
    assert [(s.drone, s.after) for s in plan.steps] == [("alpha", "land"), ("bravo", "stay")]
    north = {"action": "move", "drone": "alpha", "origin": "here", "legs": [leg(20, "north")],
             "altitude": None, "after": "land"}  # fmt: skip
    land = {"action": "land", "drone": "alpha"}
    twice = parse_plan({"steps": [north, {**up, "drone": "bravo"}, land]}, FLEET)
    assert [s.action for s in twice.steps] == ["move", "altitude"]  # alpha's landing is flown once


def test_a_climb_to_a_height_flown_right_after_the_flight_ended_is_a_repeat() -> None:
    out = {"action": "move", "drone": "bravo", "origin": "here", "legs": [leg(40, "south")],
           "altitude": m(15), "after": "return_home"}  # fmt: skip
    again = {"action": "altitude", "drone": "bravo", "altitude": m(15), "after": "stay"}
    assert [s.action for s in parse_plan({"steps": [out, again]}, FLEET).steps] == ["move"]
    # a drone still flying climbs back to a height it flew at: a step of its own
    stays = {**out, "after": "stay"}
    down = {**again, "altitude": m(5)}
    assert len(parse_plan({"steps": [stays, down, again]}, FLEET).steps) == 3


async def test_a_move_at_0_m_flies_at_no_given_height() -> None:
    """The 0.5B model wrote "straight up to 28 m" as a 28 m leg up at an altitude of 0 m."""
    step = {"action": "move", "drone": "charlie", "legs": [leg(28, "up")], "altitude": m(0), "after": "stay",
            "origin": "here"}  # fmt: skip
    out = await compiled(step)
    assert out[0] == Call("takeoff", {"drone_id": "charlie", "alt_m": 28.0}, "charlie")
    assert not [c for c in out[1:] if c.args.get("up_m") or c.args.get("alt_m") is not None]  # no other climb


async def test_a_hold_keeps_a_drone_on_the_ground_there_and_a_flying_one_in_place() -> None:
    """A drone the request names but leaves alone ("alpha stays on the ground") is a hold step: nothing is
    sent for it on the ground; in the air it holds its position."""
    step = {"action": "hold", "drone": "alpha"}
    assert await compiled(step) == [Said("alpha stays on the ground.")]
    assert await compiled(step, FakeSensors({"alpha": flying()})) == [
        Call("hold_position", {"drone_id": "alpha"}, "alpha")
    ]
