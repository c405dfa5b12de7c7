"""What it takes to register a vehicle: validated id, MAVLink connection URL and metadata."""

from __future__ import annotations

import ipaddress
import re
from urllib.parse import urlsplit

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator
from typing_extensions import TypedDict  # pydantic validates it (update_drone's changes) on Python 3.11

VEHICLE_ID_PATTERN = r"^[a-z0-9-]{1,32}$"
NODE_TAG_PATTERN = r"^[A-Za-z0-9_.\-]{1,32}$"
CONNECTION_SCHEMES = ("udpin", "udpout", "tcpin", "tcpout", "serial")
GCS_SCHEMES = ("udpout", "udpin", "tcpin", "tcpout")
MAX_GCS_ENDPOINTS = 8
_HOSTNAME = re.compile(r"^[A-Za-z0-9.\-]{1,253}$")


def redacted(url: str) -> str:
    """``url`` as it may be shown: credentials (``user:pw@``) replaced by ``***@``."""
    scheme, sep, rest = url.partition("://")
    if sep and "@" in rest.split("/", 1)[0]:
        return f"{scheme}://***@{rest.split('@', 1)[1]}"
    return url


def validate_connection_url(url: str) -> str:
    """Check a URL in mavsdk_server syntax and return it unchanged; raise ValueError naming the problem."""
    if len(url) > 256:
        raise ValueError("connection URL longer than 256 characters")
    parts = urlsplit(url)
    if redacted(url) != url or parts.username is not None:
        raise ValueError(
            f"credentials in a MAVLink URL are not accepted (given '{redacted(url)[:80]}'): MAVLink has no "
            "login; give scheme://host:port"
        )
    if parts.scheme not in CONNECTION_SCHEMES:
        raise ValueError(f"connection URL scheme must be one of {', '.join(CONNECTION_SCHEMES)}; got '{url}'")
    if parts.scheme == "serial":
        # serial:///dev/ttyUSB0[:baud]
        path = parts.path
        if not path.startswith("/"):
            raise ValueError(f"serial URL needs a device path, e.g. serial:///dev/ttyUSB0:57600; got '{url}'")
        _device, _, baud = path.partition(":")
        if baud and not baud.isdigit():
            raise ValueError(f"serial baud rate must be a number; got '{baud}'")
        return url
    if parts.path or parts.query or parts.fragment:
        raise ValueError(f"network URL must be scheme://host:port with nothing after the port; got '{url}'")
    try:
        port = parts.port
    except ValueError as exc:
        raise ValueError(f"invalid port in '{url}'") from exc
    if port is None or not 1 <= port <= 65535:
        raise ValueError(f"network URL needs a port 1-65535, e.g. udpin://0.0.0.0:14540; got '{url}'")
    host = parts.hostname or ""
    if not _HOSTNAME.match(host):
        raise ValueError(f"network URL needs a host name or address; got '{url}'")
    return url


def validate_gcs_endpoints(urls: list[str]) -> list[str]:
    """Check ground station endpoint URLs (network MAVLink URLs, distinct); raise ValueError with one line
    saying what was given and what is accepted (the caller names the field: gcs_endpoints)."""
    accepted = "udpout://host:port, udpin://host:port, tcpin://host:port or tcpout://host:port"
    if len(urls) > MAX_GCS_ENDPOINTS:
        raise ValueError(f"{len(urls)} endpoints given; at most {MAX_GCS_ENDPOINTS} are accepted")
    seen: set[str] = set()
    for url in urls:
        shown = redacted(url)[:80] if isinstance(url, str) else repr(url)[:80]
        if not isinstance(url, str) or urlsplit(url).scheme not in GCS_SCHEMES:
            raise ValueError(f"'{shown}' is not accepted; give MAVLink URLs {accepted}")
        try:
            validate_connection_url(url)
        except ValueError as exc:
            raise ValueError(f"'{shown}' is not accepted ({exc}); give {accepted}") from None
        if url in seen:
            raise ValueError(f"'{shown}' is given twice; give each endpoint once")
        seen.add(url)
    return urls


class VehicleSpec(BaseModel):
    """A vehicle registration as an operator submits it."""

    model_config = ConfigDict(extra="forbid")

    id: str = Field(pattern=VEHICLE_ID_PATTERN, description="Vehicle id: 1-32 of a-z, 0-9 and '-'.")
    url: str = Field(
        description="MAVLink connection URL in mavsdk_server syntax, e.g. tcpout://127.0.0.1:5760"
    )
    name: str | None = Field(None, max_length=100, description="Human-readable name.")
    tags: list[str] = Field(default_factory=list, max_length=20, description="Free tags, e.g. ['survey'].")
    expected_sysid: int | None = Field(
        None, ge=1, le=255, description="MAVLink system id the vehicle must report."
    )
    node_tag: str | None = Field(
        None,
        pattern=NODE_TAG_PATTERN,
        description="Cluster only: nodes carrying this tag (GATEWAY_CLUSTER_NODE_TAGS) own the drone, "
        "e.g. the site whose radio reaches it; unset: any node.",
    )
    gcs_endpoints: list[str] = Field(
        default_factory=list,
        description="Ground stations that share the drone's MAVLink (relayed both ways; they can command "
        "it, and a mode change from one is a takeover): MAVLink URLs such as udpout://127.0.0.1:14550 "
        "(send to a ground station listening there) or tcpin://0.0.0.0:5790 (ground stations connect "
        f"here); at most {MAX_GCS_ENDPOINTS}. Binding an address other than loopback exposes the drone "
        "to that network.",
    )

    @field_validator("url")
    @classmethod
    def _url(cls, value: str) -> str:
        return validate_connection_url(value)

    @field_validator("gcs_endpoints")
    @classmethod
    def _gcs(cls, value: list[str]) -> list[str]:
        return validate_gcs_endpoints(value)

    @model_validator(mode="after")
    def _gcs_not_the_vehicle(self) -> VehicleSpec:
        own = link_address(self.url)
        for url in self.gcs_endpoints:
            if url == self.url or (own is not None and same_place(link_address(url), own)):
                raise ValueError(
                    f"gcs_endpoints: '{url}' is the drone's own link ({self.url}); give the ground "
                    "stations' endpoints"
                )
        return self

    @field_validator("tags")
    @classmethod
    def _tags(cls, value: list[str]) -> list[str]:
        for tag in value:
            if not 1 <= len(tag) <= 32 or not re.match(r"^[A-Za-z0-9_.\-]+$", tag):
                raise ValueError(f"tag '{tag[:40]}' must be 1-32 of letters, digits, '_', '.', '-'")
        return value


_ANY_HOST = frozenset({"0.0.0.0", "::", ""})


def link_address(url: str) -> tuple[str, str, int] | None:
    """(transport, host, port) of a network MAVLink URL: transport "tcp" or "udp"; None for serial."""
    parts = urlsplit(url)
    if parts.scheme == "serial" or parts.port is None:
        return None
    return parts.scheme[:3], (parts.hostname or "").lower(), parts.port


def _local(host: str) -> bool:
    if host in _ANY_HOST or host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def same_place(a: tuple[str, str, int] | None, b: tuple[str, str, int] | None) -> bool:
    """Whether two link addresses reach the same socket: same transport and port, and the same host or
    both this host (loopback, or a wildcard bind)."""
    if a is None or b is None or a[0] != b[0] or a[2] != b[2]:
        return False
    return a[1] == b[1] or (_local(a[1]) and _local(b[1]))


def gcs_endpoint_conflict(spec: VehicleSpec, others: list[VehicleSpec], gateway_port: int) -> str | None:
    """Why one of ``spec``'s ground station endpoints would carry another vehicle or the gateway itself
    (another registered drone's link, the gateway's HTTP port), in one line; None when none does."""
    for url in spec.gcs_endpoints:
        place = link_address(url)
        for other in others:
            if other.id != spec.id and same_place(place, link_address(other.url)):
                return (
                    f"gcs_endpoints: '{url}' is drone '{other.id}''s own link ({other.url}); a ground "
                    f"station endpoint of '{spec.id}' must lead to a ground station, never another vehicle"
                )
        if same_place(place, ("tcp", "127.0.0.1", gateway_port)):
            return f"gcs_endpoints: '{url}' is the gateway's own HTTP port; give a ground station's endpoint"
    return None


class VehicleChanges(TypedDict, total=False):
    """What a registration update may change (`Store.update_vehicle`, the registry's ``update``): the
    fields given are set, the others kept."""

    name: str | None
    tags: list[str]
    expected_sysid: int | None
    node_tag: str | None
    url: str
    gcs_endpoints: list[str]
    auto_connect: bool
