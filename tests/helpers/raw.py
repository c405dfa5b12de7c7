"""``raw_mavlink``: a minimal asyncio MAVLink 2 ground station over TCP, for protocol-level tests."""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import AsyncIterator, Callable

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.mavlink import Codec
from tests.helpers.timing import scaled


class RawMavlink:
    """Sends as system 245 / component 190 (like mavsdk_server); keeps every received message."""

    def __init__(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter, sysid: int = 245) -> None:
        self._reader, self._writer = reader, writer
        self.codec = Codec(sysid, 190)
        self.received: list[tuple[float, mav.MAVLink_message]] = []
        self._new = asyncio.Condition()
        self._task = asyncio.create_task(self._read())
        self.target_system = 1
        self.last_mark = 0

    async def _read(self) -> None:
        with contextlib.suppress(ConnectionError, asyncio.CancelledError):
            while True:
                data = await self._reader.read(65536)
                if not data:
                    return
                msgs = self.codec.decode(data)
                if msgs:
                    now = time.monotonic()
                    async with self._new:
                        self.received.extend((now, m) for m in msgs)
                        self._new.notify_all()

    def send(self, msg: mav.MAVLink_message) -> None:
        self._writer.write(self.codec.encode(msg))

    async def close(self) -> None:
        self._task.cancel()
        with contextlib.suppress(asyncio.CancelledError, Exception):
            await self._task
        self._writer.close()

    def mark(self) -> int:
        """A position in the received log, to wait for messages from there on (see ``wait(since=)``)."""
        return len(self.received)

    async def wait(
        self,
        kind: str,
        predicate: Callable[[mav.MAVLink_message], bool] = lambda _m: True,
        timeout_s: float = 10,
        since: int | None = None,
    ) -> mav.MAVLink_message:
        """Next message of type ``kind`` satisfying predicate, received after this call (or after ``since``,
        a ``mark()``; ``last_mark`` is the mark taken just before the last ``command()`` was sent)."""
        start = len(self.received) if since is None else since

        async def scan() -> mav.MAVLink_message:
            index = start
            while True:
                async with self._new:
                    while index >= len(self.received):
                        await self._new.wait()
                    batch = self.received[index:]
                index += len(batch)
                for _t, msg in batch:
                    if msg.get_type() == kind and predicate(msg):
                        return msg

        return await asyncio.wait_for(scan(), scaled(timeout_s))

    async def command(self, command: int, *params: float, timeout_s: float = 10) -> mav.MAVLink_message:
        """COMMAND_LONG with up to 7 params; returns its COMMAND_ACK."""
        p = [*params, *([0.0] * (7 - len(params)))]
        self.last_mark = self.mark()
        waiter = asyncio.create_task(
            self.wait("COMMAND_ACK", lambda m: m.command == command, timeout_s, since=self.last_mark)
        )
        self.send(mav.MAVLink_command_long_message(self.target_system, 1, command, 0, *p))
        return await waiter

    def since(self, t0: float) -> list[mav.MAVLink_message]:
        return [m for t, m in self.received if t >= t0]


@contextlib.asynccontextmanager
async def raw_mavlink(url: str, sysid: int = 245) -> AsyncIterator[RawMavlink]:
    """Connect to a ``tcpout://host:port`` URL as a bare MAVLink 2 GCS."""
    if not url.startswith("tcpout://"):
        raise ValueError(f"raw_mavlink needs a tcpout:// URL, got {url!r}")
    host, port = url[len("tcpout://") :].rsplit(":", 1)
    reader, writer = await asyncio.open_connection(host, int(port))
    client = RawMavlink(reader, writer, sysid)
    try:
        yield client
    finally:
        await client.close()
