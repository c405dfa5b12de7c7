"""Real autopilots (test equipment): ArduCopter SITL and PX4 SIH started from the binaries that
``eval "$(../shared/sitl/install)"`` points at (``ARDUPILOT_SITL``, ``ARDUPILOT_DEFAULTS``, ``PX4_BUILD``).

Used by the ``tests/real`` fixtures and by benchmarks that compare the simulator with a real autopilot.
Each autopilot runs on an instance number whose ports are free, in a folder of the caller's, in its own
process group, and is always stopped (SIGTERM, then SIGKILL)."""

from __future__ import annotations

import contextlib
import fcntl
import os
import random
import signal
import socket
import subprocess
import tempfile
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from tests.helpers.timing import scaled

HOME = (-35.363261, 149.165230, 584.0, 353.0)  # lat, lon, alt AMSL, heading: ArduPilot's CMAC

#: PX4 SIH's simulation speed (PX4_SIM_SPEED_FACTOR), for test modules that set none of their own. SIH
#: in SITL runs lockstep: its simulated clock drives PX4's, so at factor F the autopilot lives F seconds
#: per wall second when it gets the CPU, and slower when it does not. Measured on a 2-core machine as CI has
#: (load average 5-10 from other work), one PX4, 25-30 s windows, CPU from /proc/<pid>/stat, simulated
#: time from time_boot_ms:
#:
#:   factor   on the ground        hovering at 2.5 m
#:   1        20 % CPU, 0.99 x     20 % CPU, 0.99 x
#:   2        35 % CPU, 1.94 x     30 % CPU, 1.95 x
#:   3        51 % CPU, 2.86 x     48 % CPU, 2.88 x
#:   4        54 % CPU, 3.75 x     59 % CPU, 3.77 x
#:   4 on one core beside two busy loops: 27 % CPU, 3.84 x, hovering within 3 cm
#:
#: 3 keeps one PX4 near half a core, so that with the gateway and its sidecar a test worker stays within
#: its own core; a module flying several PX4 at once sets a lower factor
#: (test_tour_px4.py: three in real time).
PX4_SPEED_FACTOR = 3.0

#: The test equipment climbs, descends and lands faster than PX4's defaults, kept beside the speed
#: factor: every takeoff, Return and landing of the tests flies at these rates, which halve those legs
#: again, and no check depends on PX4's default rates. Set at boot through PX4_PARAM_<name>, which
#: etc/init.d-posix/rcS applies after the airframe; never by the gateway. Each stays within PX4's range
#: (parameters.json of the build) and the gateway's max_vertical_speed_mps (5 m/s). What each does, from
#: PX4's mc_pos_control and navigator sources. Return descends to RTL_DESCEND_ALT (30 m) before it lands:
#: kept, so a pilot's Return keeps the drone in the air for the takeover tests' 10 s of the agent trying
#: (at 10 m the drone was down within them).
PX4_TEST_PARAMS: dict[str, float] = {
    "MPC_TKO_SPEED": 3.0,  # takeoff climb rate (1.5 m/s; range 1-5)
    "MPC_Z_V_AUTO_DN": 3.0,  # descent in autonomous modes: RTL, Land above MPC_LAND_ALT1 (1.5; 0.5-4)
    "MPC_Z_VEL_MAX_DN": 3.0,  # the cap of every descent, MPC_Z_V_AUTO_DN included (1.5; 0.5-4)
    "MPC_LAND_SPEED": 1.5,  # the last metres of a landing, below MPC_LAND_ALT2 (0.7; min 0.6)
    "MPC_LAND_ALT1": 5.0,  # from here down the descent slows towards MPC_LAND_SPEED (10 m)
    "MPC_LAND_ALT2": 2.0,  # from here down it is MPC_LAND_SPEED (5 m)
    "RTL_RETURN_ALT": 30.0,  # Return climbs to at most this (RTL_CONE_ANG lowers it near home; 60 m)
}


class Unavailable(RuntimeError):
    """The autopilot cannot be started here (variables unset, no free instance); the text says why."""


@dataclass
class Autopilot:
    url: str  # for mavsdk_server
    process: subprocess.Popen[bytes]
    log: Path
    started_at: float  # time.monotonic() just before the process was started
    #: another ground station's way in (pymavlink syntax): ArduCopter SITL's SERIAL1 TCP port, PX4's GCS
    #: MAVLink instance (UDP; it answers whoever writes to it)
    gcs: str | None = None

    def log_tail(self, n: int = 30) -> str:
        with contextlib.suppress(OSError):
            return "\n".join(self.log.read_text(errors="replace").splitlines()[-n:])
        return ""


def missing(*names: str) -> str | None:
    """Why a real autopilot is not available (None when the variables are all set)."""
    absent = [n for n in names if not os.environ.get(n)]
    if not absent:
        return None
    return (
        f"real autopilot not available: {', '.join(absent)} unset "
        '(run eval "$(../shared/sitl/install)" or point them at your own SITL build)'
    )


def ardupilot_missing() -> str | None:
    return missing("ARDUPILOT_SITL", "ARDUPILOT_DEFAULTS")


def px4_missing() -> str | None:
    return missing("PX4_BUILD")


def _tcp_free(port: int) -> bool:
    with socket.socket() as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


def _udp_free(port: int) -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


@contextlib.contextmanager
def _free_instance(
    kind: str,
    ports: Callable[[int], tuple[int, ...]],
    check: Callable[[int], bool],
    instances: range,
    taken: set[int] | None,
) -> Iterator[int]:
    """An instance number whose ports are free and that is not in ``taken`` (the numbers of autopilots
    just started, whose ports may not be bound yet; added to it), held for the ``with`` block by an
    exclusive lock file: a port check alone lets two test processes pick one number, since an autopilot's
    link ports are bound only once a gateway connects to it."""
    for instance in random.sample(instances, len(instances)):
        if taken is not None and instance in taken:
            continue
        claim = open(Path(tempfile.gettempdir()) / f"fleet-tests-{kind}-{instance}.lock", "wb")
        try:
            fcntl.flock(claim, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:  # another test process runs this instance
            claim.close()
            continue
        if not all(check(p) for p in ports(instance)):
            claim.close()
            continue
        if taken is not None:
            taken.add(instance)
        try:
            yield instance
        finally:
            claim.close()
        return
    raise Unavailable("no autopilot instance number has its ports free on this host")


def _stop(proc: subprocess.Popen[bytes]) -> None:
    if proc.poll() is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=scaled(10))
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=scaled(10))


@contextlib.contextmanager
def _running(
    argv: list[str], folder: Path, name: str, env: Mapping[str, str]
) -> Iterator[tuple[subprocess.Popen[bytes], Path, float]]:
    """Run an autopilot in ``folder`` (its own process group, output to NAME.log); always stopped."""
    log = folder / f"{name}.log"
    with log.open("wb") as out:
        started = time.monotonic()
        proc = subprocess.Popen(
            argv, cwd=folder, env=dict(env), stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
            start_new_session=True,
        )  # fmt: skip
    try:
        yield proc, log, started
    finally:
        _stop(proc)


@contextlib.contextmanager
def arducopter(
    folder: Path, speedup: float = 5.0, sysid: int | None = 1, taken: set[int] | None = None
) -> Iterator[Autopilot]:
    """ArduCopter SITL (frame +, SITL default parameters), TCP 5760 + 10 * instance; system id ``sysid``
    (None: the instance number, so that several flying together have distinct ones)."""
    why = ardupilot_missing()
    if why:
        raise Unavailable(why)
    ports = lambda i: (5760 + 10 * i, 5762 + 10 * i, 5763 + 10 * i)  # noqa: E731
    with _free_instance("arducopter", ports, _tcp_free, range(1, 40), taken) as instance:
        yield from _arducopter_on(instance, folder, speedup, sysid)


def _arducopter_on(instance: int, folder: Path, speedup: float, sysid: int | None) -> Iterator[Autopilot]:
    argv = [
        os.environ["ARDUPILOT_SITL"], "--model", "+", "--speedup", f"{speedup:g}", f"-I{instance}",
        "--sysid", str(instance if sysid is None else sysid), "--defaults", os.environ["ARDUPILOT_DEFAULTS"],
        "--home", ",".join(str(x) for x in HOME),
    ]  # fmt: skip
    with _running(argv, folder, f"arducopter-{instance}", os.environ) as (proc, log, started):
        yield Autopilot(
            f"tcpout://127.0.0.1:{5760 + 10 * instance}",
            proc,
            log,
            started,
            f"tcp:127.0.0.1:{5762 + 10 * instance}",
        )


@contextlib.contextmanager
def px4(
    folder: Path, taken: set[int] | None = None, speed_factor: float = PX4_SPEED_FACTOR
) -> Iterator[Autopilot]:
    """PX4 SIH (physics inside the autopilot) at ``speed_factor`` times real time (lockstep), MAVLink UDP
    14540 + instance, system id instance + 1, with PX4_TEST_PARAMS. Each instance runs in its own
    subfolder (PX4 keeps its parameters and logs there). PX4's rcS multiplies its link-loss timeouts
    (COM_DL_LOSS_T, COM_RC_LOSS_T, COM_OF_LOSS_T, COM_DISARM_PRFLT) by the factor, so that they stay the
    same in wall time."""
    if not 0 < speed_factor <= 10:
        raise ValueError(
            f"speed_factor: {speed_factor!r} is not a PX4 SIH speed factor (accepted: above 0, at most 10)"
        )
    why = px4_missing()
    if why:
        raise Unavailable(why)
    px4_ports = lambda i: (14540 + i, 14580 + i, 18570 + i, 14280 + i, 13030 + i, 19450 + i)  # noqa: E731
    # PX4 sends to 14540 + instance only for instances 0-9
    with _free_instance("px4", px4_ports, _udp_free, range(1, 10), taken) as instance:
        yield from _px4_on(instance, folder, speed_factor)


def _px4_on(instance: int, folder: Path, speed_factor: float) -> Iterator[Autopilot]:
    build = Path(os.environ["PX4_BUILD"])
    sih = {"PX4_SIM_MODEL": "sihsim_quadx", "PX4_SIMULATOR": "sihsim", "PX4_SYS_AUTOSTART": "10040",
           "PX4_SIM_SPEED_FACTOR": f"{speed_factor:g}"}  # fmt: skip
    sih |= {f"PX4_PARAM_{name}": f"{value:g}" for name, value in PX4_TEST_PARAMS.items()}
    argv = [str(build / "bin" / "px4"), "-d", "-i", str(instance), str(build / "etc")]
    home = folder / f"px4-{instance}"
    home.mkdir(exist_ok=True)
    with _running(argv, home, "px4", {**os.environ, **sih}) as (proc, log, started):
        yield Autopilot(
            f"udpin://127.0.0.1:{14540 + instance}",
            proc,
            log,
            started,
            f"udpout:127.0.0.1:{18570 + instance}",
        )
