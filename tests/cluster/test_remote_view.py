"""A drone another node owns, as this node shows it: the console's fleet view and the dialect's answers
(modes, landed state, protected parameters) from the autopilot its owner reports."""

from __future__ import annotations

import pytest

from gateway.api.fleetview import vehicle_view
from gateway.cluster.remote import OwnedElsewhere, RemoteVehicle
from gateway.config import Settings
from gateway.errors import InvalidArgument
from gateway.fleet.safety import LockBook
from gateway.registry.spec import VehicleSpec


class NoOperations:
    def latest(self, vehicle_id: str) -> None:
        return None


def remote(autopilot: str | None) -> RemoteVehicle:
    view = RemoteVehicle(VehicleSpec(id="d1", url="tcpout://127.0.0.1:5760"), Settings())
    view.set_owner("node-c", 1)
    view.apply({"node": "node-c", "epoch": 1, "seq": 1, "status": {"state": "ready", "autopilot": autopilot}})
    return view


def test_the_console_shows_a_drone_owned_elsewhere() -> None:
    row = vehicle_view(remote("ardupilot"), NoOperations(), LockBook())
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
    with pytest.raises(OwnedElsewhere, match=r"owned by cluster node node-c"):
        await px4.set_return_altitude(30.0)
