"""Build the compose tests' images ahead, or remove them: CI builds them while the test suite runs.

    .venv/bin/python scripts/compose_images.py prepare [--cluster]
    .venv/bin/python scripts/compose_images.py remove

``prepare`` sets up podman and the base image as scripts/swarm_test.py does, then builds the gateway image
(and with ``--cluster`` the NATS and PostgreSQL images of scripts/cluster_test.py), each labelled as built
ahead, with the digest of its sources. `swarm_test.py --prepared` and `cluster_test.py --prepared` then run
these images instead of building their own, and leave them, so the two tests can run at once; ``remove``
removes every image built ahead. An image built ahead from the same sources is kept, one from other sources
rebuilt; an image of the same name that was not built ahead is left alone and the run fails, saying so.
Exit status: 0 built (or removed), 1 failed, and swarm_test.py's SKIPPED status (0) with a line saying
SKIPPED where containers cannot run here.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import cluster_test as c
import swarm_test as s

DEBIAN = s.ROOT / "deploy" / "debian"
GATEWAY = (s.IMAGE, s.DOCKERFILE)
CLUSTER = (
    (c.NATS_IMAGE, DEBIAN / "nats.Containerfile"),
    (c.POSTGRES_IMAGE, DEBIAN / "postgres.Containerfile"),
)


def prepare(env: dict[str, str], base: str, images: list[tuple[str, Path]]) -> str:
    for image, containerfile in images:
        owner = s.image_label(image, s.TEST_LABEL, env)
        if s.image_exists(image, env) and owner != s.PREPARED:
            raise s.Failed(
                f"{image} exists and was not built ahead (label {owner or 'none'}): remove it first"
            )
        if owner == s.PREPARED:
            if s.image_label(image, s.SOURCES_LABEL, env) == s.build_digest(base, containerfile):
                s.log(f"{image}: built ahead from these sources already")
                continue
            s.run(["podman", "rmi", "-f", image], env=env, timeout=120)
        started = time.monotonic()
        s.build_image(image, containerfile, base, s.PREPARED, env)
        s.log(f"built {image} ({s.image_mb(image, env)} MB) ahead in {time.monotonic() - started:.1f} s")
    return f"compose-images: {', '.join(image for image, _ in images)} built ahead from these sources"


def remove(env: dict[str, str]) -> str:
    ours = f"label={s.TEST_LABEL}={s.PREPARED}"
    images = s.run(["podman", "images", "-q", "--filter", ours], env=env, timeout=120).split()
    if images:
        s.run(["podman", "rmi", "-f", *images], env=env, timeout=300)
    left = s.run(["podman", "images", "-q", "--filter", ours], env=env, timeout=120).split()
    if left:
        raise s.Failed(f"images built ahead still there after podman rmi: {left}")
    return f"compose-images: removed {len(set(images))} images built ahead"


def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("action", choices=("prepare", "remove"))
    parser.add_argument("--cluster", action="store_true", help="also the cluster test's NATS and PostgreSQL")
    args = parser.parse_args()
    if args.action == "remove":
        return s.run_on_podman("compose-images", lambda env, _base: remove(env), needs_base=False)
    images = [GATEWAY, *(CLUSTER if args.cluster else ())]
    kept = "; the images built so far stay until `compose_images.py remove`"
    return s.run_on_podman("compose-images", lambda env, base: prepare(env, base, images), interrupted=kept)


if __name__ == "__main__":
    sys.exit(main())
