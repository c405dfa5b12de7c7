"""No source file in gateway/ grows past 600 lines: a module that long does more than one job and is
split instead. Third-party files copied under a vendor/ folder are not the project's and do not count."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MOST_LINES = 600
SOURCE_SUFFIXES = (".py", ".js", ".css", ".html")


def oversized(package: Path, most: int = MOST_LINES) -> list[str]:
    """Each source file below `package` with more than `most` lines, as 'path: N lines'."""
    found = []
    for path in sorted(package.rglob("*")):
        if path.is_file() and path.suffix in SOURCE_SUFFIXES and "vendor" not in path.parts:
            lines = len(path.read_text(encoding="utf-8").splitlines())
            if lines > most:
                found.append(f"{path.relative_to(package)}: {lines} lines")
    return found


def test_no_gateway_source_file_is_over_600_lines() -> None:
    assert oversized(ROOT / "gateway") == []


def test_the_check_names_a_file_one_line_over(tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "long.py").write_text("x = 1\n" * (MOST_LINES + 1))
    (tmp_path / "fits.py").write_text("x = 1\n" * MOST_LINES)
    (tmp_path / "notes.txt").write_text("x\n" * (MOST_LINES + 5))
    (tmp_path / "vendor").mkdir()
    (tmp_path / "vendor" / "lib.js").write_text("x;\n" * (MOST_LINES + 5))
    assert oversized(tmp_path) == [f"{Path('sub/long.py')}: {MOST_LINES + 1} lines"]
