"""No two gateway modules import each other (every import statement counts: top level, under
`if TYPE_CHECKING:`, inside functions); scripts/import_cycles.py is what says so."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def run(package: Path, *options: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "scripts/import_cycles.py", *options, str(package)],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )


def test_gateway_has_no_import_cycle() -> None:
    result = run(ROOT / "gateway")
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.strip().endswith("cycles: 0")


def test_the_script_sees_cycles_through_type_checking_and_function_imports(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "host.py").write_text("from pkg.sub import part\n")
    (pkg / "sub" / "part.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg.host import Host\n"
    )
    (pkg / "a.py").write_text("def f():\n    from . import b\n")
    (pkg / "b.py").write_text("import pkg.a\n")
    (pkg / "alone.py").write_text("from pkg import host\n")
    result = run(pkg)
    assert result.returncode == 1
    assert "pkg.host -> pkg.sub.part" in result.stdout
    assert "pkg.sub.part -> pkg.host" in result.stdout
    assert "pkg.a -> pkg.b" in result.stdout and "pkg.b -> pkg.a" in result.stdout
    assert "pkg.alone" not in result.stdout
    assert result.stdout.strip().endswith("cycles: 2")


def test_the_script_prints_the_longest_chain(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "top.py").write_text("from pkg import mid\nfrom pkg import low\n")
    (pkg / "mid.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg.low import f\n"
    )
    (pkg / "low.py").write_text("def f():\n    from pkg import base\n")
    (pkg / "base.py").write_text("")
    (pkg / "side.py").write_text("import pkg.base\n")
    result = run(pkg, "--longest")
    assert result.returncode == 0, result.stdout + result.stderr
    chain = result.stdout.split("longest import chain: 4 modules\n")[1].split()
    assert chain == ["pkg.top", "pkg.mid", "pkg.low", "pkg.base"]
