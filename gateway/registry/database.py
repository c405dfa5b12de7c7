"""The database itself: an async engine for a URL (SQLite gets WAL mode and a busy timeout) and the
schema's Alembic migrations (upgrade to head, one upgrade at a time; the head and current revisions)."""

from __future__ import annotations

import asyncio
import os
import sys
import weakref
from pathlib import Path
from typing import TYPE_CHECKING

from sqlalchemy import event, text
from sqlalchemy.engine import Connection
from sqlalchemy.engine.interfaces import DBAPIConnection
from sqlalchemy.pool import ConnectionPoolEntry

from gateway.registry.sql_async import AsyncEngine, create_async_engine

if TYPE_CHECKING:
    from alembic.config import Config

# The Alembic scripts: ``migrations/`` at the top of a checkout, installed as the package
# ``gateway.migrations`` (setup.py maps it), so a wheel carries them inside ``gateway`` wherever pip puts
# it: a virtual environment, ``--user``, a distribution's system pip, a ``--target`` directory, the image.
# A checkout (editable install, or run from its root) has them beside the package.
PACKAGE_DIR = Path(__file__).resolve().parents[1]
INSTALLED_MIGRATIONS = PACKAGE_DIR / "migrations"
CHECKOUT_MIGRATIONS = PACKAGE_DIR.parent / "migrations"


def migrations_dir() -> Path:
    """The directory of the Alembic scripts (``env.py``, ``versions/``) this package runs with."""
    if (INSTALLED_MIGRATIONS / "env.py").is_file():
        return INSTALLED_MIGRATIONS
    # beside the package only in a checkout: a site-packages may hold another project's migrations/
    if (PACKAGE_DIR.parent / "pyproject.toml").is_file() and (CHECKOUT_MIGRATIONS / "env.py").is_file():
        return CHECKOUT_MIGRATIONS
    raise RuntimeError(
        f"the database migrations are missing: neither {INSTALLED_MIGRATIONS} (an installed package) nor "
        f"{CHECKOUT_MIGRATIONS} (a checkout) has env.py (a damaged install? reinstall fleet-gateway)"
    )


SQLITE_BUSY_TIMEOUT_MS = 10_000
#: how long a schema upgrade waits for another process's upgrade (which holds the write lock for all of
#: its migrations: seconds on a busy machine, more than a serving gateway's writes wait)
SQLITE_UPGRADE_WAIT_MS = 300_000


def _is_sqlite(url: str) -> bool:
    return url.startswith("sqlite")


def _install_sqlite_pragmas(engine: AsyncEngine) -> None:
    @event.listens_for(engine.sync_engine, "connect")
    def _on_connect(dbapi_connection: DBAPIConnection, _record: ConnectionPoolEntry) -> None:
        cursor = dbapi_connection.cursor()
        cursor.execute(f"PRAGMA busy_timeout={SQLITE_BUSY_TIMEOUT_MS}")
        cursor.execute("PRAGMA journal_mode=WAL")
        cursor.execute("PRAGMA synchronous=NORMAL")
        cursor.execute("PRAGMA foreign_keys=ON")
        cursor.close()


def create_engine_for(url: str) -> AsyncEngine:
    """An async engine for ``url``, with SQLite's pragmas installed when it is SQLite."""
    if not _is_sqlite(url):
        return create_async_engine(url, pool_pre_ping=True)
    engine = create_async_engine(
        url, pool_pre_ping=False, connect_args={"timeout": SQLITE_BUSY_TIMEOUT_MS / 1000}
    )
    _install_sqlite_pragmas(engine)
    return engine


def alembic_config(url: str) -> Config:
    """An Alembic Config pointing at the project's migrations and ``url``."""
    from alembic.config import Config

    cfg = Config()
    cfg.set_main_option("script_location", str(migrations_dir()))
    cfg.set_main_option("sqlalchemy.url", url.replace("%", "%%"))
    return cfg


# Alembic keeps its migration context in module globals: two upgrades interleaving in one event loop
# would clobber each other, so they take turns (one lock per loop; tests run many loops).
MIGRATION_LOCK_KEY = 0x666C6565  # PostgreSQL advisory lock id of schema upgrades ("flee")
_MIGRATION_LOCKS: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, asyncio.Lock] = (
    weakref.WeakKeyDictionary()
)


async def upgrade_schema(engine: AsyncEngine, url: str, revision: str = "head") -> None:
    """Run Alembic migrations up to ``revision`` on ``engine`` (sharing its connection).

    Across processes, the whole upgrade is one transaction holding the database's write lock (SQLite:
    ``BEGIN IMMEDIATE``; PostgreSQL: an advisory lock): a second gateway or ``db upgrade`` starting at
    the same time waits, then finds the schema current.
    """
    from alembic import command

    cfg = alembic_config(url)

    def _run(connection: Connection) -> None:
        cfg.attributes["connection"] = connection
        command.upgrade(cfg, revision)

    lock = _MIGRATION_LOCKS.setdefault(asyncio.get_running_loop(), asyncio.Lock())
    async with lock, engine.begin() as conn:
        if conn.dialect.name == "sqlite":  # the pooled connection gets its usual wait back at the end
            await conn.exec_driver_sql(f"PRAGMA busy_timeout={SQLITE_UPGRADE_WAIT_MS}")
            try:
                await conn.exec_driver_sql("BEGIN IMMEDIATE")
                await conn.run_sync(_run)
            finally:
                await conn.exec_driver_sql(f"PRAGMA busy_timeout={SQLITE_BUSY_TIMEOUT_MS}")
            return
        if conn.dialect.name == "postgresql":  # held until this transaction ends
            await conn.execute(text("SELECT pg_advisory_xact_lock(:key)"), {"key": MIGRATION_LOCK_KEY})
        await conn.run_sync(_run)


def in_memory(url: str) -> bool:
    """True for an SQLite database that lives in its process (nothing another process could open)."""
    from sqlalchemy.engine import make_url

    parsed = make_url(url)
    return parsed.drivername.startswith("sqlite") and (
        parsed.database in (None, "", ":memory:") or "mode=memory" in url
    )


class SchemaUpgradeFailed(RuntimeError):
    """The child process's upgrade failed; the message is its own one-line error."""


async def upgrade_in_child_process(url: str) -> None:
    """Upgrade the schema at ``url`` to head in a process of its own (``fleet-gateway db upgrade``).

    A process that upgrades in itself keeps Alembic, Mako and their modules loaded for the rest of its
    life (about 11 MiB of a serving gateway); a child takes them with it when it ends. The URL goes to
    the child in its environment (``GATEWAY_DATABASE_URL``), never on its command line. Raises
    SchemaUpgradeFailed with the child's own one-line error when the upgrade fails.
    """
    env = dict(os.environ, GATEWAY_DATABASE_URL=url)
    package_parent = str(PACKAGE_DIR.parent)  # the child imports this very gateway package
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [package_parent, env.get("PYTHONPATH")]))
    child = await asyncio.create_subprocess_exec(
        sys.executable, "-m", "gateway.cli", "db", "upgrade",
        stdin=asyncio.subprocess.DEVNULL,
        stdout=asyncio.subprocess.DEVNULL,
        stderr=asyncio.subprocess.PIPE,
        env=env,
    )  # fmt: skip
    _, stderr = await child.communicate()
    if child.returncode != 0:
        lines = [line for line in stderr.decode(errors="replace").splitlines() if line.strip()]
        last = lines[-1].removeprefix("error: ") if lines else f"exit status {child.returncode}"
        raise SchemaUpgradeFailed(last)


def head_revision() -> str:
    """The newest schema revision among the project's migrations."""
    from alembic.script import ScriptDirectory

    head = ScriptDirectory.from_config(alembic_config("sqlite://")).get_current_head()
    assert head is not None, "no migrations found"
    return head


async def current_revision(engine: AsyncEngine) -> str | None:
    from alembic.runtime.migration import MigrationContext

    def _get(connection: Connection) -> str | None:
        return MigrationContext.configure(connection).get_current_revision()

    async with engine.connect() as conn:
        return await conn.run_sync(_get)
