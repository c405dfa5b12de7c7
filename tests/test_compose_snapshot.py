"""The compose tests' leftover check (scripts/swarm_test.py ``snapshot``) leaves the other compose test
project's objects alone, so that the swarm and cluster tests can run at once (CI runs them so, on images
scripts/compose_images.py built ahead), and still sees everything else: checked on real podman volumes.

The volumes live in a podman store of this test's own (CONTAINERS_STORAGE_CONF in a temporary directory):
CI starts the real swarm and cluster runs beside the suite's last files, and a volume labelled with their
project in the shared store would be removed by their teardown or counted by their leftover check."""

from __future__ import annotations

import os
import secrets
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "scripts"))

import swarm_test as s


@pytest.fixture
def podman_env() -> Iterator[dict[str, str]]:
    if shutil.which("podman") is None or os.geteuid() != 0:
        pytest.skip("needs podman as root (the compose tests' engine); `make swarm-test` installs it")
    with tempfile.TemporaryDirectory(prefix="fgw-snapshot-") as tmp:
        storage = Path(tmp) / "storage.conf"
        storage.write_text(f'[storage]\ndriver = "vfs"\ngraphroot = "{tmp}/graph"\nrunroot = "{tmp}/run"\n')
        env = {**s.containers_conf(Path(tmp)), "CONTAINERS_STORAGE_CONF": str(storage)}
        probe = subprocess.run(["podman", "volume", "ls", "-q"], env=env, capture_output=True, check=False)
        if probe.returncode != 0:
            pytest.skip(f"podman cannot list volumes here: {probe.stderr.decode()[-200:]}")
        yield env


def test_a_run_sees_its_own_and_unlabelled_objects_but_not_the_other_projects(
    podman_env: dict[str, str],
) -> None:
    tag = secrets.token_hex(4)
    made = {
        "swarm": (f"fgw-snapshot-swarm-{tag}", s.PROJECT),
        "cluster": (f"fgw-snapshot-cluster-{tag}", s.CLUSTER_PROJECT),
        "unlabelled": (f"fgw-snapshot-none-{tag}", ""),
    }
    try:
        for name, project in made.values():
            label = ["--label", f"{s.COMPOSE_PROJECT_LABEL}={project}"] if project else []
            s.run(["podman", "volume", "create", *label, name], env=podman_env, timeout=60)
        as_swarm = s.snapshot(podman_env, s.PROJECT)["volumes"]
        as_cluster = s.snapshot(podman_env, s.CLUSTER_PROJECT)["volumes"]
        shared_store = {k: v for k, v in podman_env.items() if k != "CONTAINERS_STORAGE_CONF"}
        in_shared_store = s.snapshot(shared_store, s.PROJECT)["volumes"]
    finally:
        s.run(["podman", "volume", "rm", "-f", *(n for n, _ in made.values())], env=podman_env, check=False)
    assert {made["swarm"][0], made["unlabelled"][0]} <= as_swarm
    assert made["cluster"][0] not in as_swarm
    assert {made["cluster"][0], made["unlabelled"][0]} <= as_cluster
    assert made["swarm"][0] not in as_cluster
    assert not in_shared_store & {n for n, _ in made.values()}, "volumes leaked into the shared store"
