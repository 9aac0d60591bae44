"""Debug signals (simiam/signals.py): whatever a worker returns in `debug` becomes the declared kind or None,
capped, unknown names dropped; each rule is reached by a hostile value, and each wrong version of the
rules kept in tests/data/wrong_signals/ is caught."""

from __future__ import annotations

import csv
import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

from simiam import signals
from simiam.course.weeks import spec_for_week
from simiam.signals import LABEL_CHARS, MAX_COUNT, SIGNALS, WEEKS_1_TO_4, clean_debug, declared, read_signals
from simiam.simulator import Simulator
from simiam.trace import Trace
from simiam.world import load_world

WRONG = Path(__file__).parents[1] / "data" / "wrong_signals"
# one signal of every kind (what weeks 5-7 declare), the points one sized by the 5 IR sensors
ALL_KINDS = declared(("v", "u_gtg", "ir_points_wf", "fw_direction", "switches", "at_goal"))
GOOD_POINTS = [[0.1, 0.2, 0.3, 0.4, 0.5], [1, 2, 3, 4, 5]]

# (signal, hostile value, what the trace must hold): every rule of every kind
CASES = [
    ("v", 0.5, 0.5),
    ("v", 2, 2.0),
    ("v", True, None),                       # a bool is not a number
    ("v", float("nan"), None),
    ("v", float("inf"), None),
    ("v", 10**400, None),                    # an int no float can hold
    ("v", "1.5", None),
    ("v", [1.0], None),
    ("u_gtg", [1, 2.5], [1.0, 2.5]),
    ("u_gtg", (3.0, 4.0), [3.0, 4.0]),
    ("u_gtg", [1.0, float("nan")], None),
    ("u_gtg", [1.0, 2.0, 3.0], None),        # not a 2-vector
    ("u_gtg", [1.0, "2"], None),
    ("u_gtg", [True, 1.0], None),
    ("u_gtg", {"0": 1, "1": 2}, None),
    ("ir_points_wf", GOOD_POINTS, [[0.1, 0.2, 0.3, 0.4, 0.5], [1.0, 2.0, 3.0, 4.0, 5.0]]),
    ("ir_points_wf", [[0.0] * 6, [0.0] * 6], None),         # one column per IR sensor, no more
    ("ir_points_wf", [[0.0] * 10**5, [0.0] * 10**5], None),
    ("ir_points_wf", [[0.0] * 5, [0.0] * 4], None),
    ("ir_points_wf", [[0.0] * 5, [0.0] * 5, [0.0] * 5], None),
    ("ir_points_wf", [[0.0] * 4 + [float("inf")], [0.0] * 5], None),
    ("ir_points_wf", [[0.0] * 4 + [None], [0.0] * 5], None),
    ("fw_direction", "left", "left"),
    ("fw_direction", "x" * 10**6, "x" * LABEL_CHARS),     # capped
    ("fw_direction", "a\ud800b", "a?b"),                   # a lone surrogate cannot be written as UTF-8
    ("fw_direction", 3, None),
    ("fw_direction", ["left"], None),
    ("switches", 7, 7),
    ("switches", True, None),
    ("switches", -1, None),
    ("switches", MAX_COUNT + 1, None),
    ("switches", 7.0, None),
    ("at_goal", True, True),
    ("at_goal", False, False),
    ("at_goal", 1, None),
    ("at_goal", "no", None),
    ("at_goal", [], None),
]


def problems(clean) -> list[str]:
    """What a `clean_debug` gets wrong, over CASES and the whole-dict rules."""
    found = []
    for name, value, expected in CASES:
        got = clean({name: value}, ALL_KINDS, 5).get(name)
        if got != expected or type(got) is not type(expected):
            found.append(f"{name} = {str(value)[:40]!r}: {str(got)[:40]!r}, expected {expected!r}")
    got = clean({"v": 1.0, "evil": "x" * 1000, "__proto__": {}}, ALL_KINDS, 5)
    if set(got) != {s.name for s in ALL_KINDS}:
        found.append(f"names kept: {sorted(set(got))}")
    for not_a_dict in (None, [1, 2], "debug", 3.0):
        if clean(not_a_dict, ALL_KINDS, 5) != dict.fromkeys(got):
            found.append(f"debug = {not_a_dict!r} did not give all None")
    return found


def test_every_rule_holds():
    assert problems(clean_debug) == []


def _wrong_versions():
    return sorted(p.stem for p in WRONG.glob("*.py") if not p.stem.startswith("_"))


@pytest.mark.parametrize("name", _wrong_versions())
def test_a_wrong_rule_is_caught(name, monkeypatch):
    monkeypatch.syspath_prepend(str(WRONG))
    spec = importlib.util.spec_from_file_location(f"wrong_signals_{name}", WRONG / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert problems(mod.clean_debug)


class HostileBrain:
    """WRONG brain (a test double of a forged worker): valid wheel speeds, debug full of junk."""

    def __init__(self, debug):
        self.debug = debug

    def step(self, readings):
        return {"vel_r": 1.0, "vel_l": 1.0, "estimate": None, "state": "s" * 500, "debug": self.debug}


def test_a_hostile_brain_leaves_only_declared_capped_values_in_the_trace(tmp_path):
    debug = {name: value for name, value, _ in CASES[1::7]} | {f"junk{i}": "x" * 100 for i in range(1000)}
    sim = Simulator(load_world("week3"), HostileBrain(debug), spec_for_week(3), dt=0.05,
                    signals=[s.name for s in ALL_KINDS])
    trace = sim.run(seconds=0.5)
    expected = {name: want for name, _, want in CASES[1::7]}
    for name in trace.signal_names:
        assert trace.steps[name][1:] == [expected.get(name)] * (len(trace) - 1)
    assert not any(c.startswith("junk") for c in trace.steps)
    assert {len(s) for s in trace.steps["state"][1:]} == {80}
    csv_path, json_path = trace.write(tmp_path)  # NaN-free, surrogate-free: both files are written
    json.loads(json_path.read_text())
    with csv_path.open() as f:
        head = next(csv.reader(f))
    assert "fw_direction" in head and "u_gtg_y" in head and "ir_points_wf_y5" in head


def test_an_undeclared_name_is_refused_where_a_week_declares_it():
    with pytest.raises(ValueError, match="u_gtgg"):
        declared(("u_gtg", "u_gtgg"))
    with pytest.raises(ValueError, match="twice"):
        declared(("v", "v"))
    with pytest.raises(ValueError, match="u_gtgg"):
        Simulator(load_world("week3"), HostileBrain({}), spec_for_week(3), signals=("u_gtgg",))


class _Controller:
    theta_g = np.float64(0.25)
    u_ao = np.array([1.0, 2.0])
    ir_distances_wf = np.arange(15.0).reshape(3, 5)  # the course's 3x5 homogeneous points
    u_gtg = [1.0, float("nan")]


class _Supervisor:
    current_controller = _Controller()
    outputs = (np.float32(0.5), 2)
    fw_direction = "right"
    switches_seen = np.int64(3)
    event_values = {"at_goal": np.bool_(True)}


def test_the_robot_side_reads_numpy_values_as_plain_json():
    got = read_signals(_Supervisor(), declared(WEEKS_1_TO_4 + ("u_gtg", "fw_direction", "switches", "at_goal",
                                                               "unsafe", "sigma")), 5)
    assert got == {"theta_g": 0.25, "u_ao": [1.0, 2.0], "ir_points_wf": [[0, 1, 2, 3, 4], [5, 6, 7, 8, 9]],
                   "v": 0.5, "w": 2.0, "u_gtg": None, "fw_direction": "right", "switches": 3,
                   "at_goal": True, "unsafe": None, "sigma": None}
    assert json.dumps(got) and all(type(v) is float for v in got["ir_points_wf"][0])


@pytest.mark.parametrize("kind", sorted(signals._READ))  # noqa: SLF001 - the readers themselves
def test_every_reader_gives_none_for_none(kind):
    # read_signals and the worker's record writer skip the reader for None (most steps' absent signals):
    # exact only while every reader says None for it, as a reader mapping None to a value would not
    assert signals._READ[kind](None, 5) is None  # noqa: SLF001


def test_read_signals_skips_no_reader_but_for_none(monkeypatch):
    seen = []
    monkeypatch.setitem(signals._READ, "scalar", lambda x, n: seen.append(x) or 7.0)  # noqa: SLF001

    class Sup:
        current_controller = None
        theta_g = 0.0
        outputs = (None, 0.5)

    got = read_signals(Sup(), declared(("v", "w")), 5)
    assert got == {"v": None, "w": 7.0} and seen == [0.5]


def test_the_robot_side_survives_hostile_objects():
    class Boom:
        def __getitem__(self, i):
            raise RuntimeError("no")

        def __float__(self):
            raise RuntimeError("no")

    class Sup:
        current_controller = None
        outputs = Boom()
        event_values = Boom()

    got = read_signals(Sup(), declared(("v", "u_ao", "at_goal")), 5)
    assert got == {"v": None, "u_ao": None, "at_goal": None}


def test_the_ir_count_comes_from_the_robot_spec(tmp_path):
    from dataclasses import replace

    spec = replace(spec_for_week(4), ir_mounts=spec_for_week(4).ir_mounts[1:4])
    seen = []

    class Three:
        def step(self, readings):
            seen.append(len(readings["ir_raw"]))
            return {"vel_r": 1.0, "vel_l": 1.0, "debug": {"ir_points_wf": [[1, 2, 3], [4, 5, 6]]}}

    trace = Simulator(load_world("week4"), Three(), spec, dt=0.05).run(seconds=0.2)
    assert set(seen) == {3} and trace.steps["ir_points_wf"][1] == [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]
    assert trace.signals[2] == {"name": "ir_points_wf", "kind": "points", "size": 3}
    head = trace.csv_header()
    assert "ir_raw_3" in head and "ir_raw_4" not in head and "ir_points_wf_y3" in head
    assert Trace.from_json(trace.to_json()).csv_header() == head


def test_every_registered_signal_has_a_known_kind_and_owner():
    for s in SIGNALS.values():
        assert s.kind in ("scalar", "vector2", "points", "label", "count", "flag") and s.doc
        assert s.owner in ("supervisor", "controller") and s.name.isidentifier()


def test_a_week_that_declares_an_unknown_signal_is_refused():
    from dataclasses import replace

    from simiam.course.weeks import get_week

    with pytest.raises(ValueError, match="week 4: no debug signal is declared with the name 'u_aoo'"):
        replace(get_week(4), debug_signals=("v", "u_aoo"))


def test_events_are_recorded_as_check_event_gave_them_in_this_step():
    from pathlib import Path

    from simiam.control.local_brain import LocalBrain
    from simiam.course.loader import load_submission
    from simiam.course.weeks import get_week

    week = get_week(3)
    sub = load_submission(Path(__file__).parents[2] / "solutions/week3", week)
    brain = LocalBrain(sub, week, {"goal": [0.0, 0.0]})  # at the goal from the start: at_goal is checked
    brain.supervisor.event_values = {"unsafe": True}      # a stale value from an earlier step
    brain.step({"t": 0.033, "dt": 0.033, "ticks": [0, 0], "ir_raw": [200] * 5})
    assert read_signals(brain.supervisor, declared(("at_goal", "unsafe")), 5) == {"at_goal": True,
                                                                                 "unsafe": None}


def test_week7_records_the_sigma_its_sliding_tests_solved() -> None:
    """The week-7 solution's run carries sigma_left (what sliding_left solved) in its trace, beside the
    sliding events: the replay and the report can show why the automaton stayed at a wall."""
    from simiam.control.local_brain import LocalBrain
    from simiam.course.loader import load_submission
    from simiam.course.weeks import get_week
    from simiam.signals import week_signals

    week = get_week(7)
    submission = load_submission(Path(__file__).resolve().parents[2] / "solutions/week7", week)
    brain = LocalBrain(submission, week, week.settings.as_dict())
    sim = Simulator(load_world(week.world), brain, spec=week.spec, dt=week.dt, signals=week_signals(week))
    steps = sim.run(seconds=30.0).steps  # the robot reaches the wall, and follows it, after ~10 s
    sigmas = [s for s in steps["sigma_left"] if s is not None]
    checked = [k for k, flag in enumerate(steps["sliding_left"]) if flag is not None]
    assert sigmas and all(len(s) == 2 for s in sigmas)
    assert checked and steps["sigma_left"][checked[0]] is not None


# --- reading numpy arrays at once (issue 24): the same values as element by element -------------------

def _elementwise_vector2(u):
    """What _read_vector2 returned before its fast path for numpy arrays (kept as the reference)."""
    try:
        values = [signals._maybe(u[i]) for i in range(2)]
    except (TypeError, IndexError, KeyError):
        return None
    got = [v for v in values if v is not None]
    return got if len(got) == 2 else None


def _elementwise_points(p, n):
    try:
        rows = [[signals._maybe(p[r][i]) for i in range(n)] for r in range(2)]
    except (TypeError, IndexError, KeyError):
        return None
    got = [[v for v in row if v is not None] for row in rows]
    return got if all(len(row) == n for row in got) else None


def _arrays():
    rng = np.random.default_rng(24)
    for shape in [(2,), (3,), (1,), (0,), (2, 5), (3, 5), (3, 4), (3, 6), (1, 5), (3, 1)]:
        for kind in ("plain", "nan", "inf", "huge", "float32", "int", "negative zero"):
            a = rng.normal(size=shape)
            if kind in ("nan", "inf") and a.size:
                a.flat[rng.integers(a.size)] = np.nan if kind == "nan" else -np.inf
            a = {"huge": a * 1e308, "float32": a.astype(np.float32), "int": (a * 10).astype(np.int64),
                 "negative zero": a * -0.0}.get(kind, a)
            yield f"{shape} {kind}", a


def _read_differs() -> list[str]:
    differs = []
    with np.errstate(all="ignore"):  # NaN and inf casts and products are the point
        for label, a in _arrays():
            if signals._read_vector2(a, 0) != _elementwise_vector2(a):
                differs.append(f"vector2 {label}")
            for n in (4, 5, 6):
                fast, slow = signals._read_points(a, n), _elementwise_points(a, n)
                if fast != slow or (fast is not None and [[math.copysign(1, v) for v in r] for r in fast]
                                    != [[math.copysign(1, v) for v in r] for r in slow]):
                    differs.append(f"points {label} n={n}")
    return differs


def test_numpy_vectors_and_points_read_as_element_by_element():
    assert _read_differs() == []


def test_the_wrong_version_that_skips_the_finiteness_test_differs(monkeypatch):
    monkeypatch.setattr(signals, "_finite_rows", lambda rows: True)
    differs = _read_differs()
    assert "points (2, 5) nan n=5" in differs and "vector2 (2,) inf" in differs
