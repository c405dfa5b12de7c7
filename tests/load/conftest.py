"""The load tests share the MCP area's integration stack (gateway + simulator + real sidecars)."""

from tests.mcp.conftest import stack  # noqa: F401 (module-scoped fixture, reused)
