"""GET /flights/{id}/tlog serves the flight's raw MAVLink log when this node wrote one (the frames as
received, each after its receive time), cut at ``flight_tlog_max_mib``, and falls back to the
reconstruction from the 1 Hz track otherwise; the response says which (X-Tlog-Source, X-Tlog-Cut)."""

from __future__ import annotations

import itertools
import time
from collections.abc import AsyncIterator
from datetime import UTC, datetime
from pathlib import Path

import httpx
import pytest
from fastapi import FastAPI
from pymavlink import mavutil
from pymavlink.dialects.v20 import ardupilotmega as mavlink

from gateway.app import create_app
from gateway.config import Settings
from gateway.fleet.missions.raw_tlog import PREROLL_BYTES, PREROLL_S, RawTlog, tlog_folder
from gateway.registry.store import Store
from tests.fakes import FakeRegistry

from .live import lifespan_running

T0 = datetime(2026, 5, 1, 12, 0, tzinfo=UTC)


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return Settings(database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}", flight_tlog_max_mib=1)


@pytest.fixture
async def client(settings: Settings) -> AsyncIterator[tuple[httpx.AsyncClient, FastAPI]]:
    async with lifespan_running(create_app(settings, registry_factory=FakeRegistry)) as app:
        transport = httpx.ASGITransport(app=app)
        async with httpx.AsyncClient(transport=transport, base_url="http://127.0.0.1:8765") as http:
            yield http, app


def store_of(app: FastAPI) -> Store:
    store: Store = app.state.gateway.store
    return store


def _frames(count: int, sysid: int = 42) -> list[bytes]:
    mav = mavlink.MAVLink(None, srcSystem=sysid, srcComponent=1)
    mix = [
        mavlink.MAVLink_heartbeat_message(2, 3, 209, 4, 4, 3),  # armed, GUIDED
        mavlink.MAVLink_attitude_message(1, 0.1, 0.2, 0.3, 0.0, 0.0, 0.0),
        mavlink.MAVLink_statustext_message(6, b"Arming motors"),
    ]
    return [bytes(mix[i % len(mix)].pack(mav)) for i in range(count)]


def _read(path: Path) -> list[tuple[str, int, float]]:
    log = mavutil.mavlink_connection(str(path), dialect="ardupilotmega")
    out = []
    while (msg := log.recv_match()) is not None:
        out.append((msg.get_type(), msg.get_srcSystem(), msg._timestamp))
    return out


async def test_the_raw_log_is_served_as_written(
    client: tuple[httpx.AsyncClient, FastAPI], settings: Settings, tmp_path: Path
) -> None:
    http, app = client
    store = store_of(app)
    flight_id = await store.open_flight("alpha", T0)
    folder = tlog_folder(settings, store.url)
    assert folder == Path(f"{tmp_path / 'gateway.db'}-tlogs")
    raw = RawTlog(folder, "alpha", settings.flight_tlog_max_mib * 1024 * 1024)
    before = _frames(3)
    for data in before:  # heard before the flight opened: its pre-roll
        raw.received(data)
    raw.open(flight_id)
    during = _frames(300)
    stream = b"".join(during[:150]) + b"\x00noise" + b"".join(during[150:])
    # as the relay reads them: frames cut across two reads, several in one, noise between
    cuts = [0, 5, 30, 31, 400, 401, 2000, len(stream)]
    for a, b in itertools.pairwise(cuts):
        raw.received(stream[a:b])
    raw.flush()  # a flight in progress: what is written so far

    got = await http.get(f"/api/v1/flights/{flight_id}/tlog")
    assert got.status_code == 200
    assert got.headers["x-tlog-source"] == "autopilot" and got.headers["x-tlog-cut"] == "false"
    assert 'filename="alpha-flight-' in got.headers["content-disposition"]
    raw.close()
    path = tmp_path / "got.tlog"
    path.write_bytes(got.content)
    # each record: 8-byte big-endian receive time in microseconds, then the frame byte for byte
    assert got.content[8 : 8 + len(before[0])] == before[0]
    messages = _read(path)
    assert [m[0] for m in messages] == ["HEARTBEAT", "ATTITUDE", "STATUSTEXT"] * 101
    assert {m[1] for m in messages} == {42}
    times = [m[2] for m in messages]
    assert times == sorted(times) and abs(times[-1] - datetime.now(UTC).timestamp()) < 60


async def test_the_raw_log_stops_at_its_cap_and_says_so(
    client: tuple[httpx.AsyncClient, FastAPI], settings: Settings
) -> None:
    http, app = client
    flight_id = await store_of(app).open_flight("alpha", T0)
    folder = tlog_folder(settings, store_of(app).url)
    assert folder is not None
    raw = RawTlog(folder, "alpha", settings.flight_tlog_max_mib * 1024 * 1024)
    raw.open(flight_id)
    frames = _frames(60_000)  # about 2.2 MiB with their time stamps
    for data in frames:
        raw.received(data)
    raw.close()
    got = await http.get(f"/api/v1/flights/{flight_id}/tlog")
    assert got.headers["x-tlog-source"] == "autopilot" and got.headers["x-tlog-cut"] == "true"
    assert 1024 * 1024 - 300 < len(got.content) <= 1024 * 1024


def test_the_pre_roll_is_bounded_in_bytes_and_in_time(monkeypatch: pytest.MonkeyPatch) -> None:
    raw = RawTlog(Path("unused"), "alpha", 1 << 20)
    frames = _frames(3 * PREROLL_BYTES // 30)
    for data in frames:
        raw.received(data)
    kept = sum(len(data) for _, data in raw._preroll)
    assert PREROLL_BYTES - 300 < kept <= PREROLL_BYTES
    assert raw._preroll[-1][1] == frames[-1]
    later = time.time() + PREROLL_S + 1
    monkeypatch.setattr(time, "time", lambda: later)
    raw.received(frames[0])  # read after the others have grown too old to be written
    assert [data for _, data in raw._preroll] == [frames[0]]


async def test_a_flight_without_a_raw_log_is_reconstructed(client: tuple[httpx.AsyncClient, FastAPI]) -> None:
    http, app = client
    flight_id = await store_of(app).open_flight("alpha", T0)
    got = await http.get(f"/api/v1/flights/{flight_id}/tlog")
    assert got.status_code == 200
    assert got.headers["x-tlog-source"] == "reconstructed" and got.headers["x-tlog-cut"] == "false"


def test_none_records_no_raw_log(tmp_path: Path) -> None:
    off = Settings(flight_tlog_dir="none")
    assert not off.records_flight_frames
    assert tlog_folder(off, f"sqlite+aiosqlite:///{tmp_path / 'g.db'}") is None
    given = Settings(flight_tlog_dir=str(tmp_path / "logs"))
    assert tlog_folder(given, "postgresql+asyncpg://u@h/db") == tmp_path / "logs"
    assert tlog_folder(Settings(), "postgresql+asyncpg://u@h/db") == Path("fleet-gateway-tlogs")
