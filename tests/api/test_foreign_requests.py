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


MCP_LIST = {  # a 2025-era client's opening request
    "jsonrpc": "2.0",
    "id": 1,
    "method": "initialize",
    "params": {
        "protocolVersion": "2025-06-18",
        "capabilities": {},
        "clientInfo": {"name": "t", "version": "1"},
    },
}
MCP_HEADERS = {"accept": "application/json, text/event-stream"}


@pytest.mark.parametrize(
    ("host", "answered"),
    [
        ("LOCALHOST:8765", True),
        ("LocalHost", True),
        ("127.0.0.1:8765", True),
        ("[::1]:8765", True),
        ("127.0.0.1:8765@evil.example", False),
        ("localhost:8765/x", False),
        ("127.0.0.1:notaport", False),
        ("evil.example:8765", False),
    ],
)
def test_one_host_rule_for_rest_and_mcp(base_url: str, host: str, answered: bool) -> None:
    """Host names in any case pass on both doors; a Host that is not a host (userinfo, a path) on none."""
    rest = httpx.get(f"{base_url}/api/v1/vehicles", headers={"Host": host}, timeout=scaled(30))
    mcp = httpx.post(f"{base_url}/mcp", json=MCP_LIST, headers={**MCP_HEADERS, "Host": host}, timeout=30)
    if answered:
        assert rest.status_code == 200, rest.text
        assert mcp.status_code == 200 and "serverInfo" in mcp.text, mcp.text
    else:
        assert rest.status_code == 421, rest.text
        assert mcp.status_code == 421, mcp.text
        assert "is not one this gateway answers" in mcp.json()["error"]["message"]


def test_a_foreign_origin_is_refused_on_mcp_in_the_rest_words(base_url: str) -> None:
    headers = {**MCP_HEADERS, "Origin": "http://evil.example"}
    r = httpx.post(f"{base_url}/mcp", json=MCP_LIST, headers=headers, timeout=scaled(30))
    assert r.status_code == 403 and "may not change anything here" in r.json()["error"]["message"], r.text
    own = {**MCP_HEADERS, "Origin": base_url}
    assert httpx.post(f"{base_url}/mcp", json=MCP_LIST, headers=own, timeout=scaled(30)).status_code == 200


def test_an_mcp_name_header_padded_with_whitespace_names_the_tool(base_url: str) -> None:
    """RFC 9110 5.5: whitespace around a field value is not part of it (the MCP conformance case
    sep-2243-server-accepts-whitespace-header-value). Sent raw: HTTP clients trim it themselves."""
    import json
    import socket
    from urllib.parse import urlsplit

    where = urlsplit(base_url)
    meta = {
        "io.modelcontextprotocol/protocolVersion": "2026-07-28",
        "io.modelcontextprotocol/clientCapabilities": {},
    }
    body = json.dumps(
        {
            "jsonrpc": "2.0",
            "id": 7,
            "method": "tools/call",
            "params": {"name": "get_battery", "arguments": {"drone_id": "alpha"}, "_meta": meta},
        }
    ).encode()
    head = (
        "POST /mcp HTTP/1.1\r\n"
        f"Host: {where.netloc}\r\n"
        "Content-Type: application/json\r\n"
        "Accept: application/json, text/event-stream\r\n"
        "MCP-Protocol-Version: 2026-07-28\r\n"
        "Mcp-Method: tools/call\r\n"
        "Mcp-Name:   get_battery  \r\n"
        f"Content-Length: {len(body)}\r\n"
        "Connection: close\r\n\r\n"
    ).encode()
    with socket.create_connection((where.hostname, where.port), timeout=scaled(30)) as sock:
        sock.sendall(head + body)
        answer = b""
        while chunk := sock.recv(65536):
            answer += chunk
    status_line, _, rest = answer.partition(b"\r\n")
    assert b" 200 " in status_line, answer[:600]
    assert b"does not match" not in rest and b'"id":7' in rest.replace(b" ", b""), answer[:600]
