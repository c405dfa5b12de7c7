"""The private unix socket a sidecar serves gRPC on (``GATEWAY_SIDECAR_CONFINEMENT=socket``, the default).

The confined mavsdk_server (`gateway.link.confine`) listens on ``sk:<port>`` relative to its working
directory. Each start gets a fresh directory of its own (``mkdtemp``: mode 0700, the gateway's user), so
no other user can reach the socket in it. Once the gateway's own gRPC channel is connected, the socket's
path is removed (``seal``): from then on nobody, the gateway's own user included, can open another
connection (a unix socket is reached through its path only), and the sidecar is checked to hold exactly
one connection, the gateway's; a process that slipped in before is found there and the sidecar is
restarted. The "port" is a random number that only names the socket.
"""

from __future__ import annotations

import os
import re
import secrets
import shutil
import tempfile
from pathlib import Path

from gateway.link.confine import SOCKET_NAME
from gateway.link.proc_sockets import socket_inodes, unix_rows

#: /proc/net/unix states: a listener shows SS_UNCONNECTED; a connection SS_CONNECTING while it waits in
#: the listener's queue, SS_CONNECTED once accepted
LISTENING, QUEUED, CONNECTED = "01", "02", "03"
_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]")


def socket_port() -> int:
    """A random number for the socket's name (unique among the host's sidecars in practice)."""
    return 1_000_000_000 + secrets.randbelow(1_000_000_000)


def private_directory(vehicle_id: str) -> Path:
    """A new directory only the gateway's user may enter (0700), under $XDG_RUNTIME_DIR when it is
    writable, else the system's temporary directory."""
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    base = runtime if runtime and os.access(runtime, os.W_OK | os.X_OK) else None
    path = Path(tempfile.mkdtemp(prefix=f"fleet-gateway-{_UNSAFE.sub('_', vehicle_id)[:40]}-", dir=base))
    path.chmod(0o700)
    return path


def listener_is_ours(pid: int, port: int) -> bool:
    """Process ``pid`` listens on the socket named for ``port``."""
    name = SOCKET_NAME.format(port=port)
    ours = socket_inodes(pid)
    return any(r.path == name and r.state == LISTENING and r.inode in ours for r in unix_rows())


def connections(port: int) -> int:
    """How many connections the socket named for ``port`` has accepted or queued."""
    name = SOCKET_NAME.format(port=port)
    return sum(1 for r in unix_rows() if r.path == name and r.state in (QUEUED, CONNECTED))


def seal(directory: Path, port: int) -> str | None:
    """Remove the socket's path (and its directory) now that the gateway is connected; None when the
    sidecar holds the gateway's connection alone, else what is wrong."""
    name = SOCKET_NAME.format(port=port)
    try:
        (directory / name).unlink()
    except FileNotFoundError:
        return f"the gRPC socket {directory / name} was gone before the gateway sealed it"
    remove(directory)
    held = connections(port)
    if held != 1:
        return f"the sidecar's gRPC socket holds {held} connections; only the gateway's may be there"
    return None


def remove(directory: Path | None) -> None:
    if directory is not None:
        shutil.rmtree(directory, ignore_errors=True)
