"""Checks that run before the gateway writes anything or binds anything, so that a start-up failure
is one line naming the thing and the fix (``serve``, ``demo``, ``db upgrade``, ``drones``)."""

from __future__ import annotations

import errno
import os
import socket
from pathlib import Path

from sqlalchemy.engine import make_url

from gateway.config import Settings


class StartupError(Exception):
    """A reason the gateway cannot start, worded for the operator (one or two lines)."""


def check_port_free(host: str, port: int, flag: str = "--port") -> None:
    """Raise StartupError if ``host:port`` cannot be bound (in use, or not an address of this host)."""
    family = socket.AF_INET6 if ":" in host else socket.AF_INET
    with socket.socket(family, socket.SOCK_STREAM) as probe:
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            probe.bind((host, port))
        except OSError as exc:
            if exc.errno == errno.EADDRINUSE:
                raise StartupError(
                    f"port {port} on {host} is already in use (another fleet-gateway?); "
                    f"pass {flag} N (or set GATEWAY_PORT), or stop what holds it"
                ) from None
            raise StartupError(f"cannot listen on {host}:{port}: {exc.strerror or exc}") from None


def sqlite_path(database_url: str) -> Path | None:
    """The file of a SQLite URL (None for PostgreSQL or an in-memory SQLite database)."""
    url = make_url(database_url)
    if not url.drivername.startswith("sqlite") or not url.database or url.database == ":memory:":
        return None
    return Path(url.database)


def prepare_database_location(database_url: str) -> None:
    """A SQLite file's directory is created when missing (as for the default ./fleet-gateway.db);
    StartupError when it cannot be, or when the path is not a file."""
    try:
        path = sqlite_path(database_url)
    except Exception as exc:  # sqlalchemy.exc.ArgumentError and friends: the URL itself is wrong
        raise StartupError(
            f"database URL {database_url!r} is not valid ({exc}); e.g. "
            "sqlite+aiosqlite:///./fleet-gateway.db or postgresql+asyncpg://user:password@host/db"
        ) from None
    if path is None:
        return
    if path.is_dir():
        raise StartupError(
            f"database path {path} is a directory; give a file, e.g. {path / 'fleet-gateway.db'}"
        )
    directory = path.parent
    if directory.is_dir():
        if not os.access(directory, os.W_OK):
            raise StartupError(
                f"cannot write the database in {directory}: permission denied; choose another --database-url"
            )
        return
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise StartupError(
            f"cannot create the database directory {directory}: {exc.strerror or exc}; "
            "create it or choose another --database-url"
        ) from None


def describe_database_error(database_url: str, exc: BaseException) -> str:
    """One line for a database that cannot be opened (unreachable server, bad credentials, locked
    file), with the password left out of the URL."""
    safe = make_url(database_url).render_as_string(hide_password=True)
    reason = (
        str(getattr(exc, "orig", None) or exc).strip().splitlines()[0]
        if str(exc).strip()
        else type(exc).__name__
    )
    if isinstance(exc, OSError) or "connect" in reason.lower() or "refused" in reason.lower():
        hint = "is the database server running and reachable? check --database-url / GATEWAY_DATABASE_URL"
    else:
        hint = "check --database-url / GATEWAY_DATABASE_URL"
    return f"cannot open the database {safe}: {reason[:200]}; {hint}"


def check_sidecar_binary(settings: Settings) -> None:
    """The mavsdk_server the sidecars start from exists and can be made loopback-only."""
    from gateway.link.sidecar import mavsdk_server_binary

    explicit = settings.mavsdk_server_path
    if explicit and not Path(explicit).is_file():
        raise StartupError(
            f"mavsdk_server not found at {explicit} (GATEWAY_MAVSDK_SERVER_PATH); point it at the binary, "
            "or unset it to use the one bundled with mavsdk-grpc"
        )
    try:
        binary = Path(mavsdk_server_binary(settings))
    except Exception as exc:  # ConfinementError, FileNotFoundError: their text names the fix
        raise StartupError(f"cannot prepare the mavsdk_server binary: {exc}") from None
    if not binary.is_file() or not os.access(binary, os.X_OK):
        raise StartupError(
            f"mavsdk_server at {binary} is missing or not executable; reinstall mavsdk-grpc "
            "(make install) or set GATEWAY_MAVSDK_SERVER_PATH"
        )


def check_nats_reachable(nats_url: str, timeout_s: float = 5.0) -> None:
    """A cluster node's NATS server answers (GATEWAY_CLUSTER_NATS_URL); StartupError in one line if not."""
    import asyncio

    from gateway.cluster.bus import probe

    try:
        asyncio.run(probe(nats_url, timeout_s))
    except Exception as exc:
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise StartupError(
            f"cannot reach NATS at {nats_url} (GATEWAY_CLUSTER_NATS_URL): {reason[:200]}; is nats-server "
            "running and reachable? fix the URL, or unset GATEWAY_CLUSTER_NATS_URL to run a gateway alone"
        ) from None
