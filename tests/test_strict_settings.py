"""Settings refuse non-finite numbers at start: a limit of inf (or nan) would hold nothing."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from gateway.config import Settings
from gateway.server_cli import main

LIMITS = ["GATEWAY_MAX_ALTITUDE_M", "GATEWAY_MAX_DISTANCE_M", "GATEWAY_MAX_SPEED_MPS"]


@pytest.mark.parametrize("name", LIMITS)
def test_an_infinite_limit_is_refused_naming_the_variable(monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    monkeypatch.setenv(name, "inf")
    with pytest.raises(ValidationError, match=f"{name} must be a finite number; got inf"):
        Settings(_env_file=None)


def test_serve_does_not_start_with_an_infinite_limit(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("GATEWAY_MAX_ALTITUDE_M", "inf")
    assert main(["serve", "--port", "1"]) == 2
    assert "GATEWAY_MAX_ALTITUDE_M must be a finite number" in capsys.readouterr().err
