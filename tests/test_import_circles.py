"""Imports run one way: no module of simiam/, grader/ or instructor_tools/ imports one that imports it,
directly or through others (issue 33).

The graph is read from the source with `ast`, not by importing anything. An edge A -> B is any `import B` or
`from B import x` in A (absolute or relative; `from P import m` is an edge to the module P.m when it is
one), wherever it stands:
- an import inside a function counts: it runs whenever the function does, and a circle through one is still
  two modules that need each other (the robot model asking the course for a week's robot was one);
- an import under `if TYPE_CHECKING:` does not: it never runs, and type hints may point either way;
- a package's __init__ is not counted as imported by its submodules' importers (`import a.b.c` runs a and
  a.b first, but a package that re-exports its modules would otherwise be a circle with each of them);
- a module named in a string (a week's `checks="grader.checks.week3"`, the worker's probes module) is data,
  not an import.
A circle is a strongly connected part of the graph; the failure names one loop through it with the file and
line of each import, so the fix starts from there.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("simiam", "grader", "instructor_tools")
WRONG = ROOT / "tests" / "data" / "import_circle"  # a package with a circle (its README says which)



@dataclass(frozen=True)
class Edge:
    target: str
    line: int


def modules(root: Path, packages: Iterable[str]) -> dict[str, Path]:
    """Every module of `packages` under `root`, by dotted name (a package by its own name)."""
    found = {}
    for package in packages:
        for path in sorted((root / package).rglob("*.py")):
            name = ".".join(path.relative_to(root).with_suffix("").parts)
            found[name.removesuffix(".__init__")] = path
    return found


def _type_checking_only(node: ast.AST) -> bool:
    if not isinstance(node, ast.If):
        return False
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _import_nodes(node: ast.AST) -> Iterable[ast.Import | ast.ImportFrom]:
    """Every import statement under `node`, leaving out the bodies of `if TYPE_CHECKING:`."""
    for child in ast.iter_child_nodes(node):
        if isinstance(child, (ast.Import, ast.ImportFrom)):
            yield child
        elif _type_checking_only(child):
            for other in child.orelse:  # type: ignore[attr-defined]
                yield from _import_nodes(ast.Module(body=[other], type_ignores=[]))
        else:
            yield from _import_nodes(child)


def edges(name: str, path: Path, known: dict[str, Path]) -> list[Edge]:
    """The modules of `known` that module `name` (at `path`) imports, each with the line of its import."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    out = []
    for node in _import_nodes(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        else:
            base = node.module or ""
            if node.level:
                parts = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(parts + ([base] if base else []))
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in known else base
                       for alias in node.names]
        out += [Edge(t, node.lineno) for t in targets if t in known and t != name]
    return out


def graph(root: Path, packages: Iterable[str]) -> tuple[dict[str, list[Edge]], dict[str, Path]]:
    known = modules(root, packages)
    return {name: edges(name, path, known) for name, path in known.items()}, known


def circles(imports: dict[str, list[Edge]]) -> list[frozenset[str]]:
    """The strongly connected parts of more than one module (Tarjan's algorithm, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for start in sorted(imports):
        if start in index:
            continue
        work = [(start, iter(imports[start]))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, rest = work[-1]
            edge = next(rest, None)
            if edge is not None:
                if edge.target not in index:
                    index[edge.target] = low[edge.target] = len(index)
                    stack.append(edge.target)
                    on_stack.add(edge.target)
                    work.append((edge.target, iter(imports[edge.target])))
                elif edge.target in on_stack:
                    low[node] = min(low[node], index[edge.target])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                part = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    part.add(member)
                    if member == node:
                        break
                if len(part) > 1:
                    found.append(frozenset(part))
    return found


def one_loop(part: frozenset[str], imports: dict[str, list[Edge]], files: dict[str, Path], root: Path) -> str:
    """A loop through `part`, each step "file:line imports module", from its first module in order."""
    start = min(part)
    paths: dict[str, list[tuple[str, Edge]]] = {start: []}
    todo = [start]
    while todo:  # breadth first: the shortest way back to the start
        node = todo.pop(0)
        for edge in imports[node]:
            if edge.target == start:
                steps = [*paths[node], (node, edge)]
                return "\n".join(f"  {files[a].relative_to(root).as_posix()}:{e.line} imports {e.target}"
                                 for a, e in steps)
            if edge.target in part and edge.target not in paths:
                paths[edge.target] = [*paths[node], (node, edge)]
                todo.append(edge.target)
    raise AssertionError(f"no loop through {sorted(part)}")


def report(found: list[frozenset[str]], imports: dict[str, list[Edge]], files: dict[str, Path],
           root: Path) -> str:
    return "\n".join(f"import circle {sorted(part)}:\n{one_loop(part, imports, files, root)}"
                     for part in found)


def test_no_import_circle() -> None:
    imports, files = graph(ROOT, PACKAGES)
    found = circles(imports)
    assert found == [], report(found, imports, files, ROOT)


def test_a_circle_is_caught() -> None:
    """The wrong version: fakepkg's engine and report import each other (one inside a function); the
    TYPE_CHECKING import back from types_only is no circle."""
    imports, files = graph(WRONG, ["fakepkg"])
    found = circles(imports)
    circle = frozenset({"fakepkg.engine", "fakepkg.sub.report"})
    assert found == [circle], report(found, imports, files, WRONG)
    loop = one_loop(found[0], imports, files, WRONG)
    assert "fakepkg/engine.py:5 imports fakepkg.sub.report" in loop, loop
    assert "fakepkg/sub/report.py:7 imports fakepkg.engine" in loop, loop
    assert {e.target for e in imports["fakepkg.types_only"]} == set(), imports["fakepkg.types_only"]


def test_a_circle_planted_in_the_tree_is_caught(tmp_path: Path) -> None:
    """The course's week registry importing the robot model's importer back, inside a function, as the
    robot model once did: found, and named with its file and line."""
    for path in (ROOT / "simiam").rglob("*.py"):
        target = tmp_path / path.relative_to(ROOT)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(path.read_bytes())
    quickbot = tmp_path / "simiam" / "robot" / "quickbot.py"
    quickbot.write_text(quickbot.read_text() + "\n\ndef spec_for_week(week):\n"
                        "    from simiam.course.weeks import get_week\n\n    return get_week(week).spec\n")
    imports, files = graph(tmp_path, ["simiam"])
    found = circles(imports)
    assert len(found) == 1 and {"simiam.robot.quickbot", "simiam.course.weeks"} <= found[0], found
    assert "simiam/robot/quickbot.py" in report(found, imports, files, tmp_path)
