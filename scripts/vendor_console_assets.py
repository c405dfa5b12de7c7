"""Copy the console's JavaScript/CSS libraries from the npm registry into gateway/console/static/vendor.

The console must work without internet (field laptops), so its libraries are served by the gateway from
the repository, never from a CDN. This script is how they got there and how to update them: bump a
version below, run it, look at the diff. It needs `npm` (only to fetch the pinned packages) and writes
each package's files, its licence, and vendor/VENDORED.md (package, version, licence, files).

Usage: python scripts/vendor_console_assets.py
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tarfile
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VENDOR = ROOT / "gateway" / "console" / "static" / "vendor"


@dataclass(frozen=True)
class Package:
    name: str
    version: str
    why: str
    #: path inside the npm tarball's package/ -> path under vendor/<dir>/
    files: dict[str, str]

    @property
    def dir(self) -> str:
        return self.name.replace("/", "-").lstrip("@")


PACKAGES = (
    Package(
        "leaflet",
        "1.9.4",
        "the map: markers, polylines, GeoJSON layers, scale bar; any CRS, so it draws without tiles",
        {
            "dist/leaflet.js": "leaflet.js",
            "dist/leaflet.css": "leaflet.css",
            "dist/images/layers.png": "images/layers.png",
            "dist/images/layers-2x.png": "images/layers-2x.png",
            "dist/images/marker-icon.png": "images/marker-icon.png",
            "dist/images/marker-icon-2x.png": "images/marker-icon-2x.png",
            "dist/images/marker-shadow.png": "images/marker-shadow.png",
            "LICENSE": "LICENSE",
        },
    ),
    Package(
        "proj4",
        "2.22.0",
        "the azimuthal equidistant projection centred on the fleet's home (metres, offline map)",
        {"dist/proj4.js": "proj4.js", "LICENSE.md": "LICENSE.md"},
    ),
    Package(
        "proj4leaflet",
        "1.0.2",
        "turns a proj4 projection into a Leaflet CRS",
        {"src/proj4leaflet.js": "proj4leaflet.js", "LICENSE": "LICENSE"},
    ),
    Package(
        "preact",
        "11.2.0",
        "the page's components and state (4 kB, ES modules, no build step)",
        {"dist/preact.mjs": "preact.mjs", "hooks/dist/hooks.mjs": "hooks.mjs", "LICENSE": "LICENSE"},
    ),
    Package(
        "htm",
        "3.1.1",
        "JSX-like templates in plain JavaScript for Preact (no build step)",
        {"dist/htm.module.js": "htm.module.js", "LICENSE": "LICENSE"},
    ),
    Package(
        "eventsource-parser",
        "4.1.3",
        "parses the server-sent event stream read with fetch (which, unlike EventSource, sends the "
        "Authorization header)",
        {
            "dist/index.js": "index.js",
            "dist/parse.js": "parse.js",
            "dist/errors.js": "errors.js",
            "dist/stream.js": "stream.js",
            "LICENSE": "LICENSE",
        },
    ),
)


#: Bare module names some files import, and the vendored file that provides each: rewritten to relative
#: paths so the browser loads them without an import map (an inline script the page's CSP would block).
BARE_IMPORTS = {'from"preact"': 'from"./preact.mjs"', "from 'preact'": "from './preact.mjs'"}


def _adapt(path: Path) -> None:
    """Drop sourceMappingURL comments (the maps are not vendored: the browser would ask for them) and
    point bare imports at the vendored files."""
    if path.suffix not in (".js", ".mjs", ".css"):
        return
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines(keepends=True)
    adapted = "".join(line for line in lines if "sourceMappingURL=" not in line)
    for bare, relative in BARE_IMPORTS.items():
        adapted = adapted.replace(bare, relative)
    if adapted != text:
        path.write_text(adapted, encoding="utf-8")


def vendor(package: Package, work: Path) -> dict[str, str]:
    spec = f"{package.name}@{package.version}"
    out = subprocess.run(
        ["npm", "pack", spec, "--json", "--pack-destination", str(work)],
        check=True,
        capture_output=True,
        text=True,
    )
    tarball = work / json.loads(out.stdout)[0]["filename"]
    unpacked = work / package.dir
    with tarfile.open(tarball) as archive:
        archive.extractall(unpacked, filter="data")
    meta = json.loads((unpacked / "package" / "package.json").read_text())
    target = VENDOR / package.dir
    shutil.rmtree(target, ignore_errors=True)
    for source, dest in package.files.items():
        path = target / dest
        path.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(unpacked / "package" / source, path)
        _adapt(path)
    return {"licence": str(meta.get("license", "?")), "version": str(meta["version"])}


def main() -> int:
    if shutil.which("npm") is None:
        print(
            "vendor_console_assets: npm is needed to fetch the packages (apt-get install npm)",
            file=sys.stderr,
        )
        return 1
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for package in PACKAGES:
            meta = vendor(package, Path(tmp))
            files = ", ".join(sorted(package.files.values()))
            rows.append(
                f"| {package.name} | {meta['version']} | {meta['licence']} | {package.why} | {files} |"
            )
            print(f"vendored {package.name} {meta['version']} ({meta['licence']})")
    (VENDOR / "VENDORED.md").write_text(
        "# Vendored libraries of the console\n\n"
        "Copied from the npm registry by `scripts/vendor_console_assets.py` (do not edit by hand; bump the\n"
        "version there and run it). Each directory holds the package's licence. Changed on the way:\n"
        "source-map comments removed (the maps are not copied), and preact's hooks import\n"
        "`./preact.mjs` instead of the bare name `preact` (no import map needed).\n\n"
        "| package | version | licence | why | files |\n|---|---|---|---|---|\n" + "\n".join(rows) + "\n",
        encoding="utf-8",
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
