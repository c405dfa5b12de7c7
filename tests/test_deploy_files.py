"""The shipped deploy files say what the docs promise."""

from __future__ import annotations

import configparser
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _unit() -> configparser.ConfigParser:
    parser = configparser.ConfigParser(strict=False, interpolation=None)
    parser.optionxform = str  # type: ignore[assignment,method-assign]
    parser.read(ROOT / "deploy" / "fleet-gateway.service")
    return parser


def test_systemd_unit_restarts_and_runs_unprivileged() -> None:
    service = _unit()["Service"]
    assert service["Restart"] == "on-failure"
    assert service["User"] not in ("", "root")
    assert service["StateDirectory"] == "fleet-gateway"
    raw = (ROOT / "deploy" / "fleet-gateway.service").read_text().splitlines()
    database = "sqlite+aiosqlite:////var/lib/fleet-gateway/fleet-gateway.db"
    assert f"Environment=GATEWAY_DATABASE_URL={database}" in raw
    assert service["ExecStart"].endswith("fleet-gateway serve")
    assert service["KillMode"] == "control-group"
    assert service["NoNewPrivileges"] == "yes"
    assert service["CapabilityBoundingSet"] == ""


def test_env_example_covers_every_setting() -> None:
    from gateway.config import Settings

    text = (ROOT / "deploy" / ".env.example").read_text()
    for name in Settings.model_fields:
        assert f"GATEWAY_{name.upper()}=" in text
