"""A vehicle's MAVLink shared with ground stations: the gateway holds the drone's link and relays it.

When a registration lists ``gcs_endpoints``, the vehicle's URL is opened here instead of by its
``mavsdk_server``; the sidecar talks to this relay over a loopback TCP connection
(``tcpout://127.0.0.1:P``, P chosen by the kernel), and every ground station endpoint is opened as its
URL says. TCP, not UDP: the drone's frames reach the sidecar one by one, and a burst of them (the
parameter list, ~1,300 PARAM_VALUE at once) as as many loopback datagrams overflows the sidecar's
socket buffer whenever mavsdk_server is not scheduled for a moment; TCP holds them until it reads
(up to ``SIDECAR_BUFFER`` bytes). Routing, as a MAVLink router does it:

* every frame from the vehicle goes to the sidecar and to every ground station; a frame addressed to
  one system (``target_system`` set) goes only to the endpoints that system was heard on (the
  sidecar's system id is the gateway's, a ground station's is its own), so a mission upload or a
  COMMAND_ACK reaches the one that asked;
* every frame from the sidecar or a ground station goes to the vehicle only, byte for byte: each keeps
  its own system id, and the sidecar never sees a ground station's traffic (only what the vehicle
  does about it: a mode change in its HEARTBEAT is the takeover watch's business). A ground station's
  frame that acts on the drone (a target, a mission change, a command: `gateway.link.ground_commands`)
  is noted in ``ground_commands``, which the takeover watch reads.

Frames are split by their MAVLink v1/v2 framing and checked by CRC where the message is known (an
unknown message id is relayed as framed); bytes that are no frame are dropped. The relay runs as long
as the vehicle's link is wanted, across sidecar restarts, so ground stations keep the drone while
the gateway's own session comes and goes.

A drone without ground stations is relayed too while the gateway records its flights' raw MAVLink
(``flight_tlog_dir``, every drone by default): the relay is then the one place the drone's bytes pass
whole. Every read from the drone is handed as it came to ``on_vehicle_bytes``
(`gateway.fleet.missions.raw_tlog`, which cuts frames only while a flight is written). With no ground
station there is nothing to route: the drone's bytes go to the sidecar as read, one write per read and
no per-frame work; only the sidecar's few frames to the drone are cut (a UDP drone takes whole frames).
"""

from __future__ import annotations

import asyncio
import contextlib
import ipaddress
import logging
import os
import time
from collections import deque
from collections.abc import Callable

from gateway.link.contract import GroundCommand
from gateway.link.mavlink_frames import Frame, target_system
from gateway.link.proc_sockets import proc_net_rows, socket_inodes
from gateway.link.relay_endpoints import REOPEN_S, Endpoint, TcpEndpoint, open_endpoint
from gateway.util.json_types import JsonObject, JsonValue

log = logging.getLogger("gateway.relay")

#: what the drone may send while its sidecar does not read, before frames to it are dropped (a stalled
#: mavsdk_server holds a few seconds of a fast link; one that is gone holds no more than this)
SIDECAR_BUFFER = 16 * 1024 * 1024


class Relay:
    """The vehicle's link, its sidecar's loopback socket and its ground stations, routed."""

    def __init__(
        self,
        vehicle_id: str,
        vehicle_url: str,
        gcs_urls: list[str],
        sidecar_pid: Callable[[], int | None] | None = None,
        on_refused: Callable[[str, str], None] | None = None,
        on_vehicle_bytes: Callable[[bytes], None] | None = None,
    ) -> None:
        """``sidecar_pid``: the sidecar's process id now; given, only a socket of that process is
        taken as the sidecar (another local process cannot step in between it and the drone).
        ``on_refused(url, reason)``: told when a ground station endpoint is stopped because its peer is
        no ground station. ``on_vehicle_bytes(data)``: given every read from the vehicle as it came (one
        or more frames, or part of one; not copied), before it is forwarded; settable while relaying."""
        self._on_refused = on_refused
        self.on_vehicle_bytes = on_vehicle_bytes
        self.vehicle_id = vehicle_id
        self.vehicle_url = vehicle_url
        self.gcs_urls = list(gcs_urls)
        #: frames are cut and routed one by one only when ground stations share the link
        self.routes = bool(self.gcs_urls)
        self.vehicle = open_endpoint(vehicle_url, self._from_vehicle if self.routes else None)
        self.vehicle.on_bytes = self._vehicle_bytes
        self.sidecar = TcpEndpoint("tcpin://127.0.0.1:0", self._to_vehicle, max_buffer=SIDECAR_BUFFER)
        if sidecar_pid is not None:
            self.sidecar.accept = lambda peer: _tcp_socket_of(sidecar_pid(), peer)
        self.ground_stations = [open_endpoint(url, self._to_vehicle) for url in self.gcs_urls]
        self._started: list[Endpoint] = []
        self._retries: list[asyncio.Task[None]] = []
        self._log = logging.getLogger(f"gateway.relay.{vehicle_id}")
        #: the ground stations' frames that acted on the drone, newest last
        self.ground_commands: deque[GroundCommand] = deque(maxlen=32)

    @property
    def sidecar_url(self) -> str:
        """What the sidecar is started with instead of the vehicle's URL."""
        return f"tcpout://127.0.0.1:{self.sidecar.bound_port}"

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

    def status(self) -> list[JsonValue]:
        return [gcs.status() for gcs in self.ground_stations]

    def carried(self) -> JsonObject:
        """The bytes the drone's side and the sidecar's side read and wrote, and the sidecar's
        connections now: where a drone that is heard but not streaming lost its bytes."""
        vehicle, sidecar = self.vehicle.stats, self.sidecar.stats
        return {
            "vehicle_bytes_in": vehicle.bytes_in,
            "vehicle_bytes_out": vehicle.bytes_out,
            "sidecar_bytes_in": sidecar.bytes_in,
            "sidecar_bytes_out": sidecar.bytes_out,
            "sidecar_connections": len(self.sidecar.connections),
        }

    def _vehicle_bytes(self, data: bytes) -> None:
        sink = self.on_vehicle_bytes
        if sink is not None:
            sink(data)
        if not self.routes:
            self.sidecar.send(data)

    def _from_vehicle(self, _source: Endpoint, frame: Frame) -> None:
        outputs: list[Endpoint] = [self.sidecar, *(g for g in self.ground_stations if g.refused is None)]
        target = target_system(frame)
        if target:
            heard = [e for e in outputs if target in e.sysids]
            if heard:
                outputs = heard
        for endpoint in outputs:
            endpoint.send(frame.data)

    def _to_vehicle(self, source: Endpoint, frame: Frame) -> None:
        if source is not self.sidecar:
            # the rules read the frame with pymavlink's dialect: imported with the first ground station's
            # frame, not for a drone relayed only for its raw flight log
            from gateway.link import ground_commands

            if not self._from_a_ground_station(source, frame):
                return
            what = ground_commands.acting(frame, self.vehicle.sysids)
            if what is not None:
                self.ground_commands.append(GroundCommand(frame.sysid, what, time.monotonic()))
                self._log.info("%s: ground station %d sent %s", self.vehicle_id, frame.sysid, what)
        self.vehicle.send(frame.data)

    def _from_a_ground_station(self, source: Endpoint, frame: Frame) -> bool:
        """Whether ``frame`` from a ground station endpoint may go to the drone: its peer has said with a
        HEARTBEAT that it is a ground station (nothing before is relayed), and nothing says it is another
        vehicle or the drone itself; an endpoint whose peer is one is stopped for good."""
        from gateway.link import ground_commands

        if source.refused is not None:
            return False
        problem = ground_commands.not_a_ground_station(frame, self.vehicle.sysids)
        if problem is not None:
            self._refuse(source, problem)
            return False
        if ground_commands.is_heartbeat(frame):
            source.verified = True
        return source.verified

    def _refuse(self, endpoint: Endpoint, problem: str) -> None:
        endpoint.refused = (
            f"{endpoint.url} refused: {problem}; the endpoint is stopped and nothing from it was relayed"
        )
        self._log.error("%s: %s", self.vehicle_id, endpoint.refused)
        self._retries.append(asyncio.create_task(endpoint.close(), name=f"relay-refuse-{endpoint.url}"))
        if self._on_refused is not None:
            self._on_refused(endpoint.url, endpoint.refused)

    def commands_since(self, since: float) -> list[GroundCommand]:
        """The ground stations' frames that acted on the drone at or after ``since`` (monotonic)."""
        return [c for c in self.ground_commands if c.at >= since]


def _tcp_socket_of(pid: int | None, peer: tuple[str, int]) -> bool:
    """Whether the TCP socket connecting from ``peer`` (a loopback address and port) belongs to process
    ``pid``."""
    if pid is None:
        return False
    inodes = {row.inode for row in proc_net_rows("tcp") if row.port == peer[1]}
    return bool(inodes & socket_inodes(pid))


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False
