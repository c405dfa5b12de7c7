"""Keep every sidecar's gRPC control port away from everyone but the gateway.

mavsdk_server 4.0.5 listens for gRPC on ``0.0.0.0:<port>`` (``"0.0.0.0:" + std::to_string(port)`` in
``GrpcServer::setup_port``, no option). Left as is, each sidecar is an unauthenticated side door to a
drone around every safety rule. The binary is statically linked, so an LD_PRELOAD bind shim cannot
help, and a network namespace needs privileges and a MAVLink bridge.

What works unprivileged: a copy of the binary in which the 8 bytes ``"0.0.0.0:"`` of that one address
read ``"127.0.1:"`` (same length; the inet_aton short form of 127.0.0.1, which gRPC's resolver
accepts); sidecars run from the copy. Where the compiler put those bytes depends on the architecture
of the build, read from the ELF header:

* x86-64: an 8-byte immediate operand, ``movabs rax, "0.0.0.0:"`` (``48 b8`` + the bytes), three
  times in ``setup_port``;
* aarch64: a NUL-terminated 8-byte literal in ``.rodata`` that ``setup_port`` loads with
  ``adrp``/``add`` and prepends to the port (``basic_string::_M_replace(0, 0, literal, 8)``); it is
  the only such literal in the binary and the only reference to it is in ``setup_port`` (checked
  with ``aarch64-linux-gnu-objdump`` on the mavsdk-grpc 4.0.5 aarch64 wheel).

The default (``socket``) writes ``"unix:sk:"`` there instead (same length): mavsdk_server then listens
on the unix socket ``sk:<port>``, a path relative to its working directory, which the supervisor makes a
private directory (mode 0700) of the gateway's user, and removes once the gateway's own gRPC channel is
connected (``gateway.link.sidecar_socket``): no TCP port at all, and no path anyone can connect to.

Nothing else is touched, and the copy is only made when the bytes are exactly as expected; anything
else (another build, another architecture) fails closed with a message saying what to do. The patch
is not the only guard: the sidecar supervisor checks in /proc, after every start, that the gRPC port
listens on loopback only, whatever the binary (``gateway.link.sidecar``), and stops a sidecar that
does not.
"""

from __future__ import annotations

import hashlib
import logging
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

log = logging.getLogger(__name__)


#: what the listen-address prefix is rewritten to, per confinement mode (8 bytes each, as the original)
PREFIXES = {"loopback": b"127.0.1:", "socket": b"unix:sk:"}
#: the unix socket a ``socket`` sidecar listens on, relative to its working directory, for its "port"
SOCKET_NAME = "sk:{port}"


@dataclass(frozen=True)
class ListenSite:
    """How one architecture's build holds the gRPC listen-address prefix (``0.0.0.0:``)."""

    architecture: str
    before: bytes  # the bytes just before the prefix
    after: bytes  # the bytes just after it
    occurrences: int

    def site(self, prefix: bytes) -> bytes:
        return self.before + prefix + self.after

    @property
    def exposed(self) -> bytes:
        return self.site(b"0.0.0.0:")

    @property
    def loopback(self) -> bytes:
        return self.site(PREFIXES["loopback"])


# ELF e_machine -> the site of that architecture's build
_SITES = {
    62: ListenSite("x86-64", b"\x48\xb8", b"", 3),  # EM_X86_64: movabs rax, imm64
    183: ListenSite("aarch64", b"\x00", b"\x00", 1),  # EM_AARCH64: a NUL-terminated .rodata literal
}
_MACHINE_NAMES = {
    3: "x86 (32-bit)",
    8: "MIPS",
    20: "PowerPC",
    21: "PowerPC64",
    40: "ARM (32-bit)",
    243: "RISC-V",
}
SUPPORTED_ARCHITECTURES = tuple(site.architecture for site in _SITES.values())


class ConfinementError(RuntimeError):
    """The sidecar binary cannot be confined to loopback."""


def bundled_mavsdk_server() -> Path:
    """The mavsdk_server binary shipped with the mavsdk-grpc package."""
    from gateway.link.mavsdk_system import bundled_binary

    return bundled_binary()


def default_cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "fleet-gateway"


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def elf_machine(data: bytes) -> int | None:
    """The ELF header's e_machine (62 x86-64, 183 aarch64), or None when ``data`` is no ELF file."""
    if len(data) < 20 or data[:4] != b"\x7fELF":
        return None
    return int.from_bytes(data[18:20], "little" if data[5] == 1 else "big")


def listen_site(data: bytes) -> ListenSite:
    """The listen-address site for the binary's architecture; fails closed for any other."""
    machine = elf_machine(data)
    if machine is None:
        raise ConfinementError(
            "mavsdk_server is not an ELF executable, so it cannot be confined to loopback; set "
            "GATEWAY_MAVSDK_SERVER_PATH to mavsdk-grpc 4.0.5's binary"
        )
    site = _SITES.get(machine)
    if site is None:
        name = _MACHINE_NAMES.get(machine, f"ELF machine {machine}")
        raise ConfinementError(
            f"mavsdk_server is built for {name}; the gateway can confine its gRPC port to loopback on "
            f"{' and '.join(SUPPORTED_ARCHITECTURES)} only. Run on one of those, or set "
            "GATEWAY_SIDECAR_CONFINEMENT=none and firewall the sidecar ports yourself."
        )
    return site


def patch_listen_address(data: bytes, mode: str = "loopback") -> bytes:
    """Return the binary with its gRPC listen address moved from all interfaces to 127.0.0.1
    (``loopback``) or to the unix socket ``sk:<port>`` in its working directory (``socket``)."""
    site = listen_site(data)
    wanted = site.site(PREFIXES[mode])
    found = data.count(site.exposed)
    if found != site.occurrences:
        already = data.count(wanted)
        if found == 0 and already == site.occurrences:
            return data
        raise ConfinementError(
            f"mavsdk_server ({site.architecture}) does not have the expected gRPC listen-address code "
            f"({found} matches, expected {site.occurrences}); it is not the 4.0.5 build this gateway knows "
            "how to confine. Use mavsdk-grpc 4.0.5, or set GATEWAY_SIDECAR_CONFINEMENT=none and firewall "
            "the sidecar ports yourself."
        )
    return data.replace(site.exposed, wanted)


def is_confined(data: bytes, mode: str = "loopback") -> bool:
    """The binary is a confined copy of ``mode`` (its site reads the mode's prefix as often as the build
    has it)."""
    try:
        site = listen_site(data)
    except ConfinementError:
        return False
    return data.count(site.exposed) == 0 and data.count(site.site(PREFIXES[mode])) == site.occurrences


def loopback_mavsdk_server(
    source: Path | None = None, cache_dir: Path | None = None, mode: str = "loopback"
) -> Path:
    """Path of a confined copy of ``source`` for ``mode`` (loopback or socket; made once per source
    build, then reused)."""
    source = source or bundled_mavsdk_server()
    cache_dir = cache_dir or default_cache_dir()
    data = source.read_bytes()
    target = cache_dir / f"mavsdk_server-{mode}-{_sha256(data)[:16]}"
    if target.exists() and os.access(target, os.X_OK):
        if is_confined(target.read_bytes(), mode):
            return target
        log.warning("confined sidecar binary %s is damaged; writing it again", target)
    patched = patch_listen_address(data, mode)
    cache_dir.mkdir(parents=True, exist_ok=True)
    fd, tmp_name = tempfile.mkstemp(dir=cache_dir, prefix=".mavsdk_server-")
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(patched)
        os.chmod(tmp_name, 0o755)
        os.replace(tmp_name, target)
    except BaseException:
        Path(tmp_name).unlink(missing_ok=True)
        raise
    where = "a private unix socket" if mode == "socket" else "127.0.0.1 only"
    log.info("sidecars run from %s (gRPC bound to %s)", target, where)
    return target


def sidecar_binary(confinement: str, explicit_path: str | None, cache_dir: Path | None = None) -> Path:
    """The binary sidecars are started from, for the configured confinement mode.

    ``socket`` (default): a copy that listens on a unix socket in its working directory.
    ``loopback``: a loopback-only copy of the configured (or bundled) binary.
    ``none``: the binary as is; its gRPC port is then reachable on every interface.
    """
    source = Path(explicit_path) if explicit_path else bundled_mavsdk_server()
    if confinement == "none":
        log.warning(
            "GATEWAY_SIDECAR_CONFINEMENT=none: sidecar gRPC ports listen on all interfaces; "
            "anyone who reaches this host can command the drones around the safety layer"
        )
        return source
    if confinement not in PREFIXES:
        raise ConfinementError(
            f"unknown sidecar confinement '{confinement}'; use 'socket', 'loopback' or 'none'"
        )
    return loopback_mavsdk_server(source, cache_dir, confinement)
