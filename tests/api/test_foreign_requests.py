"""A web page a person visits cannot command drones through a token-less gateway on their machine: REST
refuses a foreign Host (DNS rebinding) and a foreign browser Origin, over real HTTP, and nothing
changes. Strict request types: `lock: 0` and `?until=0.5` are 422s, not false and 1970."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from gateway.app import create_app
from gateway.config import Settings
from gateway.hosts import foreign_request
from tests.api.server import serve_in_thread
from tests.fakes import FakeRegistry
from tests.helpers.timing import scaled

DRONE = {"id": "alpha", "url": "udpin://127.0.0.1:14550", "expected_sysid": 1}


@pytest.fixture
def base_url(tmp_path: Path) -> Iterator[str]:
    config = Settings(_env_file=None, database_url=f"sqlite+aiosqlite:///{tmp_path / 'gateway.db'}")
    with serve_in_thread(create_app(config, registry_factory=FakeRegistry)) as url:
        created = httpx.post(f"{url}/api/v1/vehicles", json=DRONE, timeout=scaled(30))
        assert created.status_code == 201, created.text
        yield url


def locks(base_url: str) -> list[dict[str, object]]:
    return httpx.get(f"{base_url}/api/v1/locks", timeout=scaled(30)).json()["items"]


@pytest.mark.parametrize(
    ("headers", "status", "words"),
    [
        ({"Host": "evil.example"}, 421, "Host 'evil.example' is not one this gateway answers"),
        ({"Host": "evil.example:8765", "Origin": "http://evil.example"}, 421, "not one this gateway answers"),
        ({"Origin": "http://evil.example"}, 403, "Origin 'http://evil.example' may not change anything"),
        ({"Origin": "null"}, 403, "Origin 'null' may not change anything"),
        ({"Sec-Fetch-Site": "cross-site"}, 403, "a cross-site browser request may not change anything"),
    ],
)
def test_a_stop_or_kill_from_another_site_is_refused_and_nothing_changes(
    base_url: str, headers: dict[str, str], status: int, words: str
) -> None:
    for path, body in (("/api/v1/fleet/stop", {"action": "land"}), ("/api/v1/vehicles/alpha/kill", None)):
        r = httpx.post(f"{base_url}{path}", json=body, headers=headers, timeout=scaled(30))
        assert r.status_code == status, (path, r.text)
        assert words in r.json()["error"]["message"] and "nothing was done" in r.json()["error"]["message"]
    assert locks(base_url) == []  # the stop did not even lock the fleet
    page = httpx.get(f"{base_url}/api/v1/audit", timeout=scaled(30)).json()
    assert not [a for a in page["items"] if a["action"] in ("fleet_stop", "stop_all", "kill")], page["items"]


def test_the_same_requests_from_here_or_from_a_script_go_through(base_url: str) -> None:
    own_page = {"Origin": base_url, "Sec-Fetch-Site": "same-origin"}
    r = httpx.post(f"{base_url}/api/v1/fleet/lock", json={"reason": "console"}, headers=own_page, timeout=30)
    assert r.status_code == 200, r.text
    assert httpx.delete(f"{base_url}/api/v1/fleet/lock", timeout=scaled(30)).status_code == 200  # curl-like
    stop = httpx.post(f"{base_url}/api/v1/fleet/stop", timeout=scaled(30))  # no body, no headers: a script
    assert stop.status_code == 200, stop.text
    assert [lk["scope"] for lk in locks(base_url)] == ["*"]
    # reads from a foreign Host are refused too (a rebinding page could read positions)
    read = httpx.get(f"{base_url}/api/v1/vehicles", headers={"Host": "evil.example"}, timeout=scaled(30))
    assert read.status_code == 421


@pytest.mark.parametrize("lock", [0, 1, "true", "yes", None])
def test_a_stop_lock_that_is_not_a_boolean_is_refused(base_url: str, lock: object) -> None:
    r = httpx.post(f"{base_url}/api/v1/fleet/stop", json={"lock": lock}, timeout=scaled(30))
    assert r.status_code == 422, r.text
    assert "lock" in r.json()["error"]["message"]
    assert locks(base_url) == []


@pytest.mark.parametrize("path", ["/api/v1/audit", "/api/v1/flights", "/api/v1/vehicles/alpha/statustexts"])
def test_a_time_that_is_a_bare_number_is_refused(base_url: str, path: str) -> None:
    r = httpx.get(f"{base_url}{path}", params={"since": "0.5"}, timeout=scaled(30))
    assert r.status_code == 422, r.text
    assert (
        "must be an ISO 8601 time" in r.json()["error"]["message"] and "'0.5'" in r.json()["error"]["message"]
    )
    assert (
        httpx.get(f"{base_url}{path}", params={"since": "2026-11-27T10:00:00Z"}, timeout=30).status_code
        == 200
    )


def test_the_allow_list_is_configurable_for_a_proxy() -> None:
    behind = Settings(_env_file=None, allowed_hosts="fleet.example.org")
    assert foreign_request(True, "fleet.example.org", "https://fleet.example.org", None, behind) is None
    assert foreign_request(True, "fleet.example.org:443", None, None, behind) is None
    assert foreign_request(True, "other.example", None, None, behind) is not None
    assert foreign_request(True, "[::1]:8765", None, "none", Settings(_env_file=None)) is None
    old_name = Settings(_env_file=None, mcp_allowed_hosts="gw.local")
    assert foreign_request(True, "gw.local:8765", "http://gw.local:8765", None, old_name) is None
