"""The gateway process killed (SIGKILL) while a drone flies its goto, then restarted on the same database:
the truth about the flying drone, and a pilot's later switch is still a takeover.

Expected: ``monitor_flight`` and ``check_arrival`` on the restarted gateway say the gateway restarted
while the goto was running, the mode the drone is in and how far it is from the goto's target (never
"nothing was started"); the mode watch is armed again for the drone, so a second ground station's switch
to LOITER (the simulator's control API, as a pilot's) locks it for agents as before the restart.
"""

from __future__ import annotations

import signal
from pathlib import Path
from typing import Any

import httpx

from gateway.fleet import geo
from tests.fault.test_gateway_sigkill import _get_ok, _is, gateway_process, mcp_client, until
from tests.helpers import sim_process
from tests.helpers.timing import scaled


async def test_a_drone_flying_through_a_gateway_restart_is_reported_and_watched(tmp_path: Path) -> None:
    db, log = tmp_path / "gateway.db", tmp_path / "gateway.log"
    async with sim_process(count=1, speedup=4.0) as sim:
        url = sim.urls[0]
        with gateway_process(db, log) as (proc, base):
            await until("gateway up", lambda: _get_ok(base, "/healthz"), log)
            async with httpx.AsyncClient(base_url=base, timeout=scaled(10)) as http:
                r = await http.post("/api/v1/vehicles", json={"id": "d1", "url": url, "expected_sysid": 1})
                assert r.status_code == 201, r.text
            await until("d1 ready", lambda: _is(base, "ready"), log)
            home = await sim.control.state(0)
            far = geo.offset_position(home["lat"], home["lon"], 600, 0)
            async with mcp_client(base) as c:

                async def took_off() -> Any:  # pre-arm checks pass once the simulated EKF has settled
                    r = await c.call_tool("takeoff", {"drone_id": "d1", "alt_m": 10})
                    return not r.is_error and r.structured_content["status"] == "succeeded"

                await until("takeoff", took_off, log)
                r = await c.call_tool(
                    "go_to_location",
                    {"drone_id": "d1", "lat_deg": far[0], "lon_deg": far[1], "alt_m": 10, "wait": False},
                )
                assert not r.is_error, r.content
            proc.send_signal(signal.SIGKILL)
            proc.wait(timeout=scaled(10))

        with gateway_process(db, log) as (proc, base):
            await until("d1 restored and ready", lambda: _is(base, "ready"), log)
            async with mcp_client(base) as c:

                async def heading() -> Any:  # once the autopilot's target (asked for at 2 Hz) is heard
                    r = await c.call_tool("monitor_flight", {"drone_id": "d1"})
                    assert not r.is_error, r.content
                    view = r.structured_content
                    return view if "the autopilot's target" in view["message"] else None

                view = await until("monitor_flight naming the autopilot's target", heading, log)
                assert view["kind"] == "goto" and view["status"] == "interrupted", view
                said = view["message"]
                print(f"\nmonitor_flight after the restart: {said}")
                assert "the gateway restarted while this operation was running" in said, said
                assert "now: mode GUIDED, in the air" in said and "m from the goto's target" in said, said
                # POSITION_TARGET_GLOBAL_INT: "heading for the autopilot's target N m away (lat, lon)", or
                # "holding at" it when the drone arrived while the gateway was down
                assert "the autopilot's target" in said, said
                r = await c.call_tool("check_arrival", {"drone_id": "d1"})
                arrival = r.structured_content
                assert arrival["arrived"] is False and "the gateway restarted" in arrival["message"], arrival

                async def watched() -> bool:  # the restarted gateway looks at the drone once it hears it
                    return "d1: found flying in GUIDED after the restart" in log.read_text()

                await until("the mode watch armed again", watched, log)
                await sim.control.pilot_mode(0, "LOITER")

                async def taken_over() -> Any:
                    async with httpx.AsyncClient(base_url=base, timeout=scaled(5)) as http:
                        return (await http.get("/api/v1/vehicles/d1")).json().get("taken_over")

                taken = await until("the takeover after the restart", taken_over, log)
                assert "LOITER" in taken["reason"] and "left GUIDED" in taken["reason"], taken
                r = await c.call_tool("move_to_relative", {"drone_id": "d1", "north_m": 10, "east_m": 0})
                assert r.is_error and "taken_over" in r.content[0].text, r.content
                assert (await sim.control.state(0))["mode"] == "LOITER"
