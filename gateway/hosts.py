"""Which Host names and browser Origins the gateway answers: one allow-list for /mcp and the REST API.

A web page a person visits must not be able to command drones through a gateway on that person's
machine: by DNS rebinding (a foreign name that resolves to 127.0.0.1, seen in the Host header) or by a
cross-site form or fetch (seen in the Origin and Sec-Fetch-Site headers, which browsers always send on
such requests and scripts such as curl never do). Loopback names are always allowed; a deployment behind
a proxy names its own in GATEWAY_ALLOWED_HOSTS ('*': any, when the proxy checks them itself).
"""

from __future__ import annotations

import re
from urllib.parse import urlsplit

from gateway.config import Settings

LOOPBACK_NAMES = ("127.0.0.1", "localhost", "::1")
#: what Sec-Fetch-Site says for a request the gateway's own pages (or no page: typed URL, bookmark) made
SAME_SITE_FETCHES = frozenset({"same-origin", "none"})


def extra_hosts(settings: Settings) -> list[str]:
    """The names configured besides loopback (GATEWAY_ALLOWED_HOSTS and its older MCP-only spelling)."""
    text = f"{settings.allowed_hosts},{settings.mcp_allowed_hosts}"
    return list(dict.fromkeys(h.strip().lower() for h in text.split(",") if h.strip()))


#: a Host header as RFC 9110 has it: a name, an IPv4 address or a bracketed IPv6 address, then an optional
#: port; nothing else ('127.0.0.1:8765@evil.example' is no host)
_HOST_HEADER = re.compile(r"^(?:\[(?P<ipv6>[0-9a-f:.]+)\]|(?P<name>[a-z0-9_.-]+))(?::(?P<port>[0-9]{1,5}))?$")


def _hostname(host_header: str) -> str | None:
    """The name of a Host header value without its port, lower-case ('[::1]:8765' -> '::1',
    'LOCALHOST:8765' -> 'localhost'); None for a value that is not a host."""
    found = _HOST_HEADER.match(host_header.strip().lower())
    if found is None:
        return None
    return found["ipv6"] or found["name"]


def host_allowed(host_header: str | None, settings: Settings) -> bool:
    """The one Host rule of REST and /mcp: a well-formed Host whose name (any case, any port) is a
    loopback name or one GATEWAY_ALLOWED_HOSTS gives (with its port, or any)."""
    if not host_header:
        return False
    extras = extra_hosts(settings)
    if "*" in extras:
        return True
    name = _hostname(host_header)
    if name is None:
        return False
    return name in LOOPBACK_NAMES or name in extras or host_header.strip().lower() in extras


def origin_allowed(origin: str | None, settings: Settings) -> bool:
    """No Origin (not a browser) is allowed; 'null' (a sandboxed or privacy-redirected page) is not."""
    if origin is None:
        return True
    parts = urlsplit(origin.strip())
    if parts.scheme not in ("http", "https") or not parts.netloc:
        return False
    return host_allowed(parts.netloc, settings)


def foreign_request(
    method_changes_state: bool,
    host: str | None,
    origin: str | None,
    fetch_site: str | None,
    settings: Settings,
) -> tuple[int, str] | None:
    """(status, message) refusing a request that came from elsewhere, or None to let it through.

    Host is checked on every request (DNS rebinding could read positions too); Origin and
    Sec-Fetch-Site on requests that change state (a browser sends both on any cross-site POST)."""
    if not host_allowed(host, settings):
        return 421, (
            f"Host {str(host)[:80]!r} is not one this gateway answers (loopback names and "
            "GATEWAY_ALLOWED_HOSTS); nothing was done"
        )
    if not method_changes_state:
        return None
    if not origin_allowed(origin, settings):
        return 403, (
            f"Origin {str(origin)[:80]!r} may not change anything here (a web page on another site); "
            "nothing was done. Allowed: loopback and GATEWAY_ALLOWED_HOSTS"
        )
    if origin is None and fetch_site is not None and fetch_site.strip().lower() not in SAME_SITE_FETCHES:
        return (
            403,
            f"a {fetch_site.strip()[:20]} browser request may not change anything here; nothing was done",
        )
    return None


def mcp_foreign_request(host: str | None, origin: str | None, settings: Settings) -> tuple[int, str] | None:
    """(status, message) refusing an /mcp request from elsewhere, or None: the REST rule for the Host,
    and a browser's Origin (when it sends one) must be allowed (every MCP request can change state; an
    MCP client that is no browser sends no Origin)."""
    if not host_allowed(host, settings):
        return foreign_request(False, host, None, None, settings)
    if origin is not None and not origin_allowed(origin, settings):
        return foreign_request(True, host, origin, None, settings)
    return None
