"""Which operations a node that takes a drone over follows again, from their stored params (units)."""

from __future__ import annotations

from gateway.cluster.takeover import tracker_for
from gateway.fleet.operations.trackers import GotoTracker, TakeoffTracker

LEG = {"lat_deg": 47.3978, "lon_deg": 8.5456, "alt_m": 15.0}


def test_a_relative_move_is_followed_again_unless_it_took_off_first() -> None:
    """A move that took off first may have been lost before its leg was sent: it is not followed as a
    goto (None: the new owner closes it as interrupted, saying to check the drone)."""
    followed = tracker_for("move_to_relative", LEG, 2.0)
    assert isinstance(followed, GotoTracker) and followed.alt_rel_m == 15.0
    assert tracker_for("move_to_relative", {**LEG, "takeoff_first": True}, 2.0) is None
    assert isinstance(tracker_for("takeoff", {"alt_m": 10.0}, 2.0), TakeoffTracker)
