"""fleet-gateway: an MCP gateway that lets LLMs fly a fleet of MAVLink drones under operator control."""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version


def package_version() -> str:
    """The installed fleet-gateway version (reported by the REST API and the MCP server)."""
    try:
        return version("fleet-gateway")
    except PackageNotFoundError:
        return "0+unknown"
