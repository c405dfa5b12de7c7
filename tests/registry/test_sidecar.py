"""Sidecar supervisor against real mavsdk_server processes and a bare MAVLink heartbeat sender."""

from __future__ import annotations

import asyncio
import os
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

from gateway.config import Settings
from gateway.link import proc_sockets
from gateway.link import sidecar as sidecar_mod
from gateway.link.sidecar import Sidecar, SidecarState
from gateway.util.ports import free_udp_port
from tests.helpers.timing import scaled
from tests.registry.heartbeat import HeartbeatVehicle
from tests.registry.procs import alive, mavsdk_servers_of

WAIT = scaled(30.0)  # generous: waiting is never an assertion


def _settings(**overrides: object) -> Settings:
    # loopback: these tests are about the gRPC port (its choice, its squatters); the default, a private
    # unix socket, is tested in tests/security/test_sidecar_socket.py
    base = {
        "sidecar_backoff_initial_s": 0.1,
        "sidecar_backoff_max_s": 0.5,
        "sidecar_max_restarts": 3,
        "sidecar_confinement": "loopback",
    }
    base.update(overrides)
    return Settings(**base)  # type: ignore[arg-type]


async def _wait_for(predicate, within_s: float = WAIT) -> None:
    loop = asyncio.get_running_loop()
    deadline = loop.time() + within_s
    while not predicate():
        if loop.time() > deadline:
            raise AssertionError("condition not reached in time")
        await asyncio.sleep(0.05)


@pytest.fixture
async def stopper():
    made: list[Sidecar] = []
    yield made
    for car in made:
        await car.stop()


async def test_serves_after_discovery_and_stop_leaves_nothing(stopper: list[Sidecar]) -> None:
    udp = free_udp_port()
    car = Sidecar("alpha", f"udpin://127.0.0.1:{udp}", _settings())
    stopper.append(car)
    car.start()
    # no vehicle yet: mavsdk_server runs but opens no gRPC port, and waiting does not hang
    assert await car.wait_serving(1.5) is False
    assert car.state == SidecarState.STARTING
    assert car.grpc_port is None
    pid = car.pid
    assert pid is not None and alive(pid)
    async with HeartbeatVehicle(udp, sysid=3):
        assert await car.wait_serving(WAIT)
        assert car.state == SidecarState.SERVING
        port = car.grpc_port
        assert port is not None
        # a start whose port another process took is respawned on another port: the process serving now
        pid = car.pid
        assert pid is not None
        # the gRPC port really is open, and by our process
        assert proc_sockets.listening_inodes(port) <= proc_sockets.socket_inodes(pid)
        assert car.status()["vehicle_discovered"] is True
        await car.stop()
    assert not alive(pid)
    assert car.state == SidecarState.STOPPED
    assert pid not in mavsdk_servers_of()


async def test_kill_9_is_restarted(stopper: list[Sidecar]) -> None:
    udp = free_udp_port()
    down: list[str] = []
    car = Sidecar("bravo", f"udpin://127.0.0.1:{udp}", _settings(), on_down=down.append)
    stopper.append(car)
    async with HeartbeatVehicle(udp):
        car.start()
        assert await car.wait_serving(WAIT)
        first = car.pid
        assert first is not None
        os.kill(first, signal.SIGKILL)
        await _wait_for(lambda: car.pid not in (None, first) and car.state == SidecarState.SERVING)
        assert car.info.restarts == 1
        assert down and "code -9" in down[0]
        assert not alive(first)


def _pidfd_works() -> bool:
    try:
        os.close(os.pidfd_open(os.getpid()))
    except (AttributeError, OSError):
        return False
    return True


def _waiter_threads() -> int:
    """asyncio's ThreadedChildWatcher names each thread that waits for a child ``asyncio-waitpid-N``."""
    return sum(1 for thread in threading.enumerate() if "waitpid-" in thread.name)


@pytest.mark.skipif(not _pidfd_works(), reason="no pidfd_open on this kernel")
async def test_a_sidecar_is_waited_for_on_the_event_loop_not_by_a_thread(stopper: list[Sidecar]) -> None:
    udp = free_udp_port()
    down: list[str] = []
    car = Sidecar("delta", f"udpin://127.0.0.1:{udp}", _settings(), on_down=down.append)
    stopper.append(car)
    threads_before = _waiter_threads()
    async with HeartbeatVehicle(udp):
        car.start()
        assert await car.wait_serving(WAIT)
        assert _waiter_threads() <= threads_before  # no thread of its own waits for this sidecar
        first = car.pid
        assert first is not None
        os.kill(first, signal.SIGKILL)  # and its end is still seen: it is restarted
        await _wait_for(lambda: car.pid not in (None, first) and car.state == SidecarState.SERVING)
        assert down and "code -9" in down[0]
        assert _waiter_threads() <= threads_before


async def test_stop_right_after_start_leaves_nothing() -> None:
    for i in range(6):  # stop at different points of the spawn
        car = Sidecar("lima", f"udpin://127.0.0.1:{free_udp_port()}", _settings())
        car.start()
        await asyncio.sleep(0.002 * i)
        await car.stop()
        assert car.pid is None
    assert mavsdk_servers_of() == []


async def test_recycle_restarts_the_process(stopper: list[Sidecar]) -> None:
    udp = free_udp_port()
    serving: list[int] = []
    car = Sidecar("kilo", f"udpin://127.0.0.1:{udp}", _settings(), on_serving=serving.append)
    stopper.append(car)
    async with HeartbeatVehicle(udp):
        car.start()
        assert await car.wait_serving(WAIT)
        first = car.pid
        car.recycle()  # what the vehicle does when it cannot open a gRPC session on a serving sidecar
        await _wait_for(lambda: car.pid not in (None, first) and car.state == SidecarState.SERVING)
        assert len(serving) == 2 and car.info.restarts == 1
        assert first is not None and not alive(first)


async def test_foreign_listener_on_port_moves_to_another_port(
    stopper: list[Sidecar], monkeypatch: pytest.MonkeyPatch
) -> None:
    # A SO_REUSEPORT listener (what another gRPC server would hold) makes mavsdk_server start "fine"
    # on the same port; the supervisor must notice and move on.
    squatter = socket.socket()
    squatter.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEPORT, 1)
    squatter.bind(("0.0.0.0", 0))
    squatter.listen()
    taken = squatter.getsockname()[1]
    real = sidecar_mod.free_tcp_port
    picks = iter([taken])
    monkeypatch.setattr(sidecar_mod, "free_tcp_port", lambda: next(picks, None) or real())
    udp = free_udp_port()
    car = Sidecar("charlie", f"udpin://127.0.0.1:{udp}", _settings())
    stopper.append(car)
    try:
        async with HeartbeatVehicle(udp):
            car.start()
            assert await car.wait_serving(WAIT)
            assert car.grpc_port not in (None, taken)
            assert car.info.restarts == 0
    finally:
        squatter.close()


async def test_plain_bound_port_moves_to_another_port(
    stopper: list[Sidecar], monkeypatch: pytest.MonkeyPatch
) -> None:
    squatter = socket.socket()
    squatter.bind(("127.0.0.1", 0))
    squatter.listen()
    taken = squatter.getsockname()[1]
    real = sidecar_mod.free_tcp_port
    picks = iter([taken])
    monkeypatch.setattr(sidecar_mod, "free_tcp_port", lambda: next(picks, None) or real())
    udp = free_udp_port()
    car = Sidecar("delta", f"udpin://127.0.0.1:{udp}", _settings())
    stopper.append(car)
    try:
        async with HeartbeatVehicle(udp):
            car.start()
            assert await car.wait_serving(WAIT)
            assert car.grpc_port not in (None, taken)
    finally:
        squatter.close()


async def test_repeated_crashes_end_in_failed_with_reason(stopper: list[Sidecar], tmp_path) -> None:
    broken = tmp_path / "mavsdk_server"
    broken.write_text("#!/bin/sh\necho 'cannot open serial port' >&2\nexit 3\n")
    broken.chmod(0o755)
    # a stand-in script cannot be confined to loopback (that fails closed): run it as is
    settings = _settings(mavsdk_server_path=str(broken), sidecar_confinement="none")
    car = Sidecar("echo", "serial:///dev/does-not-exist:57600", settings)
    stopper.append(car)
    car.start()
    await _wait_for(lambda: car.state == SidecarState.FAILED)
    assert car.info.restarts == 3
    assert "gave up after 4 consecutive failures" in (car.info.last_error or "")
    assert "cannot open serial port" in (car.info.last_error or "")
    assert await car.wait_serving(0.1) is False


def test_confinement_wrapper_is_applied_to_the_command() -> None:
    def netns(plan: sidecar_mod.SpawnPlan) -> sidecar_mod.SpawnPlan:
        return sidecar_mod.SpawnPlan(["ip", "netns", "exec", "fleet", *plan.argv], plan.env, plan.grpc_port)

    car = Sidecar("foxtrot", "udpin://127.0.0.1:14550", _settings(gcs_sysid=200), confine=netns)
    plan = car.plan(50123)
    assert plan.argv[:4] == ["ip", "netns", "exec", "fleet"]
    assert plan.argv[-1] == "udpin://127.0.0.1:14550"
    assert ["-p", "50123"] == plan.argv[5:7]
    assert "--sysid" in plan.argv and "200" in plan.argv
    assert "--heartbeat-watchdog-timeout" not in plan.argv
    # the watchdog is enabled over gRPC once the vehicle session exists, never on the command line
    with_watchdog = Sidecar("golf", "udpin://127.0.0.1:14550", _settings(sidecar_heartbeat_watchdog_s=4))
    assert "--heartbeat-watchdog-timeout" not in with_watchdog.plan(50124).argv


_GATEWAY_STANDIN = """
import asyncio, sys
from gateway.config import Settings
from gateway.link import sidecar
if sys.argv[1] == "shim":
    sidecar.shutil.which = lambda name: None  # force the Python exec shim instead of setpriv
async def main():
    car = sidecar.Sidecar("hotel", "udpin://127.0.0.1:" + sys.argv[2], Settings())
    car.start()
    while car.pid is None:
        await asyncio.sleep(0.05)
    print(car.pid, flush=True)
    await asyncio.sleep(3600)
asyncio.run(main())
"""


def _poll(predicate, within_s: float = WAIT) -> None:
    deadline = time.monotonic() + within_s
    while not predicate():
        assert time.monotonic() < deadline, "condition not reached in time"
        time.sleep(0.05)


@pytest.mark.parametrize("wrapper", ["setpriv", "shim"])
def test_sidecar_dies_with_a_sigkilled_gateway(wrapper: str, process_reaper) -> None:
    gateway = subprocess.Popen(
        [sys.executable, "-c", _GATEWAY_STANDIN, wrapper, str(free_udp_port())],
        stdout=subprocess.PIPE,
        text=True,
    )
    process_reaper.append(gateway)
    pid = int(gateway.stdout.readline())
    _poll(lambda: mavsdk_servers_of(gateway.pid) == [pid])
    gateway.kill()  # SIGKILL: no atexit, no stop(); only PR_SET_PDEATHSIG can clean up
    gateway.wait()
    _poll(lambda: not alive(pid))


async def test_link_that_cannot_open_is_restarted_then_failed(stopper: list[Sidecar]) -> None:
    # mavsdk_server prints "Connection failed" for a missing serial device and then waits forever
    car = Sidecar("india", "serial:///dev/fleet-gateway-no-such-device:57600", _settings())
    stopper.append(car)
    car.start()
    await _wait_for(lambda: car.state == SidecarState.FAILED)
    assert car.info.restarts == 3
    assert "could not open serial:///dev/fleet-gateway-no-such-device:57600" in (car.info.last_error or "")
    assert "No such file or directory" in (car.info.last_error or "")


async def test_sidecars_start_a_few_at_a_time(stopper: list[Sidecar], monkeypatch) -> None:
    """With one start slot, a second sidecar is spawned only once the first serves; a start whose
    vehicle never answers frees its slot after the slot's time (``STARTS.hold_at_most_s``)."""
    monkeypatch.setattr(sidecar_mod.STARTS, "slots", 1)
    monkeypatch.setattr(sidecar_mod.STARTS, "hold_at_most_s", 600.0)
    udp_a, udp_b = free_udp_port(), free_udp_port()
    first = Sidecar("first", f"udpin://127.0.0.1:{udp_a}", _settings())
    second = Sidecar("second", f"udpin://127.0.0.1:{udp_b}", _settings())
    stopper += [first, second]
    first.start()
    await _wait_for(lambda: first.pid is not None)
    second.start()
    async with HeartbeatVehicle(udp_b, sysid=4):
        # the second's vehicle answers, but its sidecar waits for the first's slot
        assert await second.wait_serving(1.5) is False
        assert second.pid is None and second.state == SidecarState.STARTING
        async with HeartbeatVehicle(udp_a, sysid=3):
            assert await first.wait_serving(WAIT)
            assert await second.wait_serving(WAIT)
    assert first.info.serving_since is not None and second.info.started_at is not None
    assert second.info.started_at >= first.info.serving_since


async def test_a_start_that_never_serves_frees_its_slot(stopper: list[Sidecar], monkeypatch) -> None:
    monkeypatch.setattr(sidecar_mod.STARTS, "slots", 1)
    monkeypatch.setattr(sidecar_mod.STARTS, "hold_at_most_s", 0.5)
    udp_a, udp_b = free_udp_port(), free_udp_port()
    silent = Sidecar("silent", f"udpin://127.0.0.1:{udp_a}", _settings())  # no vehicle ever answers
    other = Sidecar("other", f"udpin://127.0.0.1:{udp_b}", _settings())
    stopper += [silent, other]
    silent.start()
    await _wait_for(lambda: silent.pid is not None)
    other.start()
    async with HeartbeatVehicle(udp_b, sysid=4):
        assert await other.wait_serving(WAIT)
    assert silent.state == SidecarState.STARTING
