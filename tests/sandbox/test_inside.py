"""Issue 14: what runs inside the sandbox lives in one package, grader.inside, that imports nothing trusted.

The walk starts at every module of grader/inside and follows every import (top level or inside a function,
absolute or relative) and every module named in a string (the worker imports its preload list and the
probes module by name), transitively through simiam. A module may be reached only if it is the standard
library, numpy (the students' library, preloaded for them), grader.inside itself or one of the
student-facing modules grader.sandbox.exposed lists; anything else (grader.reference, grader.checks, the
simulator and its physics, the hidden sets, instructor_tools) is a failure naming the file that imports it.
"""

from __future__ import annotations

import ast
import re
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from grader.sandbox import exposed

REPO = Path(__file__).resolve().parents[2]
WRONG = REPO / "tests" / "data" / "inside_wrong"
PACKAGE = "grader.inside"
# a dotted name of ours in a string: "grader.inside.probes", "simiam.course.loader:load_submission"
_NAMED = re.compile(r"((?:simiam|grader|instructor_tools)(?:\.\w+)+)(?::\w+)?")


def _module(relative: str) -> str:
    return relative.removesuffix(".py").removesuffix("/__init__").replace("/", ".")


def _file_of(module: str) -> Path | None:
    base = REPO / module.replace(".", "/")
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _imports(path: Path, module: str) -> set[str]:
    """Every module `path` imports or names in a string; `from a import b` gives a and a.b."""
    names: set[str] = set()
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1] + ([base] if base else []))
            names.add(base)
            names.update(f"{base}.{a.name}" for a in node.names)
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            names.update(m.group(1) for m in _NAMED.finditer(node.value) if m.group(0) == node.value)
    return names


def reached(source: Callable[[str], Path | None] = _file_of) -> dict[str, list[str]]:
    """What grader.inside reaches that it may not, as {importing module: [forbidden names]}."""
    allowed = {_module(r) for r in exposed.EXPOSED}
    start = [_module(str(p.relative_to(REPO))) for p in sorted((REPO / "grader" / "inside").glob("*.py"))]
    seen, todo, bad = set(start), list(start), {}
    while todo:
        module = todo.pop()
        path = source(module)
        assert path is not None, module
        for name in sorted(_imports(path, module)):
            top = name.split(".")[0]
            if top in sys.stdlib_module_names or top == "numpy" or top == "__future__":
                continue
            ours = name if name in allowed or _file_of(name) else name.rsplit(".", 1)[0]  # `from m import f`
            if ours not in allowed and not ours.startswith(PACKAGE):
                bad.setdefault(module, []).append(name)
            elif ours not in seen:
                seen.add(ours)
                todo.append(ours)
    return bad


def test_grader_inside_imports_nothing_trusted() -> None:
    assert reached() == {}


def test_every_module_of_grader_inside_is_exposed_and_the_worker_starts_there() -> None:
    """The whole package reaches the worker's library (else it could not run there), and the worker's
    entry point, its probes and its loop are in it."""
    package = {str(p.relative_to(REPO)) for p in (REPO / "grader" / "inside").glob("*.py")}
    assert package <= set(exposed.EXPOSED)
    assert exposed.WORKER == "grader/inside/worker.py"
    assert {"grader/inside/probes.py", "grader/inside/worker_loop.py"} <= package
    assert not [f for f in exposed.EXPOSED if f.startswith("grader/") and not f.startswith("grader/inside/")
                and f != "grader/__init__.py"]


@pytest.mark.parametrize(("planted", "forbidden"), [
    ("probes_import_reference.py", "grader.reference"),          # a nested `from grader import reference`
    ("probes_name_the_checks.py", "grader.checks.week3"),       # importlib.import_module("grader.checks...")
    ("probes_reach_the_physics.py", "simiam.robot.dynamics"),   # relative import of the physics
])
def test_the_walk_sees_a_trusted_import(planted: str, forbidden: str, tmp_path: Path) -> None:
    """The wrong versions (tests/data/inside_wrong/): today's probes with a function planted at the end
    that imports trusted code, in three ways."""
    wrong = tmp_path / "probes.py"
    wrong.write_text((REPO / "grader/inside/probes.py").read_text() + "\n\n" + (WRONG / planted).read_text())

    def source(module: str) -> Path | None:
        return wrong if module == "grader.inside.probes" else _file_of(module)

    bad = reached(source)
    assert forbidden in bad.get("grader.inside.probes", []), bad
