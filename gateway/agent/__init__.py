"""The agent host: an OpenAI-compatible chat model flies the fleet through the gateway's MCP tools.

Modules: ``host`` (the tool loop), ``mcp_link`` (MCP client), ``toolbox`` (tool selection, validation,
results), ``parsing`` (tool calls written as text), ``display`` (rich / JSON lines), ``cli``
(``fleet-gateway agent``), ``settings`` (environment fallbacks). The benchmark's harness (missions,
scripted endpoint, local stack) lives in ``bench/agent_harness``, outside the installed package.
"""
