"""Several gateway nodes as one fleet: PostgreSQL leases decide which node runs each vehicle's sidecar,
NATS carries telemetry snapshots to every node and calls to each vehicle's owner (docs/cluster.md)."""
