"""List the import cycles among gateway's modules, and with --longest its longest import chain.

Every `import`/`from` statement counts: top level, under `if TYPE_CHECKING:` and inside functions.
A cycle is a strongly connected group of two or more modules (or one that imports itself). A chain is
a path of imports, each module importing the next; without cycles the longest one is well defined.

    python scripts/import_cycles.py [package_dir]              # prints each cycle, then "cycles: N"
    python scripts/import_cycles.py --longest [package_dir]    # then the longest chain, one module a line
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path


def module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imports_of(path: Path, name: str, modules: set[str]) -> set[str]:
    """The project modules `path` names in any import statement."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base_parts = package.split(".")
                base_parts = base_parts[: len(base_parts) - (node.level - 1)]
                base = ".".join(base_parts + ([node.module] if node.module else []))
            else:
                base = node.module or ""
            # `from pkg import sub` names the submodule when there is one, else the package.
            targets = [
                f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base for alias in node.names
            ]
        else:
            continue
        for target in targets:
            # `import a.b.c` names the deepest project module it reaches.
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target and target != name:
                found.add(target)
    return found


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected groups of two or more modules (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    groups: list[list[str]] = []
    counter = 0

    def visit(v: str) -> None:
        nonlocal counter
        index[v] = low[v] = counter
        counter += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(sorted(group))

    sys.setrecursionlimit(10_000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(groups)


def longest_chain(graph: dict[str, set[str]]) -> list[str]:
    """The longest path of imports (the graph must have no cycle); ties go to the first in name order."""
    memo: dict[str, list[str]] = {}

    def from_(v: str) -> list[str]:
        if v not in memo:
            tails = [from_(w) for w in sorted(graph[v])]
            memo[v] = [v, *max(tails, key=len, default=[])]
        return memo[v]

    sys.setrecursionlimit(10_000)
    return max((from_(v) for v in sorted(graph)), key=len, default=[])


def main() -> int:
    args = sys.argv[1:]
    longest = "--longest" in args
    args = [a for a in args if a != "--longest"]
    root = Path(args[0] if args else "gateway").resolve()
    files = {module_name(p, root): p for p in root.rglob("*.py")}
    modules = set(files)
    graph = {name: imports_of(path, name, modules) for name, path in files.items()}
    found = cycles(graph)
    for group in found:
        members = set(group)
        print(f"cycle of {len(group)} modules:")
        for name in group:
            print(f"  {name} -> {', '.join(sorted(graph[name] & members))}")
    print(f"cycles: {len(found)}")
    if longest and not found:
        chain = longest_chain(graph)
        print(f"longest import chain: {len(chain)} modules")
        for name in chain:
            print(f"  {name}")
    return 1 if found else 0


if __name__ == "__main__":
    raise SystemExit(main())
