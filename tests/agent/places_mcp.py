"""A small places server for the host's tests: named places to coordinates, over MCP on stdio, no network.

python -m tests.agent.places_mcp        # what ``fleet-gateway agent --server ...`` starts
"""

from __future__ import annotations

from typing import Any

from mcp.server.mcpserver import MCPServer
from mcp.server.mcpserver.exceptions import ToolError
from mcp.types import ToolAnnotations

#: the places it knows: name -> (lat_deg, lon_deg); the toy fleet's "water tower" is 40 m north of home
PLACES = {"water tower": (47.3981, 8.5456), "old mill": (47.3969, 8.5470)}

server = MCPServer("places")


@server.tool(annotations=ToolAnnotations(readOnlyHint=True))
def find_place(place: str) -> dict[str, Any]:
    """Coordinates (lat_deg, lon_deg) of a named place, e.g. a landmark the user mentions."""
    key = place.strip().lower().removeprefix("the ")
    if key not in PLACES:
        raise ToolError(f"unknown place {place!r}; known: {', '.join(sorted(PLACES))}")
    lat, lon = PLACES[key]
    return {"name": key, "lat_deg": lat, "lon_deg": lon}


@server.tool()
def takeoff(drone_id: str, alt_m: float) -> str:
    """A tool named like one of the gateway's: the host must never route a gateway call here."""
    return "the places server cannot fly"


if __name__ == "__main__":
    server.run("stdio")
