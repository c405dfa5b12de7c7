"""The distribution carries the migrations: a wheel built from an sdist of this checkout (as pip builds one
from an index) and installed into a fresh virtual environment upgrades a new SQLite database to head with
the installed package's own copy of ``migrations/`` (installed as ``gateway.migrations``).

The fresh environment gets the dependencies of the running one through a ``.pth`` line (installing them
again would take minutes and an index); the package itself comes from the wheel only, and the commands run
outside the checkout. Skipped, with the reason, where the build tools cannot be had.
"""

from __future__ import annotations

import os
import shutil
import sqlite3
import subprocess
import sysconfig
import tarfile
import venv
from pathlib import Path

import pytest

from gateway.registry.models import metadata
from gateway.registry.schema_check import head_from_files

ROOT = Path(__file__).resolve().parent.parent
#: what an sdist is built from (the rest of the checkout is not part of the distribution)
SOURCES = ("pyproject.toml", "setup.py", "README.md", "LICENSE", "gateway", "fleet_agent", "migrations")
BUILD_TOOLS = ("setuptools>=77", "wheel")  # pyproject.toml's [build-system] requires
STEP_TIMEOUT_S = 300


def _run(cmd: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=STEP_TIMEOUT_S)


def _checked(cmd: list[str], cwd: Path) -> str:
    done = _run(cmd, cwd)
    assert done.returncode == 0, f"{' '.join(cmd)} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


def _copy_sources(dest: Path) -> None:
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info", "build", "dist")
    for name in SOURCES:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, dest / name, ignore=ignore)
        else:
            shutil.copy2(src, dest / name)


def _build(python: Path, what: str, project: Path, out: Path) -> Path:
    """``build_sdist`` or ``build_wheel`` of setuptools' PEP 517 backend, run in ``project``."""
    code = f"import sys; from setuptools import build_meta; print(build_meta.{what}(sys.argv[1]))"
    name = _checked([str(python), "-c", code, str(out)], project).strip().splitlines()[-1]
    return out / name


@pytest.fixture(scope="module")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh virtual environment with fleet-gateway installed from a wheel built from an sdist."""
    tmp = tmp_path_factory.mktemp("wheel")
    env_dir = tmp / "venv"
    try:
        venv.create(env_dir, with_pip=True)
    except (OSError, subprocess.CalledProcessError) as exc:  # e.g. Debian without python3-venv
        pytest.skip(f"cannot build the wheel: no virtual environment with pip ({exc})")
    python = env_dir / "bin" / "python"
    tools = _run([str(python), "-m", "pip", "install", "--quiet", *BUILD_TOOLS], tmp)
    if tools.returncode != 0:
        last = (tools.stderr.strip().splitlines() or ["no output"])[-1]
        pytest.skip(f"cannot build the wheel: pip could not install {' '.join(BUILD_TOOLS)} ({last})")

    source = tmp / "source"
    source.mkdir()
    _copy_sources(source)
    (tmp / "dist").mkdir()
    sdist = _build(python, "build_sdist", source, tmp / "dist")
    with tarfile.open(sdist) as archive:
        if hasattr(tarfile, "data_filter"):  # Python >= 3.11.4
            archive.extractall(tmp / "unpacked", filter="data")
        else:
            archive.extractall(tmp / "unpacked")  # our own sdist, just built
    (unpacked,) = (tmp / "unpacked").iterdir()
    wheel = _build(python, "build_wheel", unpacked, tmp / "dist")
    _checked([str(python), "-m", "pip", "install", "--quiet", "--no-deps", "--no-index", str(wheel)], tmp)

    where = "import sysconfig; print(sysconfig.get_paths()['purelib'])"
    own_site = Path(_checked([str(python), "-c", where], tmp).strip())
    deps = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]}  # the running environment's
    (own_site / "fleet_gateway_test_deps.pth").write_text("\n".join(sorted(deps)) + "\n")
    return env_dir


def test_the_installed_package_runs_its_own_migrations(installed: Path) -> None:
    code = (
        "import gateway; from gateway.registry.database import migrations_dir; "
        "print(gateway.__file__); print(migrations_dir())"
    )
    python = installed / "bin" / "python"
    package_file, migrations = _checked([str(python), "-c", code], installed).splitlines()
    site = installed.resolve()
    assert Path(package_file).resolve().is_relative_to(site), package_file  # not the checkout
    assert Path(migrations) == Path(package_file).parent / "migrations"
    assert sorted(p.name for p in Path(migrations, "versions").glob("*.py")) == sorted(
        p.name for p in (ROOT / "migrations" / "versions").glob("*.py")
    )


def test_the_installed_package_upgrades_a_fresh_database_to_head(installed: Path, tmp_path: Path) -> None:
    db = tmp_path / "fresh.db"
    cli = installed / "bin" / "fleet-gateway"
    _checked([str(cli), "db", "upgrade", "--database-url", f"sqlite+aiosqlite:///{db}"], tmp_path)
    with sqlite3.connect(db) as conn:
        (version,) = conn.execute("SELECT version_num FROM alembic_version").fetchone()
        tables = {row[0] for row in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
    assert version == head_from_files(ROOT / "migrations" / "versions")
    assert set(metadata.tables) <= tables
