"""CONTRIBUTING.md's layout is today's tree: every path it names exists, and it names every package of
gateway/ and fleet_agent/ and every module at their top.

The layout is the code block under "## Layout": an entry line starts with a file or folder name,
indented two spaces per folder level, with its description from column 21; a line indented 21 spaces
goes on with the description above it. A name in a description (``store_core.py``, ``static/vendor/``,
``docs/cluster.md``) is looked up inside the entry's folder, beside the entry, and from the repository's
top when it holds a slash.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CONTRIBUTING = ROOT / "CONTRIBUTING.md"
DESCRIPTION_COLUMN = 21
PACKAGES = ("gateway", "fleet_agent")
_EXTENSIONS = r"(?:py|md|toml|ini|json|mako|yml|service)"
PATH_MENTION = re.compile(
    rf"(?<![\w/.-])((?:[\w-]+/)+(?:[\w-]+\.{_EXTENSIONS})?|[\w-]+\.{_EXTENSIONS})(?![\w/])"
)


@dataclass
class Entry:
    path: Path  # relative to the repository
    text: str  # its description, continuation lines included
    line: int


def layout_lines(markdown: str) -> list[tuple[int, str]]:
    """The lines of the code block under "## Layout", with their line numbers in the file."""
    lines = markdown.splitlines()
    start = lines.index("## Layout")
    fence = next(i for i in range(start, len(lines)) if lines[i].startswith("```"))
    end = next(i for i in range(fence + 1, len(lines)) if lines[i].startswith("```"))
    return [(i + 1, lines[i]) for i in range(fence + 1, end)]


def parse_layout(markdown: str) -> list[Entry]:
    entries: list[Entry] = []
    folders: list[Path] = []  # the folder of each indentation level
    for number, line in layout_lines(markdown):
        if not line.strip():
            continue
        if line[:DESCRIPTION_COLUMN].isspace():
            assert entries, f"CONTRIBUTING.md:{number}: a description before any entry"
            entries[-1].text += " " + line.strip()
            continue
        indent = len(line) - len(line.lstrip(" "))
        assert indent % 2 == 0, f"CONTRIBUTING.md:{number}: indent by two spaces per folder level"
        depth = indent // 2
        assert depth <= len(folders), f"CONTRIBUTING.md:{number}: indented deeper than its folder"
        name, _, text = line.strip().partition(" ")
        del folders[depth:]
        path = (folders[-1] if folders else Path()) / name.rstrip("/")
        if name.endswith("/"):
            folders.append(path)
        entries.append(Entry(path, text.strip(), number))
    return entries


def resolve_mention(entry: Entry, mention: str) -> Path | None:
    """Where a name in an entry's description points: inside the entry's folder, beside the entry, or
    (a name with a slash) from the repository's top; None when it is in none of them."""
    candidates = [entry.path / mention, entry.path.parent / mention]
    if "/" in mention:
        candidates.append(Path(mention))
    for candidate in candidates:
        if (ROOT / candidate).exists():
            return Path(candidate.as_posix().rstrip("/"))
    return None


def python_folders_and_top_modules() -> tuple[set[Path], set[Path]]:
    """Every folder holding Python modules under gateway/ and fleet_agent/, and the modules at their top."""
    folders: set[Path] = set()
    modules: set[Path] = set()
    for package in PACKAGES:
        for module in (ROOT / package).rglob("*.py"):
            if "__pycache__" in module.parts:
                continue
            relative = module.relative_to(ROOT)
            folders.add(relative.parent)
            if relative.parent == Path(package) and module.name != "__init__.py":
                modules.add(relative)
    return folders, modules


def test_every_path_the_layout_names_exists() -> None:
    missing: list[str] = []
    for entry in parse_layout(CONTRIBUTING.read_text()):
        if not (ROOT / entry.path).exists():
            missing.append(f"CONTRIBUTING.md:{entry.line}: {entry.path} does not exist")
        for mention in PATH_MENTION.findall(entry.text):
            if resolve_mention(entry, mention) is None:
                missing.append(
                    f"CONTRIBUTING.md:{entry.line}: {mention} (in the lines of {entry.path}) exists neither "
                    f"in {entry.path}, beside it, nor from the repository's top"
                )
    assert not missing, "the layout names paths that are gone:\n" + "\n".join(missing)


def test_the_layout_names_every_package_and_top_module() -> None:
    entries = parse_layout(CONTRIBUTING.read_text())
    named = {entry.path for entry in entries}
    for entry in entries:
        named.update(p for m in PATH_MENTION.findall(entry.text) if (p := resolve_mention(entry, m)))
    folders, modules = python_folders_and_top_modules()
    absent = sorted(f"{p}/ (a line of its own)" for p in folders - {e.path for e in entries})
    absent += sorted(f"{p} (a line of its own, or named in its folder's lines)" for p in modules - named)
    assert not absent, "CONTRIBUTING.md's layout leaves out:\n" + "\n".join(absent)


def test_the_parser_reads_folders_continuations_and_mentions() -> None:
    text = "## Layout\n\n```\ngateway/\n  link/              a\n    session.py       b; contract.py\n"
    text += " " * DESCRIPTION_COLUMN + "c, docs/cluster.md\nbench/             d\n```\n"
    entries = parse_layout(text)
    assert [(e.path.as_posix(), e.text) for e in entries] == [
        ("gateway", ""),
        ("gateway/link", "a"),
        ("gateway/link/session.py", "b; contract.py c, docs/cluster.md"),
        ("bench", "d"),
    ]
    session = entries[2]
    assert PATH_MENTION.findall(session.text) == ["contract.py", "docs/cluster.md"]
    assert resolve_mention(session, "contract.py") == Path("gateway/link/contract.py")
    assert resolve_mention(session, "docs/cluster.md") == Path("docs/cluster.md")
    assert resolve_mention(session, "gone.py") is None
    assert PATH_MENTION.findall("GET /api/v1/events, /mcp, QGC .plan, x86-64") == []
