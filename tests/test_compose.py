"""deploy/docker-compose.yml runs what the swarm test runs: the same services, commands and addresses
(both come from tests/swarm/topology.py), and deploy/Dockerfile builds an image that can run them."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import yaml

from tests.swarm import topology as t

ROOT = Path(__file__).resolve().parent.parent
COMPOSE = ROOT / "deploy" / "docker-compose.yml"
DOCKERFILE = ROOT / "deploy" / "Dockerfile"
COMPOSE_SPEEDUP = 1.0  # real time in compose; the swarm test runs the same command faster


def _compose() -> dict[str, Any]:
    return yaml.safe_load(COMPOSE.read_text())


def _address(service: dict[str, Any]) -> str:
    return service["networks"]["swarm"]["ipv4_address"]


def test_services_are_the_gateway_five_drones_and_their_registrars() -> None:
    services = _compose()["services"]
    drones = [f"drone-{i + 1}" for i in range(t.DRONES)]
    registrars = [f"register-drone-{i + 1}" for i in range(t.DRONES)]
    assert sorted(services) == sorted(["gateway", *drones, *registrars])
    for service in services.values():  # one image, built from the repository root with deploy/Dockerfile
        assert service["image"] == "fleet-gateway:latest"
        assert (
            COMPOSE.parent / service["build"]["context"] / service["build"]["dockerfile"]
        ).resolve() == DOCKERFILE


def test_drones_run_the_swarm_tests_commands_at_the_same_addresses() -> None:
    services = _compose()["services"]
    for i in range(t.DRONES):
        drone = services[f"drone-{i + 1}"]
        assert drone["command"] == t.drone_command(i, COMPOSE_SPEEDUP)
        assert _address(drone) == t.drone_address(i)
        assert drone["command"][drone["command"].index("--bind") + 1] == t.drone_address(i)
        registrar = services[f"register-drone-{i + 1}"]
        api = f"http://{t.GATEWAY_ADDRESS}:{t.GATEWAY_PORT}"
        assert registrar["command"] == t.register_command(i, api)
        assert t.drone_url(i) in registrar["command"]
        assert registrar["depends_on"]["gateway"]["condition"] == "service_healthy"
        assert registrar["restart"] == "no"
        assert registrar["environment"]["GATEWAY_OPERATOR_TOKENS"].startswith("${GATEWAY_OPERATOR_TOKENS:?")
    addresses = [_address(services[f"drone-{i + 1}"]) for i in range(t.DRONES)] + [
        _address(services["gateway"])
    ]
    assert len(set(addresses)) == len(addresses)


def test_gateway_service_network_volume_and_healthcheck() -> None:
    compose = _compose()
    gateway = compose["services"]["gateway"]
    assert gateway["command"] == t.gateway_command()
    assert _address(gateway) == t.GATEWAY_ADDRESS
    subnet = compose["networks"]["swarm"]["ipam"]["config"][0]["subnet"]
    assert subnet == t.SUBNET
    # the database lives on a named volume
    volume, mount = gateway["volumes"][0].split(":")
    assert volume in compose["volumes"]
    database = gateway["environment"]["GATEWAY_DATABASE_URL"]
    assert database.startswith("sqlite+aiosqlite:///") and database.removeprefix(
        "sqlite+aiosqlite:///"
    ).startswith(mount + "/")
    for key, value in t.GATEWAY_ENV.items():
        assert gateway["environment"][key] == value
    # operator tokens are required to listen beyond loopback: compose refuses to start without one
    assert ":?" in gateway["environment"]["GATEWAY_OPERATOR_TOKENS"]
    assert any("/readyz" in part for part in gateway["healthcheck"]["test"])
    # published on loopback only, on 8765 unless GATEWAY_PUBLISH_PORT says otherwise (the swarm test's port)
    assert gateway["ports"] == [f"127.0.0.1:${{GATEWAY_PUBLISH_PORT:-{t.GATEWAY_PORT}}}:{t.GATEWAY_PORT}"]


def test_the_gateway_answers_the_host_its_registrars_call() -> None:
    """The gateway refuses foreign Host headers: the registrars' --api address must be one it answers."""
    from urllib.parse import urlsplit

    from gateway.config import Settings
    from gateway.hosts import host_allowed

    services = _compose()["services"]
    env = services["gateway"]["environment"]
    settings = Settings(_env_file=None, allowed_hosts=env.get("GATEWAY_ALLOWED_HOSTS", ""))
    for i in range(t.DRONES):
        command = services[f"register-drone-{i + 1}"]["command"]
        api = urlsplit(command[command.index("--api") + 1])
        assert host_allowed(api.netloc, settings), api.netloc
    assert not host_allowed("evil.example:8765", settings)


def test_registrars_wait_for_the_gateway_themselves() -> None:
    """podman-compose ignores `condition: service_healthy`: each registrar waits for /readyz itself."""
    for i in range(t.DRONES):
        command = _compose()["services"][f"register-drone-{i + 1}"]["command"]
        assert float(command[command.index("--wait") + 1]) >= 60


def test_dockerfile_runs_unprivileged_and_ships_the_migrations() -> None:
    text = DOCKERFILE.read_text()
    user = re.search(r"^USER\s+(\S+)", text, re.M)
    assert user is not None and user.group(1) not in ("root", "0")
    # one user name across the image and the systemd unit
    unit = (ROOT / "deploy" / "fleet-gateway.service").read_text()
    assert re.search(rf"^User={re.escape(user.group(1))}$", unit, re.M)
    assert re.search(rf"--create-home {re.escape(user.group(1))}$", text, re.M)
    # no VOLUME: it gives every container (drones too) an anonymous volume that outlives it
    assert not re.search(r"^VOLUME\b", text, re.M)
    # the package carries the migrations; the build checks the store finds them
    assert "pip install ." in text and "migrations_dir" in text
    cmd = re.search(r"^CMD (\[.*\])$", text, re.M)
    assert cmd is not None and json.loads(cmd.group(1)) == t.gateway_command()
    # every file the Dockerfile copies exists
    for line in re.findall(r"^COPY (.+) \S+$", text, re.M):
        for name in line.split():
            assert (ROOT / name).exists(), name


def test_image_build_checks_the_migrations_the_store_uses() -> None:
    """The image installs the wheel, which carries the migrations inside the package; in a checkout the
    store finds them at the top level, beside the package."""
    from gateway.registry.database import migrations_dir

    text = (ROOT / "deploy" / "Dockerfile").read_text()
    assert "pip install ." in text and "migrations_dir" in text
    assert migrations_dir() == ROOT / "migrations"
    assert (migrations_dir() / "env.py").is_file()
