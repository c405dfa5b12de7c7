"""An operator's mission over REST on a simulated ArduCopter behind a real sidecar: a file with an item
the gateway cannot check is stored and started marked unchecked (answer, operation, audit row); the
start reads the held mission back and still holds the operator to the limits; malformed .plan files get
a 4xx naming the problem and an audit row, never a 500."""

from __future__ import annotations

import asyncio
from pathlib import Path

import httpx

from gateway.app import create_app
from tests.helpers import sim_process
from tests.helpers.timing import scaled

from .live import live_settings
from .server import serve_in_thread

MISSION = (Path(__file__).resolve().parents[1] / "data" / "missions" / "CANGPSCopterMission.txt").read_text()
AUX = "3\t0\t3\t218\t31.000000\t2.000000"  # item 3 as DO_AUX_FUNCTION 31 (motor emergency stop)


async def _ready(http: httpx.AsyncClient, drone: str) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + scaled(60)
    while (await http.get(f"/api/v1/vehicles/{drone}")).json().get("state") != "ready":
        assert loop.time() < deadline, "the simulated drone never became ready"
        await asyncio.sleep(0.2)


async def _put(http: httpx.AsyncClient, drone: str, content: str, **params: str) -> httpx.Response:
    for _ in range(3):  # under load the simulator's estimate can lapse for a moment after "ready"
        answer = await http.put(f"/api/v1/vehicles/{drone}/mission", content=content, params=params)
        if "vehicle_not_ready" not in answer.text:
            return answer
        await _ready(http, drone)
    return answer


async def test_an_operator_stores_and_starts_an_unchecked_mission_marked_so(tmp_path: Path) -> None:
    aux = MISSION.replace("3\t0\t3\t115\t640.000000\t20.000000", AUX)
    assert aux != MISSION
    async with sim_process(count=1, speedup=10) as sim:
        app = create_app(live_settings(tmp_path / "gateway.db"))
        with serve_in_thread(app) as base:
            async with httpx.AsyncClient(base_url=base, timeout=scaled(60)) as http:
                created = await http.post("/api/v1/vehicles", json={"id": "alpha", "url": sim.urls[0]})
                assert created.status_code == 201, created.text
                await _ready(http, "alpha")
                stored = await _put(http, "alpha", aux)
                assert stored.status_code == 200, stored.text
                assert (
                    "unchecked by the gateway: mission item 3: DO_AUX_FUNCTION (218)"
                    in stored.json()["message"]
                )

                started = await http.post("/api/v1/vehicles/alpha/mission/start")
                assert started.status_code == 200, started.text
                body = started.json()
                assert body["outcome"] == "sent" and body["operation_id"]
                assert "unchecked by the gateway: mission item 3: DO_AUX_FUNCTION" in body["message"]
                ops = (await http.get("/api/v1/operations", params={"vehicle_id": "alpha"})).json()["items"]
                op = next(o for o in ops if o["id"] == body["operation_id"])
                assert op["params"]["unchecked"] == [
                    "mission item 3: DO_AUX_FUNCTION (218) is a command whose effect the gateway cannot "
                    "check on ArduCopter"
                ]
                await http.post("/api/v1/vehicles/alpha/land")
                # the start's row names the mission's operation and ends as it did: the land superseded it
                loop = asyncio.get_running_loop()
                deadline = loop.time() + scaled(30)
                while True:
                    audit = (await http.get("/api/v1/audit", params={"vehicle_id": "alpha"})).json()["items"]
                    rows = {a["action"]: a for a in audit}
                    if rows["rest.start_mission"]["outcome"] != "running":
                        break
                    assert loop.time() < deadline, rows["rest.start_mission"]
                    await asyncio.sleep(0.2)
                assert rows["rest.put_mission_file"]["outcome"] == "ok"
                assert rows["rest.start_mission"]["outcome"] == "superseded"
                assert rows["rest.start_mission"]["operation_id"] == body["operation_id"]
                for action in ("rest.put_mission_file", "rest.start_mission"):
                    assert "DO_AUX_FUNCTION" in str(rows[action]["arguments"]["unchecked"])


def _wpl(home: tuple[float, float], rows: list[tuple[int, int, float, float, float, float, float]]) -> str:
    """A WPL file over the simulator's home: (frame, command, p1, p2, north m, east m, alt) rows."""
    from gateway.fleet import geo

    lines = [f"QGC WPL 110\n0\t1\t0\t16\t0\t0\t0\t0\t{home[0]}\t{home[1]}\t584\t1\n"]
    for seq, (frame, command, p1, p2, north, east, alt) in enumerate(rows, start=1):
        lat, lon = geo.offset_position(home[0], home[1], north, east) if (north, east) != (0, 0) else (0, 0)
        lines.append(f"{seq}\t0\t{frame}\t{command}\t{p1}\t{p2}\t0\t0\t{lat}\t{lon}\t{alt}\t1\n")
    return "".join(lines)


async def test_a_mission_whose_motors_stop_in_the_air_ends_failed(tmp_path: Path) -> None:
    """A motor emergency stop from inside the mission (the operator's unchecked DO_AUX_FUNCTION 31):
    the drone falls; the operation ends failed, never "succeeded: mission finished"."""
    async with sim_process(count=1, speedup=10) as sim:
        app = create_app(live_settings(tmp_path / "gateway.db"))
        with serve_in_thread(app) as base:
            async with httpx.AsyncClient(base_url=base, timeout=scaled(60)) as http:
                created = await http.post("/api/v1/vehicles", json={"id": "alpha", "url": sim.urls[0]})
                assert created.status_code == 201, created.text
                await _ready(http, "alpha")
                state = await sim.control.state(0)
                text = _wpl(
                    (state["lat"], state["lon"]),
                    # the stop is the last item: the mission "finishes" as the drone falls
                    [(3, 22, 0, 0, 0, 0, 20), (3, 16, 0, 0, 30, 0, 20), (2, 218, 31, 2, 0, 0, 0)],
                )  # fmt: skip
                stored = await _put(http, "alpha", text)
                assert stored.status_code == 200, stored.text
                started = await http.post("/api/v1/vehicles/alpha/mission/start")
                assert started.status_code == 200, started.text
                op_id = started.json()["operation_id"]
                loop = asyncio.get_running_loop()
                deadline = loop.time() + scaled(120)
                while True:
                    ops = (await http.get("/api/v1/operations", params={"vehicle_id": "alpha"})).json()[
                        "items"
                    ]
                    op = next(o for o in ops if o["id"] == op_id)
                    if op["status"] != "running":
                        break
                    assert loop.time() < deadline, op
                    await asyncio.sleep(0.3)
                assert op["status"] == "failed", op
                assert "falling" in op["message"] or "came down" in op["message"], op["message"]
                assert "item 3 of 3" in op["message"], op["message"]
                print(f"\nFIGURE motor stop in a mission, the operation's end: {op['message']}")
                fallen = await sim.control.state(0)
                assert fallen["landed"], fallen


async def test_malformed_input_gets_a_4xx_naming_the_problem_and_an_audit_row(tmp_path: Path) -> None:
    async with sim_process(count=1, speedup=10) as sim:
        app = create_app(live_settings(tmp_path / "gateway.db"))
        with serve_in_thread(app) as base:
            async with httpx.AsyncClient(base_url=base, timeout=scaled(60)) as http:
                created = await http.post("/api/v1/vehicles", json={"id": "alpha", "url": sim.urls[0]})
                assert created.status_code == 201, created.text
                await _ready(http, "alpha")
                boolean = (
                    '{"fileType": "Plan", "mission": {"items": [{"type": "SimpleItem", "command": true, '
                    '"frame": 3, "params": [0, 0, 0, 0, -35.36, 149.16, 20]}]}}'
                )
                answer = await _put(http, "alpha", boolean)
                assert answer.status_code == 422, answer.text
                assert (
                    "mission item 1: command must be an integer; got true"
                    in answer.json()["error"]["message"]
                )
                nested = await _put(http, "alpha", "[" * 100_000, format="plan")
                assert nested.status_code == 422, nested.text
                assert "nests its JSON too deeply" in nested.json()["error"]["message"]
                told = await _put(http, "alpha", "[" * 100_000)  # not JSON-looking: read as a WPL file
                assert told.status_code == 422 and "begins with 'QGC WPL 110'" in told.text
                for loose in ("10", True):  # numbers are JSON numbers at this door too
                    took = await http.post("/api/v1/vehicles/alpha/takeoff", json={"alt_rel_m": loose})
                    assert took.status_code == 422 and "alt_rel_m" in took.text, took.text
                assert not (await sim.control.state(0))["armed"]
                audit = (await http.get("/api/v1/audit", params={"vehicle_id": "alpha"})).json()["items"]
                puts = [a for a in audit if a["action"] == "rest.put_mission_file"]
                assert len(puts) == 3 and all(a["outcome"] == "error" for a in puts), puts
