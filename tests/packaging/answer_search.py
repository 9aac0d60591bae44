"""What counts as an answer, derived from the code blocks of solutions/ (every week, so a new week is
covered the day its solutions exist), and a search for those answers in any file (issue 11: the wheel holds
no answers).

Three rules, all computed from each block, never from a list of names:

- **Lines**: a normalised code line of a block (whitespace collapsed, trailing comment dropped) that the
  course does not give every student anyway (provided code outside the blocks, the stubs' placeholders),
  and that does more than assign one number or word (a gain or a setting is a choice, not maths).
- **Expressions**, to catch the same maths in other wording: every expression of a block, with local names
  replaced by `_` (module names such as `math` and attribute names such as `.max_vel` kept), numbers as
  floats, the operands of `+` and `*` sorted, and locals assigned once inlined (so `c = math.cos(theta)`
  then `[c, -s, x]` reads like `[math.cos(theta), -math.sin(theta), x]`). Expressions that provided code
  holds are not answers. A file holds a block's answer if it contains one of the block's expressions of
  weight >= DISTINCT (weight: the number of operands, operators, calls, names and constants), or at least
  SEVERAL distinct expressions of weight >= SMALL of one block inside one function. One small expression
  alone is ordinary geometry (`d * math.cos(heading)`, the midpoint `(a + b) / 2`), which the simulator
  and the report need; the same three of them in one function are an odometry update. Arithmetic of
  names alone (`a * (x - x0) - b * (y - y0)`) never counts: it is any rotation or difference.
- **Values**, to catch algebra in other wording: a block's expression of weight >= DISTINCT made of + - * /
  ** and math functions over 2 to 4 names is evaluated with the names bound to fixed numbers in every
  order; a file's expression with the same results is the same maths (`(v + w * L / 2) / R` is
  `(2 * v + w * L) / (2 * R)`).

What it cannot see: maths spread over several functions, loops, or numpy calls it does not evaluate. The
wrong versions in tests/data/wheel_answers/ show what it does see.
"""

from __future__ import annotations

import ast
import itertools
import math
import operator
import re
import textwrap
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path

from simiam.course.blocks import find_blocks

DISTINCT = 8
SMALL = 5
SEVERAL = 3
MODULES = frozenset({"math", "np", "numpy", "cmath"})
_WEIGHED = (ast.BinOp, ast.UnaryOp, ast.Call, ast.Attribute, ast.Subscript, ast.Compare, ast.BoolOp,
            ast.IfExp, ast.Name, ast.Constant)
_SORTED = (ast.Add, ast.Mult)
# Only names and + - * /: `a * (x - x0) - b * (y - y0)` is any rotation, lerp or difference; an answer's
# expression has something of the course in it (a number, a call, an attribute, an index).
_GENERIC = re.compile(r"(?:BinOp\(|Add\(|Mult\(|Sub\(\)|Div\(\)|UnaryOp\(USub\(\)|_|,|\))+")


def norm_line(line: str) -> str:
    return re.sub(r"\s+", " ", line.split("  #")[0]).strip()


class _Shapes:
    """Shapes and weights of the expressions of one scope, as written (`inline=False`) and with the locals
    it assigns exactly once replaced by their expressions (`inline=True`); memoised per node."""

    def __init__(self, scope: ast.AST) -> None:
        counts: dict[str, int] = {}
        values: dict[str, ast.expr] = {}
        for node in _own_nodes(scope):
            if isinstance(node, ast.Assign) and len(node.targets) == 1:
                for name, value in _pairs(node.targets[0], node.value):
                    counts[name] = counts.get(name, 0) + 1
                    values[name] = value
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                counts[node.id] = counts.get(node.id, 0) + 1  # loop variables, augmented and other targets
        self.values = {k: v for k, v in values.items() if counts.get(k) == 2}  # the Assign and its Name
        self.memo: dict[tuple[int, bool], tuple[str, int]] = {}
        self.busy: set[str] = set()

    def of(self, node: ast.AST, inline: bool | str) -> tuple[str, int]:
        """`inline`: False (as written), True (every local assigned once), "aliases" (only names bound to
        another name or attribute, such as `cos = math.cos`)."""
        key = (id(node), inline)
        if key not in self.memo:
            self.memo[key] = self._of(node, inline)
        return self.memo[key]

    def _of(self, node: ast.AST, inline: bool | str) -> tuple[str, int]:
        if isinstance(node, ast.Name):
            value = self.values.get(node.id) if inline and isinstance(node.ctx, ast.Load) else None
            if inline == "aliases" and not isinstance(value, ast.Name | ast.Attribute):
                value = None
            if value is not None and node.id not in self.busy:
                self.busy.add(node.id)
                try:
                    return self.of(value, inline)
                finally:
                    self.busy.discard(node.id)
            return (node.id if node.id in MODULES else "_"), 1
        if isinstance(node, ast.Constant):
            value = node.value
            number = isinstance(value, int | float) and not isinstance(value, bool)
            return (repr(float(value)) if number else repr(value)), 1
        weight = 1 if isinstance(node, _WEIGHED) else 0
        if isinstance(node, ast.BinOp) and isinstance(node.op, _SORTED):
            kind = type(node.op)
            terms: list[ast.AST] = []
            stack: list[ast.AST] = [node]
            while stack:
                n = stack.pop()
                if isinstance(n, ast.BinOp) and isinstance(n.op, kind):
                    stack += [n.left, n.right]
                    weight += n is not node
                else:
                    terms.append(n)
            parts = [self.of(t, inline) for t in terms]
            return (f"{kind.__name__}({','.join(sorted(s for s, _ in parts))})",
                    weight + sum(w for _, w in parts))
        if isinstance(node, ast.Attribute):
            inner, w = self.of(node.value, inline)
            return f"{inner}.{node.attr}", weight + w
        kids = [c for c in ast.iter_child_nodes(node) if not isinstance(c, ast.expr_context)]
        parts = [self.of(c, inline) for c in kids]
        return f"{type(node).__name__}({','.join(s for s, _ in parts)})", weight + sum(w for _, w in parts)


_MATH = {"sin": math.sin, "cos": math.cos, "tan": math.tan, "atan2": math.atan2, "sqrt": math.sqrt,
         "hypot": math.hypot, "exp": math.exp, "arctan2": math.atan2, "pi": math.pi}
_OPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
        ast.Pow: operator.pow}
_POOLS = ((0.37, 1.91, -0.83, 2.71), (1.13, -0.29, 0.61, -1.77))


class _Values(_Shapes):
    """The same maths in any algebraic wording: an expression of + - * / ** and math functions over 2 to 4
    free names is evaluated with the names bound to fixed numbers in every order; the sorted results are its
    fingerprint, equal for `(2 * v + w * L) / (2 * R)` and `(v + w * L / 2) / R`, whatever the names."""

    def free(self, node: ast.AST, inline: bool) -> frozenset[str] | None:
        """The free names (attribute chains such as robot.max_vel count as one), or None if not maths."""
        if isinstance(node, ast.Name):
            value = self.values.get(node.id) if inline else None
            if value is not None and node.id not in self.busy:
                self.busy.add(node.id)
                try:
                    return self.free(value, True)
                finally:
                    self.busy.discard(node.id)
            return None if node.id in MODULES else frozenset({node.id})
        if isinstance(node, ast.Attribute):
            if isinstance(node.value, ast.Name) and node.value.id in MODULES:
                return frozenset() if node.attr in _MATH else None
            inner = _chain(node)
            return None if inner is None else frozenset({inner})
        if isinstance(node, ast.Constant):
            number = isinstance(node.value, int | float) and not isinstance(node.value, bool)
            return frozenset() if number else None
        if isinstance(node, ast.BinOp) and type(node.op) in _OPS:
            left, right = self.free(node.left, inline), self.free(node.right, inline)
            return None if left is None or right is None else left | right
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
            return self.free(node.operand, inline)
        if isinstance(node, ast.Call) and _math_call(node) and not node.keywords:
            parts = [self.free(a, inline) for a in node.args]
            return None if any(x is None for x in parts) else frozenset().union(*parts)
        return None

    def evaluate(self, node: ast.AST, inline: bool, env: dict[str, float]) -> float:
        if isinstance(node, ast.Name):
            value = self.values.get(node.id) if inline else None
            if value is not None and node.id not in self.busy:
                self.busy.add(node.id)
                try:
                    return self.evaluate(value, True, env)
                finally:
                    self.busy.discard(node.id)
            return env[node.id]
        if isinstance(node, ast.Attribute):
            if isinstance(node.value, ast.Name) and node.value.id in MODULES:
                return float(_MATH[node.attr])  # math.pi
            return env[_chain(node) or ""]
        if isinstance(node, ast.Constant):
            return float(node.value)
        if isinstance(node, ast.BinOp):
            return float(_OPS[type(node.op)](self.evaluate(node.left, inline, env),
                                             self.evaluate(node.right, inline, env)))
        if isinstance(node, ast.UnaryOp):
            value = self.evaluate(node.operand, inline, env)
            return -value if isinstance(node.op, ast.USub) else value
        assert isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
        return float(_MATH[node.func.attr](*(self.evaluate(a, inline, env) for a in node.args)))

    def fingerprint(self, node: ast.AST, inline: bool) -> tuple | None:
        names = self.free(node, inline)
        if names is None or not 2 <= len(names) <= 4:
            return None
        order = sorted(names)
        results = []
        try:
            for pool in _POOLS:
                for values in itertools.permutations(pool[:len(order)]):
                    value = self.evaluate(node, inline, dict(zip(order, values, strict=True)))
                    if isinstance(value, complex) or not math.isfinite(value):
                        return None
                    results.append(f"{value:.9g}")
        except (ArithmeticError, ValueError, KeyError, TypeError):
            return None
        return len(order), tuple(sorted(results))


def _chain(node: ast.AST) -> str | None:
    """`robot.max_vel` -> "robot.max_vel"; None for anything but names and attributes."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        inner = _chain(node.value)
        return None if inner is None else f"{inner}.{node.attr}"
    return None


def _math_call(node: ast.Call) -> bool:
    f = node.func
    return isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id in MODULES \
        and f.attr in _MATH and f.attr != "pi"


def _pairs(target: ast.expr, value: ast.expr) -> list[tuple[str, ast.expr]]:
    if isinstance(target, ast.Name):
        return [(target.id, value)]
    if isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and len(target.elts) == len(value.elts):
        return [p for t, v in zip(target.elts, value.elts, strict=True) for p in _pairs(t, v)]
    return []


_FUNCTIONS = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)


def _own_nodes(scope: ast.AST) -> Iterator[ast.AST]:
    """The nodes of a function (with the functions nested in it), or of a module outside its functions."""
    stack = list(ast.iter_child_nodes(scope))
    while stack:
        node = stack.pop()
        if isinstance(scope, ast.Module) and isinstance(node, _FUNCTIONS):
            continue
        yield node
        stack.extend(ast.iter_child_nodes(node))


def _scopes(tree: ast.AST) -> Iterator[ast.AST]:
    """The module (outside its functions) and every function in it."""
    yield tree
    for node in ast.walk(tree):
        if isinstance(node, _FUNCTIONS):
            yield node


def expressions(scope: ast.AST, minimum: int = SMALL) -> dict[str, int]:
    """{shape: weight} of every expression of `scope`, as written and with single-assignment locals
    inlined."""
    shapes = _Shapes(scope)
    out: dict[str, int] = {}
    for node in _own_nodes(scope):
        if isinstance(node, ast.expr) and not isinstance(node, ast.Name | ast.Constant):
            for inline in (False, True, "aliases"):
                shape, weight = shapes.of(node, inline)
                if weight >= minimum and not _GENERIC.fullmatch(shape):
                    out[shape] = weight
    return out


def values(scope: ast.AST, minimum: int = SMALL) -> dict[tuple, int]:
    """{fingerprint: weight} of every expression of `scope` that is maths over 2 to 4 names (_Values)."""
    shapes = _Values(scope)
    out: dict[tuple, int] = {}
    for node in _own_nodes(scope):
        if isinstance(node, ast.BinOp | ast.Call | ast.UnaryOp):
            for inline in (False, True):
                weight = shapes.of(node, inline)[1]
                if weight >= minimum and (fp := shapes.fingerprint(node, inline)) is not None:
                    out[fp] = max(weight, out.get(fp, 0))
    return out


def _all_values(tree: ast.AST, minimum: int) -> dict[tuple, int]:
    out: dict[tuple, int] = {}
    for scope in _scopes(tree):
        out.update(values(scope, minimum))
    return out


def _all_expressions(tree: ast.AST, minimum: int) -> dict[str, int]:
    out: dict[str, int] = {}
    for scope in _scopes(tree):
        out.update(expressions(scope, minimum))
    return out


@dataclass
class Answers:
    """What counts as an answer: code lines and expression shapes, each with the block it comes from."""

    lines: dict[str, str]
    shapes: dict[str, tuple[int, str]]  # shape -> (weight, block)
    values: dict[tuple, tuple[int, str]]  # fingerprint of an expression of weight >= DISTINCT -> same

    def blocks(self) -> set[str]:
        return {b for _, b in self.shapes.values()} | {b for _, b in self.values.values()} | set(
            self.lines.values())


def _provided(repo: Path) -> tuple[set[str], set[str], set[tuple]]:
    """Lines and shapes every student receives anyway: the stubs outside the blocks, and each stub block
    that is a placeholder (its body differs from the solution's; a later week's stub ships earlier blocks
    filled in, and those stay answers), so no list of placeholders is needed."""
    lines: set[str] = set()
    shapes: set[str] = set()
    prints: set[tuple] = set()
    for stub in sorted(repo.glob("assignments/week*/*.py")):
        text = stub.read_text()
        solution = repo / "solutions" / stub.parent.name / stub.name
        solved = {b.key: b.body for b in find_blocks(solution.read_text(), stub.name)} if solution.is_file() \
            else {}
        blanked = text.splitlines()
        for b in find_blocks(text, stub.name):
            if b.body != solved.get(b.key):  # a placeholder: given to every student
                lines.update(norm_line(ln) for ln in b.body.splitlines())
                shapes.update(_all_expressions(ast.parse(textwrap.dedent(b.body)), 1))
                prints.update(_all_values(ast.parse(textwrap.dedent(b.body)), 1))
            blanked[b.start_line:b.end_line - 1] = [f"{b.indent}pass"] * (b.end_line - 1 - b.start_line)
        lines.update(norm_line(ln) for ln in blanked)
        shapes.update(_all_expressions(ast.parse("\n".join(blanked)), 1))
        prints.update(_all_values(ast.parse("\n".join(blanked)), 1))
    return lines, shapes, prints


def _setting(code: str) -> bool:
    """`self.Kp = 2.5`, `self.fw_direction = "left"`: one number or word assigned, a choice (a gain, a
    setting the framework may default to), not maths. A list of numbers (the IR fit) is not a setting."""
    try:
        (statement,) = ast.parse(code).body
    except (SyntaxError, ValueError):
        return False
    return isinstance(statement, ast.Assign) and isinstance(statement.value, ast.Constant)


def answers_of(repo: Path) -> Answers:
    """Every answer of every block of solutions/week*/ (see the module's docstring)."""
    provided_lines, provided_shapes, provided_values = _provided(repo)
    lines: dict[str, str] = {}
    shapes: dict[str, tuple[int, str]] = {}
    prints: dict[tuple, tuple[int, str]] = {}
    for path in sorted(repo.glob("solutions/week*/*.py")):
        for b in find_blocks(path.read_text(), path.name):
            where = f"{path.relative_to(repo)} {b.describe()}"
            for line in b.body.splitlines():
                code = norm_line(line)
                trivial = not code or code.startswith("#") or re.fullmatch(r"\w+:", code) or _setting(code)
                if not trivial and code not in provided_lines:
                    lines[code] = where
            body = ast.parse(textwrap.dedent(b.body))
            for shape, weight in _all_expressions(body, SMALL).items():
                if shape not in provided_shapes:
                    shapes[shape] = (weight, where)
            for fp, weight in _all_values(body, DISTINCT).items():
                if fp not in provided_values:
                    prints[fp] = (weight, where)
    return Answers(lines, shapes, prints)


def found_in(text: str, answers: Answers) -> list[str]:
    """The answers `text` holds, in words (empty: none). Python files are searched by lines and shapes,
    any other file by lines."""
    own = {norm_line(x) for x in text.splitlines()}
    hits = sorted(f"line {ln!r} of {where}" for ln, where in answers.lines.items() if ln in own)
    try:
        tree = ast.parse(text)
    except (SyntaxError, ValueError):
        return hits
    for scope in _scopes(tree):
        per_block: dict[str, set[str]] = {}
        for shape in expressions(scope).keys() & answers.shapes.keys():
            weight, where = answers.shapes[shape]
            if weight >= DISTINCT:
                hits.append(f"the expression {shape} of {where}")
            per_block.setdefault(where, set()).add(shape)
        for fp in values(scope).keys() & answers.values.keys():
            hits.append(f"an expression equal to one of {answers.values[fp][1]} (same maths, other wording)")
        name = getattr(scope, "name", "the module")
        hits.extend(f"{len(found)} expressions of {where} in {name}: {sorted(found)}"
                    for where, found in per_block.items() if len(found) >= SEVERAL)
    return sorted(set(hits))


def search(files: Iterable[tuple[str, str]], answers: Answers) -> dict[str, list[str]]:
    """{file name: the answers it holds} over (name, text) pairs."""
    return {name: found for name, text in files if (found := found_in(text, answers))}
