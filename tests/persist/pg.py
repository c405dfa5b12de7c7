"""A throwaway PostgreSQL server on a free loopback port, for the store's portability tests."""

from __future__ import annotations

import fcntl
import hashlib
import os
import shutil
import signal
import subprocess
import tempfile
import time
import uuid
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from gateway.util.ports import free_tcp_port
from tests.helpers.timing import scaled

PG_BIN_DIRS = [Path(p) for p in sorted(Path("/usr/lib/postgresql").glob("*/bin"), reverse=True)]


# A test server: durability against a machine crash is not wanted, speed is (no fsync). Commits stay
# synchronous: with synchronous_commit=off a server killed by a test (the cluster's fault matrix) loses
# the transactions it acknowledged in its last ~0.6 s, and the audit rows of those calls are gone; with
# fsync off, a synchronous commit only writes its WAL to the OS, which keeps it when the server is killed.
FAST_UNSAFE = ["-c", "fsync=off", "-c", "full_page_writes=off"]


def find_pg_bin(name: str) -> str | None:
    found = shutil.which(name)
    if found:
        return found
    for directory in PG_BIN_DIRS:
        if (directory / name).exists():
            return str(directory / name)
    return None


def _as_postgres_user(cmd: list[str]) -> list[str]:
    """PostgreSQL refuses to run as root: drop to the 'postgres' system user when we are root."""
    if os.geteuid() == 0:
        return ["runuser", "-u", "postgres", "--", *cmd]
    return cmd


def initdb_template(initdb: str) -> Path:
    """A data directory made by ``initdb`` once on this machine (per PostgreSQL build and user), which
    every test server copies instead of running initdb again: initdb took 6-7 s at a load of 12 on 2
    cores, the copy 0.5 s. Made under an exclusive lock file (test processes start servers at once) in a
    folder renamed into place once complete, so a copy never sees half of one."""
    built = os.stat(initdb)
    key = hashlib.sha256(f"{initdb} {built.st_mtime_ns} {built.st_size} {os.geteuid()}".encode()).hexdigest()
    template = Path(tempfile.gettempdir()) / f"fleet-tests-pgdata-{key[:16]}"
    with open(f"{template}.lock", "wb") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if (template / "data" / "PG_VERSION").is_file():
            return template / "data"
        shutil.rmtree(template, ignore_errors=True)
        building = Path(tempfile.mkdtemp(prefix=f"{template.name}-", dir=template.parent))
        try:
            if os.geteuid() == 0:
                shutil.chown(building, "postgres", "postgres")
            options = ["-A", "trust", "-U", "gw", "--no-sync", "-E", "UTF8"]
            subprocess.run(
                _as_postgres_user([initdb, "-D", str(building / "data"), *options]),
                check=True,
                capture_output=True,
                timeout=scaled(120),
            )
            building.chmod(0o755)  # mkdtemp's 0700: the copy runs as the server's user
            building.rename(template)
        finally:
            shutil.rmtree(building, ignore_errors=True)
    return template / "data"


class PostgresServer:
    """A throwaway PostgreSQL server on 127.0.0.1 that a test may stop and start again (same port, same
    data): the database's outage as its clients see it (connections refused, then back)."""

    def __init__(self, timeout_s: float = 60.0) -> None:
        initdb, postgres = find_pg_bin("initdb"), find_pg_bin("postgres")
        if not initdb or not postgres:
            raise FileNotFoundError("PostgreSQL server binaries (initdb, postgres) are not installed")
        self.postgres = postgres
        self.timeout_s = timeout_s
        self.root = Path(tempfile.mkdtemp(prefix="gw-pg-"))
        self.data = self.root / "data"
        self.port = free_tcp_port()
        self.proc: subprocess.Popen | None = None
        if os.geteuid() == 0:
            shutil.chown(self.root, "postgres", "postgres")
        subprocess.run(
            _as_postgres_user(["cp", "-a", str(initdb_template(initdb)), str(self.data)]),
            check=True,
            capture_output=True,
            timeout=scaled(60),
        )

    @property
    def url(self) -> str:
        return f"postgresql+asyncpg://gw@127.0.0.1:{self.port}"

    @property
    def running(self) -> bool:
        return self.proc is not None and self.proc.poll() is None

    def start(self) -> None:
        cmd = [
            self.postgres,
            "-D",
            str(self.data),
            "-h",
            "127.0.0.1",
            "-p",
            str(self.port),
            "-k",
            str(self.root),
        ]
        self.proc = proc = subprocess.Popen(
            _as_postgres_user([*cmd, *FAST_UNSAFE]),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            start_new_session=True,
        )
        started = time.time() - 1.0  # the pid file's mtime has whole-second precision on some filesystems
        deadline = time.monotonic() + scaled(self.timeout_s)
        while True:
            if proc.poll() is not None:
                assert proc.stderr is not None
                raise RuntimeError(f"postgres exited: {proc.stderr.read().decode(errors='replace')[-2000:]}")
            if self._ready(started):
                return
            if time.monotonic() > deadline:
                raise TimeoutError("postgres did not accept connections in time")
            time.sleep(0.2)

    def _ready(self, started: float) -> bool:
        """Our postmaster says it accepts connections on our port: read from its pid file in our data
        directory, not probed on the port, which another server could hold if it took the port first."""
        pid_file = self.data / "postmaster.pid"
        try:
            fresh = pid_file.stat().st_mtime >= started
            lines = pid_file.read_text().splitlines()
        except OSError:
            return False
        ours = len(lines) >= 8 and lines[3].strip() == str(self.port)
        return fresh and ours and lines[7].strip() == "ready"

    def stop(self) -> None:
        """Fast shutdown: open connections are closed, new ones refused."""
        proc, self.proc = self.proc, None
        if proc is None or proc.poll() is not None:
            return
        os.killpg(proc.pid, signal.SIGINT)  # postmaster: fast shutdown
        try:
            proc.wait(timeout=scaled(20))
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(timeout=scaled(10))

    def remove(self) -> None:
        self.stop()
        shutil.rmtree(self.root, ignore_errors=True)


@contextmanager
def restartable_postgres(timeout_s: float = 60.0) -> Iterator[PostgresServer]:
    """A started :class:`PostgresServer`, stopped and removed on exit."""
    server = PostgresServer(timeout_s)
    try:
        server.start()
        yield server
    finally:
        server.remove()


@contextmanager
def postgres_server(timeout_s: float = 60.0) -> Iterator[str]:
    """Start PostgreSQL on 127.0.0.1:<free port>; yield its base URL (no database path)."""
    with restartable_postgres(timeout_s) as server:
        yield server.url


async def create_database(base_url: str) -> str:
    """A new, empty database on the server at ``base_url``; returns its URL."""
    import asyncpg

    name = f"gw_{uuid.uuid4().hex[:12]}"
    dsn = base_url.replace("postgresql+asyncpg://", "postgresql://") + "/postgres"
    conn = await asyncpg.connect(dsn)
    try:
        await conn.execute(f'CREATE DATABASE "{name}"')
    finally:
        await conn.close()
    return f"{base_url}/{name}"
