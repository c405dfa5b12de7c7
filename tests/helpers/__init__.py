"""Shared integration-test helpers: a simulator subprocess and mavsdk_server sidecars.

    async with sim_process(count=2, speedup=10) as sim:
        sim.urls          # ["tcpout://127.0.0.1:PORT", ...], one per vehicle
        sim.sysids        # [1, 2]
        sim.control       # gateway.sim.control.SimControl (fault injection, true state)
        async with mavsdk_system(sim.urls[0]) as drone:   # a connected mavsdk_grpc.System
            ...

Both always clean up their processes (terminate, then kill), also when the body raises.
"""

from tests.helpers.mavsdk import MavsdkServer, mavsdk_server_binary, mavsdk_system, start_mavsdk_server
from tests.helpers.sim import SimProcess, sim_process

__all__ = [
    "MavsdkServer",
    "SimProcess",
    "mavsdk_server_binary",
    "mavsdk_system",
    "sim_process",
    "start_mavsdk_server",
]
