"""A fake gateway for *unit* tests of the MCP surface (in-process client, no sidecars). Integration tests
use the real simulator and mavsdk_server instead."""

from __future__ import annotations

import asyncio
import time
from collections import deque
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

from gateway.config import Settings
from gateway.errors import UnknownVehicle, VehicleNotReady
from gateway.fleet import geo
from gateway.fleet.dialects import ARDUPILOT
from gateway.fleet.modes import ModeChoice, require_mode
from gateway.fleet.operations import OperationManager

HOME = (47.397742, 8.545594, 488.0)


@dataclass
class Sample:
    value: Any
    received_at: float = field(default_factory=time.monotonic)

    @property
    def age_s(self) -> float:
        return time.monotonic() - self.received_at


def _pos(lat: float, lon: float, alt: float) -> SimpleNamespace:
    return SimpleNamespace(lat_deg=lat, lon_deg=lon, rel_alt_m=alt, abs_alt_m=HOME[2] + alt)


class FakeTelemetry(SimpleNamespace):
    live = True

    def snapshot(self) -> dict[str, Any]:
        return {
            k: {"value": v.value, "age_s": v.age_s} for k, v in vars(self).items() if isinstance(v, Sample)
        }


class FakeVehicle:
    """Moves at `speed` m/s in a straight line toward its target; records every command sent."""

    def __init__(self, vid: str, speed: float = 40.0) -> None:
        self.id = vid
        self.spec = SimpleNamespace(id=vid, name=vid.upper())
        self.state = "ready"
        self.speed = speed
        self.sent: list[tuple] = []
        self.params = {"WPNAV_SPEED": 1000.0, "RTL_ALT": 1500.0, "FENCE_ENABLE": 0.0}
        self.params.update({f"SR0_P{i:03d}": float(i) for i in range(300)})
        self.mission: list[Any] = []
        self.telemetry = FakeTelemetry(
            position=Sample(_pos(*HOME[:2], 0.0)),
            home=Sample(_pos(*HOME[:2], 0.0)),
            armed=Sample(False),
            in_air=Sample(False),
            heading_deg=Sample(0.0),
            velocity_ned=Sample(SimpleNamespace(north_mps=0.0, east_mps=0.0, down_mps=0.0)),
            battery=Sample(SimpleNamespace(remaining_pct=87.0, voltage_v=12.3)),
            attitude=Sample(SimpleNamespace(roll_deg=0.1, pitch_deg=-0.2, yaw_deg=0.0)),
            gps_info=Sample(SimpleNamespace(num_satellites=12, fix_type="FIX_3D")),
            flight_mode=Sample("STABILIZE"),
            landed_state=Sample("ON_GROUND"),
            health=Sample({"is_gyrometer_calibration_ok": True, "is_armable": True}),
            rc_status=Sample({"is_available": False, "signal_strength_percent": 0.0}),
            imu=Sample({"temperature_degc": 30.0}),
            odometry=Sample({"x_m": 0.0}),
            mission_progress=Sample(SimpleNamespace(current=0, total=0)),
            status_texts=deque(
                [(time.time(), "INFO", "ArduCopter V4.7"), (time.time(), "WARNING", "PreArm ok")]
            ),
        )
        self._task: asyncio.Task | None = None
        self.arm_delay_s = 0.0

    # --- state helpers
    def _set(self, **parts: Any) -> None:
        for k, v in parts.items():
            setattr(self.telemetry, k, Sample(v))

    def pos(self) -> tuple[float, float, float]:
        p = self.telemetry.position.value
        return p.lat_deg, p.lon_deg, p.rel_alt_m

    def status(self) -> dict[str, Any]:
        return {"state": self.state, "is_simulator": True}

    def return_altitude_param(self) -> tuple[str, float]:
        return "RTL_ALT", 100.0  # this fake is an ArduPilot before 4.7

    async def set_return_altitude(self, alt_m: float) -> tuple[str, float]:
        stored, _kind = await self.set_param("RTL_ALT", round(alt_m * 100))
        return "RTL_ALT", stored

    @property
    def protected_params(self) -> tuple[str, ...]:
        return ARDUPILOT.protected_params

    def initialising(self) -> str | None:
        return None

    async def wait_initialised(self) -> None:
        self.require_ready()

    def require_ready(self) -> None:
        if self.state != "ready":
            raise VehicleNotReady(f"drone {self.id} is not ready (state: {self.state})")

    def _fly(self, lat: float, lon: float, alt: float, then: Any = None) -> None:
        if self._task is not None:
            self._task.cancel()

        async def run() -> None:
            while True:
                la, lo, al = self.pos()
                n, e = geo.ned_offset(la, lo, lat, lon)
                d = (n * n + e * e + (alt - al) ** 2) ** 0.5
                step = self.speed * 0.05
                if d <= step:
                    self._set(position=_pos(lat, lon, alt))
                    break
                f = step / d
                la2, lo2 = geo.offset_position(la, lo, n * f, e * f)
                self._set(position=_pos(la2, lo2, al + (alt - al) * f))
                await asyncio.sleep(0.05)
            if then:
                then()

        self._task = asyncio.create_task(run())

    # --- actions (contract of gateway.fleet.vehicle.Vehicle)
    async def arm(self) -> None:
        self.sent.append(("arm",))
        self._set(armed=True, flight_mode="GUIDED")

    async def disarm(self) -> None:
        self.sent.append(("disarm",))
        self._set(armed=False)

    async def kill(self) -> None:
        self.sent.append(("kill",))
        self._set(armed=False, in_air=False, position=_pos(*self.pos()[:2], 0.0))

    async def takeoff(self, alt: float) -> None:
        await asyncio.sleep(self.arm_delay_s)  # arming takes a while on a real vehicle
        self.sent.append(("takeoff", alt))
        self._set(armed=True, in_air=True, flight_mode="GUIDED")
        self._fly(*self.pos()[:2], alt)

    async def goto(self, lat: float, lon: float, alt: float, yaw: float | None = None) -> None:
        self.sent.append(("goto", lat, lon, alt))
        self._fly(lat, lon, alt)

    async def hold(self) -> None:
        self.sent.append(("hold",))
        if self._task:
            self._task.cancel()

    def _landed(self) -> None:
        self._set(in_air=False, armed=False)

    async def land(self) -> None:
        self.sent.append(("land",))
        self._fly(*self.pos()[:2], 0.0, then=self._landed)

    async def return_to_launch(self) -> None:
        self.sent.append(("rtl",))
        self._fly(HOME[0], HOME[1], 0.0, then=self._landed)

    async def set_yaw(self, heading: float) -> None:
        self.sent.append(("yaw", heading))
        self._set(heading_deg=heading)

    async def set_max_speed(self, mps: float) -> None:
        self.sent.append(("speed", mps))

    def resolve_mode(self, name: str) -> ModeChoice:
        return require_mode(name, ARDUPILOT, self.id)

    async def set_flight_mode(self, name: str) -> None:
        self.resolve_mode(name)
        self.sent.append(("mode", name))
        self._set(flight_mode=name)

    async def upload_mission(self, items: list[Any]) -> None:
        self.sent.append(("upload", len(items)))
        self.mission = list(items)
        self._set(mission_progress=SimpleNamespace(current=0, total=len(items)))

    async def download_mission(self) -> list[Any]:
        return list(self.mission)

    async def clear_mission(self) -> None:
        self.sent.append(("clear",))
        self.mission = []

    async def start_mission(self) -> None:
        self.sent.append(("start_mission",))
        self._set(
            in_air=True, armed=True, mission_progress=SimpleNamespace(current=1, total=len(self.mission))
        )
        last = self.mission[-1]
        self._fly(last.lat, last.lon, max(last.alt_rel_m, 5.0), then=self._mission_done)

    def _mission_done(self) -> None:
        self._set(mission_progress=SimpleNamespace(current=len(self.mission), total=len(self.mission)))
        self.finished = True

    async def is_mission_finished(self) -> bool:
        return bool(getattr(self, "finished", False))

    async def set_current_mission_item(self, index: int) -> None:
        self.sent.append(("set_current", index))

    async def get_param(self, name: str) -> tuple[float, str]:
        return self.params[name], "float"

    async def set_param(self, name: str, value: float) -> tuple[float, str]:
        self.sent.append(("param", name, value))
        self.params[name] = value
        return value, "float"

    async def list_params(self) -> dict[str, float]:
        return dict(self.params)


class FakeRegistry:
    def __init__(self, vehicles: list[FakeVehicle]) -> None:
        self.vehicles = {v.id: v for v in vehicles}

    def get(self, vid: str) -> FakeVehicle:
        try:
            return self.vehicles[vid]
        except KeyError:
            raise UnknownVehicle(vid, list(self.vehicles)) from None

    def all(self) -> list[FakeVehicle]:
        return list(self.vehicles.values())


class FakeGateway:
    def __init__(self, settings: Settings, store: Any = None, n: int = 2) -> None:
        self.settings = settings
        self.store = store
        self.registry = FakeRegistry([FakeVehicle(f"d{i + 1}") for i in range(n)])
        self.operations = OperationManager(settings, store)
