"""Fixtures of the cluster tests: PostgreSQL for the lease tests (tests/persist's throwaway server)."""

from tests.persist.conftest import pg_base_url  # noqa: F401 (session-scoped server, reused)
