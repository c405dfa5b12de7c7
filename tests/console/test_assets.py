"""The console's files: everything the page loads is in the package (no CDN), every vendored library
carries its licence, the wheel's package-data covers them; plus the tile setting and the stream's queue."""

from __future__ import annotations

import asyncio
import fnmatch
import re
import sys
import tomllib
from pathlib import Path

import pytest
from pydantic import ValidationError

from gateway.api.events import QUEUE_SIZE, Subscriber
from gateway.config import Settings
from gateway.console import STATIC_DIR, content_security_policy
from tests.helpers.timing import scaled

ROOT = Path(__file__).resolve().parents[2]
VENDOR = STATIC_DIR / "vendor"
LICENCE_NAMES = ("LICENSE", "LICENSE.md", "LICENCE")


def _vendor_script_packages() -> list[str]:
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "vendor_assets", ROOT / "scripts" / "vendor_console_assets.py"
    )
    assert spec and spec.loader
    module = importlib.util.module_from_spec(spec)
    sys.modules["vendor_assets"] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return [p.dir for p in module.PACKAGES]


def test_every_vendored_library_has_its_licence_and_is_listed() -> None:
    directories = sorted(p.name for p in VENDOR.iterdir() if p.is_dir())
    assert directories == sorted(_vendor_script_packages())
    listed = (VENDOR / "VENDORED.md").read_text()
    for name in directories:
        assert any((VENDOR / name / licence).is_file() for licence in LICENCE_NAMES), f"{name} has no licence"
        assert f"| {name} |" in listed


def _local_references(path: Path) -> list[Path]:
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".html":
        names = re.findall(r'(?:src|href)="(/console/static/[^"]+)"', text)
        return [STATIC_DIR / n.removeprefix("/console/static/") for n in names]
    names = re.findall(r'(?:from|import)\s*["\'](\.{1,2}/[^"\']+)["\']', text)
    return [(path.parent / n).resolve() for n in names]


def test_the_page_loads_only_files_the_gateway_serves() -> None:
    """index.html and the module graph below it resolve to files in the package; nothing points outside."""
    seen: set[Path] = set()
    pending = [STATIC_DIR / "index.html"]
    while pending:
        path = pending.pop()
        if path in seen:
            continue
        seen.add(path)
        assert path.is_file(), f"missing: {path.relative_to(STATIC_DIR)}"
        if path.suffix in (".html", ".js", ".mjs"):
            pending.extend(_local_references(path))
    assert {"app.js", "map.js", "panels.js", "api.js"} <= {p.name for p in seen}
    assert any(p.name == "leaflet.js" for p in seen) and any(p.name == "preact.mjs" for p in seen)
    for own in [*STATIC_DIR.glob("*.js"), *STATIC_DIR.glob("*.html"), *STATIC_DIR.glob("*.css")]:
        assert not re.search(r"(src|href|import|from|url)\W*[\"'(]https?://", own.read_text()), own.name


def test_the_wheel_carries_every_console_file() -> None:
    globs = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"][
        "gateway.console"
    ]
    package = STATIC_DIR.parent
    for path in STATIC_DIR.rglob("*"):
        if path.is_file():
            relative = path.relative_to(package).as_posix()
            assert any(fnmatch.fnmatch(relative, g) and relative.count("/") == g.count("/") for g in globs), (
                relative
            )


def test_tile_url_setting_names_what_it_accepts() -> None:
    with pytest.raises(ValidationError) as raised:
        Settings(_env_file=None, console_tiles_url="https://tiles.example.org/tile.png")
    assert "{z}, {x} and {y}" in str(raised.value) and "tiles.example.org/tile.png" in str(raised.value)
    assert Settings(_env_file=None, console_tiles_url="").console_tiles_url is None
    url = "https://{s}.tile.example.org/{z}/{x}/{y}.png"
    assert Settings(_env_file=None, console_tiles_url=url).console_tiles_url == url
    assert "img-src 'self' data: https://*.tile.example.org;" in content_security_policy(url)
    assert "img-src 'self' data:;" in content_security_policy(None)


async def test_a_stream_that_cannot_keep_up_is_ended_not_grown() -> None:
    sub = Subscriber()
    for i in range(QUEUE_SIZE + 10):
        sub.put("fleet", str(i))
    assert sub.overflowed and sub.queue.qsize() == 1
    end = await asyncio.wait_for(sub.queue.get(), scaled(1))
    assert end == ("", "")  # the end marker, the backlog dropped
