"""A sidecar's gRPC control port is reachable from this host only, never through another interface."""

from __future__ import annotations

import os
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


def test_patch_rewrites_exactly_the_listen_operands() -> None:
    blob = b"head" + (b"\x48\xb8" + b"0.0.0.0:" + b"pad") * 3 + b"udpin://0.0.0.0:14540"
    patched = confine.patch_listen_address(blob)
    assert patched.count(b"\x48\xb8127.0.1:") == 3
    assert b"udpin://0.0.0.0:14540" in patched  # strings elsewhere untouched
    assert len(patched) == len(blob)
    assert confine.patch_listen_address(patched) == patched  # already confined: unchanged


def test_patch_fails_closed_on_unknown_binary() -> None:
    with pytest.raises(confine.ConfinementError, match="expected"):
        confine.patch_listen_address(b"\x48\xb8" + b"0.0.0.0:")


def test_unknown_confinement_mode_is_refused(tmp_path: Path) -> None:
    with pytest.raises(confine.ConfinementError, match="unknown sidecar confinement"):
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
