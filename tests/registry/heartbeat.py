"""A bare MAVLink heartbeat sender: enough for mavsdk_server to discover a "vehicle".

Used by the sidecar supervisor tests, which need no flight behaviour, only discovery.
"""

from __future__ import annotations

import asyncio
import socket

from pymavlink.dialects.v20 import ardupilotmega as mavlink


class HeartbeatVehicle:
    """Sends HEARTBEAT (ArduCopter, disarmed) at ``rate_hz`` to a mavsdk_server udpin port.

    It also answers COMMAND_LONG as ArduCopter does for the few commands the gateway sends raw:
    DO_SET_MODE (changes the mode in the next HEARTBEAT), SET_MESSAGE_INTERVAL (ACCEPTED),
    REQUEST_MESSAGE (FAILED: not a simulator); everything received is kept in ``received``.
    """

    def __init__(self, target_port: int | None, sysid: int = 1, rate_hz: float = 4.0) -> None:
        """``target_port`` None: a vehicle that speaks only after a ground station spoke to it (what a
        ``udpout://`` link needs); it listens on ``self.port`` and answers whoever sent last."""
        self.target = ("127.0.0.1", target_port) if target_port is not None else None
        self.listening = target_port is None
        self.sysid = sysid
        self.rate_hz = rate_hz
        self._sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self._sock.bind(("127.0.0.1", 0))
        self._sock.setblocking(False)
        self.port = int(self._sock.getsockname()[1])
        self._mav = mavlink.MAVLink(None, srcSystem=sysid, srcComponent=1)
        self._task: asyncio.Task[None] | None = None
        self._rx: asyncio.Task[None] | None = None
        self.custom_mode = 4
        self.received: list[object] = []
        self._peer: tuple[str, int] | None = None

    async def __aenter__(self) -> HeartbeatVehicle:
        self._task = asyncio.create_task(self._run())
        self._rx = asyncio.create_task(self._receive())
        return self

    async def __aexit__(self, *exc: object) -> None:
        for task in (self._task, self._rx):
            if task is not None:
                task.cancel()
                try:
                    await task
                except asyncio.CancelledError:
                    pass
        self._sock.close()

    async def _receive(self) -> None:
        loop = asyncio.get_running_loop()
        parser = mavlink.MAVLink(None)
        while True:
            data, peer = await loop.sock_recvfrom(self._sock, 4096)
            self._peer = peer
            if self.listening:
                self.target = peer
            for msg in parser.parse_buffer(data) or []:
                self.received.append(msg)
                if msg.get_type() == "COMMAND_LONG":
                    self._answer(msg)

    def _answer(self, msg: object) -> None:
        command = int(msg.command)  # type: ignore[attr-defined]
        result = mavlink.MAV_RESULT_UNSUPPORTED
        if command == mavlink.MAV_CMD_DO_SET_MODE:
            self.custom_mode = int(msg.param2)  # type: ignore[attr-defined]
            result = mavlink.MAV_RESULT_ACCEPTED
        elif command == mavlink.MAV_CMD_SET_MESSAGE_INTERVAL:
            result = mavlink.MAV_RESULT_ACCEPTED
        elif command == mavlink.MAV_CMD_REQUEST_MESSAGE:
            result = mavlink.MAV_RESULT_FAILED
        if self.target is None:
            return
        ack = self._mav.command_ack_encode(command, result, 0, 0, msg.get_srcSystem(), msg.get_srcComponent())  # type: ignore[attr-defined]
        self._sock.sendto(ack.pack(self._mav), self.target)

    async def _run(self) -> None:
        while True:
            msg = self._mav.heartbeat_encode(
                mavlink.MAV_TYPE_QUADROTOR, mavlink.MAV_AUTOPILOT_ARDUPILOTMEGA, 89, self.custom_mode, 3
            )
            if self.target is not None:
                try:
                    self._sock.sendto(msg.pack(self._mav), self.target)
                except OSError:
                    pass
            await asyncio.sleep(1.0 / self.rate_hz)
