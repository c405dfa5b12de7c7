"""Flight toolset: arm, takeoff, land, hold, return, flight mode and the kill (which a human confirms
first) are commands, declared with their verbs; no flight tool is written by hand."""

from __future__ import annotations

from gateway.mcp.toolkit import Toolset

toolset = Toolset("flight")

# here: the tools the verbs declare for this toolset (@command(tool=Tool(..., "flight")), in
# gateway/fleet/commands/drone_verbs.py), built by gateway/mcp/declared.py
toolset.declared_here()
