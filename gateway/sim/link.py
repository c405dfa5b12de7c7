"""MAVLink transports of one simulated vehicle: a TCP server port (one client at a time, like SITL's
SERIALn TCP ports) and an optional UDP output. Each link has its own codec and stream rates."""

from __future__ import annotations

import asyncio
import contextlib
import logging
import socket
from abc import ABC, abstractmethod
from collections import deque
from collections.abc import Callable

from gateway.sim.mavlink import Codec, MAVLinkMessage
from gateway.sim.streams import StreamTable

log = logging.getLogger(__name__)

Receiver = Callable[["Link", MAVLinkMessage], None]
RATE_REQUESTS_KEPT = 32


class Link(ABC):
    """Base: encoding, stream table, and the vehicle's fault switches (link down, packet loss)."""

    name = "link"

    def __init__(self, sysid: int, receiver: Receiver, faults: LinkFaults) -> None:
        self.codec = Codec(sysid)
        self.streams = StreamTable()
        self._receiver = receiver
        self._faults = faults
        self.bytes_out = 0
        self.bytes_in = 0
        #: the last rate requests (MAV_CMD_SET_MESSAGE_INTERVAL) on this link: (message id, interval in us)
        self.rate_requests: deque[tuple[int, float]] = deque(maxlen=RATE_REQUESTS_KEPT)

    @property
    @abstractmethod
    def connected(self) -> bool:
        """Whether a ground station is attached to this link."""

    def describe(self) -> dict:
        """What the control API shows of this link: the messages it streams (id: interval in seconds)
        and the bytes it carried, to tell a vehicle that was never asked from one that was not heard."""
        streamed = {str(m): self.streams.interval(m) for m in sorted(self.streams.streamed())}
        return {
            "name": self.name,
            "connected": self.connected,
            "bytes_in": self.bytes_in,
            "bytes_out": self.bytes_out,
            "streams": streamed,
            "rate_requests": [list(r) for r in self.rate_requests],
        }

    @abstractmethod
    def _write(self, data: bytes) -> None:
        """Put encoded bytes on the wire."""

    def send(self, msg: MAVLinkMessage) -> None:
        if not self.connected or not self._faults.passes():
            return
        data = self.codec.encode(msg)
        self.bytes_out += len(data)
        self._write(data)

    def _received(self, data: bytes) -> None:
        self.bytes_in += len(data)
        for msg in self.codec.decode(data):
            if self._faults.passes():
                self._receiver(self, msg)

    @abstractmethod
    async def start(self) -> None:
        """Open the link (listen or connect)."""

    @abstractmethod
    async def stop(self) -> None:
        """Close the link."""


class LinkFaults:
    """Injected link faults shared by all links of a vehicle."""

    def __init__(self, rng) -> None:
        self.up = True
        self.loss_pct = 0.0
        self._rng = rng

    def passes(self) -> bool:
        if not self.up:
            return False
        return self.loss_pct <= 0 or self._rng.random() * 100.0 >= self.loss_pct


class TcpServerLink(Link):
    """Listens on bind:port; serves one client at a time, further clients wait in the backlog."""

    def __init__(self, sysid: int, receiver: Receiver, faults: LinkFaults, bind: str, port: int) -> None:
        super().__init__(sysid, receiver, faults)
        self.bind, self.port = bind, port
        self.name = f"tcp:{bind}:{port}"
        self._sock: socket.socket | None = None
        self._writer: asyncio.StreamWriter | None = None
        self._task: asyncio.Task | None = None
        self.on_connect: Callable[[Link], None] | None = None
        self.clients_served = 0

    @property
    def connected(self) -> bool:
        return self._writer is not None and not self._writer.is_closing()

    def describe(self) -> dict:
        return {**super().describe(), "clients_served": self.clients_served}

    def _write(self, data: bytes) -> None:
        assert self._writer is not None
        transport = self._writer.transport
        # A client that stopped reading must not make us buffer without bound (SITL drops too).
        if transport.get_write_buffer_size() > 1_000_000:
            return
        self._writer.write(data)

    async def start(self) -> None:
        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind((self.bind, self.port))
        sock.listen(4)
        sock.setblocking(False)
        self._sock = sock
        self.port = sock.getsockname()[1]
        self._task = asyncio.create_task(self._serve(), name=f"sim-{self.name}")

    async def _serve(self) -> None:
        loop = asyncio.get_running_loop()
        assert self._sock is not None
        while True:
            conn, _addr = await loop.sock_accept(self._sock)
            conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            reader, writer = await asyncio.open_connection(sock=conn)
            self._writer = writer
            self.clients_served += 1
            if self.on_connect:
                self.on_connect(self)
            try:
                while True:
                    data = await reader.read(4096)
                    if not data:
                        break
                    self._received(data)
            except (ConnectionError, OSError):
                pass
            finally:
                self._writer = None
                writer.close()
                with contextlib.suppress(Exception):
                    await writer.wait_closed()

    def drop_client(self) -> None:
        """Close the current client connection (as a vehicle reboot would)."""
        if self._writer is not None:
            self._writer.close()

    async def stop(self) -> None:
        if self._task:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await self._task
        if self._writer is not None:
            self._writer.close()
            self._writer = None
        if self._sock is not None:
            self._sock.close()
            self._sock = None


class _UdpProtocol(asyncio.DatagramProtocol):
    def __init__(self, link: UdpOutLink) -> None:
        self.link = link

    def datagram_received(self, data: bytes, addr) -> None:
        self.link._received(data)


class UdpOutLink(Link):
    """Sends to host:port (SITL's ``--out udp:...``) and accepts the replies on the same socket."""

    def __init__(self, sysid: int, receiver: Receiver, faults: LinkFaults, host: str, port: int) -> None:
        super().__init__(sysid, receiver, faults)
        self.host, self.port = host, port
        self.name = f"udp:{host}:{port}"
        self._transport: asyncio.DatagramTransport | None = None

    @property
    def connected(self) -> bool:
        return self._transport is not None

    def _write(self, data: bytes) -> None:
        assert self._transport is not None
        with contextlib.suppress(OSError):
            self._transport.sendto(data, (self.host, self.port))

    async def start(self) -> None:
        loop = asyncio.get_running_loop()
        self._transport, _ = await loop.create_datagram_endpoint(
            lambda: _UdpProtocol(self), local_addr=("127.0.0.1", 0)
        )

    async def stop(self) -> None:
        if self._transport is not None:
            self._transport.close()
            self._transport = None
