"""Whether a week's parts agree (tests/course/test_week_parts.py): its declaration (simiam/course/weeks/),
its checks (grader/checks/) and the probes they send into the sandbox (grader/inside/probes*.py).

Which probes a check sends is read from the source, without running anything: from the check's `run`
(a function, a closure a factory made, or a functools.partial), every function it names is followed, in
its own module and in the modules it imports from our own code, and every `ctx.probe("name", ...)` or
`ctx.probe_each("name", ...)` on the way is one the check sends. A probe named by anything but a string
literal is reported as a problem (the test could not say which probe it is).

What each probe runs of the student's code is its own declaration (`@exercises("file:scope")`,
grader/inside/probing.py), in the spelling of the week's blocks (Placeholder file and scope).
"""

from __future__ import annotations

import ast
import functools
import inspect
import sys
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from simiam.course.week import Week

ROOT = Path(__file__).resolve().parents[2]
PROBE_METHODS = ("probe", "probe_each")
# Where a probe name is passed on, not chosen: Context.probe and probe_each send the name their caller gave.
PASSED_ON = {("grader.checks", "Context")}


def _source(module: str) -> Path:
    """The checkout's source of one of our modules, by its name: not the module's __file__, which another
    test in the same process may have left pointing at a sourceless copy (a wheel's bytecode)."""
    base = ROOT.joinpath(*module.split("."))
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return Path(inspect.getfile(sys.modules[module]))


@functools.cache
def _tree(module: str) -> tuple[ast.Module, dict[str, ast.AST], dict[str, tuple[str, str | None]]]:
    """A module's syntax tree, its top-level definitions by name, and what it imports by local name
    ((module, attribute) for `from m import a`; (module, None) for `import m as x`)."""
    path = _source(module)
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    defined: dict[str, ast.AST] = {}
    imported: dict[str, tuple[str, str | None]] = {}
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(parts + ([base] if base else []))
            for alias in node.names:
                whole = f"{base}.{alias.name}"
                local = alias.asname or alias.name
                imported[local] = (whole, None) if whole in sys.modules else (base, alias.name)
        elif isinstance(node, ast.Import):
            for alias in node.names:
                imported[alias.asname or alias.name.split(".")[0]] = (alias.name if alias.asname else
                                                                      alias.name.split(".")[0], None)
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            defined[node.name] = node
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for target in targets:
                if isinstance(target, ast.Name):
                    defined[target.id] = node
    return tree, defined, imported


@functools.cache
def _ours(module: str) -> bool:
    """Code whose probes count: Python source of this checkout outside the simulator (which never probes)
    and outside any virtual environment in it (a clean clone keeps its .venv, numpy's compiled modules
    included, inside the checkout)."""
    file = getattr(sys.modules.get(module), "__file__", None)
    if file is None or not file.endswith(".py"):
        return False
    path = Path(file).resolve()
    if not path.is_relative_to(ROOT):
        return False
    parts = path.relative_to(ROOT).parts
    return parts[0] != "simiam" and not parts[0].startswith(".") and "site-packages" not in parts


def _origin(run: Callable[..., Any]) -> tuple[str, str]:
    """(module, top-level name) where a check's run function is written."""
    while isinstance(run, functools.partial):
        run = run.func
    target = run if inspect.isfunction(run) or inspect.ismethod(run) else type(run)
    return target.__module__, target.__qualname__.split(".")[0]


def _code(node: ast.AST) -> list[ast.AST]:
    """Every node under `node` except those of annotations (a name in a type hint is never called)."""
    found: list[ast.AST] = []
    todo = [node]
    while todo:
        current = todo.pop()
        found.append(current)
        for field, value in ast.iter_fields(current):
            if field in ("annotation", "returns"):
                continue
            children = value if isinstance(value, list) else [value]
            todo += [child for child in children if isinstance(child, ast.AST)]
    return found


@functools.cache
def _scan(module: str, name: str) -> tuple[frozenset[str], tuple[str, ...], tuple[tuple[str, str], ...]]:
    """What the top-level definition `name` of `module` sends itself (probe names, probes named otherwise
    than by a literal) and the definitions it names, to follow."""
    _, defined, imported = _tree(module)
    if name not in defined:
        home = imported.get(name)
        return frozenset(), (), ((home[0], home[1]),) if home is not None and home[1] is not None else ()
    names: set[str] = set()
    unclear: list[str] = []
    follow: list[tuple[str, str]] = []
    for node in _code(defined[name]):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in PROBE_METHODS:
            first = node.args[0] if node.args else None
            if isinstance(first, ast.Constant) and isinstance(first.value, str):
                names.add(first.value)
            else:
                unclear.append(f"{module}, line {node.lineno}: a probe named by an expression")
        elif isinstance(node, ast.Name):
            if node.id in defined:
                follow.append((module, node.id))
            elif node.id in imported and imported[node.id][1] is not None:
                follow.append(imported[node.id])  # type: ignore[arg-type]
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                and node.value.id in imported and imported[node.value.id][1] is None:
            follow.append((imported[node.value.id][0], node.attr))  # module.function
    return frozenset(names), tuple(unclear), tuple(follow)


def probes_sent(run: Callable[..., Any]) -> tuple[set[str], list[str]]:
    """The probe names a check's `run` sends, and where it names one other than by a string literal."""
    names: set[str] = set()
    unclear: list[str] = []
    seen: set[tuple[str, str]] = set()
    todo = [_origin(run)]
    while todo:
        where = todo.pop()
        if where in seen or where in PASSED_ON or not _ours(where[0]):
            continue
        seen.add(where)
        sent, named_otherwise, follow = _scan(*where)
        names |= sent
        unclear += named_otherwise
        todo += follow
    return names, unclear


def declared_blocks(weeks: Iterable[Week], upto: int) -> set[tuple[str, str]]:
    """(file, scope) of every block declared by the weeks up to `upto`."""
    return {(b.file, b.scope) for week in weeks if week.number <= upto for b in week.blocks}


def problems(week: Week, weeks: Iterable[Week], checks: Iterable[Any],
             probes: Mapping[str, Callable[..., Any]]) -> list[str]:
    """What in `week` does not fit together: a check needing a file the week has not, a check naming a
    probe the sandbox has not, a probe running student code that is no block of this week or an earlier
    one (or in a file the check does not need). Empty when the parts agree."""
    found = []
    blocks = declared_blocks(weeks, week.number)
    where = f"week {week.number} ({week.checks})"
    for check in checks:
        missing_files = sorted(set(check.needs) - set(week.student_files))
        if missing_files:
            found.append(f"{where}: check {check.id} needs {missing_files}, not among the week's "
                         "student_files")
        sent, unclear = probes_sent(check.run)
        found += [f"{where}: check {check.id}: {text}" for text in unclear]
        for name in sorted(sent):
            probe = probes.get(name)
            if probe is None:
                found.append(f"{where}: check {check.id} sends probe {name!r}, which the sandbox has not "
                             "(add it to a grader/inside/probes_weekN.py and register it in "
                             "grader/inside/probes.py)")
                continue
            for spot in getattr(probe, "exercises", ()):
                file, _, scope = spot.partition(":")
                if (file, scope) not in blocks:
                    found.append(f"{where}: check {check.id} sends probe {name!r}, which runs {spot}: "
                                 f"no week up to {week.number} declares a block there "
                                 f"(simiam/course/weeks/week{week.number}.py, blocks)")
                elif check.needs and file not in check.needs:
                    found.append(f"{where}: check {check.id} sends probe {name!r}, which runs {spot}, "
                                 f"but its needs {list(check.needs)} leave out {file}")
    return found


def unsent(probes: Mapping[str, Callable[..., Any]], checks: Iterable[Any]) -> list[str]:
    """The probes no check sends (each a line saying where it is defined)."""
    sent: set[str] = set()
    for check in checks:
        sent |= probes_sent(check.run)[0]
    return [f"probe {name!r} ({probe.__module__}) is sent by no week's checks: remove it or check with it"
            for name, probe in sorted(probes.items()) if name not in sent]


def undeclared(probes: Mapping[str, Callable[..., Any]]) -> list[str]:
    """The probes that do not say which student code they run (so no block could be checked for them)."""
    return [f"probe {name!r} ({probe.__module__}) does not declare the student code it runs: "
            "@exercises(\"file:scope\") from grader/inside/probing.py"
            for name, probe in sorted(probes.items()) if not getattr(probe, "exercises", ())]
