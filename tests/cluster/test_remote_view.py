"""A drone another node owns, as this node shows it: the console's fleet view, the dialect's answers
(modes, landed state, protected parameters) from the autopilot its owner reports, and the operation its
owner runs."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pytest

from gateway.api.fleetview import vehicle_view
from gateway.cluster.forwarding import ClusterRouter
from gateway.cluster.remote import OwnedElsewhere, RemoteVehicle
from gateway.config import Settings
from gateway.errors import InvalidArgument
from gateway.fleet.commands.commander import Commander
from gateway.fleet.policy.operator_locks import LockBook
from gateway.fleet.vehicles.protocols import flying
from gateway.registry.spec import VehicleSpec
from tests.fakes import fake_gateway, unit_settings


def remote(autopilot: str | None) -> RemoteVehicle:
    view = RemoteVehicle(VehicleSpec(id="d1", url="tcpout://127.0.0.1:5760"), Settings())
    view.set_owner("node-c", 1)
    view.apply({"node": "node-c", "epoch": 1, "seq": 1, "status": {"state": "ready", "autopilot": autopilot}})
    return view


def test_the_console_shows_a_drone_owned_elsewhere() -> None:
    row = vehicle_view(remote("ardupilot"), lambda vehicle_id: None, LockBook())
    assert row["id"] == "d1" and row["state"] == "ready" and row["flight_id"] is None, row


async def test_a_remote_drone_answers_with_its_owners_autopilot_dialect() -> None:
    px4, ardupilot = remote("px4"), remote("ardupilot")
    assert px4.resolve_mode("MISSION").native == "AUTO.MISSION"
    assert ardupilot.resolve_mode("MISSION").native == "AUTO"
    with pytest.raises(InvalidArgument, match=r"not a mode of drone 'd1' \(PX4\)"):
        px4.resolve_mode("SMART_RTL")
    assert "COM_*" in px4.protected_params and "ARMING_*" in ardupilot.protected_params
    assert set(remote(None).protected_params) >= {"COM_*", "ARMING_*"}  # autopilot not known yet: all
    assert px4.return_altitude_param() == ("RTL_RETURN_ALT", 1.0)
    px4.telemetry.put("in_air", False)
    px4.telemetry.put("landed_state", "LANDING")
    assert px4.on_ground(fresh=False) is False  # PX4's land detector decides, not in_air
    assert px4.flown_here() is None  # a view: the commands go to its owner
    with pytest.raises(OwnedElsewhere, match=r"owned by cluster node node-c"):
        flying(px4)


async def test_a_drone_owned_elsewhere_reports_the_operation_its_owner_published(tmp_path: Path) -> None:
    """What list_drones, fleet_status, get_telemetry and the console read: the Commander's
    current_operation, here the owner's as it came with its last snapshot."""
    view = remote("ardupilot")
    goto = {"id": "op-7", "kind": "goto", "status": "running", "progress": 0.4, "message": "20 m to go",
            "target_alt_m": 12.0, "eta_s": 3.5, "elapsed_s": 6.0,
            "params": {"lat_deg": 47.4, "lon_deg": 8.5, "alt_m": 12.0}}  # fmt: skip
    view.apply({"node": "node-c", "epoch": 1, "seq": 2, "status": {"state": "ready"}, "operation": goto})
    node = SimpleNamespace(registry=SimpleNamespace(find=lambda vid: view, is_local=lambda vid: False))
    router = ClusterRouter(node)  # type: ignore[arg-type]
    async with fake_gateway(unit_settings(tmp_path), []) as gw:
        base = gw.commander
        commander = Commander(gw.settings, base.registry, gw.store, base.operations, base.fleet,
                              base.safety, base.locks, router=router)  # fmt: skip
        current = commander.current_operation("d1")
    assert current is not None
    assert {k: v for k, v in current.items() if k != "elapsed_s"} == {
        "operation_id": "op-7", "drone_id": "d1", "kind": "goto", "status": "running", "progress": 0.4,
        "message": "20 m to go", "eta_s": 3.5, "params": goto["params"],
    }  # fmt: skip
    assert current["elapsed_s"] >= 6.0  # aged by the snapshot's age
    running = router.running("d1")
    assert running is not None and running.operation_id == "op-7" and running.target_alt_m == 12.0
    # the owner's next snapshot says it ended: no current action any more, the finished one still told
    view.apply({"node": "node-c", "epoch": 1, "seq": 3, "status": {"state": "ready"},
                "operation": {**goto, "status": "succeeded", "progress": 1.0}})  # fmt: skip
    assert router.running("d1") is None
    assert (router.published("d1") or {}).get("status") == "succeeded"
    row = vehicle_view(view, commander.current_operation, LockBook())
    assert row["operation"]["operation_id"] == "op-7" and row["operation"]["status"] == "succeeded", row
