"""A lease tick that fails because the database is slow or away logs one line; anything else keeps its
traceback (a bug in the keeper must stay visible)."""

from __future__ import annotations

import logging

import pytest
from sqlalchemy.exc import OperationalError

from gateway.cluster.node import _log_keeping_failure


@pytest.mark.parametrize(
    "failure",
    [
        TimeoutError("the lease tick did not finish in time (the database does not answer)"),
        ConnectionRefusedError(111, "Connect call failed"),
        OperationalError("UPDATE leases", {}, Exception("server closed the connection\nunexpectedly")),
    ],
)
def test_a_database_fault_is_one_warning_line(failure: Exception, caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="gateway.cluster"):
        _log_keeping_failure(failure)
    [record] = caplog.records
    assert record.levelno == logging.WARNING
    assert record.exc_info is None
    assert "\n" not in record.getMessage()
    assert type(failure).__name__ in record.getMessage()


def test_any_other_failure_keeps_its_traceback(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING, logger="gateway.cluster"):
        _log_keeping_failure(KeyError("vehicle"))
    [record] = caplog.records
    assert record.levelno == logging.ERROR
    assert record.exc_info is not None and record.exc_info[0] is KeyError
