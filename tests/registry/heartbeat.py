"""A bare MAVLink heartbeat sender: enough for mavsdk_server to discover a "vehicle".

Used by the sidecar supervisor tests, which need no flight behaviour, only discovery.
"""

from __future__ import annotations

import asyncio
import socket

from pymavlink.dialects.v20 import ardupilotmega as mavlink


class HeartbeatVehicle:
    """Sends HEARTBEAT (ArduCopter GUIDED, disarmed) at ``rate_hz`` to a mavsdk_server udpin port."""

    def __init__(self, target_port: int, sysid: int = 1, rate_hz: float = 4.0) -> None:
        self.target = ("127.0.0.1", target_port)
        self.sysid = sysid
        self.rate_hz = rate_hz
        self._sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self._sock.bind(("127.0.0.1", 0))
        self._sock.setblocking(False)
        self._mav = mavlink.MAVLink(None, srcSystem=sysid, srcComponent=1)
        self._task: asyncio.Task[None] | None = None

    async def __aenter__(self) -> HeartbeatVehicle:
        self._task = asyncio.create_task(self._run())
        return self

    async def __aexit__(self, *exc: object) -> None:
        if self._task is not None:
            self._task.cancel()
            try:
                await self._task
            except asyncio.CancelledError:
                pass
        self._sock.close()

    async def _run(self) -> None:
        while True:
            msg = self._mav.heartbeat_encode(
                mavlink.MAV_TYPE_QUADROTOR, mavlink.MAV_AUTOPILOT_ARDUPILOTMEGA, 89, 4, 3
            )
            try:
                self._sock.sendto(msg.pack(self._mav), self.target)
            except OSError:
                pass
            await asyncio.sleep(1.0 / self.rate_hz)
