"""The gateway process killed with SIGKILL mid-flight, then restarted on the same database.

Expected: its sidecars die with it (no orphan holding the drone's link), the drone flies its last command
on its own, the restarted gateway restores the vehicle, closes the flight the dead process left open at its
last committed track sample (none of those samples lost) and records the rest of the flight as a new
one; the SQLite file passes ``PRAGMA integrity_check``.
"""

from __future__ import annotations

import contextlib
import signal
import sqlite3
from pathlib import Path
from typing import Any

from tests.fault.gateway_proc import fly_d1_toward, gateway_process, get_ok, is_state, mcp_client, until
from tests.helpers import sim_process
from tests.helpers.timing import scaled


def query(db: Path, sql: str, *args: Any) -> list[tuple]:
    with contextlib.closing(sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=scaled(10))) as conn:
        return conn.execute(sql, args).fetchall()


def sidecars_for(url: str) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                cmd = (entry / "cmdline").read_bytes().split(b"\0")
            except OSError:
                continue
            if cmd and b"mavsdk_server" in cmd[0] and url.encode() in cmd:
                found.append(int(entry.name))
    return found


async def test_gateway_sigkill_mid_flight_then_restart(tmp_path: Path) -> None:
    db, log = tmp_path / "gateway.db", tmp_path / "gateway.log"
    async with sim_process(count=1, speedup=8.0) as sim:
        url = sim.urls[0]
        with gateway_process(db, log) as (proc, base):
            await until("gateway up", lambda: get_ok(base, "/healthz"), log)
            await fly_d1_toward(base, url, await sim.control.state(0), 60, log)

            async def some_samples() -> bool:
                rows = query(db, "SELECT count(*) FROM track_samples")
                return rows[0][0] >= 3

            await until("track samples committed", some_samples, log)
            committed = query(db, "SELECT flight_id, t, lat, lon FROM track_samples ORDER BY id")
            (flight_id,) = {row[0] for row in committed}
            proc.send_signal(signal.SIGKILL)
            proc.wait(timeout=scaled(10))

            async def no_sidecar() -> bool:
                return not sidecars_for(url)

            await until("the dead gateway's sidecar gone", no_sidecar, log)
        # the drone keeps flying its last command on its own
        s = await sim.control.state(0)
        assert s["armed"] and s["mode"] == "GUIDED", s

        with gateway_process(db, log) as (proc, base):
            await until("d1 restored and ready", lambda: is_state(base, "ready"), log)
            flights = {
                row[0]: row
                for row in query(db, "SELECT id, ended_at, duration_s FROM flights WHERE vehicle_id = 'd1'")
            }
            assert flights[flight_id][1] is not None, f"flight {flight_id} left open: {flights}"
            sql = "SELECT flight_id, t, lat, lon FROM track_samples WHERE flight_id = ?"
            kept = query(db, sql, flight_id)
            assert set(committed) <= set(kept), "a committed track sample was lost"

            async def resumed() -> list[tuple]:
                return query(db, "SELECT id FROM flights WHERE vehicle_id = 'd1' AND ended_at IS NULL")

            (new_flight,) = (await until("the rest of the flight recorded", resumed, log))[0]
            assert new_flight != flight_id
            async with mcp_client(base) as c:
                r = await c.call_tool("land", {"drone_id": "d1"})
                assert not r.is_error and r.structured_content["status"] == "succeeded", r.content

            async def closed() -> bool:
                rows = query(db, "SELECT ended_at FROM flights WHERE id = ?", new_flight)
                return rows[0][0] is not None

            await until("the resumed flight closed after landing", closed, log)
        assert query(db, "PRAGMA integrity_check") == [("ok",)]
        assert not sidecars_for(url)
