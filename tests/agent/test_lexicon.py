"""What the request's own words settle in a plan: units written after numbers, and which endings it asks."""

from __future__ import annotations

from typing import Any

import pytest

from fleet_agent.consistency import as_request_says, placed_by_name, split_formation
from fleet_agent.lexicon import compass_points, number_units, stated_ways, tokens
from fleet_agent.units import Unit


def _m(value: float, unit: str = "m") -> dict[str, Any]:
    return {"value": value, "unit": unit}


def _move(after: str, *legs: tuple[float, str, str]) -> dict[str, Any]:
    return {"action": "move", "drone": "alpha", "origin": "here", "altitude": None, "after": after,
            "legs": [{"distance": _m(v, u), "direction": d} for v, u, d in legs]}  # fmt: skip


def test_a_number_takes_the_unit_written_after_it_in_any_language() -> None:
    assert number_units("Alpha: climb to 30 ft, fly 0,05 km east") == {30.0: {Unit.ft}, 0.05: {Unit.km}}
    assert number_units("Lleva a charlie 30 metros al norte, 100 yardas") == {
        30.0: {Unit.m},
        100.0: {Unit.yd},
    }
    assert number_units("bravo 50ft up, then 2 mi") == {50.0: {Unit.ft}, 2.0: {Unit.mi}}
    assert number_units("alpha 10 m and 10 ft") == {10.0: {Unit.m, Unit.ft}}
    assert number_units("if the battery is above 40 %") == {}
    assert number_units("half a mile north, then 20 m up") == {None: {Unit.mi}, 20.0: {Unit.m}}


def test_centimetres_are_a_unit_and_a_height_in_centimetres_is_not_flown_in_metres() -> None:
    assert number_units("Bravo, survole le pré à 70 cm du sol") == {70.0: {Unit.cm}}
    data = {"steps": [_move("stay", (40, "m", "east")) | {"altitude": _m(70)}]}
    out = as_request_says("Bravo, 40 m ost, in 70 Zentimeter Höhe", data)
    assert out["steps"][0]["altitude"] == _m(70, "cm") and out["steps"][0]["legs"][0]["distance"] == _m(40)


def test_a_length_written_in_metres_takes_the_requests_unit() -> None:
    data = {"steps": [{"action": "altitude", "drone": "alpha", "altitude": _m(30), "after": "stay"},
                      _move("stay", (150, "m", "south"), (10, "m", "up"))]}  # fmt: skip
    out = as_request_says("alpha to 30 ft, then 150 yards south and 10 m up, stay there", data)
    assert out["steps"][0]["altitude"] == _m(30, "ft")
    assert [leg["distance"] for leg in out["steps"][1]["legs"]] == [_m(150, "yd"), _m(10)]


def test_a_fraction_written_in_metres_takes_the_unit_named_without_a_number() -> None:
    data = {"steps": [_move("stay", (0.1, "m", "west"), (0.5, "m", "north"), (50, "m", "south"))]}
    out = as_request_says("alpha: a tenth of a mile west, 0.5 m north, then 50 yards south", data)
    assert [leg["distance"] for leg in out["steps"][0]["legs"]] == [_m(0.1, "mi"), _m(0.5), _m(50, "yd")]


def test_an_ending_the_model_wrote_is_kept_whatever_the_request_says() -> None:
    for request in ("alpha 30 m north and hold there", "alpha 30 m north, then set it down"):
        for after in ("stay", "land", "return_home"):
            data = {"steps": [_move(after, (30, "m", "north"))]}
            assert as_request_says(request, data)["steps"][0]["after"] == after, (request, after)
    steps = [_move("stay", (30, "m", "north")), {"action": "return_home", "drone": "alpha"}]
    assert as_request_says(
        "charlie 30 metros al norte y déjalo ahí", {"steps": [dict(s) for s in steps]}
    ) == {"steps": steps}


def test_a_landing_the_plan_leaves_out_is_not_added_by_words() -> None:
    data = {"steps": [{"action": "takeoff", "drone": "alpha", "altitude": _m(10), "after": "stay"},
                      _move("stay", (20, "m", "south"))]}  # fmt: skip
    out = as_request_says("Alpha auf 10 m starten, 20 m nach Süden fliegen und dann landen.", data)
    assert [s["after"] for s in out["steps"]] == ["stay", "stay"]
    pushed = {"steps": [_move("stay", (20, "m", "north"))]}
    assert (
        as_request_says("Pousse alpha de 20 m vers le nord et laisse-le là.", pushed)["steps"][0]["after"]
        == "stay"
    )


def _here(drone: str, value: float, direction: str) -> dict[str, Any]:
    return {**_move("stay", (value, "m", direction)), "drone": drone}


def test_a_move_from_here_is_measured_from_the_drone_named_after_its_distance() -> None:
    fleet = ["alpha", "bravo", "charlie"]
    out = placed_by_name(
        "Put alpha 25 m north of bravo, at 15 m.", fleet, {"steps": [_here("alpha", 25, "north")]}
    )
    assert out["steps"][0]["origin"] == "bravo"
    fr = placed_by_name(
        "Place charlie à 20 m à l'ouest d'alpha.", fleet, {"steps": [_here("charlie", 20, "west")]}
    )
    assert fr["steps"][0]["origin"] == "alpha"
    apart = {"steps": [_here("alpha", 20, "north")]}
    assert placed_by_name("Alpha 20 m north. Bravo stays down.", fleet, apart)["steps"][0]["origin"] == "here"
    before = {"steps": [_here("alpha", 20, "north")]}
    assert placed_by_name("Bravo stays, alpha 20 m north", fleet, before)["steps"][0]["origin"] == "here"


def test_a_formation_whose_drones_are_each_named_before_a_leg_is_one_move_each() -> None:
    legs = [{"distance": _m(25), "direction": "east"}, {"distance": _m(30), "direction": "north"}]
    formation = {"action": "formation", "drones": ["bravo", "alpha"], "shape": "line", "spacing": _m(25),
                 "altitude": _m(10), "legs": legs}  # fmt: skip
    out = split_formation("alpha 25 m east and bravo 30 m north, both at 10 m", {"steps": [dict(formation)]})
    assert [(s["action"], s["drone"], s["legs"]) for s in out["steps"]] == [
        ("move", "alpha", [legs[0]]),
        ("move", "bravo", [legs[1]]),
    ]
    assert {s["altitude"]["value"] for s in out["steps"]} == {10}
    together = split_formation(
        "alpha and bravo in a line, 25 m east and 30 m north", {"steps": [dict(formation)]}
    )
    assert together["steps"] == [formation]


def test_a_climb_to_zero_is_left_as_written_for_the_compiler() -> None:
    zero = {"action": "altitude", "drone": "alpha", "altitude": _m(0, "ft"), "after": "stay"}
    out = as_request_says(
        "alpha 40 m south, then climb another 20 feet there and hover", {"steps": [dict(zero)]}
    )
    assert out["steps"] == [zero]


def test_a_move_measured_from_its_own_drone_is_from_its_home_only_where_the_request_says_home() -> None:
    own = {**_move("stay", (20, "m", "north")), "origin": "alpha"}
    home = as_request_says("alpha 30 m west, then to a point 20 m north of its home", {"steps": [dict(own)]})
    assert home["steps"][0]["origin"] == "home"
    itself = {**own, "origin": {"kind": "drone", "drone": "alpha"}}
    here = as_request_says("alpha 20 m north and hover", {"steps": [dict(itself)]})
    assert here["steps"][0]["origin"] == {"kind": "drone", "drone": "alpha"}
    back = [dict(own), {"action": "return_home", "drone": "alpha"}]
    returned = as_request_says("alpha 20 m north of where it is, then home", {"steps": back})
    assert returned["steps"][0]["origin"] == "alpha"


def test_a_word_ends_where_its_script_changes_and_a_latin_word_stays_whole() -> None:
    assert tokens("alpha를 10미터") == ["alpha", "를", "10", "미터"]
    assert tokens("bravoを15メートルまで") == ["bravo", "を", "15", "メートル", "まで"]
    assert tokens("Größe côté, bravoу 0,05 km") == ["Größe", "côté", "bravo", "у", "0,05", "km"]
    assert number_units("alphaを30フィート、bravo 12 pies") == {12.0: {Unit.ft}}


def test_the_restatement_gives_each_number_the_compass_point_after_it_in_its_clause() -> None:
    said = "Alpha flies to 12 m, then 30 m south-west and 10 m back north east; 0,5 km northwards, 5 m up."
    want = [(12, None), (30, "southwest"), (10, "northeast"), (0.5, "north"), (5, "up")]
    assert stated_ways(said) == want
    assert stated_ways("Echo flies 20 m east of delta at 15 m.") == [(20, "east"), (15, None)]
    assert stated_ways("Nothing flies, alpha2 neither.") == []
    aside = "Take bravo to x = 30 m, y = -10 m (x runs east and y north) at 12 m"
    assert stated_ways(aside) == [(30, None), (-10, None), (12, None)]


@pytest.mark.parametrize(
    ("text", "points"),
    [
        ("Emeld 12 méterre, 20 métert nyugatra, aztán 20 métert északra", ["west", "north"]),
        ("charlie को 25 मीटर पूर्व की ओर ले जाओ", ["east"]),
        ("Il est parti à l'est, puis vers le nord-ouest", ["east", "northwest"]),
        ("este dron vuela al este y al sur, luego al suroeste", ["east", "south", "southwest"]),
        ("alphaを北西へ20メートル、向东飞", ["northwest", "east"]),
        ("bay về phía tây bắc 20 m rồi hướng nam", ["northwest", "south"]),
        ("Nordwesten, sudoeste; на юго-запад", ["northwest", "southwest", "southwest"]),
        ("північно-східний; βορειοανατολικά", ["northeast", "northeast"]),
        ("الشمال الشرقي ثم غربا", ["northeast", "west"]),
        ("북동쪽으로 20미터, 그리고 서쪽", ["northeast", "west"]),
        ("ตะวันออกเฉียงเหนือ; ke barat laut", ["northeast", "northwest"]),
        ("pierwszy bok na północny wschód, potem na południowy zachód", ["northeast", "southwest"]),
        ("30 m į pietryčius, tada į šiaurės rytus ir pietvakarius", ["southeast", "northeast", "southwest"]),
        ("north of east, then 20 m south, 10 m west", ["north", "east", "south", "west"]),
        ("name the place, ida y vuelta, zachowaj wysokość, laut Plan, sur le toit, sul tetto", []),
    ],
)  # fmt: skip
def test_compass_words_of_the_languages_operators_write_in(text: str, points: list[str]) -> None:
    assert compass_points(text) == points


def test_a_request_gives_a_number_the_way_named_after_it_or_in_a_clause_of_its_own_before_it() -> None:
    assert stated_ways("Vidd 0,03 kilométerre nyugatra, és ott tedd le.") == [(0.03, "west")]
    assert stated_ways("alphaを北へ20メートル、東へ10メートル") == [(20, "north"), (10, "east")]
    assert stated_ways("Nosta alpha 10 metriin, sitten 5 metriä ylemmäs ja 20 metriä pohjoiseen") == [
        (10, None), (5, "up"), (20, "north")]  # fmt: skip
