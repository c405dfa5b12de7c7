"""The shipped deploy files say what the docs promise."""

from __future__ import annotations

import configparser
import shutil
import subprocess
from pathlib import Path

import pytest

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


def _verify_unit(tmp_path: Path, text: str) -> subprocess.CompletedProcess[str]:
    """`systemd-analyze verify` on ``text`` installed into a root made of the host's system units and an
    executable where ExecStart points (the unit names the installed gateway, absent here)."""
    root = tmp_path / "root"
    shutil.copytree(SYSTEM_UNITS, root / "usr/lib/systemd/system", symlinks=True)
    exe = root / "opt/fleet-gateway/.venv/bin/fleet-gateway"
    exe.parent.mkdir(parents=True)
    exe.write_text("#!/bin/sh\n")
    exe.chmod(0o755)
    (root / "etc/systemd/system").mkdir(parents=True)
    (root / "etc/systemd/system/fleet-gateway.service").write_text(text)
    return subprocess.run(
        ["systemd-analyze", "verify", f"--root={root}", "fleet-gateway.service"],
        capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip


SYSTEM_UNITS = next(
    (
        p
        for p in (Path("/usr/lib/systemd/system"), Path("/lib/systemd/system"))
        if (p / "sysinit.target").exists()
    ),
    None,
)


@pytest.mark.skipif(shutil.which("systemd-analyze") is None, reason="systemd-analyze is not installed")
@pytest.mark.skipif(SYSTEM_UNITS is None, reason="no systemd system units (sysinit.target) on this host")
def test_systemd_unit_passes_systemd_analyze_verify(tmp_path: Path) -> None:
    text = (ROOT / "deploy" / "fleet-gateway.service").read_text()
    done = _verify_unit(tmp_path / "shipped", text)
    assert done.returncode == 0 and (done.stdout + done.stderr).strip() == "", done.stdout + done.stderr
    # the check sees mistakes: a bad value is reported
    broken = _verify_unit(tmp_path / "broken", text.replace("Type=exec", "Type=sometimes"))
    assert "Failed to parse service type" in broken.stdout + broken.stderr
