"""Long-running actions as tracked operations: the trackers, the operation manager and its mode watch
(takeover detection), fleet operations built of per-drone steps, their views, and where a verb runs
(routing)."""
