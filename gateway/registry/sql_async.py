"""SQLAlchemy's asyncio engine and connections, without its ORM.

``sqlalchemy/ext/asyncio/__init__.py`` imports the asyncio session (``AsyncSession``,
``async_sessionmaker``, scoped sessions) and with it the whole ORM: 45 modules, about 7.5 MiB of a
serving gateway's RSS (docs/benchmarks.md). The store writes Core statements on the engine's
connections (`gateway.registry.models`), so ``sqlalchemy.ext.asyncio`` is registered as a bare package
(`gateway.util.bare_package`) and its engine module imported alone. A name asked of the package itself
(``from sqlalchemy.ext.asyncio import AsyncSession``, as Alembic's scripts or a test may) runs its own
``__init__`` then, with the ORM. Nothing is done where the package is imported already.

Every module of the gateway takes the engine's names from here (tests/test_lean_start.py fails when
the ORM is loaded by a serving gateway).
"""

from __future__ import annotations

from gateway.util.bare_package import own_init_when_missed, register_bare_package

PACKAGE = "sqlalchemy.ext.asyncio"

register_bare_package(PACKAGE, own_init_when_missed(PACKAGE), "SQLAlchemy's asyncio extension")

# ruff: noqa: E402 - these come after the bare package is registered
from sqlalchemy.ext.asyncio.engine import AsyncConnection, AsyncEngine, create_async_engine

__all__ = ["AsyncConnection", "AsyncEngine", "create_async_engine"]
