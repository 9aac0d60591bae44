"""The debug signals: named values the brain reports each step, only ever plotted (docs/design.md, Seam 1).

An open, declared set. Each `Signal` has a name (its trace column and CSV prefix), a kind (how it is
validated, stored and drawn) and where the brain side reads it: an attribute of the supervisor or of the
current controller, optionally indexed. A week declares the NAMES it records (weeks 1-4: `WEEKS_1_TO_4`);
adding a signal is one `Signal(...)` line in `SIGNALS` plus the week's tuple of names.

Two halves, one module so that they cannot drift apart:
- `read_signals` runs on the robot's side (LocalBrain, also inside the sandbox worker): it turns whatever
  the student's objects hold (numpy scalars and arrays too) into plain JSON values, or None.
- `clean_debug` runs on the trusted side (the simulator's command validation): the worker may send
  anything, so unknown names are dropped, a value of the wrong kind becomes None and everything is capped
  (string length, number of points, finite floats).

This module imports nothing but the standard library: the worker may import it.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Literal, TypeGuard

Kind = Literal["scalar", "vector2", "points", "label", "count", "flag"]
KINDS: tuple[str, ...] = ("scalar", "vector2", "points", "label", "count", "flag")

LABEL_CHARS = 80        # a label signal (as a state name: simiam.brain caps those at the same length)
MAX_POINTS = 64         # columns of a points signal (a QuickBot has 5 IR sensors)
MAX_COUNT = 10**9       # a count signal (switches in a run: far fewer)
MAX_SIGNALS = 64        # signals one trace declares
NAME_CHARS = 40         # a signal's name (a column of the trace and the CSV)
# The unit of a vector2 that is two numbers, not a vector in the world (week 7's sigma: the coefficients of
# u_gtg and u_ao): plotted over time, never drawn as an arrow from the robot (it ran out of the arena).
COEFFICIENTS = "coefficients"


@dataclass(frozen=True)
class Signal:
    """One debug signal: `name`, `kind`, and where the brain reads it: `owner` ("supervisor" or
    "controller", the current one), its attribute `attr`, then `[index]` if not None. `size` is the
    number of columns of a points signal (None: one per IR sensor). `unit` labels plots; a scalar in
    "rad" is a heading, which the replay draws as a direction from the robot."""

    name: str
    kind: Kind
    owner: Literal["supervisor", "controller"]
    attr: str
    index: int | str | None = None
    size: int | None = None
    doc: str = ""
    unit: str = ""

    def header(self, n_ir: int) -> dict:
        """What a trace's header says of this signal (a trace is read without this registry)."""
        out: dict = {"name": self.name, "kind": self.kind}
        if self.unit:
            out["unit"] = self.unit
        if self.kind == "points":
            out["size"] = self.columns(n_ir)
        return out

    def columns(self, n_ir: int) -> int:
        """Columns of a points signal: its `size`, else one per IR sensor."""
        return self.size if self.size is not None else n_ir


def _c(name: str, kind: Kind, attr: str | None = None, doc: str = "", unit: str = "") -> Signal:
    return Signal(name, kind, "controller", attr or name, doc=doc, unit=unit)


def _s(name: str, kind: Kind, attr: str | None = None, index: int | str | None = None, doc: str = "",
       unit: str = "") -> Signal:
    return Signal(name, kind, "supervisor", attr or name, index, doc=doc, unit=unit)


# Every signal any week may record. Weeks 5-7 names follow the original sp14 controllers (§5.2-5.3 of
# ../shared/reference/original-simulator.md); their owners add the attributes these read.
SIGNALS: dict[str, Signal] = {s.name: s for s in (
    _s("v", "scalar", "outputs", 0, "the v the running controller returned, before ensure_w", "m/s"),
    _s("w", "scalar", "outputs", 1, "the w the running controller returned, before ensure_w", "rad/s"),
    _c("theta_g", "scalar", doc="the heading the controller steers to (GoToGoal's theta_g, AO's theta_ao)",
       unit="rad"),
    _c("u_ao", "vector2", doc="avoid-obstacles vector, world frame"),
    _c("ir_points_wf", "points", "ir_distances_wf", "the IR points in the world frame (x row, y row)"),
    _c("u_gtg", "vector2", doc="go-to-goal vector, world frame"),
    _c("u_ao_gtg", "vector2", doc="the blend of u_gtg and u_ao (AOandGTG)"),
    _c("u_fw_t", "vector2", doc="follow-wall: the vector along the wall"),
    _c("u_fw_tp", "vector2", doc="follow-wall: u_fw_t normalised"),
    _c("u_fw_p", "vector2", doc="follow-wall: the perpendicular from the robot to the wall"),
    _c("u_fw_pp", "vector2", doc="follow-wall: u_fw_p minus d_fw along it"),
    _c("u_fw", "vector2", doc="follow-wall: the vector followed"),
    _s("sigma", "vector2", doc="sliding mode: [u_gtg u_ao] sigma = u_fw", unit=COEFFICIENTS),
    # week 7 keeps one sigma per side: the last one its sliding_left / sliding_right computed
    _s("sigma_left", "vector2", doc="sliding mode, wall on the left: the last sigma sliding_left solved",
       unit=COEFFICIENTS),
    _s("sigma_right", "vector2", doc="sliding mode, wall on the right: the last sigma sliding_right solved",
       unit=COEFFICIENTS),
    _s("fw_direction", "label", doc="follow-wall direction, 'left' or 'right'"),
    _s("d_prog", "scalar", doc="progress point: the closest the estimate has been to the goal", unit="m"),
    # as they happen (Supervisor.switches_seen): several in one step, and a controller changed around
    # switch_to_state, count too
    _s("switches", "count", "switches_seen", doc="how many times the supervisor switched state"),
    # what check_event(name) returned this step (None: not checked this step)
    *(_s(event, "flag", "event_values", event, doc=f"the event {event}, as check_event gave it this step")
      for event in ("at_goal", "at_obstacle", "unsafe", "obstacle_cleared", "progress_made",
                    "sliding_left", "sliding_right")),
)}

# What weeks 1-4 record: exactly the five values of the first release, in its column order.
WEEKS_1_TO_4: tuple[str, ...] = ("theta_g", "u_ao", "ir_points_wf", "v", "w")


def week_signals(week: Any) -> tuple[str, ...]:
    """The signal names a week declares (its `debug_signals`), else weeks 1-4's."""
    return tuple(getattr(week, "debug_signals", None) or WEEKS_1_TO_4)


def declared(names: Iterable[str]) -> tuple[Signal, ...]:
    """The Signals called `names`, in order; a name nobody declared is a ValueError naming it (a typo in
    a week's declaration must not silently plot nothing)."""
    out = []
    for name in names:
        if name not in SIGNALS:
            raise ValueError(f"no debug signal is declared with the name {name!r} (simiam/signals.py "
                             f"declares: {', '.join(SIGNALS)})")
        out.append(SIGNALS[name])
    if len({s.name for s in out}) != len(out):
        raise ValueError(f"a debug signal is declared twice in {list(names)}")
    return tuple(out)


# --- the trusted side: whatever arrives becomes the declared kind, or None -------------------------------

def real(x: Any) -> TypeGuard[float]:
    """A finite int or float (bool and numpy scalars are not), small enough to become a float."""
    t = type(x)
    if t is float:
        return x - x == 0.0  # false for inf and nan
    return t is int and -1e308 < x < 1e308


_FLOAT = {float}


def _scalar(x: Any, _n: int) -> float | None:
    if type(x) is float:  # every step of a run: the common case without the calls below
        return x if x - x == 0.0 else None
    return float(x) if real(x) else None


def _vector2(p: Any, _n: int) -> list[float] | None:
    if type(p) is list and len(p) == 2:  # the common case: two floats, one finiteness test for both
        a, b = p
        if type(a) is float and type(b) is float and (a + b) - (a + b) == 0.0:
            return [a, b]
    if isinstance(p, (list, tuple)) and len(p) == 2 and real(p[0]) and real(p[1]):
        return [float(p[0]), float(p[1])]
    return None


def _points(p: Any, n: int) -> list[list[float]] | None:
    if type(p) is list and len(p) == 2 and n <= MAX_POINTS:  # the common case: two lists of n floats
        xs, ys = p
        if (type(xs) is list and type(ys) is list and len(xs) == n and len(ys) == n
                and set(map(type, xs + ys)) == _FLOAT):
            # what the loop below gives them: None unless each row's sum is finite
            tx = sum(xs)
            ty = sum(ys)
            return [xs[:], ys[:]] if tx - tx == 0.0 and ty - ty == 0.0 else None
    if not (isinstance(p, (list, tuple)) and len(p) == 2) or n > MAX_POINTS:
        return None
    out = []
    for row in p:
        if not (isinstance(row, (list, tuple)) and len(row) == n):
            return None
        if set(map(type, row)) == _FLOAT:  # the common case: one finiteness test for the whole row
            total = sum(row)
            if total - total != 0.0:
                return None
            out.append(list(row))
        elif all(real(c) for c in row):
            out.append([float(c) for c in row])
        else:
            return None
    return out


def _label(x: Any, _n: int) -> str | None:
    if type(x) is not str:
        return None
    if len(x) > LABEL_CHARS:
        x = x[:LABEL_CHARS]
    # a lone surrogate (from a student's own string) cannot be written as UTF-8: shown as "?"
    return x if x.isascii() else x.encode("utf-8", "replace").decode("utf-8")


def _count(x: Any, _n: int) -> int | None:
    return x if type(x) is int and 0 <= x <= MAX_COUNT else None


def _flag(x: Any, _n: int) -> bool | None:
    return x if type(x) is bool else None


_CLEAN: dict[str, Callable[[Any, int], Any]] = {"scalar": _scalar, "vector2": _vector2, "points": _points,
                                                "label": _label, "count": _count, "flag": _flag}


Plan = tuple[tuple[str, Callable[[Any, int], Any], int], ...]


def debug_plan(signals: tuple[Signal, ...], n_ir: int) -> Plan:
    """(name, rule, columns) per signal: what `clean_debug` does, worked out once per run."""
    return tuple((s.name, _CLEAN[s.kind], s.columns(n_ir)) for s in signals)


def clean_debug(debug: Any, signals: tuple[Signal, ...], n_ir: int, plan: Plan | None = None
                ) -> dict[str, Any]:
    """The debug values of one command: every declared signal, each a value of its kind or None. Names
    not declared are dropped; `debug` that is not a dict gives all None. `n_ir` sizes points signals;
    `plan` (from `debug_plan(signals, n_ir)`) saves working that out every step."""
    if not isinstance(debug, dict):
        debug = {}
    get = debug.get
    out = {}
    for name, rule, n in plan or debug_plan(signals, n_ir):  # a loop: cheaper than a comprehension's call
        x = get(name)
        if rule is _scalar and type(x) is float and x - x == 0.0:  # `_scalar`'s common case, without the call
            out[name] = x
        else:
            out[name] = rule(x, n)
    return out


# --- the robot's side: read the student's objects into plain values ----------------------------------------

def plain(x: Any) -> Any:
    """A real number as a Python float (numpy scalars included); anything else unchanged."""
    if type(x) is float:  # most values, every step of a run: spare them the ABC checks below
        return x
    if isinstance(x, numbers.Real) and not isinstance(x, bool):
        try:
            return float(x)
        except Exception:  # noqa: BLE001 - a hostile "number": the trusted side's validation rejects it
            return x
    return x


def _maybe(x: Any) -> float | None:
    x = plain(x)
    return x if isinstance(x, float) and math.isfinite(x) else None


def _read_scalar(x: Any, _n: int) -> float | None:
    return _maybe(x)


def _float_array(a: Any, ndim: int) -> bool:
    """Whether `a` is exactly a numpy array of doubles with `ndim` dimensions (not a subclass: a student's
    class may override anything), which `tolist` reads as the element-wise path below would, at once."""
    kind = type(a)
    return (kind.__name__ == "ndarray" and kind.__module__ == "numpy" and a.ndim == ndim
            and a.dtype.char == "d")


def _finite_rows(rows: list[list[float]]) -> bool:
    total = sum(map(sum, rows))
    return total - total == 0.0 or all(v - v == 0.0 for row in rows for v in row)  # a sum may overflow


def _read_vector2(u: Any, _n: int) -> list[float] | None:
    if _float_array(u, 1) and len(u) >= 2:  # most of week 5-7's vectors, every step
        values = u[:2].tolist()
        return values if _finite_rows([values]) else None
    try:
        values = [_maybe(u[i]) for i in range(2)]
    except (TypeError, IndexError, KeyError):
        return None
    got = [v for v in values if v is not None]
    return got if len(got) == 2 else None


def _read_points(p: Any, n: int) -> list[list[float]] | None:
    """The first two rows (x, y) of a 2xN or 3xN array, N columns each."""
    if _float_array(p, 2) and p.shape[0] >= 2 and p.shape[1] >= n:  # the IR points, every step
        rows = p[:2, :n].tolist()
        return rows if _finite_rows(rows) else None
    try:
        rows = [[_maybe(p[r][i]) for i in range(n)] for r in range(2)]
    except (TypeError, IndexError, KeyError):
        return None
    got = [[v for v in row if v is not None] for row in rows]
    return got if all(len(row) == n for row in got) else None


def _read_label(x: Any, _n: int) -> str | None:
    return x if isinstance(x, str) else None


def _read_count(x: Any, _n: int) -> int | None:
    if isinstance(x, numbers.Integral) and not isinstance(x, bool):
        try:
            return int(x)
        except Exception:  # noqa: BLE001 - a hostile "integer"
            return None
    return None


def _read_flag(x: Any, _n: int) -> bool | None:
    t = type(x)
    if t is bool or (t.__module__ == "numpy" and t.__name__ in ("bool", "bool_")):  # numpy's bool too
        return bool(x)
    return None


_READ: dict[str, Callable[[Any, int], Any]] = {
    "scalar": _read_scalar, "vector2": _read_vector2, "points": _read_points, "label": _read_label,
    "count": _read_count, "flag": _read_flag}
_MISSING = object()


ReadPlan = tuple[tuple[str, bool, str, int | str | None, Callable[[Any, int], Any], int], ...]


def read_plan(signals: tuple[Signal, ...], n_ir: int) -> ReadPlan:
    """(name, from the controller?, attribute, index, reader, columns) per signal: what `read_signals`
    does, worked out once per run."""
    return tuple((s.name, s.owner == "controller", s.attr, s.index, _READ[s.kind], s.columns(n_ir))
                 for s in signals)


def read_signals(supervisor: Any, signals: tuple[Signal, ...], n_ir: int, plan: ReadPlan | None = None
                 ) -> dict[str, Any]:
    """Each signal read from the supervisor or its current controller as a plain value, or None when the
    attribute is missing or holds something else. Never raises for what the objects hold. `plan` (from
    `read_plan(signals, n_ir)`) saves working that out every step."""
    controller = getattr(supervisor, "current_controller", None)
    out = {}
    for name, of_controller, attr, index, reader, n in plan or read_plan(signals, n_ir):
        value = getattr(controller if of_controller else supervisor, attr, None)
        if index is not None and value is not None:
            try:
                value = value[index]
            except Exception:  # noqa: BLE001 - a student's object may raise anything when indexed
                value = None
        # every reader gives None for None (an absent attribute, a controller without the signal): most
        # steps' absent signals skip the reader, whose general path would raise and catch for None
        out[name] = None if value is None else reader(value, n)
    return out


def headers(signals: tuple[Signal, ...], n_ir: int) -> list[dict]:
    """The trace header's declaration of `signals` (name, kind, size of points)."""
    return [s.header(n_ir) for s in signals]


def from_headers(items: Any) -> list[dict]:
    """A trace header's signal declarations, checked: a list of {"name", "kind"[, "size"]}; raises
    ValueError otherwise (a trace file is read by the viewer and the report without this registry)."""
    if not isinstance(items, list) or len(items) > MAX_SIGNALS:
        raise ValueError(f"the trace's 'signals' must be a list of at most {MAX_SIGNALS}")
    out = []
    for item in items:
        if not (isinstance(item, Mapping) and isinstance(item.get("name"), str)
                and item["name"].isidentifier() and len(item["name"]) <= NAME_CHARS
                and item.get("kind") in KINDS):
            raise ValueError(f"a signal declaration needs a name (a Python identifier of at most "
                             f"{NAME_CHARS} characters) and one of the kinds {', '.join(KINDS)}")
        entry = {"name": item["name"], "kind": item["kind"]}
        if isinstance(item.get("unit"), str) and item["unit"]:
            entry["unit"] = item["unit"][:20]
        if item["kind"] == "points":
            size = item.get("size")
            if not (type(size) is int and 0 < size <= MAX_POINTS):
                raise ValueError(f"the points signal {item['name']!r} needs a size from 1 to {MAX_POINTS}")
            entry["size"] = size
        out.append(entry)
    return out
