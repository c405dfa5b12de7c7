"""The agent host: a chat model writes a typed plan, the host compiles it to the gateway's MCP calls (over
MCP only, nothing of ``gateway`` imported): ``plan`` is the schema, ``decoding`` asks the model, ``compiler``
turns steps into tool calls (units, geometry, order), ``checks`` vet each call, ``host`` a turn."""
