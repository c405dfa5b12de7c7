"""The safety policy and who is asking: the rules and their wording, what the checks read, the checks,
geofences, the limits parameters may set, operator and takeover locks, the caller."""
