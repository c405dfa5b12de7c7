"""The check a node runs before it answers a call for a drone: against the lease epoch it holds (an owner's
lease, or a fenced node's stop path), one check with the words of each."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from gateway.cluster.bus import epoch_check
from gateway.cluster.fenced_stops import STOP_PATH_WORDS
from gateway.cluster.owner_calls import LEASE_WORDS
from gateway.errors import NoOwner, NotRun


@dataclass(frozen=True)
class Held:
    epoch: int


def test_a_call_for_the_epoch_held_or_for_no_epoch_runs() -> None:
    check = epoch_check({"d1": Held(7)}, "d1", "n1", LEASE_WORDS)
    check(7)
    check(None)


def test_an_owner_that_holds_no_lease_says_it_no_longer_owns_the_drone() -> None:
    with pytest.raises(NoOwner, match=r"^node n1 no longer owns drone 'd1': not run; retry$"):
        epoch_check({"d2": Held(7)}, "d1", "n1", LEASE_WORDS)(7)


def test_a_call_sent_for_another_epoch_is_not_run_and_names_both() -> None:
    with pytest.raises(NotRun) as lease:
        epoch_check({"d1": Held(8)}, "d1", "n1", LEASE_WORDS)(7)
    assert str(lease.value.args[0]).startswith(
        "a call for drone 'd1' sent for lease epoch 7 reached node n1, which holds epoch 8: not run"
    )
    with pytest.raises(NotRun) as stop:
        epoch_check({"d1": Held(8)}, "d1", "n1", STOP_PATH_WORDS)(7)
    assert str(stop.value.args[0]) == (
        "a stop for drone 'd1' sent for lease epoch 7 reached node n1, which last held epoch 8: "
        "not run; retry"
    )


def test_a_fenced_node_without_the_stop_path_says_so() -> None:
    with pytest.raises(NoOwner, match=r"^node n1 has no stop path to drone 'd1' any more: retry$"):
        epoch_check({}, "d1", "n1", STOP_PATH_WORDS)(None)
