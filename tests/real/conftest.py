"""Real autopilots for tests: ArduCopter SITL and PX4 SIH, started from the binaries that
``eval "$(../shared/sitl/install)"`` points at (``ARDUPILOT_SITL``, ``ARDUPILOT_DEFAULTS``, ``PX4_BUILD``).
Without them every test here skips and says so. Each test starts its own autopilot on an instance
number whose ports are free, in a temporary folder, and stops it afterwards, also when it fails."""

from __future__ import annotations

import contextlib
import os
import random
import signal
import socket
import subprocess
from collections.abc import AsyncIterator, Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

import pytest

from gateway.fleet.registry import Registry
from tests.registry.conftest import fast_settings

pytestmark = pytest.mark.real

HOME = (-35.363261, 149.165230, 584.0, 353.0)  # lat, lon, alt AMSL, heading: ArduPilot's CMAC


@dataclass
class Autopilot:
    url: str  # for mavsdk_server
    process: subprocess.Popen[bytes]
    log: Path

    def log_tail(self, n: int = 30) -> str:
        with contextlib.suppress(OSError):
            return "\n".join(self.log.read_text(errors="replace").splitlines()[-n:])
        return ""


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


def _free_instance(
    ports: Callable[[int], tuple[int, ...]], check: Callable[[int], bool], instances: range, taken: set[int]
) -> int:
    for instance in random.sample(instances, len(instances)):
        if instance not in taken and all(check(p) for p in ports(instance)):
            taken.add(instance)
            return instance
    pytest.skip("no autopilot instance number has its ports free on this host")


def _stop(proc: subprocess.Popen[bytes]) -> None:
    if proc.poll() is None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=10)


@contextlib.contextmanager
def _running(
    argv: list[str], folder: Path, name: str, env: Mapping[str, str]
) -> Iterator[tuple[subprocess.Popen[bytes], Path]]:
    """Run an autopilot in ``folder`` (its own process group, output to NAME.log); always stopped."""
    log = folder / f"{name}.log"
    with log.open("wb") as out:
        proc = subprocess.Popen(
            argv, cwd=folder, env=dict(env), stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
            start_new_session=True,
        )  # fmt: skip
    try:
        yield proc, log
    finally:
        _stop(proc)


def _need(*names: str) -> None:
    missing = [n for n in names if not os.environ.get(n)]
    if missing:
        pytest.skip(
            f"real autopilot not available: {', '.join(missing)} unset "
            '(run eval "$(../shared/sitl/install)" or point them at your own SITL build)'
        )


@contextlib.contextmanager
def launch_arducopter(folder: Path, taken: set[int]) -> Iterator[Autopilot]:
    """ArduCopter SITL at speed-up 5 (about 9 s from start to flyable), TCP 5760 + 10 * instance,
    system id = instance."""
    _need("ARDUPILOT_SITL", "ARDUPILOT_DEFAULTS")
    ports = lambda i: (5760 + 10 * i, 5762 + 10 * i, 5763 + 10 * i)  # noqa: E731
    instance = _free_instance(ports, _tcp_free, range(1, 40), taken)
    argv = [
        os.environ["ARDUPILOT_SITL"], "--model", "+", "--speedup", "5", f"-I{instance}",
        "--sysid", str(instance), "--defaults", os.environ["ARDUPILOT_DEFAULTS"],
        "--home", ",".join(str(x) for x in HOME),
    ]  # fmt: skip
    with _running(argv, folder, f"arducopter-{instance}", os.environ) as (proc, log):
        yield Autopilot(f"tcpout://127.0.0.1:{5760 + 10 * instance}", proc, log)


@contextlib.contextmanager
def launch_px4(folder: Path, taken: set[int]) -> Iterator[Autopilot]:
    """PX4 SIH (physics inside the autopilot; real time only), MAVLink UDP 14540 + instance, system id
    instance + 1. Each instance runs in its own folder (PX4 keeps its parameters and logs there)."""
    _need("PX4_BUILD")
    build = Path(os.environ["PX4_BUILD"])
    instance = _free_instance(
        lambda i: (14540 + i, 14580 + i, 18570 + i, 14280 + i, 13030 + i, 19450 + i),
        _udp_free,
        range(1, 10),
        taken,
    )  # PX4 sends to 14540 + instance only for instances 0-9
    sih = {"PX4_SIM_MODEL": "sihsim_quadx", "PX4_SIMULATOR": "sihsim", "PX4_SYS_AUTOSTART": "10040"}
    argv = [str(build / "bin" / "px4"), "-d", "-i", str(instance), str(build / "etc")]
    home = folder / f"px4-{instance}"
    home.mkdir()
    with _running(argv, home, "px4", {**os.environ, **sih}) as (proc, log):
        yield Autopilot(f"udpin://127.0.0.1:{14540 + instance}", proc, log)


@pytest.fixture
def arducopter(tmp_path: Path) -> Iterator[Autopilot]:
    with launch_arducopter(tmp_path, set()) as autopilot:
        yield autopilot


@pytest.fixture
def px4(tmp_path: Path) -> Iterator[Autopilot]:
    with launch_px4(tmp_path, set()) as autopilot:
        yield autopilot


@pytest.fixture
def launch(tmp_path: Path) -> Iterator[Callable[[str, int], list[Autopilot]]]:
    """``launch(kind, n)``: n autopilots of one kind ("ardupilot" or "px4") started together, each on its
    own instance number; all stopped at the end of the test, also when it fails."""
    taken: set[int] = set()
    with contextlib.ExitStack() as stack:

        def start(kind: str, n: int) -> list[Autopilot]:
            launcher = {"ardupilot": launch_arducopter, "px4": launch_px4}[kind]
            return [stack.enter_context(launcher(tmp_path, taken)) for _ in range(n)]

        yield start


@pytest.fixture
async def registry(store) -> AsyncIterator[Registry]:  # type: ignore[no-untyped-def]
    reg = Registry(fast_settings(link_lost_after_s=3.0), store)
    await reg.start()
    try:
        yield reg
    finally:
        await reg.stop()
