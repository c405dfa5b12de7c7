"""A MAVSDK System with only the plugins the gateway uses, over grpclib; the one place the gateway imports
mavsdk_grpc.

The gateway talks to its mavsdk_server sidecar with grpclib (pure-Python gRPC over asyncio and h2) and
mavsdk_grpc's ``*_pb2`` messages (`gateway.link.mavsdk_rpc`), never with grpcio: mavsdk_grpc's plugin
wrappers import their ``*_pb2_grpc`` modules, which import grpcio, whose core library was the larger part
of a link's memory (``bench/grpc_link.py``). So no wrapper module is imported here, only ``*_pb2`` ones.

``mavsdk_grpc``'s package ``__init__`` imports its ``System``, whose module imports all 40 plugin
wrappers (and grpcio). Here the package is registered as a bare package (its directory, without running
its ``__init__``) before anything of it is imported, so only the ``*_pb2`` modules asked for are loaded.
A program that imports ``mavsdk_grpc`` itself before this module (the tests' helpers, the benchmarks)
gets the whole package as usual, and this module works on that too; ``mavsdk_grpc.System`` stays
reachable on the bare package (imported when first asked for).

One `System` is one channel with one connection, never reconnected: a sidecar that restarts serves a
new session on a new channel (``gateway.link.session.Link``), and the sealed private socket of a
confined sidecar could not be reached again anyway. grpclib sends no HTTP/2 keepalive pings unless
configured to (it is not).
"""

from __future__ import annotations

import asyncio
import types
from pathlib import Path
from typing import Any, overload

from grpclib.client import Channel
from grpclib.protocol import H2Protocol

from gateway.link.mavsdk_rpc import ChannelClosed, Plugin, positional
from gateway.util.bare_package import register_bare_package


def _library_name(_package: types.ModuleType, name: str) -> Any:  # Any: mavsdk_grpc, untyped
    if name == "System":  # the library's own System, with all its plugins
        from mavsdk_grpc.system import System as LibrarySystem

        return LibrarySystem
    raise AttributeError(f"module 'mavsdk_grpc' has no attribute {name!r}")


register_bare_package("mavsdk_grpc", _library_name, "the mavsdk_grpc package (mavsdk-grpc)")

# ruff: noqa: E402 - these must come after the bare package is registered
from mavsdk_grpc import (
    action_pb2,
    core_pb2,
    events_pb2,
    info_pb2,
    mavlink_direct_pb2,
    mission_pb2,
    mission_raw_pb2,
    param_pb2,
    telemetry_pb2,
)


def bundled_binary() -> Path:
    """The mavsdk_server binary shipped with the mavsdk-grpc package."""
    import mavsdk_grpc.bin as bin_pkg

    return Path(bin_pkg.__file__).parent / "mavsdk_server"


__all__ = ["PLUGINS", "MavlinkMessage", "MissionRawItem", "System"]

#: the plugins the gateway uses, by the name MAVSDK gives them, with their ``*_pb2`` modules
_MODULES: dict[str, types.ModuleType] = {
    "action": action_pb2,
    "core": core_pb2,
    "events": events_pb2,
    "info": info_pb2,
    "mavlink_direct": mavlink_direct_pb2,
    "mission": mission_pb2,
    "mission_raw": mission_raw_pb2,
    "param": param_pb2,
    "telemetry": telemetry_pb2,
}
PLUGINS = tuple(_MODULES)

#: mavlink_direct's message and mission_raw's item, made from their fields in order as the wrappers'
#: classes are (``MavlinkMessage(name, system_id, component_id, target_system, target_component, json)``)
MavlinkMessage = positional(mavlink_direct_pb2.MavlinkMessage)
MissionRawItem = positional(mission_raw_pb2.MissionItem)

#: seconds between connection attempts while mavsdk_server does not accept yet (the caller bounds it)
CONNECT_RETRY_S = 0.2


class _OneConnection(Channel):
    """A grpclib channel that connects once: a lost connection is not made again (a call then fails
    with `ChannelClosed`, as a grpcio channel's call fails when its server is gone)."""

    _made = False

    async def _create_connection(self) -> H2Protocol:
        if self._made:
            raise ChannelClosed("the connection to mavsdk_server was lost (the session ends with it)")
        protocol = await super()._create_connection()
        self._made = True
        return protocol


def channel_for(address: str, port: int) -> Channel:
    """The channel to a sidecar: ``unix:<dir>/sk`` (`gateway.link.sidecar.Sidecar.grpc_address`) is the
    private socket ``<dir>/sk:<port>``; anything else a host for TCP."""
    if address.startswith("unix:"):
        return _OneConnection(path=f"{address.removeprefix('unix:')}:{port}")
    return _OneConnection(address, port)


class _Plugin:
    """A plugin of the `System`, by the name MAVSDK gives it (made by ``System.connect()``; read before
    that, it raises)."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, system: None, owner: type) -> _Plugin: ...
    @overload
    def __get__(self, system: System, owner: type) -> Plugin: ...
    def __get__(self, system: System | None, owner: type) -> _Plugin | Plugin:
        if system is None:
            return self
        plugin: Plugin | None = system._plugins.get(self.name)
        if plugin is None:
            raise RuntimeError(f"the MAVSDK {self.name} plugin is not ready: System.connect() has not run")
        return plugin


class System:
    """One gRPC session to a running mavsdk_server, with the gateway's plugins (``PLUGINS``).

    The same calls as ``mavsdk_grpc.System`` for those plugins (``await System(address, port).connect()``,
    then ``system.telemetry`` and so on), through `gateway.link.mavsdk_rpc`; it never starts a
    mavsdk_server of its own (the gateway's sidecar does), and ``close()`` closes its channel (its
    streams end, its calls fail with `ChannelClosed`)."""

    action = _Plugin()
    core = _Plugin()
    events = _Plugin()
    info = _Plugin()
    mavlink_direct = _Plugin()
    mission = _Plugin()
    mission_raw = _Plugin()
    param = _Plugin()
    telemetry = _Plugin()

    def __init__(self, mavsdk_server_address: str, port: int) -> None:
        self._address = mavsdk_server_address
        self._port = port
        self._channel: Channel | None = None
        self._plugins: dict[str, Plugin] = {}
        self.closed = False

    async def connect(self) -> None:
        """Connect to mavsdk_server (waits, trying again, until it accepts: the caller bounds the wait)
        and make the plugins."""
        channel = channel_for(self._address, self._port)
        self._channel = channel
        while True:
            try:
                await channel.__connect__()
                break
            except ChannelClosed:
                raise
            except OSError:
                if self.closed:
                    raise
                await asyncio.sleep(CONNECT_RETRY_S)
        self._plugins = {
            name: Plugin(channel, module, name, lambda: self.closed) for name, module in _MODULES.items()
        }

    async def close(self) -> None:
        """Close the channel (its streams end); nothing to do before ``connect``."""
        self.closed = True
        channel, self._channel = self._channel, None
        if channel is not None:
            channel.close()
