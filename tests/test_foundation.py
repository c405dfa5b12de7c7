"""Unit tests of the shared foundation: settings, vehicle registration spec, geodesy."""

from __future__ import annotations

import math

import pytest
from pydantic import ValidationError

from gateway.config import Settings
from gateway.errors import InvalidArgument, UnknownVehicle
from gateway.fleet import geo
from gateway.registry.spec import VehicleSpec


def test_settings_defaults_and_env(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("GATEWAY_MCP_TOOLSETS", "flight, telemetry")
    monkeypatch.setenv("GATEWAY_MAX_ALTITUDE_M", "80")
    settings = Settings(_env_file=None)
    assert settings.toolsets == ["flight", "telemetry"]
    assert settings.max_altitude_m == 80
    assert settings.host == "127.0.0.1"
    assert settings.gcs_sysid not in (1, 255)


def test_settings_reject_unknown_toolset() -> None:
    with pytest.raises(ValidationError, match="unknown toolset"):
        Settings(_env_file=None, mcp_toolsets="flight,teleport")


@pytest.mark.parametrize(
    "url",
    [
        "udpin://0.0.0.0:14540",
        "udpout://10.0.0.5:14550",
        "tcpin://127.0.0.1:5760",
        "tcpout://drone-1.local:5760",
        "serial:///dev/ttyUSB0:57600",
        "serial:///dev/ttyACM0",
    ],
)
def test_vehicle_spec_accepts_mavsdk_urls(url: str) -> None:
    assert VehicleSpec(id="alpha-1", url=url).url == url


@pytest.mark.parametrize(
    ("field", "value", "fragment"),
    [
        ("id", "Alpha", "id"),
        ("id", "a" * 33, "id"),
        ("id", "", "id"),
        ("url", "http://x:1", "scheme"),
        ("url", "udpin://0.0.0.0", "port"),
        ("url", "tcpout://host:99999", "port"),
        ("url", "tcpout://host:5760/extra", "nothing after"),
        ("url", "serial://ttyUSB0", "device path"),
        ("expected_sysid", 0, "expected_sysid"),
        ("expected_sysid", 256, "expected_sysid"),
    ],
)
def test_vehicle_spec_rejects_bad_input(field: str, value: object, fragment: str) -> None:
    data: dict[str, object] = {"id": "alpha", "url": "tcpout://127.0.0.1:5760"}
    data[field] = value
    with pytest.raises(ValidationError) as info:
        VehicleSpec(**data)
    assert fragment in str(info.value)


def test_unknown_vehicle_lists_known_ids() -> None:
    err = UnknownVehicle("zulu", ["bravo", "alpha"])
    assert "zulu" in err.message and "alpha, bravo" in err.message
    assert err.to_dict()["code"] == "unknown_vehicle"


def test_geo_round_trip_and_distance() -> None:
    lat0, lon0 = -35.363261, 149.165230
    lat, lon = geo.offset_position(lat0, lon0, 100.0, 0.0)
    assert lat > lat0 and math.isclose(lon, lon0, abs_tol=1e-9)
    assert math.isclose(geo.horizontal_distance_m(lat0, lon0, lat, lon), 100.0, abs_tol=0.01)
    north, east = geo.ned_offset(lat0, lon0, *geo.offset_position(lat0, lon0, -30.0, 40.0))
    assert math.isclose(north, -30.0, abs_tol=0.01) and math.isclose(east, 40.0, abs_tol=0.01)
    assert math.isclose(
        geo.bearing_deg(lat0, lon0, *geo.offset_position(lat0, lon0, 0, 50)), 90.0, abs_tol=0.01
    )
    # one degree of latitude is about 111 km
    assert 110_000 < geo.horizontal_distance_m(0.0, 0.0, 1.0, 0.0) < 112_000


def test_altitude_frames_are_inverse() -> None:
    assert geo.relative_to_amsl(10.0, 584.0) == 594.0
    assert geo.amsl_to_relative(594.0, 584.0) == 10.0


@pytest.mark.parametrize(
    ("lat", "lon"), [(91, 0), (0, 181), (math.nan, 0), (0, math.inf), ("1", 0), (True, 0)]
)
def test_check_lat_lon_rejects(lat: object, lon: object) -> None:
    with pytest.raises(InvalidArgument):
        geo.check_lat_lon(lat, lon)  # type: ignore[arg-type]
