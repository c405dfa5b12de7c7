"""The commands: each verb declared once with its arguments and, where it has one, its MCP tool
(`command_core`, `arguments`); one pass runs it (`command_pass`: resolve the drone, build its context,
apply the policy, send under the drone's lock, track, audit); the Commander composes the verbs
(`commander`)."""
