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

import importlib.util
import os
import sys
import types
from pathlib import Path
from typing import Any

#: gRPC experiments turned off in the gateway's process (its sidecars inherit them; measured without
#: effect there): the EventEngine client and what rides on it, so a stream item wakes one thread less
CLIENT_EXPERIMENTS = "-event_engine_client,-event_engine_for_all_other_endpoints,-event_engine_callback_cq"
os.environ.setdefault("GRPC_EXPERIMENTS", CLIENT_EXPERIMENTS)


def _install_bare_package() -> None:
    if "mavsdk_grpc" in sys.modules:
        return
    spec = importlib.util.find_spec("mavsdk_grpc")  # finds the package without running its __init__
    if spec is None or spec.submodule_search_locations is None:
        raise ImportError("the mavsdk_grpc package (mavsdk-grpc) is not installed")
    package = types.ModuleType("mavsdk_grpc")
    package.__spec__ = spec
    package.__file__ = spec.origin
    package.__path__ = list(spec.submodule_search_locations)
    package.__package__ = "mavsdk_grpc"

    def whole_package_name(name: str) -> Any:  # Any: mavsdk_grpc, untyped
        if name == "System":  # the library's own System, with all its plugins
            from mavsdk_grpc.system import System as LibrarySystem

            return LibrarySystem
        raise AttributeError(f"module 'mavsdk_grpc' has no attribute {name!r}")

    package.__getattr__ = whole_package_name  # type: ignore[method-assign]
    sys.modules["mavsdk_grpc"] = package


_install_bare_package()

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


#: the plugins the gateway uses, by the name MAVSDK gives them
PLUGINS = (
    "action",
    "core",
    "events",
    "info",
    "mavlink_direct",
    "mission",
    "mission_raw",
    "param",
    "telemetry",
)

__all__ = ["PLUGINS", "System", "mavlink_direct_plugin", "mission_raw_plugin"]


class System:
    """One gRPC session to a running mavsdk_server, with the gateway's plugins (``PLUGINS``).

    The same calls as ``mavsdk_grpc.System`` for those plugins (``await System(address, port).connect()``,
    then ``system.telemetry`` and so on); it never starts a mavsdk_server of its own (the gateway's
    sidecar does), and ``close()`` closes its gRPC channel."""

    def __init__(self, mavsdk_server_address: str, port: int) -> None:
        self._address = mavsdk_server_address
        self._port = port
        self._manager: Any = None  # Any: mavsdk_grpc, its untyped channel manager
        self._action: action_plugin.Action | None = None
        self._core: core_plugin.Core | None = None
        self._events: events_plugin.Events | None = None
        self._info: info_plugin.Info | None = None
        self._mavlink_direct: mavlink_direct_plugin.MavlinkDirect | None = None
        self._mission: mission_plugin.Mission | None = None
        self._mission_raw: mission_raw_plugin.MissionRaw | None = None
        self._param: param_plugin.Param | None = None
        self._telemetry: telemetry_plugin.Telemetry | None = None

    async def connect(self) -> None:
        """Open the gRPC channel (waits until mavsdk_server answers) and make the plugins' stubs."""
        manager = await AsyncPluginManager.create(host=self._address, port=self._port)
        self._manager = manager
        self._action = action_plugin.Action(manager)
        self._core = core_plugin.Core(manager)
        self._events = events_plugin.Events(manager)
        self._info = info_plugin.Info(manager)
        self._mavlink_direct = mavlink_direct_plugin.MavlinkDirect(manager)
        self._mission = mission_plugin.Mission(manager)
        self._mission_raw = mission_raw_plugin.MissionRaw(manager)
        self._param = param_plugin.Param(manager)
        self._telemetry = telemetry_plugin.Telemetry(manager)

    async def close(self) -> None:
        """Close the gRPC channel (its streams end); nothing to do before ``connect``."""
        manager, self._manager = self._manager, None
        if manager is not None:
            await manager.channel.close(grace=None)

    @staticmethod
    def _ready(plugin: Any, name: str) -> Any:  # Any: mavsdk_grpc, its untyped plugins
        if plugin is None:
            raise RuntimeError(f"the MAVSDK {name} plugin is not ready: System.connect() has not run")
        return plugin

    @property
    def action(self) -> action_plugin.Action:
        return self._ready(self._action, "action")

    @property
    def core(self) -> core_plugin.Core:
        return self._ready(self._core, "core")

    @property
    def events(self) -> events_plugin.Events:
        return self._ready(self._events, "events")

    @property
    def info(self) -> info_plugin.Info:
        return self._ready(self._info, "info")

    @property
    def mavlink_direct(self) -> mavlink_direct_plugin.MavlinkDirect:
        return self._ready(self._mavlink_direct, "mavlink_direct")

    @property
    def mission(self) -> mission_plugin.Mission:
        return self._ready(self._mission, "mission")

    @property
    def mission_raw(self) -> mission_raw_plugin.MissionRaw:
        return self._ready(self._mission_raw, "mission_raw")

    @property
    def param(self) -> param_plugin.Param:
        return self._ready(self._param, "param")

    @property
    def telemetry(self) -> telemetry_plugin.Telemetry:
        return self._ready(self._telemetry, "telemetry")
