"""The relay's endpoints, one per URL: UDP (`udpin`/`udpout`), TCP (`tcpin` as a server, `tcpout` as a
client that reconnects) and serial (`serial`), each opened again while it cannot be, and counting what
it carried.

What an endpoint receives is handed on in one call per read (a datagram, or what a socket or device had
waiting), with no task, future or copy in between (TCP connections are asyncio protocols, not streams):
to ``on_bytes`` as read, and cut into frames for ``deliver`` when the endpoint has one. An endpoint
without ``deliver`` does no per-frame work at all: the relay's drone side when no ground station shares
the link, whose bytes go to the sidecar as they came."""

from __future__ import annotations

import abc
import asyncio
import contextlib
import os
import termios
import time
from collections.abc import Awaitable, Callable, Hashable
from dataclasses import dataclass
from typing import TypeVar
from urllib.parse import urlsplit

from gateway.link.mavlink_frames import MAX_BUFFER, Frame, FrameSplitter
from gateway.util.json_types import JsonObject, json_list
from gateway.util.tasks import cancel_and_wait

RECONNECT_INITIAL_S = 0.5
RECONNECT_MAX_S = 5.0

_Opened = TypeVar("_Opened")  # what an endpoint's open gives: a socket's streams, a device's fd
#: how often an endpoint that could not be opened (port taken...) is tried again
REOPEN_S = 3.0
#: a UDP send error (nobody listening) is forgotten after this long without another
UDP_ERROR_QUIET_S = 3.0

_BAUDS = {
    int(name[1:]): getattr(termios, name)
    for name in dir(termios)
    if name.startswith("B") and name[1:].isdigit()
}


Deliver = Callable[["Endpoint", Frame], None]


@dataclass
class EndpointStats:
    frames_in: int = 0  # counted only where frames are cut (``deliver``)
    frames_out: int = 0  # sends: a frame each where frames are cut, else what one read brought
    bytes_in: int = 0
    bytes_out: int = 0
    last_in: float | None = None  # monotonic


class Endpoint(abc.ABC):
    """One side of the relay: opened as its URL says; hands what it receives to ``on_bytes`` as read
    and every frame of it to ``deliver`` (None: frames are not cut). Each transport (UDP, TCP, serial)
    opens, sends and closes in its own way."""

    def __init__(self, url: str, deliver: Deliver | None) -> None:
        self.url = url
        parts = urlsplit(url)
        self.scheme = parts.scheme
        self.host = parts.hostname or ""
        self.port = parts.port or 0
        self.stats = EndpointStats()
        self.sysids: set[int] = set()
        self.complaint: str | None = None
        #: a ground station endpoint: its peer sent a HEARTBEAT of a ground station (until then nothing it
        #: sends is relayed to the drone)
        self.verified = False
        #: why the relay stopped this endpoint for good (its peer is no ground station), or None
        self.refused: str | None = None
        self._deliver = deliver
        #: given every read as it came (bytes of one or more frames, or of part of one), before ``deliver``
        self.on_bytes: Callable[[bytes], None] | None = None
        self._splitters: dict[Hashable, FrameSplitter] = {}

    @abc.abstractmethod
    async def start(self) -> None: ...

    @abc.abstractmethod
    def send(self, data: bytes) -> None: ...

    @abc.abstractmethod
    async def close(self) -> None: ...

    @property
    def peer(self) -> str | None:
        return None

    def received(self, data: bytes, source: Hashable = None) -> None:
        stats = self.stats
        stats.bytes_in += len(data)
        stats.last_in = time.monotonic()
        if self.on_bytes is not None:
            self.on_bytes(data)
        deliver = self._deliver
        if deliver is None:
            return
        splitter = self._splitters.get(source)
        if splitter is None:
            splitter = self._splitters[source] = FrameSplitter()
        for frame in splitter.feed(data):
            stats.frames_in += 1
            self.sysids.add(frame.sysid)
            deliver(self, frame)

    async def _reopen_forever(
        self,
        open_: Callable[[], Awaitable[_Opened]],
        failure: Callable[[OSError], str],
        serve: Callable[[_Opened], Awaitable[None]],
    ) -> None:
        """Open, serve until the connection ends, and again: an open that fails sets the complaint to
        ``failure``'s words and is retried after RECONNECT_INITIAL_S, doubling up to RECONNECT_MAX_S; an
        ended connection is opened again after RECONNECT_INITIAL_S."""
        delay = RECONNECT_INITIAL_S
        while True:
            try:
                opened = await open_()
            except OSError as exc:  # TimeoutError too
                self.complaint = failure(exc)
                await asyncio.sleep(delay)
                delay = min(delay * 2, RECONNECT_MAX_S)
                continue
            self.complaint = None
            delay = RECONNECT_INITIAL_S
            await serve(opened)
            await asyncio.sleep(delay)

    def status(self) -> JsonObject:
        age = None if self.stats.last_in is None else round(time.monotonic() - self.stats.last_in, 3)
        return {
            "url": self.url,
            "peer": self.peer,
            "frames_in": self.stats.frames_in,
            "frames_out": self.stats.frames_out,
            "last_in_age_s": age,
            "system_ids": json_list(sorted(self.sysids)),
            "error": self.refused or self.complaint,
            "refused": self.refused is not None,
        }


class _Datagrams(asyncio.DatagramProtocol):
    def __init__(self, owner: UdpEndpoint) -> None:
        self.owner = owner

    def datagram_received(self, data: bytes, addr: tuple[str, int]) -> None:
        self.owner.datagram(data, addr)

    def error_received(self, exc: Exception) -> None:  # e.g. ICMP port unreachable: nobody listens yet
        reason = os.strerror(exc.errno) if isinstance(exc, OSError) and exc.errno else str(exc)
        self.owner.complaint = f"{self.owner.url}: {reason}"
        self.owner.error_at = time.monotonic()


class UdpEndpoint(Endpoint):
    """``udpin``: bind host:port, answer the latest sender; ``udpout``: send to host:port."""

    def __init__(self, url: str, deliver: Deliver | None) -> None:
        super().__init__(url, deliver)
        self._transport: asyncio.DatagramTransport | None = None
        self._peer: tuple[str, int] | None = None
        self.error_at = 0.0  # monotonic, of the last send error the kernel reported
        #: udpin: whether a new sender may become the peer (None: anyone, the latest sender wins)
        self.accept: Callable[[tuple[str, int]], bool] | None = None

    @property
    def bound_port(self) -> int:
        assert self._transport is not None
        return int(self._transport.get_extra_info("sockname")[1])

    @property
    def peer(self) -> str | None:
        return None if self._peer is None else f"{self._peer[0]}:{self._peer[1]}"

    async def start(self) -> None:
        loop = asyncio.get_running_loop()
        if self.scheme == "udpin":
            transport, _ = await loop.create_datagram_endpoint(
                lambda: _Datagrams(self), local_addr=(self.host, self.port)
            )
        else:
            self._peer = (self.host, self.port)
            transport, _ = await loop.create_datagram_endpoint(
                lambda: _Datagrams(self), remote_addr=(self.host, self.port)
            )
        self._transport = transport

    def datagram(self, data: bytes, addr: tuple[str, int]) -> None:
        if self.scheme == "udpin":
            peer = (str(addr[0]), int(addr[1]))
            if peer != self._peer and self.accept is not None and not self.accept(peer):
                return  # not who this endpoint is for (the sidecar's socket: another local process)
            self._peer = peer
        self.complaint = None
        self.received(data, self._peer)

    def send(self, data: bytes) -> None:
        if self._transport is None or self._peer is None:
            return  # udpin: nobody has spoken to us yet
        if self.scheme == "udpin":
            self._transport.sendto(data, self._peer)
        else:
            self._transport.sendto(data)
        self.stats.frames_out += 1
        self.stats.bytes_out += len(data)
        if self.complaint is not None and time.monotonic() - self.error_at > UDP_ERROR_QUIET_S:
            self.complaint = None  # sent on without an error coming back: someone listens again

    async def close(self) -> None:
        if self._transport is not None:
            self._transport.close()
            self._transport = None


class _Connection(asyncio.Protocol):
    """One TCP connection of a `TcpEndpoint`: what it reads goes to the endpoint at once, from the event
    loop's read callback (no stream buffer, no task woken per read)."""

    def __init__(self, owner: TcpEndpoint) -> None:
        self.owner = owner
        self.transport: asyncio.Transport | None = None
        self.closed: asyncio.Future[None] = asyncio.get_running_loop().create_future()

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        assert isinstance(transport, asyncio.Transport)
        peer = transport.get_extra_info("peername")
        accept = self.owner.accept
        if accept is not None and not (peer and accept((str(peer[0]), int(peer[1])))):
            transport.close()  # not who this endpoint is for (the sidecar's socket: another local process)
            return
        self.transport = transport
        self.owner.connections.append(self)

    def data_received(self, data: bytes) -> None:
        self.owner.received(data, self)

    def connection_lost(self, exc: Exception | None) -> None:
        self.owner.dropped(self)
        if not self.closed.done():
            self.closed.set_result(None)


class TcpEndpoint(Endpoint):
    """``tcpout``: connect to host:port (again and again while it fails or drops); ``tcpin``: listen on
    host:port, every client connected gets every frame."""

    def __init__(self, url: str, deliver: Deliver | None, max_buffer: int = MAX_BUFFER) -> None:
        """``max_buffer``: the bytes a connection may have waiting to be sent; a frame beyond is dropped
        for that connection (a stalled reader does not hold memory without bound)."""
        super().__init__(url, deliver)
        self.max_buffer = max_buffer
        self.connections: list[_Connection] = []
        self._server: asyncio.Server | None = None
        self._task: asyncio.Task[None] | None = None
        #: tcpin: whether a client connecting from (host, port) is served (None: every client)
        self.accept: Callable[[tuple[str, int]], bool] | None = None

    @property
    def bound_port(self) -> int:
        assert self._server is not None and self._server.sockets
        return int(self._server.sockets[0].getsockname()[1])

    @property
    def peer(self) -> str | None:
        peers = [c.transport.get_extra_info("peername") for c in self.connections if c.transport is not None]
        return ", ".join(f"{p[0]}:{p[1]}" for p in peers if p) or None

    async def start(self) -> None:
        loop = asyncio.get_running_loop()
        if self.scheme == "tcpin":
            self._server = await loop.create_server(lambda: _Connection(self), self.host, self.port)
        else:
            self._task = asyncio.create_task(self._connect_loop(), name=f"relay-{self.url}")

    async def _connect_loop(self) -> None:
        loop = asyncio.get_running_loop()

        async def connect() -> _Connection:
            opening = loop.create_connection(lambda: _Connection(self), self.host, self.port)
            _, connection = await asyncio.wait_for(opening, 10.0)
            return connection

        def failure(exc: OSError) -> str:
            reason = os.strerror(exc.errno) if exc.errno else "no answer within 10 s"
            return f"cannot connect to {self.host}:{self.port}: {reason}"

        async def serve(connection: _Connection) -> None:
            try:
                await connection.closed
            finally:
                if connection.transport is not None:
                    connection.transport.close()
            self.complaint = f"{self.host}:{self.port} closed the connection"

        await self._reopen_forever(connect, failure, serve)

    def dropped(self, connection: _Connection) -> None:
        """A connection ended: its partial frame goes with it."""
        if connection in self.connections:
            self.connections.remove(connection)
        self._splitters.pop(connection, None)

    def send(self, data: bytes) -> None:
        for connection in self.connections:
            transport = connection.transport
            if transport is None or transport.is_closing():
                continue
            if transport.get_write_buffer_size() > self.max_buffer:
                continue  # a stalled reader: drop rather than buffer without bound (MAVLink is lossy)
            transport.write(data)
            self.stats.frames_out += 1
            self.stats.bytes_out += len(data)

    async def close(self) -> None:
        if self._server is not None:
            self._server.close()
        for connection in list(self.connections):
            if connection.transport is not None:
                connection.transport.close()
        await cancel_and_wait(self._task)
        if self._server is not None:
            with contextlib.suppress(Exception):
                await asyncio.wait_for(self._server.wait_closed(), 2.0)
        self._server = None
        self._task = None


class SerialEndpoint(Endpoint):
    """``serial:///dev/ttyX[:baud]``: the device in raw mode (default 57600 baud), reopened while it fails."""

    def __init__(self, url: str, deliver: Deliver | None) -> None:
        super().__init__(url, deliver)
        device, _, baud = urlsplit(url).path.partition(":")
        self.device = device
        self.baud = int(baud) if baud else 57600
        self._fd: int | None = None
        self._task: asyncio.Task[None] | None = None

    @property
    def peer(self) -> str | None:
        return self.device if self._fd is not None else None

    async def start(self) -> None:
        if self.baud not in _BAUDS:
            raise ValueError(f"serial baud rate {self.baud} is not one this system supports")
        self._task = asyncio.create_task(self._open_loop(), name=f"relay-{self.url}")

    def _open(self) -> int:
        fd = os.open(self.device, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        try:
            attrs = termios.tcgetattr(fd)
            attrs[0] = 0  # iflag
            attrs[1] = 0  # oflag
            attrs[2] = termios.CS8 | termios.CREAD | termios.CLOCAL  # cflag
            attrs[3] = 0  # lflag
            attrs[4] = attrs[5] = _BAUDS[self.baud]
            termios.tcsetattr(fd, termios.TCSANOW, attrs)
        except BaseException:
            os.close(fd)
            raise
        return fd

    async def _open_loop(self) -> None:
        async def open_device() -> int:
            return self._open()

        def failure(exc: OSError) -> str:
            return f"cannot open {self.device}: {exc.strerror or exc}"

        await self._reopen_forever(open_device, failure, self._serve_device)

    async def _serve_device(self, fd: int) -> None:
        """Relay what the device sends until it goes away (read error or end of file), then close it."""
        loop = asyncio.get_running_loop()
        gone = asyncio.Event()
        self._fd = fd

        def readable() -> None:
            try:
                data = os.read(fd, 4096)
            except BlockingIOError:
                return
            except OSError as exc:
                self.complaint = f"{self.device}: {exc.strerror or exc}"
                data = b""
            if not data:
                gone.set()
                return
            self.received(data)

        loop.add_reader(fd, readable)
        try:
            await gone.wait()
        finally:
            loop.remove_reader(fd)
            self._fd = None
            os.close(fd)

    def send(self, data: bytes) -> None:
        if self._fd is None:
            return
        try:
            os.write(self._fd, data)
            self.stats.frames_out += 1
            self.stats.bytes_out += len(data)
        except BlockingIOError:
            pass  # the device's buffer is full: dropped, MAVLink is lossy
        except OSError as exc:
            self.complaint = f"{self.device}: {exc.strerror or exc}"

    async def close(self) -> None:
        await cancel_and_wait(self._task)
        self._task = None


def open_endpoint(url: str, deliver: Deliver | None) -> Endpoint:
    scheme = urlsplit(url).scheme
    if scheme in ("udpin", "udpout"):
        return UdpEndpoint(url, deliver)
    if scheme in ("tcpin", "tcpout"):
        return TcpEndpoint(url, deliver)
    if scheme == "serial":
        return SerialEndpoint(url, deliver)
    raise ValueError(f"no MAVLink endpoint for '{url}'")


def device_present(url: str) -> bool:
    """Whether the gateway may hold the drone's link only to record it: False for a serial URL whose
    device does not exist now (the sidecar opens it and fails, as it does without the raw flight log),
    and for a udpout:// drone, which speaks only once its ground station has (through the relay it was
    never discovered: its flights keep the .tlog rebuilt from their track); True for every other URL."""
    parts = urlsplit(url)
    if parts.scheme == "udpout":
        return False
    return parts.scheme != "serial" or os.path.exists(parts.path.partition(":")[0])
