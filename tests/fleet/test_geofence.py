"""Keep-in / keep-out zones: targets in and out, legs crossing, scopes, GeoJSON input."""

from __future__ import annotations

import json

import pytest
from hypothesis import given
from hypothesis import strategies as st

from gateway.config import Settings
from gateway.errors import InvalidArgument, SafetyRefusal
from gateway.fleet.policy.geofence import GeofenceSet, load_geofence_file
from gateway.fleet.policy.safety import SafetyPolicy
from gateway.fleet.policy.safety_inputs import Target
from tests.fleet._util import HOME, at, ctx, settings, square


def fenced(*zones: tuple[str, str, dict, str]) -> SafetyPolicy:
    fences = GeofenceSet()
    for name, kind, geometry, scope in zones:
        fences.add(name, kind, geometry, scope)
    return SafetyPolicy(settings(), geofences=fences)


def target(north_m: float, east_m: float, alt: float = 20.0) -> Target:
    return Target(*at(north_m, east_m), alt)


def refusal(fn, *args, **kwargs) -> SafetyRefusal:
    with pytest.raises(SafetyRefusal) as info:
        fn(*args, **kwargs)
    return info.value


# --- keep-in -------------------------------------------------------------------------------------------


def test_keep_in_allows_inside_and_refuses_outside_with_distance() -> None:
    p = fenced(("field", "keep_in", square(0, 0, 200), "*"))
    p.check_motion(ctx(), target(190, 0))
    err = refusal(p.check_motion, ctx(), target(250, 0))
    assert err.rule == "geofence_keep_in"
    assert "target is 50 m outside keep-in zone 'field'" in err.message
    assert err.details["zone"] == "field" and err.details["metres"] == pytest.approx(50.0, abs=0.2)


def test_keep_in_path_must_stay_inside_a_concave_zone() -> None:
    # A U shape: two 100 m wide arms joined at the south; the gap between the arms is outside.
    ring = [
        at(-100, -150),
        at(-100, 150),
        at(200, 150),
        at(200, 50),
        at(0, 50),
        at(0, -50),
        at(200, -50),
        at(200, -150),
        at(-100, -150),
    ]
    u_shape = {"type": "Polygon", "coordinates": [[[lon, lat] for lat, lon in ring]]}
    p = fenced(("u", "keep_in", u_shape, "*"))
    west_arm = ctx(north_m=150, east_m=-100)
    p.check_motion(west_arm, target(-50, -100))  # down the arm into the base: inside
    err = refusal(p.check_motion, west_arm, target(150, 100))  # straight across the gap
    assert err.rule == "geofence_keep_in"
    assert "leaves keep-in zone 'u' for 100 m" in err.message


def test_keep_in_lets_a_drone_outside_come_back() -> None:
    p = fenced(("field", "keep_in", square(0, 0, 100), "*"))
    outside = ctx(north_m=300, east_m=0)
    p.check_motion(outside, target(50, 0))


def test_every_keep_in_zone_must_hold() -> None:
    p = fenced(
        ("big", "keep_in", square(0, 0, 500), "*"), ("alpha-box", "keep_in", square(0, 0, 50), "alpha")
    )
    p.check_motion(ctx("bravo"), target(200, 0))
    err = refusal(p.check_motion, ctx("alpha"), target(200, 0))
    assert err.rule == "geofence_keep_in" and err.details["zone"] == "alpha-box"


# --- keep-out ------------------------------------------------------------------------------------------


def test_keep_out_refuses_a_target_inside() -> None:
    p = fenced(("school", "keep_out", square(300, 0, 50), "*"))
    err = refusal(p.check_motion, ctx(), target(310, 0))
    assert err.rule == "geofence_keep_out"
    assert "target is inside keep-out zone 'school' (40 m from its edge)" in err.message
    p.check_motion(ctx(), target(300, 100))


def test_keep_out_refuses_a_leg_that_crosses_it() -> None:
    p = fenced(("school", "keep_out", square(300, 0, 50), "*"))
    err = refusal(p.check_motion, ctx(), target(600, 0))
    assert err.rule == "geofence_keep_out"
    assert "the straight path to the target crosses keep-out zone 'school' for 100 m" in err.message
    assert err.details["metres"] == pytest.approx(100.0, abs=0.5)
    # The same distance, going around it, is fine.
    p.check_motion(ctx(), target(600, 200))
    # Grazing a corner counts: the edge belongs to the zone.
    err = refusal(p.check_motion, ctx(), target(600, 120))
    assert err.rule == "geofence_keep_out" and "touches keep-out zone 'school'" in err.message


def test_keep_out_may_be_left_but_not_reentered() -> None:
    p = fenced(("zone", "keep_out", square(0, 0, 50), "*"))
    inside = ctx(north_m=0, east_m=0)
    p.check_motion(inside, target(200, 0))
    # Leaves to the north and comes back in is refused: the target lies beyond the zone on the far side
    # only through a second crossing of a second zone part.
    two_parts = {
        "type": "MultiPolygon",
        "coordinates": [square(0, 0, 50)["coordinates"], square(200, 0, 50)["coordinates"]],
    }
    p2 = fenced(("pair", "keep_out", two_parts, "*"))
    err = refusal(p2.check_motion, inside, target(400, 0))
    assert err.rule == "geofence_keep_out" and "crosses keep-out zone 'pair'" in err.message


def test_multipolygon_keep_out_and_vehicle_scope() -> None:
    parts = {
        "type": "MultiPolygon",
        "coordinates": [square(300, 0, 20)["coordinates"], square(-300, 0, 20)["coordinates"]],
    }
    p = fenced(("tanks", "keep_out", parts, "bravo"))
    assert refusal(p.check_motion, ctx("bravo"), target(-300, 0)).rule == "geofence_keep_out"
    p.check_motion(ctx("alpha"), target(-300, 0))


def test_unknown_position_refuses_only_when_zones_apply() -> None:
    p = fenced(("school", "keep_out", square(300, 0, 50), "bravo"))
    err = refusal(p.check_motion, ctx("bravo", position=False), target(100, 0))
    assert err.rule == "position_unknown" and "1 geofence zone" in err.message
    p.check_motion(ctx("alpha", position=False), target(100, 0))


def test_mission_leg_crossing_keep_out_names_the_item() -> None:
    from tests.fleet.test_safety_limits import item

    p = fenced(("school", "keep_out", square(300, 0, 50), "*"))
    items = [item(100, 100), item(500, 100), item(500, 0), item(100, 0)]
    err = refusal(p.check_mission, ctx(), items)
    assert err.rule == "geofence_keep_out" and err.details["item"] == 4
    assert "mission item 4: the straight path" in err.message


@given(
    north=st.floats(min_value=-400, max_value=400),
    east=st.floats(min_value=-400, max_value=400),
)
def test_point_in_rectangle_matches_metric_coordinates(north: float, east: float) -> None:
    """Projection + polygon test agree with plain metric coordinates (away from the edge)."""
    fences = GeofenceSet()
    fences.add("box", "keep_out", square(0, 0, 200), "*")
    half_margin = 0.5
    inside_metric = abs(north) < 200 - half_margin and abs(east) < 200 - half_margin
    outside_metric = abs(north) > 200 + half_margin or abs(east) > 200 + half_margin
    hit = bool(fences.check_target("alpha", *at(north, east)))
    if inside_metric:
        assert hit
    elif outside_metric:
        assert not hit


# --- input ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("geometry", "fragment"),
    [
        ({"type": "Point", "coordinates": [8.5, 47.3]}, "Polygon or MultiPolygon"),
        (
            {
                "type": "Polygon",
                "coordinates": [[[8.5, 47.3], [8.6, 47.4], [8.6, 47.3], [8.5, 47.4], [8.5, 47.3]]],
            },
            "not a valid polygon",
        ),
        (
            {
                "type": "Polygon",
                "coordinates": [[[47.3, 100.0], [47.4, 100.0], [47.4, 100.1], [47.3, 100.0]]],
            },
            "[longitude, latitude]",
        ),
        ({"type": "Polygon", "coordinates": "nope"}, "malformed"),
        ("not a mapping", "Polygon or MultiPolygon"),
    ],
)
def test_bad_geometries_are_rejected_and_change_nothing(geometry, fragment: str) -> None:
    fences = GeofenceSet()
    with pytest.raises(InvalidArgument) as info:
        fences.add("bad", "keep_out", geometry)
    assert fragment in info.value.message
    assert len(fences) == 0


def test_bad_kind_and_duplicate_names() -> None:
    fences = GeofenceSet()
    with pytest.raises(InvalidArgument, match="keep_in"):
        fences.add("x", "keep_around", square(0, 0, 10))
    fences.add("x", "keep_out", square(0, 0, 10))
    with pytest.raises(InvalidArgument, match="already exists"):
        fences.add("x", "keep_in", square(0, 0, 10))
    with pytest.raises(InvalidArgument, match="zones: x"):
        fences.remove("y")
    assert fences.remove("x").name == "x" and len(fences) == 0


def test_feature_collection_file_and_records_round_trip(tmp_path) -> None:
    document = {
        "type": "FeatureCollection",
        "features": [
            {
                "type": "Feature",
                "properties": {"kind": "keep_in", "name": "field"},
                "geometry": square(0, 0, 500),
            },
            {
                "type": "Feature",
                "properties": {"kind": "keep_out", "vehicle_id": "alpha"},
                "geometry": square(300, 0, 50),
            },
        ],
    }
    path = tmp_path / "fences.geojson"
    path.write_text(json.dumps(document))
    fences = load_geofence_file(path)
    assert [(z.name, z.kind, z.scope) for z in fences] == [
        ("field", "keep_in", "*"),
        ("zone-2", "keep_out", "alpha"),
    ]
    again = GeofenceSet.from_records(json.loads(json.dumps(fences.to_records())))
    assert again.to_records() == fences.to_records()

    p = SafetyPolicy.from_settings(Settings(_env_file=None, geofence_file=str(path)))
    assert refusal(p.check_motion, ctx("alpha"), target(300, 0)).rule == "geofence_keep_out"
    assert refusal(p.check_motion, ctx("bravo"), target(600, 0)).rule == "geofence_keep_in"


def test_bad_geofence_documents(tmp_path) -> None:
    with pytest.raises(InvalidArgument, match="FeatureCollection"):
        GeofenceSet.from_geojson({"type": "Feature"})
    with pytest.raises(InvalidArgument, match=r"properties\.kind"):
        GeofenceSet.from_geojson({"type": "FeatureCollection", "features": [{"geometry": square(0, 0, 5)}]})
    with pytest.raises(InvalidArgument, match="cannot read geofence file"):
        load_geofence_file(tmp_path / "missing.geojson")
    with pytest.raises(InvalidArgument, match="lacks 'kind'"):
        GeofenceSet.from_records([{"name": "a", "geometry": square(0, 0, 5)}])


def test_home_constant_is_used_consistently() -> None:
    # The helper squares are built around HOME; a zone around home contains home.
    fences = GeofenceSet()
    fences.add("home", "keep_in", square(0, 0, 10), "*")
    assert not fences.check_target("alpha", HOME[0], HOME[1])
