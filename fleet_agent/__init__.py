"""The agent host: a chat model writes a typed plan, the host compiles it to the gateway's MCP calls.

It talks to the gateway over MCP only (it imports nothing of ``gateway``): ``plan`` is the schema the model
writes against, ``decoding`` asks the model for a plan under that schema, ``compiler`` turns each step into
tool calls (units, geometry and ordering are computed here, never by the model), ``checks`` are the
registered checks of a call before it is sent, and ``host`` runs a turn.
"""
