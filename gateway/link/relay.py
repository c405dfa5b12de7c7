"""A vehicle's MAVLink shared with ground stations: the gateway holds the drone's link and relays it.

When a registration lists ``gcs_endpoints``, the vehicle's URL is opened here instead of by its
``mavsdk_server``; the sidecar talks to this relay over a loopback UDP socket (``udpout://127.0.0.1:P``,
P chosen by the kernel), and every ground station endpoint is opened as its URL says. Routing, as a
MAVLink router does it:

* every frame from the vehicle goes to the sidecar and to every ground station; a frame addressed to
  one system (``target_system`` set) goes only to the endpoints that system was heard on (the
  sidecar's system id is the gateway's, a ground station's is its own), so a mission upload or a
  COMMAND_ACK reaches the one that asked;
* every frame from the sidecar or a ground station goes to the vehicle only, byte for byte: each keeps
  its own system id, and the sidecar never sees a ground station's traffic (only what the vehicle
  does about it: a mode change in its HEARTBEAT is the takeover watch's business).

Frames are split by their MAVLink v1/v2 framing and checked by CRC where the message is known (an
unknown message id is relayed as framed); bytes that are no frame are dropped. The relay runs as long
as the vehicle's link is wanted, across sidecar restarts, so ground stations keep the drone while
the gateway's own session comes and goes.
"""

from __future__ import annotations

import abc
import asyncio
import contextlib
import ipaddress
import logging
import os
import termios
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any
from urllib.parse import urlsplit

from pymavlink.dialects.v20 import ardupilotmega as mavlink
from pymavlink.generator.mavcrc import x25crc

from gateway.link.sidecar import proc_net_rows, socket_inodes

log = logging.getLogger("gateway.relay")

STX_V1 = 0xFE
STX_V2 = 0xFD
#: the longest a partial frame may wait for its tail before its bytes count as noise
MAX_BUFFER = 64 * 1024
RECONNECT_INITIAL_S = 0.5
RECONNECT_MAX_S = 5.0
#: how often an endpoint that could not be opened (port taken...) is tried again
REOPEN_S = 3.0
#: a UDP send error (nobody listening) is forgotten after this long without another
UDP_ERROR_QUIET_S = 3.0

_TARGETED = {
    msgid: cls
    for msgid, cls in mavlink.mavlink_map.items()
    if "target_system" in getattr(cls, "fieldnames", ())
}
_BAUDS = {
    int(name[1:]): getattr(termios, name)
    for name in dir(termios)
    if name.startswith("B") and name[1:].isdigit()
}


@dataclass(frozen=True)
class Frame:
    """One MAVLink frame as received, with what routing needs."""

    data: bytes
    sysid: int
    msgid: int


class FrameSplitter:
    """Cuts a byte stream (or datagrams) into MAVLink frames."""

    def __init__(self) -> None:
        self._buf = bytearray()

    def feed(self, data: bytes) -> list[Frame]:
        buf = self._buf
        buf += data
        frames: list[Frame] = []
        while buf:
            start = next((i for i, b in enumerate(buf) if b in (STX_V1, STX_V2)), len(buf))
            del buf[:start]
            if not buf:
                break
            if buf[0] == STX_V2:
                if len(buf) < 10:
                    break
                length = 12 + buf[1] + (13 if buf[2] & 0x01 else 0)
                header, sysid, msgid = 10, buf[5], int.from_bytes(buf[7:10], "little")
            else:
                if len(buf) < 6:
                    break
                length = 8 + buf[1]
                header, sysid, msgid = 6, buf[3], buf[5]
            if len(buf) < length:
                if len(buf) > MAX_BUFFER:
                    del buf[:1]
                    continue
                break
            payload_end = header + buf[1]
            if not _crc_ok(buf, payload_end, msgid):
                del buf[:1]  # a stray start byte: look for the next one
                continue
            frames.append(Frame(bytes(buf[:length]), sysid, msgid))
            del buf[:length]
        return frames


def _crc_ok(buf: bytearray, payload_end: int, msgid: int) -> bool:
    cls = mavlink.mavlink_map.get(msgid)
    if cls is None:
        return True  # not in the dialect: relayed as framed, the receiver checks it
    crc = x25crc(bytes(buf[1:payload_end]))
    crc.accumulate(bytes([cls.crc_extra]))
    return bool(crc.crc == int.from_bytes(buf[payload_end : payload_end + 2], "little"))


_DECODER = mavlink.MAVLink(None)
_DECODER.robust_parsing = True


def target_system(frame: Frame) -> int:
    """The system a frame is addressed to; 0 (everyone) when it has no target or cannot be read."""
    if frame.msgid not in _TARGETED:
        return 0
    try:
        msg = _DECODER.decode(bytearray(frame.data))
    except Exception:  # a frame the dialect cannot unpack (another version of the message): broadcast
        return 0
    return int(getattr(msg, "target_system", 0) or 0)


# --- endpoints ---------------------------------------------------------------------------------------------
Deliver = Callable[["Endpoint", Frame], None]


@dataclass
class EndpointStats:
    frames_in: int = 0
    frames_out: int = 0
    last_in: float | None = None  # monotonic


class Endpoint(abc.ABC):
    """One side of the relay: opened as its URL says; hands every frame it receives to ``deliver``.
    Each transport (UDP, TCP, serial) opens, sends and closes in its own way."""

    def __init__(self, url: str, deliver: Deliver) -> None:
        self.url = url
        parts = urlsplit(url)
        self.scheme = parts.scheme
        self.host = parts.hostname or ""
        self.port = parts.port or 0
        self.stats = EndpointStats()
        self.sysids: set[int] = set()
        self.complaint: str | None = None
        self._deliver = deliver
        self._splitters: dict[Any, FrameSplitter] = {}

    @abc.abstractmethod
    async def start(self) -> None: ...

    @abc.abstractmethod
    def send(self, data: bytes) -> None: ...

    @abc.abstractmethod
    async def close(self) -> None: ...

    @property
    def peer(self) -> str | None:
        return None

    def received(self, data: bytes, source: Any = None) -> None:
        splitter = self._splitters.setdefault(source, FrameSplitter())
        for frame in splitter.feed(data):
            self.stats.frames_in += 1
            self.stats.last_in = time.monotonic()
            self.sysids.add(frame.sysid)
            self._deliver(self, frame)

    def status(self) -> dict[str, Any]:
        age = None if self.stats.last_in is None else round(time.monotonic() - self.stats.last_in, 3)
        return {
            "url": self.url,
            "peer": self.peer,
            "frames_in": self.stats.frames_in,
            "frames_out": self.stats.frames_out,
            "last_in_age_s": age,
            "system_ids": sorted(self.sysids),
            "error": self.complaint,
        }


class _Datagrams(asyncio.DatagramProtocol):
    def __init__(self, owner: UdpEndpoint) -> None:
        self.owner = owner

    def datagram_received(self, data: bytes, addr: Any) -> None:
        self.owner.datagram(data, addr)

    def error_received(self, exc: Exception) -> None:  # e.g. ICMP port unreachable: nobody listens yet
        reason = os.strerror(exc.errno) if isinstance(exc, OSError) and exc.errno else str(exc)
        self.owner.complaint = f"{self.owner.url}: {reason}"
        self.owner.error_at = time.monotonic()


class UdpEndpoint(Endpoint):
    """``udpin``: bind host:port, answer the latest sender; ``udpout``: send to host:port."""

    def __init__(self, url: str, deliver: Deliver) -> None:
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

    def datagram(self, data: bytes, addr: Any) -> None:
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
        if self.complaint is not None and time.monotonic() - self.error_at > UDP_ERROR_QUIET_S:
            self.complaint = None  # sent on without an error coming back: someone listens again

    async def close(self) -> None:
        if self._transport is not None:
            self._transport.close()
            self._transport = None


class TcpEndpoint(Endpoint):
    """``tcpout``: connect to host:port (again and again while it fails or drops); ``tcpin``: listen on
    host:port, every client connected gets every frame."""

    def __init__(self, url: str, deliver: Deliver) -> None:
        super().__init__(url, deliver)
        self._writers: list[asyncio.StreamWriter] = []
        self._server: asyncio.Server | None = None
        self._task: asyncio.Task[None] | None = None
        self._readers: set[asyncio.Task[None]] = set()

    @property
    def peer(self) -> str | None:
        peers = [w.get_extra_info("peername") for w in self._writers]
        return ", ".join(f"{p[0]}:{p[1]}" for p in peers if p) or None

    async def start(self) -> None:
        if self.scheme == "tcpin":
            self._server = await asyncio.start_server(self._client, self.host, self.port)
        else:
            self._task = asyncio.create_task(self._connect_loop(), name=f"relay-{self.url}")

    async def _connect_loop(self) -> None:
        delay = RECONNECT_INITIAL_S
        while True:
            try:
                reader, writer = await asyncio.wait_for(asyncio.open_connection(self.host, self.port), 10.0)
            except (OSError, TimeoutError) as exc:
                reason = os.strerror(exc.errno) if exc.errno else "no answer within 10 s"
                self.complaint = f"cannot connect to {self.host}:{self.port}: {reason}"
                await asyncio.sleep(delay)
                delay = min(delay * 2, RECONNECT_MAX_S)
                continue
            self.complaint = None
            delay = RECONNECT_INITIAL_S
            await self._serve(reader, writer)
            self.complaint = f"{self.host}:{self.port} closed the connection"
            await asyncio.sleep(delay)

    async def _client(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        task = asyncio.current_task()
        if task is not None:
            self._readers.add(task)
        try:
            await self._serve(reader, writer)
        except asyncio.CancelledError:
            pass  # closing: asyncio's server callback would log a cancelled client task as an error
        finally:
            if task is not None:
                self._readers.discard(task)

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        self._writers.append(writer)
        try:
            while chunk := await reader.read(4096):
                self.received(chunk, id(writer))
        except OSError:
            pass
        finally:
            self._writers.remove(writer)
            self._splitters.pop(id(writer), None)
            writer.close()

    def send(self, data: bytes) -> None:
        for writer in list(self._writers):
            if writer.is_closing():
                continue
            if writer.transport.get_write_buffer_size() > MAX_BUFFER:
                continue  # a stalled reader: drop rather than buffer without bound (MAVLink is lossy)
            writer.write(data)
            self.stats.frames_out += 1

    async def close(self) -> None:
        tasks = [t for t in (self._task, *self._readers) if t is not None]
        if self._server is not None:
            self._server.close()
        for writer in list(self._writers):
            writer.close()
        for task in tasks:
            task.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)
        if self._server is not None:
            with contextlib.suppress(Exception):
                await asyncio.wait_for(self._server.wait_closed(), 2.0)
        self._server = None
        self._task = None


class SerialEndpoint(Endpoint):
    """``serial:///dev/ttyX[:baud]``: the device in raw mode (default 57600 baud), reopened while it fails."""

    def __init__(self, url: str, deliver: Deliver) -> None:
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
        loop = asyncio.get_running_loop()
        delay = RECONNECT_INITIAL_S
        while True:
            try:
                fd = self._open()
            except OSError as exc:
                self.complaint = f"cannot open {self.device}: {exc.strerror or exc}"
                await asyncio.sleep(delay)
                delay = min(delay * 2, RECONNECT_MAX_S)
                continue
            self.complaint = None
            delay = RECONNECT_INITIAL_S
            gone = asyncio.Event()
            self._fd = fd

            def readable(fd: int = fd, gone: asyncio.Event = gone) -> None:
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
            await asyncio.sleep(delay)

    def send(self, data: bytes) -> None:
        if self._fd is None:
            return
        try:
            os.write(self._fd, data)
            self.stats.frames_out += 1
        except BlockingIOError:
            pass  # the device's buffer is full: dropped, MAVLink is lossy
        except OSError as exc:
            self.complaint = f"{self.device}: {exc.strerror or exc}"

    async def close(self) -> None:
        if self._task is not None:
            self._task.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await self._task
            self._task = None


def open_endpoint(url: str, deliver: Deliver) -> Endpoint:
    scheme = urlsplit(url).scheme
    if scheme in ("udpin", "udpout"):
        return UdpEndpoint(url, deliver)
    if scheme in ("tcpin", "tcpout"):
        return TcpEndpoint(url, deliver)
    if scheme == "serial":
        return SerialEndpoint(url, deliver)
    raise ValueError(f"no MAVLink endpoint for '{url}'")


# --- the relay ---------------------------------------------------------------------------------------------
class Relay:
    """The vehicle's link, its sidecar's loopback socket and its ground stations, routed."""

    def __init__(
        self,
        vehicle_id: str,
        vehicle_url: str,
        gcs_urls: list[str],
        sidecar_pid: Callable[[], int | None] | None = None,
    ) -> None:
        """``sidecar_pid``: the sidecar's process id now; given, only a socket of that process is
        taken as the sidecar (another local process cannot step in between it and the drone)."""
        self.vehicle_id = vehicle_id
        self.vehicle_url = vehicle_url
        self.gcs_urls = list(gcs_urls)
        self.vehicle = open_endpoint(vehicle_url, self._from_vehicle)
        self.sidecar = UdpEndpoint("udpin://127.0.0.1:0", self._to_vehicle)
        if sidecar_pid is not None:
            self.sidecar.accept = lambda peer: _udp_socket_of(sidecar_pid(), peer)
        self.ground_stations = [open_endpoint(url, self._to_vehicle) for url in self.gcs_urls]
        self._started: list[Endpoint] = []
        self._retries: list[asyncio.Task[None]] = []
        self._log = logging.getLogger(f"gateway.relay.{vehicle_id}")

    @property
    def sidecar_url(self) -> str:
        """What the sidecar is started with instead of the vehicle's URL."""
        return f"udpout://127.0.0.1:{self.sidecar.bound_port}"

    async def start(self) -> None:
        """Open every endpoint. One that cannot be opened now (its port is taken, its address is not
        this host's) is reported (``complaint``, ``status``) and tried again every few seconds; it does
        not stop the others. Only the sidecar's loopback socket must open at once."""
        await self.sidecar.start()
        self._started.append(self.sidecar)
        for gcs in self.ground_stations:
            if gcs.scheme in ("udpin", "tcpin") and not _is_loopback(gcs.host):
                self._log.warning(
                    "%s: ground station endpoint %s listens beyond this host: whoever reaches it can "
                    "command the drone, outside the gateway's safety policy",
                    self.vehicle_id,
                    gcs.url,
                )
        for endpoint in (self.vehicle, *self.ground_stations):
            try:
                await endpoint.start()
            except (OSError, ValueError) as exc:
                self._failed_to_open(endpoint, exc)
                self._retries.append(
                    asyncio.create_task(self._keep_opening(endpoint), name=f"relay-open-{endpoint.url}")
                )
                continue
            self._started.append(endpoint)
        self._log.info(
            "%s: relaying %s to its sidecar (%s) and %d ground station endpoint(s): %s",
            self.vehicle_id,
            self.vehicle_url,
            self.sidecar_url,
            len(self.ground_stations),
            ", ".join(self.gcs_urls),
        )

    def _failed_to_open(self, endpoint: Endpoint, exc: Exception) -> None:
        reason = os.strerror(exc.errno) if isinstance(exc, OSError) and exc.errno else str(exc)
        endpoint.complaint = f"cannot open {endpoint.url}: {reason}"

    async def _keep_opening(self, endpoint: Endpoint) -> None:
        self._log.error("%s: %s; trying again every %g s", self.vehicle_id, endpoint.complaint, REOPEN_S)
        while True:
            await asyncio.sleep(REOPEN_S)
            try:
                await endpoint.start()
            except (OSError, ValueError) as exc:
                self._failed_to_open(endpoint, exc)
                continue
            endpoint.complaint = None
            self._started.append(endpoint)
            self._log.info("%s: %s is open now", self.vehicle_id, endpoint.url)
            return

    async def close(self) -> None:
        retries, self._retries = self._retries, []
        for task in retries:
            task.cancel()
        await asyncio.gather(*retries, return_exceptions=True)
        started, self._started = self._started, []
        for endpoint in started:
            with contextlib.suppress(Exception):
                await endpoint.close()

    @property
    def complaint(self) -> str | None:
        """Why the vehicle's side of the link is not up (refused, no device...), else None."""
        return self.vehicle.complaint

    def status(self) -> list[dict[str, Any]]:
        return [gcs.status() for gcs in self.ground_stations]

    def _from_vehicle(self, _source: Endpoint, frame: Frame) -> None:
        outputs: list[Endpoint] = [self.sidecar, *self.ground_stations]
        target = target_system(frame)
        if target:
            heard = [e for e in outputs if target in e.sysids]
            if heard:
                outputs = heard
        for endpoint in outputs:
            endpoint.send(frame.data)

    def _to_vehicle(self, _source: Endpoint, frame: Frame) -> None:
        self.vehicle.send(frame.data)


def _udp_socket_of(pid: int | None, peer: tuple[str, int]) -> bool:
    """Whether the UDP socket bound to ``peer`` (a loopback address and port) belongs to process ``pid``."""
    if pid is None:
        return False
    inodes = {row.inode for row in proc_net_rows("udp") if row.port == peer[1]}
    return bool(inodes & socket_inodes(pid))


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False
