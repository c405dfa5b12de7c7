"""A recorded flight (its 1 Hz track and status texts) in the formats of the field's tools.

* GeoJSON (RFC 7946): a Feature whose coordinates are ``[lon, lat, alt]`` with the altitude in metres
  above mean sea level (the autopilot's AMSL: the flight's home altitude plus the height above home),
  and the height above home per point in the properties. RFC 7946 names height above the WGS 84
  ellipsoid; the two differ by the local geoid undulation (within about +-100 m worldwide, e.g. +48 m
  in central Europe), far less than the height above home they replace, and AMSL is what the
  autopilot, QGroundControl and a map's terrain use.
* KML 2.2: a Placemark with the track as a LineString, ``altitudeMode`` absolute (KML's absolute is
  above sea level), and a ``gx:Track`` with the time of each point (Google Earth's time slider).
* MAVLink telemetry log (``.tlog``, what QGroundControl, Mission Planner and MAVExplorer open): each
  record an 8-byte big-endian Unix time in microseconds and one MAVLink 2 packet. A flight whose raw
  frames were recorded (`gateway.fleet.missions.raw_tlog`) is exported as those; for one without (recorded
  before the gateway kept them, with ``flight_tlog_dir`` none, or on another cluster node) the log is
  reconstructed here from the recording (1 Hz):
  per sample a HEARTBEAT as the autopilot sent it (its MAV_TYPE, its custom mode, armed), GPS_RAW_INT
  (its fix type and satellites, the position, ground speed and course), GLOBAL_POSITION_INT, VFR_HUD
  and SYS_STATUS (battery), and the flight's STATUSTEXTs at their times, from the vehicle's system id.
  So MAVExplorer, ``mavflightmodes`` and ``mavflighttime`` read the flight's modes, time in the air and
  distance. A sample recorded before the gateway kept the HEARTBEAT and GPS fix says the vehicle type
  of the autopilot's usual airframe, custom mode 0, and a 3D fix (it has a position).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from datetime import datetime
from xml.sax.saxutils import escape

from gateway.registry.records import FlightRecord, StatusTextRecord, TrackSample
from gateway.util.json_types import JsonObject, JsonValue

ALTITUDE_REFERENCE = "metres above mean sea level (home altitude AMSL + height above home)"


def amsl(flight: FlightRecord, sample: TrackSample) -> float | None:
    """The sample's altitude above mean sea level, when the flight's home altitude is known."""
    if sample.alt_rel_m is None or flight.home_alt_amsl is None:
        return None
    return flight.home_alt_amsl + sample.alt_rel_m


def track_feature(flight: FlightRecord, track: Sequence[TrackSample]) -> JsonObject:
    """A GeoJSON Feature: LineString ``[lon, lat, alt AMSL]`` with per-point arrays in the properties.

    The per-point arrays run parallel to the coordinates (``times`` as ISO 8601, like the common
    ``coordTimes`` convention; ``alt_rel_m``, the height above home). A track of one point is a Point,
    an empty one has no geometry; without a known home altitude the coordinates have no altitude.
    """
    coordinates: list[JsonValue] = []
    for s in track:
        alt = amsl(flight, s)
        coordinates.append([s.lon, s.lat, round(alt, 3)] if alt is not None else [s.lon, s.lat])
    if len(coordinates) >= 2:
        geometry: JsonObject | None = {"type": "LineString", "coordinates": coordinates}
    elif coordinates:
        geometry = {"type": "Point", "coordinates": coordinates[0]}
    else:
        geometry = None
    properties: JsonObject = flight.model_dump(mode="json")
    properties["flight_id"] = properties.pop("id")
    properties["sample_count"] = len(track)
    properties["altitude_reference"] = ALTITUDE_REFERENCE if flight.home_alt_amsl is not None else None
    properties["times"] = [s.t.isoformat() for s in track]
    for name in ("alt_rel_m", "heading_deg", "ground_speed_mps", "battery_pct"):
        properties[name] = [getattr(s, name) for s in track]
    return {"type": "Feature", "id": flight.id, "geometry": geometry, "properties": properties}


def _kml_time(t: datetime) -> str:
    return t.isoformat().replace("+00:00", "Z")


def track_kml(flight: FlightRecord, track: Sequence[TrackSample]) -> str:
    """The flight as a KML 2.2 document (LineString plus a timed gx:Track), altitudes AMSL."""
    name = escape(f"{flight.vehicle_id} flight {flight.id}")
    with_alt = flight.home_alt_amsl is not None
    mode = "absolute" if with_alt else "clampToGround"

    def coord(s: TrackSample, sep: str) -> str:
        alt = amsl(flight, s)
        return sep.join(f"{v:.7f}" if i < 2 else f"{v:.2f}" for i, v in enumerate((s.lon, s.lat, alt or 0.0)))

    points = " ".join(coord(s, ",") for s in track)
    whens = "".join(f"<when>{_kml_time(s.t)}</when>" for s in track)
    coords = "".join(f"<gx:coord>{coord(s, ' ')}</gx:coord>" for s in track)
    span = ""
    if track:
        span = (
            f"<TimeSpan><begin>{_kml_time(track[0].t)}</begin><end>{_kml_time(track[-1].t)}</end></TimeSpan>"
        )
    description = escape(
        f"started {_kml_time(flight.started_at)}; {len(track)} samples; altitudes "
        + (ALTITUDE_REFERENCE if with_alt else "unknown (no home altitude): drawn on the ground")
    )
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        '<kml xmlns="http://www.opengis.net/kml/2.2" xmlns:gx="http://www.google.com/kml/ext/2.2">\n'
        f"<Document><name>{name}</name>\n"
        '<Style id="track"><LineStyle><color>ff0080ff</color><width>3</width></LineStyle></Style>\n'
        f"<Placemark><name>{name}</name><description>{description}</description>{span}"
        f"<styleUrl>#track</styleUrl><LineString><altitudeMode>{mode}</altitudeMode>"
        f"<coordinates>{points}</coordinates></LineString></Placemark>\n"
        f"<Placemark><name>{name} (timed)</name><styleUrl>#track</styleUrl>"
        f"<gx:Track><altitudeMode>{mode}</altitudeMode>{whens}{coords}</gx:Track></Placemark>\n"
        "</Document></kml>\n"
    )


_SEVERITY = {
    "EMERGENCY": 0, "ALERT": 1, "CRITICAL": 2, "ERROR": 3, "WARNING": 4, "NOTICE": 5, "INFO": 6, "DEBUG": 7,
}  # fmt: skip
_AUTOPILOT = {"ardupilot": "MAV_AUTOPILOT_ARDUPILOTMEGA", "px4": "MAV_AUTOPILOT_PX4"}


class _Sink:
    """The file object pymavlink's encoder wants; keeps the packets."""

    def __init__(self) -> None:
        self.packets: list[bytes] = []

    def write(self, data: bytes) -> None:
        self.packets.append(bytes(data))


def _finite(value: float | None, default: float = 0.0) -> float:
    return value if value is not None and math.isfinite(value) else default


def track_tlog(
    flight: FlightRecord,
    track: Sequence[TrackSample],
    status_texts: Sequence[StatusTextRecord] = (),
    *,
    sysid: int = 1,
    autopilot: str | None = None,
) -> bytes:
    """The flight as a MAVLink 2 telemetry log, written from its recorded track (see the module doc)."""
    # ardupilotmega includes the common messages, and it is the dialect the image keeps
    # (deploy/Dockerfile); about 12 MiB, imported when a log is first exported
    from pymavlink.dialects.v20 import ardupilotmega as mavlink2

    sink = _Sink()
    mav = mavlink2.MAVLink(sink, srcSystem=sysid, srcComponent=mavlink2.MAV_COMP_ID_AUTOPILOT1)
    records: list[tuple[float, int, bytes]] = []  # (time, order, packet): sorted into time order

    def emit(t: float, order: int, message: mavlink2.MAVLink_message) -> None:
        sink.packets.clear()
        mav.send(message)
        records.append((t, order, b"".join(sink.packets)))

    armed = mavlink2.MAV_MODE_FLAG_SAFETY_ARMED | mavlink2.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED
    ap = int(getattr(mavlink2, _AUTOPILOT.get(autopilot or "", "MAV_AUTOPILOT_GENERIC")))
    home_mm = round(_finite(flight.home_alt_amsl) * 1000)
    boot = flight.started_at.timestamp()
    for s in track:
        t = s.t.timestamp()
        rel = _finite(s.alt_rel_m)
        heading = _finite(s.heading_deg) % 360
        speed = _finite(s.ground_speed_mps)
        ms = max(0, round((t - boot) * 1000)) & 0xFFFFFFFF
        vx = round(speed * math.cos(math.radians(heading)) * 100)
        vy = round(speed * math.sin(math.radians(heading)) * 100)
        mav_type = s.mav_type if s.mav_type is not None else mavlink2.MAV_TYPE_QUADROTOR
        emit(t, 0, mavlink2.MAVLink_heartbeat_message(
            mav_type, ap, armed, s.custom_mode or 0, mavlink2.MAV_STATE_ACTIVE, 3
        ))  # fmt: skip
        fix = s.gps_fix_type if s.gps_fix_type is not None else mavlink2.GPS_FIX_TYPE_3D_FIX
        emit(t, 1, mavlink2.MAVLink_gps_raw_int_message(
            round(t * 1e6), fix, round(s.lat * 1e7), round(s.lon * 1e7), home_mm + round(rel * 1000),
            65535, 65535, round(speed * 100), round(heading * 100) % 36000,
            s.satellites if s.satellites is not None else 255,
        ))  # fmt: skip
        emit(t, 1, mavlink2.MAVLink_global_position_int_message(
            ms, round(s.lat * 1e7), round(s.lon * 1e7), home_mm + round(rel * 1000), round(rel * 1000),
            vx, vy, 0, round(heading * 100) % 36000,
        ))  # fmt: skip
        emit(t, 2, mavlink2.MAVLink_vfr_hud_message(
            speed, speed, round(heading) % 360, 0, _finite(flight.home_alt_amsl) + rel, 0.0
        ))  # fmt: skip
        battery = -1 if s.battery_pct is None else max(0, min(100, round(s.battery_pct)))
        emit(t, 3, mavlink2.MAVLink_sys_status_message(0, 0, 0, 0, 0, -1, battery, 0, 0, 0, 0, 0, 0))
    for text in status_texts:
        severity = _SEVERITY.get(str(text.severity).upper(), mavlink2.MAV_SEVERITY_INFO)
        emit(text.t.timestamp(), 4, mavlink2.MAVLink_statustext_message(severity, text.text[:50].encode()))
    records.sort(key=lambda r: (r[0], r[1]))
    return b"".join(round(t * 1e6).to_bytes(8, "big") + packet for t, _order, packet in records)
