"""A MAVSDK System with only the plugins the gateway uses; the one place the gateway imports mavsdk_grpc.

``mavsdk_grpc``'s package ``__init__`` imports its ``System``, whose module imports all 40 plugin modules
with their protobuf modules (about 12 MiB of the gateway's memory), and ``System.connect`` makes a
gRPC stub for each of the 40 on every session. The gateway uses 9 (``PLUGINS``). Here the package is
registered as a bare package (its directory, without running its ``__init__``) before anything of it
is imported, so only the plugin modules asked for are loaded, and ``System`` makes only their stubs.
A program that imports ``mavsdk_grpc`` itself before this module (the tests' helpers, the benchmarks)
gets the whole package as usual, and this module works on that too; ``mavsdk_grpc.System`` stays
reachable on the bare package (imported when first asked for).

The gateway's gRPC client runs without gRPC's EventEngine client (``CLIENT_EXPERIMENTS``, put in the
environment when this module is imported, before the first channel initialises gRPC, unless
``GRPC_EXPERIMENTS`` is set already): with it, each stream item crosses an EventEngine thread, then the
asyncio poller thread, then the event loop; without it the poller thread reads the socket itself.
Measured with ``bench/wakeups.py`` (8 drones at rest, each setting beside the other under the same load):
the gateway's thread wake-ups per drone 57 -> 21 a second, its CPU per drone 0.243 -> 0.214 % of a core.

What the bare package leaves out of the ``__init__``: a Python version check, a warning for the
package's old name, and ``asyncio.set_event_loop_policy(uvloop.EventLoopPolicy())`` when uvloop is
installed (it is not a dependency; the gateway runs on the loop its server or ``asyncio.run`` makes).
"""

from __future__ import annotations

import os
import types
from collections.abc import Callable
from pathlib import Path
from typing import Any, Generic, TypeVar, overload

from gateway.util.bare_package import register_bare_package

#: gRPC experiments turned off in the gateway's process (its sidecars inherit them; measured without
#: effect there): the EventEngine client and what rides on it, so a stream item wakes one thread less
CLIENT_EXPERIMENTS = "-event_engine_client,-event_engine_for_all_other_endpoints,-event_engine_callback_cq"
os.environ.setdefault("GRPC_EXPERIMENTS", CLIENT_EXPERIMENTS)


def _library_name(_package: types.ModuleType, name: str) -> Any:  # Any: mavsdk_grpc, untyped
    if name == "System":  # the library's own System, with all its plugins
        from mavsdk_grpc.system import System as LibrarySystem

        return LibrarySystem
    raise AttributeError(f"module 'mavsdk_grpc' has no attribute {name!r}")


register_bare_package("mavsdk_grpc", _library_name, "the mavsdk_grpc package (mavsdk-grpc)")

# ruff: noqa: E402 - these must come after the bare package is registered
from mavsdk_grpc import action as action_plugin
from mavsdk_grpc import core as core_plugin
from mavsdk_grpc import events as events_plugin
from mavsdk_grpc import info as info_plugin
from mavsdk_grpc import mavlink_direct as mavlink_direct_plugin
from mavsdk_grpc import mission as mission_plugin
from mavsdk_grpc import mission_raw as mission_raw_plugin
from mavsdk_grpc import param as param_plugin
from mavsdk_grpc import telemetry as telemetry_plugin
from mavsdk_grpc.async_plugin_manager import AsyncPluginManager


def bundled_binary() -> Path:
    """The mavsdk_server binary shipped with the mavsdk-grpc package."""
    import mavsdk_grpc.bin as bin_pkg

    return Path(bin_pkg.__file__).parent / "mavsdk_server"


__all__ = ["PLUGINS", "System", "mavlink_direct_plugin", "mission_raw_plugin"]

P = TypeVar("P")


class _Plugin(Generic[P]):
    """A plugin of the `System`, by the name MAVSDK gives it: its stub, made by ``make`` in
    ``System.connect()``; read before that, it raises."""

    def __init__(self, make: Callable[[Any], P]) -> None:  # Any: mavsdk_grpc, its untyped plugin manager
        self.make = make
        self.name = ""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, system: None, owner: type) -> _Plugin[P]: ...
    @overload
    def __get__(self, system: System, owner: type) -> P: ...
    def __get__(self, system: System | None, owner: type) -> _Plugin[P] | P:
        if system is None:
            return self
        stub: P | None = getattr(system, f"_{self.name}_stub", None)
        if stub is None:
            raise RuntimeError(f"the MAVSDK {self.name} plugin is not ready: System.connect() has not run")
        return stub


class System:
    """One gRPC session to a running mavsdk_server, with the gateway's plugins (``PLUGINS``).

    The same calls as ``mavsdk_grpc.System`` for those plugins (``await System(address, port).connect()``,
    then ``system.telemetry`` and so on); it never starts a mavsdk_server of its own (the gateway's
    sidecar does), and ``close()`` closes its gRPC channel."""

    action = _Plugin(action_plugin.Action)
    core = _Plugin(core_plugin.Core)
    events = _Plugin(events_plugin.Events)
    info = _Plugin(info_plugin.Info)
    mavlink_direct = _Plugin(mavlink_direct_plugin.MavlinkDirect)
    mission = _Plugin(mission_plugin.Mission)
    mission_raw = _Plugin(mission_raw_plugin.MissionRaw)
    param = _Plugin(param_plugin.Param)
    telemetry = _Plugin(telemetry_plugin.Telemetry)

    def __init__(self, mavsdk_server_address: str, port: int) -> None:
        self._address = mavsdk_server_address
        self._port = port
        self._manager: Any = None  # Any: mavsdk_grpc, its untyped channel manager

    async def connect(self) -> None:
        """Open the gRPC channel (waits until mavsdk_server answers) and make the plugins' stubs."""
        manager = await AsyncPluginManager.create(host=self._address, port=self._port)
        self._manager = manager
        for name, plugin in _PLUGINS.items():
            setattr(self, f"_{name}_stub", plugin.make(manager))

    async def close(self) -> None:
        """Close the gRPC channel (its streams end); nothing to do before ``connect``."""
        manager, self._manager = self._manager, None
        if manager is not None:
            await manager.channel.close(grace=None)


_PLUGINS = {name: plugin for name, plugin in vars(System).items() if isinstance(plugin, _Plugin)}
#: the plugins the gateway uses, by the name MAVSDK gives them
PLUGINS = tuple(_PLUGINS)
