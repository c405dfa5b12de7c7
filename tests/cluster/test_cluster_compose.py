"""deploy/docker-compose.cluster.yml (no Docker engine here): every gateway setting in it is one the gateway
has and accepts, the nodes share one PostgreSQL and one NATS with distinct node ids, and the drones
registered are exactly the ones the simulator service serves."""

from __future__ import annotations

import re
import shlex
import subprocess
from pathlib import Path
from typing import Any

import yaml

from gateway.config import Settings
from gateway.hosts import host_allowed
from gateway.registry.spec import VehicleSpec
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]
COMPOSE = ROOT / "deploy" / "docker-compose.cluster.yml"
NODES = ["node-a", "node-b", "node-c"]


def _compose() -> dict[str, Any]:
    return yaml.safe_load(COMPOSE.read_text())


def _resolved(value: str) -> str:
    """${NAME:?message} / ${NAME:-default} as compose would fill them for a test value."""
    return re.sub(r"\$\{(\w+):[?-][^}]*\}", lambda m: f"test-{m.group(1).lower()}", value)


def test_services_are_nats_postgres_three_nodes_the_drones_and_their_registrar() -> None:
    services = _compose()["services"]
    assert sorted(services) == sorted(["nats", "postgres", "drones", "register-drones", *NODES])
    # the official images unless NATS_IMAGE / POSTGRES_IMAGE name others (deploy/debian/ builds them)
    assert services["nats"]["image"].startswith("${NATS_IMAGE:-nats:")
    assert services["postgres"]["image"].startswith("${POSTGRES_IMAGE:-postgres:")
    for name in ("nats.Containerfile", "postgres.Containerfile", "postgres-entrypoint.sh"):
        assert (ROOT / "deploy" / "debian" / name).is_file(), name


def test_every_node_is_a_valid_cluster_node_on_one_database_and_one_nats() -> None:
    services = _compose()["services"]
    urls, nats, ids, host_ports = set(), set(), set(), set()
    for name in NODES:
        node = services[name]
        env = {k: _resolved(str(v)) for k, v in node["environment"].items()}
        fields = {f"GATEWAY_{f.upper()}" for f in Settings.model_fields}
        assert set(env) <= fields, set(env) - fields
        settings = Settings(_env_file=None, **{k.removeprefix("GATEWAY_").lower(): v for k, v in env.items()})
        assert settings.clustered and settings.database_url.startswith("postgresql+asyncpg://")
        assert settings.node_id == name
        assert ":?" in node["environment"]["GATEWAY_OPERATOR_TOKENS"]  # listening beyond loopback needs it
        urls.add(settings.database_url)
        nats.add(settings.cluster_nats_url)
        ids.add(settings.node_id)
        assert node["depends_on"]["postgres"]["condition"] == "service_healthy"
        assert any("/readyz" in part for part in node["healthcheck"]["test"])
        (published,) = node["ports"]
        assert published.startswith("127.0.0.1:")
        host_ports.add(published.split(":")[1])
        assert node["command"][:2] == ["fleet-gateway", "serve"]
    assert len(urls) == 1 and len(nats) == 1 and len(ids) == 3 and len(host_ports) == 3
    (url,) = urls
    assert "@postgres:5432/fleet" in url and nats == {"nats://nats:4222"}
    pg = services["postgres"]["environment"]
    assert pg["POSTGRES_USER"] == "fleet" and pg["POSTGRES_DB"] == "fleet"


def test_the_registrar_adds_exactly_the_drones_the_simulator_serves() -> None:
    services = _compose()["services"]
    sim = services["drones"]["command"]
    count = int(sim[sim.index("--count") + 1])
    base = int(sim[sim.index("--tcp-base-port") + 1])
    script = services["register-drones"]["command"][-1].replace("$$", "$")  # compose's escape
    # the registrar's own shell loop, run by sh with each command printed instead of run
    printed = subprocess.run(
        ["sh", "-c", script.replace("fleet-gateway drones add", "echo fleet-gateway drones add")],
        capture_output=True,
        text=True,
        check=True,
        timeout=scaled(30),
    ).stdout.splitlines()
    assert len(printed) == count
    for i, line in enumerate(printed):
        args = shlex.split(line)
        assert args[:3] == ["fleet-gateway", "drones", "add"]
        spec = VehicleSpec(id=args[3], url=args[4], expected_sysid=int(args[args.index("--sysid") + 1]))
        assert spec.url == f"tcpout://drones:{base + 10 * i}" and spec.expected_sysid == i + 1
        assert "--if-missing" in args and args[args.index("--api") + 1] == "http://node-a:8765"
        # node-a answers that Host (foreign Host headers are refused)
        node_env = {k: _resolved(str(v)) for k, v in services["node-a"]["environment"].items()}
        allowed = Settings(_env_file=None, allowed_hosts=node_env.get("GATEWAY_ALLOWED_HOSTS", ""))
        assert host_allowed("node-a:8765", allowed) and not host_allowed("evil.example", allowed)
        assert float(args[args.index("--wait") + 1]) >= 60  # waits for node-a itself (podman-compose)
    assert services["register-drones"]["depends_on"]["node-a"]["condition"] == "service_healthy"
