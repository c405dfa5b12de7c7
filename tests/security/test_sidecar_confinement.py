"""A sidecar's gRPC control port is reachable from this host only, never through another interface."""

from __future__ import annotations

import asyncio
import os
import re
import socket
import subprocess
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from gateway.link import confine
from gateway.util.ports import free_tcp_port, free_udp_port
from tests.helpers.timing import scaled

os.environ.setdefault("MAVLINK20", "1")


def _elf(machine: int) -> bytes:
    """The first 20 bytes of a little-endian 64-bit ELF header for ``machine`` (e_machine)."""
    return b"\x7fELF\x02\x01\x01" + bytes(11) + machine.to_bytes(2, "little")


def test_patch_rewrites_exactly_the_listen_operands() -> None:
    blob = _elf(62) + (b"\x48\xb8" + b"0.0.0.0:" + b"pad") * 3 + b"udpin://0.0.0.0:14540"
    patched = confine.patch_listen_address(blob)
    assert patched.count(b"\x48\xb8127.0.1:") == 3
    assert b"udpin://0.0.0.0:14540" in patched  # strings elsewhere untouched
    assert len(patched) == len(blob)
    assert confine.is_confined(patched) and not confine.is_confined(blob)
    assert confine.patch_listen_address(patched) == patched  # already confined: unchanged


def test_aarch64_patch_rewrites_the_one_nul_terminated_literal() -> None:
    blob = _elf(183) + b"before?\x00" + b"0.0.0.0:\x00" + b"listen on 0.0.0.0:{}\x00udpin://0.0.0.0:14540\x00"
    patched = confine.patch_listen_address(blob)
    assert patched == blob.replace(b"\x000.0.0.0:\x00", b"\x00127.0.1:\x00")
    assert b"listen on 0.0.0.0:{}" in patched and b"udpin://0.0.0.0:14540" in patched
    assert confine.is_confined(patched)


def test_the_socket_patch_rewrites_the_same_sites_to_a_unix_socket() -> None:
    """Socket confinement: the same 8 bytes read ``unix:sk:`` (gRPC then listens on ``sk:<port>`` in the
    sidecar's working directory), on both architectures."""
    x86 = _elf(62) + (b"\x48\xb8" + b"0.0.0.0:" + b"pad") * 3
    assert confine.patch_listen_address(x86, "socket").count(b"\x48\xb8unix:sk:") == 3
    arm = _elf(183) + b"\x000.0.0.0:\x00" + b"listen on 0.0.0.0:{}\x00"
    patched = confine.patch_listen_address(arm, "socket")
    assert patched == arm.replace(b"\x000.0.0.0:\x00", b"\x00unix:sk:\x00")
    assert confine.is_confined(patched, "socket") and not confine.is_confined(patched, "loopback")


def test_patch_fails_closed_on_unknown_binary() -> None:
    with pytest.raises(confine.ConfinementError, match="expected"):
        confine.patch_listen_address(_elf(62) + b"\x48\xb8" + b"0.0.0.0:")
    with pytest.raises(confine.ConfinementError, match=r"aarch64.*0 matches, expected 1"):
        confine.patch_listen_address(_elf(183) + b"listen on 0.0.0.0:{}")
    with pytest.raises(confine.ConfinementError, match=r"RISC-V.*x86-64 and aarch64 only"):
        confine.patch_listen_address(_elf(243) + b"\x000.0.0.0:\x00")
    with pytest.raises(confine.ConfinementError, match="not an ELF executable"):
        confine.patch_listen_address(b"#!/bin/sh\n" + b"\x48\xb8" + b"0.0.0.0:")


def test_unknown_confinement_mode_is_refused(tmp_path: Path) -> None:
    with pytest.raises(confine.ConfinementError, match="use 'socket', 'loopback' or 'none'"):
        confine.sidecar_binary("maybe", None, tmp_path)


def _non_loopback_ipv4() -> str | None:
    out = subprocess.run(["ip", "-4", "-o", "addr", "show"], capture_output=True, text=True, check=False)
    for line in out.stdout.splitlines():
        fields = line.split()
        if len(fields) >= 4 and fields[1] != "lo":
            return fields[3].split("/")[0]
    return None


TEST_ADDRESS = "198.51.100.7"  # TEST-NET-2: never routed


def _ip(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ip", *args], capture_output=True, text=True, check=False)


def _add_test_address(name: str) -> tuple[str, list[tuple[str, ...]]] | None:
    """Give this host a non-loopback IPv4 address by the first means the kernel offers: a dummy link,
    a veth pair, or a second address on lo. Returns (how, undo commands), or None."""
    attempts: list[tuple[str, list[tuple[str, ...]], list[tuple[str, ...]]]] = [
        (
            "dummy link",
            [("link", "add", name, "type", "dummy"), ("addr", "add", f"{TEST_ADDRESS}/32", "dev", name),
             ("link", "set", name, "up")],
            [("link", "del", name)],
        ),
        (
            "veth pair",
            [("link", "add", name, "type", "veth", "peer", "name", f"{name}p"),
             ("addr", "add", f"{TEST_ADDRESS}/32", "dev", name), ("link", "set", name, "up"),
             ("link", "set", f"{name}p", "up")],
            [("link", "del", name)],
        ),
        (
            "address on lo",
            [("addr", "add", f"{TEST_ADDRESS}/32", "dev", "lo")],
            [("addr", "del", f"{TEST_ADDRESS}/32", "dev", "lo")],
        ),
    ]  # fmt: skip
    for how, steps, undo in attempts:
        if all(_ip(*step).returncode == 0 for step in steps):
            return how, undo
        for step in undo:
            _ip(*step)
    return None


@pytest.fixture
def host_address() -> Iterator[str]:
    """A non-loopback IPv4 address of this host; one is added when there is none (needs root)."""
    address = _non_loopback_ipv4()
    if address:
        yield address
        return
    if os.geteuid() != 0:
        pytest.skip("this host has no non-loopback IPv4 address and cannot create one without root")
    added = _add_test_address(f"fgw{os.getpid() % 100000}")
    if added is None:
        pytest.skip(
            "this host has no non-loopback IPv4 address and 'ip' could add none "
            "(no dummy or veth link type, and lo refused a second address)"
        )
    _how, undo = added
    try:
        yield TEST_ADDRESS
    finally:
        for step in undo:
            _ip(*step)


class _HeartbeatSource:
    """A minimal MAVLink vehicle: mavsdk_server opens its gRPC port only after it sees one."""

    def __init__(self, udp_port: int) -> None:
        from pymavlink import mavutil

        self._link = mavutil.mavlink_connection(
            f"udpout:127.0.0.1:{udp_port}", source_system=1, source_component=1
        )
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.is_set():
            self._link.mav.heartbeat_send(2, 3, 89, 0, 3)
            self._stop.wait(0.2)

    def __enter__(self) -> _HeartbeatSource:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join(timeout=scaled(2))
        self._link.close()


def _wait_listening(port: int, proc: subprocess.Popen, timeout: float = 20.0) -> None:
    deadline = time.monotonic() + scaled(timeout)
    while time.monotonic() < deadline:
        assert proc.poll() is None, "mavsdk_server exited early"
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
            return
        except OSError:
            time.sleep(0.1)
    raise AssertionError(f"mavsdk_server never opened gRPC port {port}")


def _reachable(address: str, port: int) -> bool:
    try:
        socket.create_connection((address, port), timeout=1.0).close()
        return True
    except OSError:
        return False


def _run_sidecar(binary: Path, reaper: list[subprocess.Popen]) -> int:
    grpc_port, udp_port = free_tcp_port(), free_udp_port()
    proc = subprocess.Popen(
        [str(binary), "-p", str(grpc_port), f"udpin://127.0.0.1:{udp_port}"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    reaper.append(proc)
    with _HeartbeatSource(udp_port):
        _wait_listening(grpc_port, proc)
    return grpc_port


def test_confined_sidecar_refuses_non_loopback(
    tmp_path: Path, host_address: str, process_reaper: list[subprocess.Popen]
) -> None:
    confined = confine.sidecar_binary("loopback", None, tmp_path)
    assert confined != confine.bundled_mavsdk_server()
    port = _run_sidecar(confined, process_reaper)
    assert _reachable("127.0.0.1", port)
    assert not _reachable(host_address, port), f"gRPC port {port} answered on {host_address}"


def test_unconfined_sidecar_is_exposed_which_is_why_we_confine(
    tmp_path: Path, host_address: str, process_reaper: list[subprocess.Popen]
) -> None:
    """Control experiment: the shipped binary answers on every interface, so the test above can fail."""
    shipped = confine.sidecar_binary("none", None, tmp_path)
    port = _run_sidecar(shipped, process_reaper)
    assert _reachable(host_address, port)


def test_confined_copy_is_reused(tmp_path: Path) -> None:
    first = confine.loopback_mavsdk_server(cache_dir=tmp_path)
    mtime = first.stat().st_mtime_ns
    second = confine.loopback_mavsdk_server(cache_dir=tmp_path)
    assert first == second and second.stat().st_mtime_ns == mtime


# --- aarch64: the arm64 build of mavsdk_server, run under qemu-user --------------------------------


def _aarch64_mavsdk_server() -> Path:
    """The aarch64 mavsdk_server of the installed mavsdk-grpc (scripts/fetch_aarch64_mavsdk_server.py)."""
    from importlib.metadata import version

    given = os.environ.get("GATEWAY_TEST_AARCH64_MAVSDK_SERVER")
    path = (
        Path(given)
        if given
        else confine.default_cache_dir() / "aarch64" / f"mavsdk_server-{version('mavsdk-grpc')}"
    )
    if not path.is_file():
        pytest.skip(
            f"no aarch64 mavsdk_server at {path}: run scripts/fetch_aarch64_mavsdk_server.py "
            "(or set GATEWAY_TEST_AARCH64_MAVSDK_SERVER)"
        )
    return path


def _qemu_aarch64() -> str:
    import shutil

    for name in ("qemu-aarch64-static", "qemu-aarch64"):
        found = shutil.which(name)
        if found:
            return found
    pytest.skip("qemu-user is not installed (Debian: apt-get install qemu-user-static)")


def test_the_aarch64_build_is_patched_at_its_one_site(tmp_path: Path) -> None:
    """The real aarch64 binary: 8 bytes change, all in the one literal, and the copy is recognised."""
    source = _aarch64_mavsdk_server()
    data = source.read_bytes()
    assert confine.listen_site(data).architecture == "aarch64"
    confined = confine.sidecar_binary("loopback", str(source), tmp_path)
    patched = confined.read_bytes()
    assert len(patched) == len(data)
    changed = [i for i, (a, b) in enumerate(zip(data, patched, strict=True)) if a != b]
    assert len(changed) <= 8 and changed[-1] - changed[0] < 8
    assert confine.is_confined(patched)
    assert os.access(confined, os.X_OK)


async def test_aarch64_sidecar_starts_confined_under_qemu(tmp_path: Path, host_address: str) -> None:
    """The aarch64 sidecar, supervised as any other (qemu-user inserted by the spawn plan's wrapper),
    serves on loopback only: the supervisor's /proc check passes and the host address does not answer."""
    import dataclasses

    from gateway.config import Settings
    from gateway.link.proc_sockets import listening_addresses, socket_inodes
    from gateway.link.sidecar import Sidecar, SidecarState
    from tests.registry.heartbeat import HeartbeatVehicle

    source, qemu = _aarch64_mavsdk_server(), _qemu_aarch64()
    settings = Settings(  # type: ignore[call-arg]
        mavsdk_server_path=str(source), sidecar_cache_dir=str(tmp_path), sidecar_confinement="loopback"
    )
    udp = free_udp_port()
    car = Sidecar(
        "arm",
        f"udpin://127.0.0.1:{udp}",
        settings,
        confine=lambda plan: dataclasses.replace(plan, argv=[qemu, *plan.argv]),
    )
    try:
        async with HeartbeatVehicle(udp, sysid=4):
            car.start()
            assert await car.wait_serving(scaled(60)), car.status()
            assert car.state == SidecarState.SERVING
            port, pid = car.grpc_port, car.pid
            assert port is not None and pid is not None
            assert car.plan(port).argv[:2] == [qemu, str(confine.loopback_mavsdk_server(source, tmp_path))]
            assert listening_addresses(port, socket_inodes(pid)) == {"127.0.0.1"}
            assert _reachable("127.0.0.1", port)
            assert not _reachable(host_address, port), f"gRPC port {port} answered on {host_address}"
    finally:
        await car.stop()


async def test_a_sidecar_listening_beyond_loopback_is_stopped(tmp_path: Path) -> None:
    """Whatever the binary: with loopback confinement on, a sidecar whose gRPC socket listens on another
    address (here the shipped, unpatched binary swapped in by the wrapper) is stopped and fails closed."""
    import dataclasses

    from gateway.config import Settings
    from gateway.link.sidecar import Sidecar, SidecarState
    from tests.registry.heartbeat import HeartbeatVehicle

    shipped = str(confine.bundled_mavsdk_server())
    settings = Settings(sidecar_cache_dir=str(tmp_path), sidecar_confinement="loopback")  # type: ignore[call-arg]
    udp = free_udp_port()
    car = Sidecar(
        "leaky",
        f"udpin://127.0.0.1:{udp}",
        settings,
        confine=lambda plan: dataclasses.replace(plan, argv=[shipped, *plan.argv[1:]]),
    )
    try:
        async with HeartbeatVehicle(udp, sysid=5):
            car.start()
            deadline = time.monotonic() + scaled(30)
            while time.monotonic() < deadline:
                if car.state == SidecarState.FAILED:
                    break
                await asyncio.sleep(0.05)
        assert car.state == SidecarState.FAILED
        # gRPC's 0.0.0.0 is a dual-stack listener, shown in /proc/net/tcp6 as ::
        assert re.search(r"listened for gRPC on (::|0\.0\.0\.0)", car.info.last_error or ""), car.info
        assert car.pid is None and car.grpc_port is None
    finally:
        await car.stop()
