"""Issue 10.7: student code inside the worker sees only what the course gives students; nothing that
implements a student block can be imported (or, under bubblewrap, read) there."""

from __future__ import annotations

import ast
import sys
from pathlib import Path

from sandbox_helpers import attack

from grader.sandbox import exposed
from grader.sandbox.isolation import BWRAP

REPO = Path(__file__).resolve().parents[2]

# Everything that implements (or checks, or holds the answers of) a student block.
REFERENCE_MODULES = ["grader.reference", "simiam.robot.dynamics", "instructor_tools.reference_brains",
                     "grader.checks", "grader.hidden", "grader.grading", "simiam.simulator",
                     "simiam.course.stubs", "simiam.course.skeletons", "grader.scenarios"]
REFERENCE_FILES = ["grader/reference.py", "simiam/robot/dynamics.py", "instructor_tools/reference_brains.py",
                   "instructor_tools/hidden/week4.json", "solutions/week3/go_to_goal.py",
                   "grader/checks/week2.py"]
# What the course gives students and the worker itself needs: these must keep importing.
COURSE_MODULES = ["simiam.control", "simiam.control.stop", "simiam.course.weeks", "grader.inside.probes"]


def test_no_reference_implementation_imports_inside_the_worker(open_session, mode):
    session = open_session("import_reference")
    seen = attack(session, modules=REFERENCE_MODULES + COURSE_MODULES,
                  paths=[str(REPO / f) for f in REFERENCE_FILES])
    assert seen["imported"] == COURSE_MODULES
    if mode == BWRAP:
        assert seen["read"] == []
        assert all(not files or set(files) <= {"__pycache__"} or path.startswith("/library")
                   for path, files in seen["listed"].items())
    else:  # documented: a plain subprocess can open what its user can read (the isolation note says so)
        assert "can import only the course's student-facing modules" in session.isolation_note
        assert "can read what its user can read" in session.isolation_note


def test_the_test_sees_a_leak(open_session, monkeypatch):
    """The wrong version: expose the whole simiam package and the checks' maths (as the worker saw them
    before), and the same attack imports them."""
    everything = tuple(str(p.relative_to(REPO)) for p in sorted((REPO / "simiam").rglob("*.py")))
    monkeypatch.setattr(exposed, "EXPOSED", everything + exposed.EXPOSED + ("grader/reference.py",))
    session = open_session("import_reference")
    seen = attack(session, modules=REFERENCE_MODULES)
    assert {"grader.reference", "simiam.robot.dynamics"} <= set(seen["imported"])


def _imports(path: Path) -> set[str]:
    """Every absolute module a file imports, at top level or inside functions."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
            names.update(f"{node.module}.{a.name}" for a in node.names)
    return names


def test_the_exposed_files_import_nothing_outside_themselves():
    """The student-facing library is closed: each exposed file imports only other exposed files, the
    standard library or numpy (issue 14: what runs inside the sandbox imports nothing trusted)."""
    exposed_modules = {f.removesuffix(".py").removesuffix("/__init__").replace("/", ".")
                       for f in exposed.EXPOSED}
    outside = {}
    for relative in exposed.EXPOSED:
        for name in _imports(exposed.source_of(relative)):
            top = name.split(".")[0]
            if top in ("simiam", "grader") and name not in exposed_modules:
                if name.rsplit(".", 1)[0] in exposed_modules:
                    continue  # `from simiam.control.pose import Pose2D`: a name of an exposed module
                outside.setdefault(relative, []).append(name)
            elif top not in ("simiam", "grader", "numpy") and top not in sys.stdlib_module_names:
                outside.setdefault(relative, []).append(name)
    assert outside == {}


def test_no_exposed_file_is_reference_code():
    for relative in REFERENCE_FILES:
        assert relative not in exposed.EXPOSED
    assert not any(f.startswith(("grader/checks", "instructor_tools", "solutions")) for f in exposed.EXPOSED)
