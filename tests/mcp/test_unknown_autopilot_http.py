"""A drone whose HEARTBEAT names an autopilot the gateway has no dialect for (MAV_AUTOPILOT_GENERIC) is
shown but never flown as another autopilot: list_drones, its telemetry and REST read it, and a takeoff is
refused in one line that names the autopilot and what to do, with nothing sent to the drone. The
simulator announces the autopilot (``sim --autopilot 0``); the gateway is served by uvicorn with a real
mavsdk_server sidecar, and an MCP client calls it over Streamable HTTP."""

from __future__ import annotations

from pathlib import Path

from tests.helpers.timing import eventually
from tests.mcp.conftest import error_text, gateway_stack, structured

NO_DIALECT = (
    "drone 'd1' runs autopilot MAV_AUTOPILOT_GENERIC (0), which this gateway has no dialect for, so it "
    "sends it no command (its telemetry and status are still shown): fly it from its own ground station, "
    "or connect a drone running ArduPilot or PX4"
)


async def test_an_autopilot_without_a_dialect_is_read_and_refused_actuation(tmp_path: Path) -> None:
    async with gateway_stack(tmp_path, count=1, sim_args=("--autopilot", "0")) as stack:
        async with stack.client() as client:
            listed = structured(await stack.call(client, "list_drones", {}))["drones"]
            assert [(d["drone_id"], d["state"]) for d in listed] == [("d1", "ready")], listed
            vehicle = await stack.rest("/vehicles/d1")
            assert vehicle["status"]["autopilot"] == "mav_autopilot_0", vehicle
            position = structured(await stack.call(client, "get_position", {"drone_id": "d1"}))
            truth = await stack.true_state("d1")
            assert abs(position["lat_deg"] - truth["lat"]) < 1e-4, (position, truth)

            before = await stack.true_state("d1")
            refused = await stack.call(client, "takeoff", {"drone_id": "d1", "alt_m": 10})
            assert NO_DIALECT in error_text(refused), error_text(refused)
            armed = await stack.call(client, "arm_drone", {"drone_id": "d1"})
            assert NO_DIALECT in error_text(armed), error_text(armed)

            async def audited() -> list[dict[str, object]]:
                rows = (await stack.rest("/audit", vehicle_id="d1", limit=100))["items"]
                acted = [r for r in rows if r["action"] in ("takeoff", "arm_drone")]
                return acted if len(acted) == 2 else []

            rows = await eventually(audited, "the two refusals in the audit log", within_s=15)
            assert all(r["outcome"] != "ok" for r in rows), rows
            after = await stack.true_state("d1")
            # nothing reached the drone: still disarmed on the ground, in the mode it was in
            assert (after["armed"], after["landed"], after["mode"]) == (False, True, before["mode"]), after
            assert after["rel_alt_m"] < 0.5, after
