"""docs/safety.md must describe every rule and quote the settings' real defaults."""

from __future__ import annotations

import re
from pathlib import Path

from gateway.config import Settings
from gateway.fleet.policy.safety_rules import Rule
from gateway.fleet.policy.vehicle_limits import split_patterns

DOC = (Path(__file__).resolve().parents[2] / "docs" / "safety.md").read_text()


def test_every_rule_is_documented() -> None:
    missing = [r.value for r in Rule if f"| `{r.value}` |" not in DOC]
    assert not missing, f"docs/safety.md lacks a table row for: {missing}"


def test_quoted_defaults_match_the_settings() -> None:
    quoted = re.findall(r"`GATEWAY_([A-Z_]+)` \(([a-z0-9.]+)\)", DOC)
    assert len(quoted) >= 8
    for name, text in quoted:
        default = Settings.model_fields[name.lower()].default
        expected = str(default).lower() if isinstance(default, bool) else f"{default:g}"
        assert text == expected, f"GATEWAY_{name}: doc says {text}, settings say {expected}"


def test_every_default_deny_pattern_is_explained() -> None:
    patterns = split_patterns(Settings.model_fields["param_deny_patterns"].default)
    missing = [p for p in patterns if f"`{p}`" not in DOC]
    assert not missing, f"docs/safety.md does not explain: {missing}"


def test_every_default_pilot_mode_is_listed() -> None:
    modes = split_patterns(Settings.model_fields["mode_deny_in_air"].default)
    missing = [m for m in modes if not re.search(rf"\b{m}\b", DOC)]
    assert not missing, f"docs/safety.md does not list: {missing}"
