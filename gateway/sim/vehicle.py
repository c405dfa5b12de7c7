"""One simulated ArduCopter: state, MAVLink I/O and the clock.

Flight behaviour (modes, navigation) lives in ``flight.py``, command handling in ``commands.py``, the
boot timeline and pre-arm checks in ``boot.py``, failsafe triggers and reactions in ``failsafe.py``;
this module ties them to the links and the clock. All times are *simulated* seconds since boot.
"""

from __future__ import annotations

import logging
import math
import random
import time

from pymavlink.dialects.v20 import ardupilotmega as mav

from gateway.sim import telemetry
from gateway.sim.battery import Battery
from gateway.sim.boot import BootSequence
from gateway.sim.commands import CommandHandler
from gateway.sim.failsafe import check_failsafes
from gateway.sim.flight import FlightController
from gateway.sim.link import Link, LinkFaults, TcpServerLink, UdpOutLink
from gateway.sim.mission import AutoState, MissionStore
from gateway.sim.modes import GUIDED_FLAG_MODES, Mode, mode_name
from gateway.sim.params import Param, ParamTable
from gateway.sim.physics import MAX_STEP_S, Body, LocalFrame
from gateway.sim.record import FlightRecord
from gateway.sim.streams import GROUP_PARAM
from gateway.sim.timeline import Timeline

log = logging.getLogger(__name__)


GPS_LOSS_TO_EKF_S = 1.0  # the EKF stops trusting its position this long after the GPS fix is gone


class SimVehicle:
    """A simulated ArduCopter 4.x speaking MAVLink 2 on a TCP port (and optionally UDP)."""

    def __init__(
        self,
        index: int,
        sysid: int,
        home: tuple[float, float, float, float],
        *,
        speedup: float = 1.0,
        seed: int | None = None,
        firmware: str = "4.7",
        bind: str = "127.0.0.1",
        tcp_port: int = 5760,
        udp_port: int | None = None,
        gcs_port: int | None = None,
        timeline: Timeline | None = None,
    ) -> None:
        """``gcs_port``: a second MAVLink TCP port (0: any free one) for another ground station, as
        SITL's SERIAL1 (5762): a pilot's GCS switching modes beside the gateway."""
        if not 1 <= sysid <= 255:
            raise ValueError(f"system id must be 1..255, got {sysid}")
        if not speedup > 0 or not math.isfinite(speedup):
            raise ValueError(f"speedup must be a positive number, got {speedup}")
        self.index = index
        self.speedup = speedup
        self.autopilot = mav.MAV_AUTOPILOT_ARDUPILOTMEGA  # what its HEARTBEAT announces (sim --autopilot)
        self.rng = random.Random(seed)
        self.timeline = timeline or Timeline()
        lat, lon, alt, heading = home
        self.frame = LocalFrame(lat, lon, alt)
        self.params = ParamTable(firmware, {"MAV_SYSID": sysid, "SIM_SPEEDUP": speedup})
        self.sysid = sysid
        self.uid2 = bytes(f"{(seed or 0) * 7919 + sysid:032x}"[-17:], "ascii") + b"\0"
        self._heading0 = heading % 360.0
        self.faults = LinkFaults(self.rng)
        self.gps_lost = False
        self.estimate_held = False  # the EKF never starts using GPS (as if still converging)
        self.battery = Battery()
        self.status_texts: list[tuple[float, int, str]] = []
        self.boots = 0
        self.record = FlightRecord()
        self.mission = MissionStore(self._mission_home, self.send_to, self._mission_uploaded, self.text)
        self.commands = CommandHandler(self)
        self._boot()
        # links
        self.links: list[Link] = [TcpServerLink(sysid, self._receive, self.faults, bind, tcp_port)]
        if udp_port:
            self.links.append(UdpOutLink(sysid, self._receive, self.faults, "127.0.0.1", udp_port))
        self.gcs_link: TcpServerLink | None = None
        if gcs_port is not None:
            self.gcs_link = TcpServerLink(sysid, self._receive, self.faults, bind, gcs_port)
            self.links.append(self.gcs_link)
        self._wall_last: float | None = None

    def _boot(self) -> None:
        """(Re)initialise the flight state as at power-on; parameters, mission and battery are kept."""
        self.boots += 1
        self.t = 0.0
        self.body = Body(yaw=self._heading0)
        self.mode = Mode.STABILIZE
        self.armed = False
        self.landed = True
        self.auto_armed = False
        self.home: tuple[float, float, float] | None = None
        self._gps_lost_at: float | None = None
        self.failsafe_gcs = False
        self.battery.failsafe = None
        self._gcs_last_seen: float | None = None
        self.flight_time_s = 0.0
        self._last_hb = -1.0
        self._last_timesync = 0.0
        self.auto = AutoState()
        self.flight = FlightController(self)
        self.boot_state = BootSequence(self)

    def reboot(self) -> None:
        """Restart like a rebooted autopilot: boot timeline from zero, stream rates gone, TCP clients
        dropped (they reconnect), MAV_SYSID re-read; parameters and the stored mission survive."""
        self.sysid = int(self.params.get("MAV_SYSID"))
        for link in self.links:
            link.codec.sysid = self.sysid
            link.streams.clear()
            if isinstance(link, TcpServerLink):
                link.drop_client()
        self._boot()

    # ------------------------------------------------------------------------------------------------
    # lifecycle
    async def start(self) -> None:
        for link in self.links:
            await link.start()
        self._wall_last = time.monotonic()

    async def stop(self) -> None:
        for link in self.links:
            await link.stop()

    @property
    def tcp_port(self) -> int:
        return self.links[0].port  # type: ignore[attr-defined]

    @property
    def url(self) -> str:
        link = self.links[0]
        return f"tcpout://{link.bind}:{link.port}"  # type: ignore[attr-defined]

    @property
    def udp_url(self) -> str | None:
        for link in self.links:
            if isinstance(link, UdpOutLink):
                return f"udpin://127.0.0.1:{link.port}"
        return None

    @property
    def gcs_url(self) -> str | None:
        """The second ground station's port (mavsdk_server / pymavlink syntax: tcpout / tcp:)."""
        link = self.gcs_link
        return None if link is None else f"tcpout://{link.bind}:{link.port}"

    def pilot_mode(self, name: str, text: str | None = None) -> None:
        """Switch mode as a pilot's RC switch or another ground station would (the gateway did not ask):
        ``text``, when given, is said first (as a failsafe announces itself). ValueError: no such mode
        or the autopilot refuses it (its words)."""
        try:
            mode = Mode[name.strip().upper()]
        except KeyError:
            raise ValueError(f"no such mode {name!r}") from None
        if text:
            self.text(mav.MAV_SEVERITY_CRITICAL, text)
        ok, why = self.flight.set_mode(int(mode))
        if not ok:
            raise ValueError(f"mode change to {mode.name} refused: {why}")

    # ------------------------------------------------------------------------------------------------
    # derived state
    @property
    def time_boot_ms(self) -> int:
        return int(self.t * 1000) & 0xFFFFFFFF

    @property
    def gps_detected(self) -> bool:
        return self.t >= self.timeline.gps_detect

    @property
    def gps_has_fix(self) -> bool:
        return self.t >= self.timeline.gps_fix and not self.gps_lost

    @property
    def origin_set(self) -> bool:
        return self.t >= self.timeline.origin

    @property
    def position_ok(self) -> bool:
        """The EKF has a horizontal position (it uses GPS and has not lost it)."""
        if self.t < self.timeline.ekf_gps or self.estimate_held:
            return False
        return not (
            self.gps_lost
            and self._gps_lost_at is not None
            and self.t - self._gps_lost_at >= GPS_LOSS_TO_EKF_S
        )

    @property
    def mode_is_auto(self) -> bool:
        return self.mode == Mode.AUTO

    @property
    def flying(self) -> bool:
        return self.armed and not self.landed

    def noise(self, sigma: float) -> float:
        return self.rng.gauss(0.0, sigma)

    def position(self) -> tuple[float, float, float]:
        lat, lon = self.frame.to_latlon(self.body.north, self.body.east)
        return lat, lon, self.frame.alt0 + self.body.up

    def gps_position(self) -> tuple[float, float, float]:
        """What the GPS reports: the true position (SITL's GPS noise defaults to 0 as well)."""
        return self.position()

    def rel_alt(self) -> float:
        home_alt = self.home[2] if self.home else self.frame.alt0
        return self.frame.alt0 + self.body.up - home_alt

    def wall_epoch_us(self) -> float:
        return time.time() * 1e6

    def landed_state(self) -> int:
        if not self.armed:
            return mav.MAV_LANDED_STATE_ON_GROUND
        if self.landed:  # spooling up counts as on the ground; touched down in LAND: still landing
            return (
                mav.MAV_LANDED_STATE_LANDING if self.flight.is_landing() else mav.MAV_LANDED_STATE_ON_GROUND
            )
        if self.flight.is_taking_off():
            return mav.MAV_LANDED_STATE_TAKEOFF
        if self.flight.is_landing():
            return mav.MAV_LANDED_STATE_LANDING
        return mav.MAV_LANDED_STATE_IN_AIR

    def nav_output(self) -> tuple[float, float, float]:
        return self.flight.nav_output()

    # ------------------------------------------------------------------------------------------------
    # output
    def heartbeat(self) -> mav.MAVLink_message:
        base = mav.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED | mav.MAV_MODE_FLAG_STABILIZE_ENABLED
        base |= mav.MAV_MODE_FLAG_MANUAL_INPUT_ENABLED
        booting = self.t < self.timeline.boot_done
        if booting or self.mode in GUIDED_FLAG_MODES:
            base |= mav.MAV_MODE_FLAG_GUIDED_ENABLED
        if self.armed:
            base |= mav.MAV_MODE_FLAG_SAFETY_ARMED
        if booting:
            status = mav.MAV_STATE_BOOT
        elif self.failsafe_gcs or self.battery.failsafe or self.flight.ekf_failsafe:
            status = mav.MAV_STATE_CRITICAL  # any failsafe, as ArduCopter's vehicle_system_status()
        else:
            status = (
                mav.MAV_STATE_ACTIVE if self.flying and not self.flight.on_ground() else mav.MAV_STATE_STANDBY
            )
        return mav.MAVLink_heartbeat_message(mav.MAV_TYPE_QUADROTOR, self.autopilot, base,
                                             int(self.mode), status, 3)  # fmt: skip

    def build(self, msg_id: int) -> mav.MAVLink_message | None:
        if msg_id == 0:
            return self.heartbeat()
        builder = telemetry.BUILDERS.get(msg_id)
        return builder(self) if builder else None

    def can_build(self, msg_id: int) -> bool:
        """True for every message id ArduCopter maps to an ap_message (some are never actually sent)."""
        return msg_id == 0 or msg_id in telemetry.BUILDERS or msg_id in telemetry.KNOWN_SILENT

    def send_to(self, link: Link, msg: mav.MAVLink_message) -> None:
        link.send(msg)

    def broadcast(self, msg: mav.MAVLink_message) -> None:
        for link in self.links:
            link.send(msg)

    def text(self, severity: int, text: str) -> None:
        self.status_texts.append((self.t, severity, text))
        del self.status_texts[:-200]
        log.debug("sysid %d: %s", self.sysid, text)
        self.broadcast(mav.MAVLink_statustext_message(severity, text.encode()[:50], 0, 0))

    def notify_param(self, name_47: str, value: float) -> None:
        """Change a parameter internally and announce it unsolicited (index 65535), as ArduPilot does."""
        param = self.params.set(self.params.canonical(name_47), value, notify=False)
        self.broadcast(self.param_value(param))

    def param_value(self, param: Param, index: int | None = None) -> mav.MAVLink_message:
        return mav.MAVLink_param_value_message(
            param.name.encode(), param.value, param.type, len(self.params), 65535 if index is None else index
        )

    # ------------------------------------------------------------------------------------------------
    # input
    def _receive(self, link: Link, msg: mav.MAVLink_message) -> None:
        try:
            self._dispatch(link, msg)
        except Exception:  # one bad message must not kill the vehicle
            log.exception("sysid %d: error handling %s", self.sysid, msg.get_type())

    def _targets_us(self, msg: mav.MAVLink_message) -> bool:
        target = getattr(msg, "target_system", None)
        return target is None or target in (0, self.sysid)

    def _dispatch(self, link: Link, msg: mav.MAVLink_message) -> None:
        kind = msg.get_type()
        if kind == "HEARTBEAT":
            if msg.get_srcSystem() == int(self.params.get("MAV_GCS_SYSID")):
                self._gcs_last_seen = self.t
            return
        if not self._targets_us(msg):
            return
        self.record.message(self.t, msg)
        if kind in ("COMMAND_LONG", "COMMAND_INT"):
            self.commands.handle(link, msg)
        elif not self.mission.handle(link, msg) and not self._dispatch_params(link, kind, msg):
            self._dispatch_control(link, kind, msg)

    def _dispatch_params(self, link: Link, kind: str, msg: mav.MAVLink_message) -> bool:
        """Parameter and stream-rate requests; False when ``kind`` is none of them."""
        if kind == "PARAM_REQUEST_LIST":
            self.commands.param_request_list(link)
        elif kind == "PARAM_REQUEST_READ":
            self.commands.param_request_read(link, msg)
        elif kind == "PARAM_SET":
            self.commands.param_set(link, msg)
        elif kind == "REQUEST_DATA_STREAM":
            self._request_data_stream(link, msg)
        else:
            return False
        return True

    def _dispatch_control(self, link: Link, kind: str, msg: mav.MAVLink_message) -> None:
        if kind == "SET_MODE":
            if msg.base_mode & mav.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED:
                self.flight.set_mode(msg.custom_mode)
        elif kind == "MISSION_SET_CURRENT":
            if self.flight.set_mission_current(msg.seq):
                link.send(telemetry.mission_current(self))
        elif kind == "TIMESYNC":
            if msg.tc1 == 0:
                link.send(mav.MAVLink_timesync_message(time.monotonic_ns(), msg.ts1))
        elif kind in ("SET_POSITION_TARGET_GLOBAL_INT", "SET_POSITION_TARGET_LOCAL_NED"):
            self.flight.position_target(msg)

    def _request_data_stream(self, link: Link, msg: mav.MAVLink_message) -> None:
        hz = msg.req_message_rate if msg.start_stop else 0
        changed = link.streams.set_group(msg.req_stream_id, hz)
        channel = self.links.index(link)
        for group in changed:
            name = f"MAV{channel + 1}_{GROUP_PARAM[group]}"
            param = self.params.find(self.params.canonical(name))
            if param is not None:
                self.params.set(param.name, hz, notify=False)

    def _mission_home(self) -> tuple[float, float, float]:
        if self.home is not None:
            return self.home
        return self.frame.lat0, self.frame.lon0, self.frame.alt0

    def _mission_uploaded(self, count: int) -> None:
        self.notify_param("MIS_TOTAL", count)  # AP_Mission's total includes home
        self.record.mission_stored(self.mission.items[1:])
        self.flight.mission_changed()

    # ------------------------------------------------------------------------------------------------
    # clock
    def tick(self) -> None:
        """Advance by the wall time elapsed since the last tick times the speed-up, in small steps."""
        now = time.monotonic()
        if self._wall_last is None:
            self._wall_last = now
        elapsed = (now - self._wall_last) * self.speedup
        self._wall_last = now
        elapsed = min(elapsed, 60.0)  # a suspended process resumes without simulating hours
        while elapsed > 1e-9:
            dt = min(MAX_STEP_S, elapsed)
            elapsed -= dt
            self._step(dt)
            self._emit()  # per step, so streams keep their spacing in simulated time
        self.mission.tick(now)

    def _step(self, dt: float) -> None:
        self.t += dt
        self.boot_state.step()
        self.flight.step(dt)
        if self.flying:
            self.flight_time_s += dt
        if not self.battery.follow_charge and self.params.get("SIM_BATT_CAP_AH") > 0:
            self.battery.follow_charge = True
        if (capacity := self.params.get("BATT_CAPACITY")) > 0:
            self.battery.capacity_mah = capacity  # as ArduPilot: remaining % is consumed mAh of BATT_CAPACITY
        self.battery.drain(dt, self.armed, self.flying)
        check_failsafes(self)
        self.record.sample(self)

    def set_origin(self) -> None:
        self.home = self.position()
        if self.params.get("MIS_TOTAL") < 1:
            self.notify_param("MIS_TOTAL", 1)  # home becomes mission item 0
        for builder in (telemetry.gps_global_origin, telemetry.home_position):
            msg = builder(self)
            if msg is not None:
                self.broadcast(msg)

    def set_home_here(self) -> None:
        self.set_home(self.position())

    def set_home(self, home: tuple[float, float, float]) -> None:
        """New home (at arming, DO_SET_HOME): announced at once, as Copter::set_home() does."""
        self.home = home
        for builder in (telemetry.home_position, telemetry.gps_global_origin):
            msg = builder(self)
            if msg is not None:
                self.broadcast(msg)

    def _emit(self) -> None:
        if self.t - self._last_hb >= 1.0:
            self._last_hb = self.t
            self.broadcast(self.heartbeat())
        if self.t - self._last_timesync >= 10.0:
            self._last_timesync = self.t
            self.broadcast(mav.MAVLink_timesync_message(0, round(self.t * 1e6) * 1000 + self.sysid))
        for link in self.links:
            if not link.connected:
                continue
            for msg_id in link.streams.due(self.t):
                msg = self.build(msg_id)
                if msg is not None:
                    link.send(msg)

    # ------------------------------------------------------------------------------------------------
    # fault injection and inspection
    def set_link(self, up: bool) -> None:
        self.faults.up = up

    def set_packet_loss(self, pct: float) -> None:
        if not 0 <= pct <= 100:
            raise ValueError(f"packet loss must be 0..100 %, got {pct}")
        self.faults.loss_pct = pct

    def set_gps(self, ok: bool) -> None:
        self.gps_lost = not ok

    def hold_estimate(self, held: bool) -> None:
        """Hold the EKF's position estimate back (GPS fix, home and the pre-arm bit in STABILIZE are
        unaffected): arming in GUIDED is refused with "Need Position Estimate", as on a real ArduCopter
        whose EKF is still converging, until it is released."""
        self.estimate_held = held

    def set_battery(self, pct: float) -> None:
        if not 0 <= pct <= 100:
            raise ValueError(f"battery level must be 0..100 %, got {pct}")
        self.battery.set_remaining(pct)

    def set_mission_capacity(self, items: int | None) -> None:
        """How many mission items the storage holds, home included (None: unlimited), as a board with
        little storage: a longer upload is refused with MISSION_ACK NO_SPACE."""
        if items is not None and not (isinstance(items, int) and 1 <= items <= 65535):
            raise ValueError(
                f"mission capacity must be 1..65535 items (home included) or null; got {items!r}"
            )
        self.mission.max_items = items

    def state(self) -> dict:
        lat, lon, alt = self.position()
        return {
            "index": self.index,
            "sysid": self.sysid,
            "url": self.url,
            "udp_url": self.udp_url,
            "gcs_url": self.gcs_url,
            "t_boot_s": round(self.t, 3),
            "boots": self.boots,
            "mode": mode_name(self.mode),
            "armed": self.armed,
            "landed": self.landed,
            "lat": lat,
            "lon": lon,
            "alt_amsl_m": alt,
            "rel_alt_m": self.rel_alt(),
            "heading_deg": self.body.yaw,
            "ground_speed_mps": self.body.ground_speed,
            "climb_mps": self.body.vu,
            "home": None
            if self.home is None
            else {"lat": self.home[0], "lon": self.home[1], "alt": self.home[2]},
            "battery_pct": self.battery.remaining_pct,
            "battery_v": self.battery.voltage,
            "gps_ok": not self.gps_lost,
            "estimate_held": self.estimate_held,
            "link_up": self.faults.up,
            "packet_loss_pct": self.faults.loss_pct,
            "failsafe_gcs": self.failsafe_gcs,
            "gcs_heartbeat_age_s": None
            if self._gcs_last_seen is None
            else round(self.t - self._gcs_last_seen, 3),
            "failsafe_battery": self.battery.failsafe,
            "position_ok": self.position_ok,
            "mission_current": self.auto.current,
            "mission_count": self.mission.count(),
            "mission_capacity": self.mission.max_items,
            "client_connected": self.links[0].connected,
            "links": [link.describe() for link in self.links],
        }
