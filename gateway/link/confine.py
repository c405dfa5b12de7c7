"""Keep every sidecar's gRPC control port reachable from this host only.

mavsdk_server 4.0.5 listens for gRPC on ``0.0.0.0:<port>`` (hard-coded in
``GrpcServer::setup_port``, no option). Left as is, each sidecar is an unauthenticated side door
to a drone around every safety rule. The binary is statically linked, so an LD_PRELOAD bind shim
cannot help, and a network namespace needs privileges and a MAVLink bridge.

What works unprivileged and everywhere: the address is an 8-byte immediate operand
(``movabs rax, "0.0.0.0:"``) used three times in ``setup_port``. We write a copy of the binary in
which those operands read ``"127.0.1:"`` (same length; the inet_aton short form of 127.0.0.1,
which gRPC's resolver accepts), and run sidecars from that copy. Nothing else in the binary is
touched, and the copy is only made when the bytes are exactly as expected; anything else fails
closed with a message saying what to do.
"""

from __future__ import annotations

import hashlib
import logging
import os
import tempfile
from pathlib import Path

log = logging.getLogger(__name__)

# movabs rax, imm64 (REX.W B8) followed by the 8 ASCII bytes of the listen-address prefix.
_ANY_OPERAND = b"\x48\xb8" + b"0.0.0.0:"
_LOOPBACK_OPERAND = b"\x48\xb8" + b"127.0.1:"
_EXPECTED_OCCURRENCES = 3


class ConfinementError(RuntimeError):
    """The sidecar binary cannot be confined to loopback."""


def bundled_mavsdk_server() -> Path:
    """The mavsdk_server binary shipped with the mavsdk-grpc package."""
    import mavsdk_grpc.bin as bin_pkg

    return Path(bin_pkg.__file__).parent / "mavsdk_server"


def default_cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "fleet-gateway"


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def patch_listen_address(data: bytes) -> bytes:
    """Return the binary with its gRPC listen address moved from all interfaces to 127.0.0.1."""
    found = data.count(_ANY_OPERAND)
    if found != _EXPECTED_OCCURRENCES:
        already = data.count(_LOOPBACK_OPERAND)
        if found == 0 and already == _EXPECTED_OCCURRENCES:
            return data
        raise ConfinementError(
            f"mavsdk_server does not have the expected gRPC listen-address code ({found} matches, "
            f"expected {_EXPECTED_OCCURRENCES}); it is not the 4.0.5 build this gateway knows how to "
            "confine. Use mavsdk-grpc 4.0.5, or set GATEWAY_SIDECAR_CONFINEMENT=none and firewall the "
            "sidecar ports yourself."
        )
    return data.replace(_ANY_OPERAND, _LOOPBACK_OPERAND)


def loopback_mavsdk_server(source: Path | None = None, cache_dir: Path | None = None) -> Path:
    """Path of a loopback-only copy of ``source`` (made once per source build, then reused)."""
    source = source or bundled_mavsdk_server()
    cache_dir = cache_dir or default_cache_dir()
    data = source.read_bytes()
    target = cache_dir / f"mavsdk_server-loopback-{_sha256(data)[:16]}"
    if target.exists() and os.access(target, os.X_OK):
        if target.read_bytes().count(_LOOPBACK_OPERAND) == _EXPECTED_OCCURRENCES:
            return target
        log.warning("confined sidecar binary %s is damaged; writing it again", target)
    patched = patch_listen_address(data)
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
    log.info("sidecars run from %s (gRPC bound to 127.0.0.1 only)", target)
    return target


def sidecar_binary(confinement: str, explicit_path: str | None, cache_dir: Path | None = None) -> Path:
    """The binary sidecars are started from, for the configured confinement mode.

    ``loopback`` (default): a loopback-only copy of the configured (or bundled) binary.
    ``none``: the binary as is; its gRPC port is then reachable on every interface.
    """
    source = Path(explicit_path) if explicit_path else bundled_mavsdk_server()
    if confinement == "none":
        log.warning(
            "GATEWAY_SIDECAR_CONFINEMENT=none: sidecar gRPC ports listen on all interfaces; "
            "anyone who reaches this host can command the drones around the safety layer"
        )
        return source
    if confinement != "loopback":
        raise ConfinementError(f"unknown sidecar confinement '{confinement}'; use 'loopback' or 'none'")
    return loopback_mavsdk_server(source, cache_dir)
