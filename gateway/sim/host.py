"""The simulated vehicle as its parts see it.

The parts (`flight.py` with its `guided.py`, `auto.py` and `failsafe.py` mixins, `boot.py`, `commands.py`,
`telemetry.py`) are handed their `SimVehicle` and read and act on it through `SimHost`, so none of them
imports the vehicle module that builds them. `SimVehicle` satisfies it.
"""

from __future__ import annotations

from typing import Protocol

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim.battery import Battery
from gateway.sim.mission import AutoState, MissionStore
from gateway.sim.modes import Mode
from gateway.sim.params import Param, ParamTable
from gateway.sim.physics import Body, LocalFrame
from gateway.sim.timeline import Timeline


class BootView(Protocol):
    """What the other parts read of the boot sequence (`gateway.sim.boot.BootSequence`)."""

    def prearm_bit(self) -> bool: ...

    def prearm_failures(self, mode: Mode | None = None) -> list[str]: ...

    def stat_params(self) -> None: ...


class FlightView(Protocol):
    """What the other parts use of the flight logic (`gateway.sim.flight.FlightController`)."""

    target: tuple[float, float, float] | None
    fence_breaches: int

    def arm(self, force: bool) -> tuple[bool, list[str]]: ...

    def disarm(self, reason: str | None = None) -> None: ...

    def set_mode(self, number: int, announce_failure: bool = True) -> tuple[bool, str | None]: ...

    def takeoff(self, alt_rel: float) -> bool: ...

    def guided_goto(self, north: float, east: float, up: float, yaw: float | None = None) -> bool: ...

    def _alt_to_up(self, alt: float, frame: int) -> float: ...

    def condition_yaw(self, angle: float, rate: float, direction: float, relative: bool) -> bool: ...

    def change_speed(self, kind: int, speed: float) -> bool: ...

    def destination_allowed(self, north: float, east: float, up: float) -> bool: ...

    def stopping_point(self) -> tuple[float, float, float]: ...

    def set_mission_current(self, seq: int) -> bool: ...

    def start_mission(self) -> None: ...

    def gcs_failsafe(self, fs_gcs: int) -> None: ...

    def battery_failsafe(self, action: int) -> None: ...

    def ekf_check(self) -> None: ...


class SimHost(Protocol):
    """The vehicle's state and actions its parts use (`gateway.sim.vehicle.SimVehicle`)."""

    # its parts (made again at each boot) and stores
    @property
    def flight(self) -> FlightView: ...

    @property
    def boot_state(self) -> BootView: ...

    auto: AutoState
    mission: MissionStore
    params: ParamTable
    battery: Battery
    body: Body
    frame: LocalFrame
    timeline: Timeline
    # state
    t: float
    speedup: float
    uid2: bytes
    mode: Mode
    armed: bool
    landed: bool
    auto_armed: bool
    home: tuple[float, float, float] | None
    gps_lost: bool
    failsafe_gcs: bool
    flight_time_s: float
    _gps_lost_at: float | None
    _gcs_last_seen: float | None

    @property
    def flying(self) -> bool: ...

    @property
    def position_ok(self) -> bool: ...

    @property
    def origin_set(self) -> bool: ...

    @property
    def gps_detected(self) -> bool: ...

    @property
    def gps_has_fix(self) -> bool: ...

    @property
    def mode_is_auto(self) -> bool: ...

    @property
    def time_boot_ms(self) -> int: ...

    def position(self) -> tuple[float, float, float]: ...

    def gps_position(self) -> tuple[float, float, float]: ...

    def rel_alt(self) -> float: ...

    def noise(self, sigma: float) -> float: ...

    def wall_epoch_us(self) -> float: ...

    def landed_state(self) -> int: ...

    def nav_output(self) -> tuple[float, float, float]: ...

    # output
    def heartbeat(self) -> mav.MAVLink_message: ...

    def build(self, msg_id: int) -> mav.MAVLink_message | None: ...

    def can_build(self, msg_id: int) -> bool: ...

    def broadcast(self, msg: mav.MAVLink_message) -> None: ...

    def text(self, severity: int, text: str) -> None: ...

    def notify_param(self, name_47: str, value: float) -> None: ...

    def param_value(self, param: Param, index: int | None = None) -> mav.MAVLink_message: ...

    # actions
    def reboot(self) -> None: ...

    def set_origin(self) -> None: ...

    def set_home(self, home: tuple[float, float, float]) -> None: ...

    def set_home_here(self) -> None: ...
