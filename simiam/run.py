"""`simiam run weekN [PATH | --solutions]`: a student's own local run of the week's scenario.

Loads the code in this process (trusted: it is the student's own machine), runs the week's scenario
headless, writes the trace (CSV and JSON) and the replay page, and prints a short summary. A submission
that does not load prints its LoadErrors (file:line: message) and exits 1; an exception inside the
student's code during the run is reported the same way, after writing the trace up to that step, and so is
a step that runs longer than grade allows (an endless loop: where it was running, as grade says it). Edits
outside the code blocks are run here but not by grade: they are listed as warnings first, and so are
settings the supervisor sets under a misspelt name (set, never read: the run keeps the default).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import re
import shutil
import sys
import tempfile
from pathlib import Path

from simiam import numerics
from simiam.control.local_brain import LocalBrain
from simiam.control.supervisor import Supervisor
from simiam.course.folders import WeekFolderNotFound, week_folder
from simiam.course.loader import load_submission, locate_in_folder
from simiam.course.week import Week
from simiam.course.weeks import get_week
from simiam.laps import Gate, count_laps
from simiam.run_limit import LimitedBrain, StepTimeout, step_limit, stuck_at
from simiam.signals import week_signals
from simiam.simulator import Simulator
from simiam.trace import BROKEN, Ending, EndReason, Trace
from simiam.world import World, WorldFileError, load_world

MAX_STEPS = 1_000_000  # 9 simulated hours at 0.033 s; a trace of that size is already ~1 GB in memory
STEP_SECONDS = 2.0  # wall time one step of the student's code may take (grade's limit per call)


def resolve_folder(week: Week, path: str | None, solutions: bool) -> Path:
    """The submission folder: PATH, or the checkout's solutions/weekN, or the default rule shared with
    `grade` and `simiam migrate` (simiam.course.folders: this folder if named weekN, ./weekN,
    ./assignments/weekN). Raises WeekFolderNotFound with a message for the student."""
    return week_folder(week.number, path, solutions=solutions)


def _fail(message: str, code: int) -> int:
    print(message, file=sys.stderr)
    return code


def main(args: argparse.Namespace) -> int:
    """Run `simiam run` with parsed arguments (week, path, solutions, seconds, dt, out, world)."""
    try:
        week = get_week(args.week)
    except ValueError as exc:
        return _fail(f"simiam run: {exc}", 2)
    if args.path and args.solutions:
        return _fail("simiam run: give either a folder or --solutions, not both", 2)
    dt = week.dt if getattr(args, "dt", None) is None else args.dt
    if not (math.isfinite(dt) and dt > 0):
        return _fail(f"simiam run: --dt must be a positive number of seconds, got {dt}", 2)
    args.dt = dt
    seconds = week.seconds if args.seconds is None else args.seconds  # the length grade's scenario runs
    if not (math.isfinite(seconds) and seconds > 0):
        return _fail(f"simiam run: --seconds must be positive, got {seconds}", 2)
    steps = seconds / args.dt
    if steps > MAX_STEPS:
        return _fail(f"simiam run: {seconds:g} s at dt = {args.dt:g} s is {steps:.3g} steps; "
                     f"at most {MAX_STEPS:,} (the trace keeps every step in memory)", 2)
    try:
        folder = resolve_folder(week, args.path, args.solutions)
    except WeekFolderNotFound as exc:
        return _fail(f"simiam run: {exc} (simiam run {week.name} PATH)", 2)
    if not folder.is_dir():
        return _fail(f"simiam run: no such folder: {folder}", 2)
    try:
        world = load_world(args.world or week.world)
    except (WorldFileError, OSError) as exc:
        return _fail(f"simiam run: cannot read the world: {exc}", 2)
    if getattr(args, "start", None) is not None:
        try:
            start = parse_start(args.start)
        except ValueError as exc:
            return _fail(f"simiam run: --start {args.start!r}: {exc}", 2)
        world = dataclasses.replace(world, starts=[start, *world.starts[1:]])  # the world as read stays

    for note in outside_edit_notes(week, folder) + misspelt_setting_notes(folder):
        print(f"warning: {note}", file=sys.stderr)
    with tempfile.TemporaryDirectory(prefix="simiam-run-") as tmp:
        run_folder, notes = fill_missing_files(week, folder, Path(tmp))
        for note in notes:
            print(f"warning: {note}", file=sys.stderr)
        return _run(args, week, folder, run_folder, world, seconds)


START_LIMIT = 100.0  # m: a start pose farther out than any course world is a typing slip, not a run


def parse_start(text: str) -> tuple[float, float, float]:
    """`X,Y,THETA` as the robot's start pose (metres, radians). THETA may use pi: `pi`, `-pi/2`, `0.5*pi`,
    `3pi/4`. ValueError says what is wrong."""
    parts = [p.strip() for p in text.split(",")]
    if len(parts) != 3:
        raise ValueError(f"give three numbers X,Y,THETA separated by commas (got {len(parts)})")
    x, y = (_number(p, name) for p, name in zip(parts[:2], ("X", "Y"), strict=True))
    theta = _angle(parts[2])
    for name, value in (("X", x), ("Y", y)):
        if abs(value) > START_LIMIT:
            raise ValueError(f"{name} = {value:g} m is outside any course world (at most {START_LIMIT:g} m)")
    if abs(theta) > 100 * math.pi:
        raise ValueError(f"THETA = {theta:g} rad: give a heading between -pi and pi")
    return x, y, theta


def _number(text: str, name: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"{name} must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {text!r}")
    return value


_PI = re.compile(r"^([+-]?)(\d+(?:\.\d*)?|\.\d+)?\s*\*?\s*pi\s*(?:/\s*(\d+(?:\.\d*)?))?$")


def _angle(text: str) -> float:
    """THETA in radians: a number, or a multiple of pi as people write it (pi, -pi/2, 0.5*pi, 3pi/4)."""
    found = _PI.match(text.strip().lower())
    if not found:
        return _number(text, "THETA")
    sign, factor, divisor = found.groups()
    below = float(divisor) if divisor else 1.0
    value = (float(factor) if factor else 1.0) * math.pi / below if below else math.inf
    if not math.isfinite(value):
        raise ValueError(f"THETA must be a finite angle, got {text!r}")
    return -value if sign == "-" else value


def fill_missing_files(week: Week, folder: Path, tmp: Path) -> tuple[Path, list[str]]:
    """`folder`, or a copy of it under `tmp` with the files the student writes nothing in this week filled
    in where they are missing, as `grade` does; and what to tell the student about each."""
    from simiam.course.shipped import files_to_write, missing_note, shipped_version
    from simiam.course.skeletons import SkeletonsMissing, skeleton_files

    try:
        skeletons = skeleton_files(week.number)
    except SkeletonsMissing:
        return folder, []
    missing = [name for name in sorted(skeletons)
               if name not in files_to_write(week.number) and not (folder / name).exists()]
    if not missing:
        return folder, []
    copy = tmp / folder.name
    shutil.copytree(folder, copy, ignore=shutil.ignore_patterns("__pycache__"))
    notes = []
    for name in missing:
        shipped = shipped_version(week.number, name)
        (copy / name).write_text(shipped if shipped is not None else skeletons[name], encoding="utf-8")
        notes.append(missing_note(week.number, name, shipped is not None))
    return copy, notes


def _run(args: argparse.Namespace, week: Week, folder: Path, run_folder: Path, world, seconds: float
         ) -> int:
    """The run itself, on `run_folder` (the student's folder, or its copy with missing files filled in);
    messages name the student's own `folder`."""
    sub = load_submission(run_folder, week)
    if not sub.ok:
        print(f"Your {week.name} code in {folder} could not be loaded:", file=sys.stderr)
        for err in sub.errors:
            print(f"  {err}", file=sys.stderr)
        return 1

    start = world.start
    try:
        with step_limit(STEP_SECONDS):
            brain = LocalBrain(sub, week, start=start)
        sim = Simulator(world, LimitedBrain(brain, STEP_SECONDS), week.spec, dt=args.dt, start=start,
                        signals=week_signals(week))
    except StepTimeout as exc:
        return _fail(_stuck(exc, run_folder, "while setting up the supervisor"), 1)
    except BaseException as exc:  # noqa: BLE001 - the student's __init__ may raise anything, sys.exit too
        if isinstance(exc, KeyboardInterrupt):
            raise
        return _fail(_student_error(exc, run_folder, "while setting up the supervisor"), 1)

    sup = brain.supervisor
    driving = sup.current_state in ("go_to_goal", "ao_and_gtg")  # states that drive to the goal (weeks 3, 5)
    goal = [float(sup.goal[0]), float(sup.goal[1])] if driving else None
    trace = sim.run(seconds, stuck=(StepTimeout,))
    trace.goal = goal or trace.goal
    # which BLAS kernel and SIMD level ran it: official grading's, or one that can differ in the last digits
    trace.meta = {"submission": str(folder), "source": "simiam run", "numerics": numerics.describe()}
    assert trace.ending is not None  # run() always says how it ended
    error = _ending_words(trace.ending, folder, run_folder)

    if error:  # first: what broke the run is what to fix; the summary below only describes the remains
        print(error, file=sys.stderr)
        print(file=sys.stderr)
        sys.stderr.flush()
    out = Path(args.out)
    try:  # never through a link (simiam.safe_write): LinkRefused is an OSError that names the link
        csv_path, json_path = trace.write(out, stem=week.name)
        replay = _write_replay(trace.to_json(), out / f"{week.name}.html")
    except OSError as exc:
        return _fail(f"simiam run: cannot write the trace into {out}: {exc.strerror or exc}", 2)
    print(f"trace: {csv_path}")
    print(f"trace: {json_path}")
    if replay is not None:
        print(f"replay: {replay}")
    print()
    print(summary(week, folder, trace, sup, gate=lap_gate(week, world)))
    if trace.meta["numerics"]["note"]:
        print(f"numerics: {trace.meta['numerics']['note']}")
    return 1 if error else 0


def _ending_words(ending: Ending, folder: Path, run_folder: Path) -> str | None:
    """What to tell the student when their code broke the run (None when it did not)."""
    when = f"at t = {ending.t:.3f} s"
    if ending.reason is EndReason.INVALID_COMMAND:
        return f"{folder.name}: your code returned an invalid command {when}: {ending.message}"
    if ending.reason is EndReason.STUCK and isinstance(ending.error, StepTimeout):
        return _stuck(ending.error, run_folder, when)
    if ending.reason is EndReason.BRAIN_ERROR and ending.error is not None:
        return _student_error(ending.error, run_folder, when)
    return None


def _student_error(exc: BaseException, folder: Path, when: str) -> str:
    file, line = locate_in_folder(exc, folder)
    where = f"{file}:{line}: " if file else ""
    if isinstance(exc, SystemExit):
        return f"{where}your code called sys.exit({exc.code if exc.code is not None else ''}) ({when})"
    text = str(exc)
    return f"{where}{type(exc).__name__}{': ' + text if text else ''} ({when})"


def _stuck(exc: StepTimeout, folder: Path, when: str) -> str:
    """The message `grade` gives for an endless loop: the time limit and where the code was running."""
    why = (f"your code did not answer in time: no answer within {STEP_SECONDS:g} s, the time limit per "
           f"step ({when})")
    where = stuck_at(exc, folder)
    return f"{why}; it was still running at {where} (an endless loop or a long wait?)" if where else why


def outside_edit_notes(week: Week, folder: Path) -> list[str]:
    """The edits outside the code blocks, as `grade` lists them (against the same packaged skeletons):
    `simiam run` runs them, `grade` does not."""
    from simiam.course.blocks import BlockError
    from simiam.course.skeletons import SkeletonsMissing, skeleton_files
    from simiam.course.splice import splice

    try:
        skeletons = skeleton_files(week.number)
    except SkeletonsMissing:
        return []
    notes = []
    for name, stub in skeletons.items():
        if not (folder / name).is_file():
            continue
        try:
            result = splice(stub, (folder / name).read_text(encoding="utf-8", errors="replace"), name)
        except BlockError:  # broken markers: grade says so; the run itself uses the whole file
            continue
        notes += [f"{edit} (simiam run ran this edit, but grade runs only the code blocks)"
                  for edit in result.outside_edits]
    return notes


def misspelt_setting_notes(folder: Path) -> list[str]:
    """Settings the student's QBSupervisor sets under a misspelt name (simiam.course.misspelt_settings):
    set and never read, they leave the run on the default value."""
    from simiam.course.misspelt_settings import misspelt_settings

    path = folder / "qb_supervisor.py"
    if not path.is_file():
        return []
    return [f"{note} (this run uses the simulator's default for it)"
            for note in misspelt_settings(path.read_text(encoding="utf-8", errors="replace"), path.name)]


def _write_replay(trace_json: dict, path: Path) -> Path | None:
    try:
        from simiam.viewer.replay import write_replay
    except ImportError:
        return None
    return write_replay(trace_json, path)


def lap_gate(week: Week, world: World) -> Gate | None:
    """The week's lap gate for a run in the week's own world (`--world` a copy of it too); None otherwise:
    a gate placed for one world says nothing about laps in another."""
    if week.lap_gate is None:
        return None
    try:
        own = load_world(week.world)
    except (WorldFileError, OSError):
        return None
    return week.lap_gate if world.obstacles == own.obstacles else None


def summary(week: Week, folder: Path, trace: Trace, sup: Supervisor, gate: Gate | None = None) -> str:
    """One paragraph: final pose, estimate, collision, then the goal (a run with one), the heading
    (a week whose `summary` names it) or the distance driven; then, with a lap `gate` (a week that
    declares one, in its world), the laps through it (counted as `grade` counts them, in whichever
    direction the robot went round)."""
    s = trace.steps
    n = len(trace) - 1
    x, y, theta = s["x"][-1], s["y"][-1], s["theta"][-1]
    wrapped = math.atan2(math.sin(theta), math.cos(theta))
    parts = [f"Week {week.number} with {folder}: {trace.seconds:.2f} s simulated, {n} steps of {trace.dt} s."]
    parts.append(f"Final true pose (x, y, theta) = ({x:.3f}, {y:.3f}, {wrapped:.3f}).")
    est = (s["x_est"][-1], s["y_est"][-1], s["theta_est"][-1])
    if None not in est:
        err = math.hypot(est[0] - x, est[1] - y)
        parts.append(f"Estimate = ({est[0]:.3f}, {est[1]:.3f}, {est[2]:.3f}), "
                     f"{err:.3f} m from the true position.")
    if trace.collision:
        c = trace.collision
        parts.append(f"COLLISION at t = {c['t']:.3f} s at ({c['pose'][0]:.3f}, {c['pose'][1]:.3f}).")
    else:
        parts.append("No collision.")
    if trace.goal is not None and "goal" in week.summary:
        gx, gy = trace.goal[0], trace.goal[1]
        d = math.hypot(x - gx, y - gy)
        # Reached as grade judges it: the TRUE position came within d_stop at some step. The robot stops
        # by its estimate, so where it stands at the end can be a little farther (or nearer); four
        # decimals, so that "not reached, 0.050 m" never sits beside "reached, 0.050 m" (issue 21).
        closest = min(math.hypot(px - gx, py - gy) for px, py in zip(s["x"], s["y"], strict=True))
        stopped = [t for t, st in zip(s["t"], s["state"], strict=True) if st == "stop"]
        ending = trace.ending
        when = (f"stopped at t = {stopped[0]:.2f} s" if stopped
                else f"was stopped by your code's error at t = {ending.t:.2f} s (printed first)"
                if ending is not None and ending.reason in BROKEN else "never stopped")
        by_estimate = ""
        if stopped and None not in est:
            by_estimate = (f" (its estimate {math.hypot(est[0] - gx, est[1] - gy):.4f} m from it: the robot "
                           "stops by its estimate)")
        reached = "reached" if closest < sup.d_stop else "not reached"
        parts.append(f"Goal ({gx:g}, {gy:g}) {reached}: the TRUE position came within {closest:.4f} m of it "
                     f"(d_stop = {sup.d_stop:g}); the robot {when}, {d:.4f} m from it{by_estimate}.")
    elif "heading" in week.summary:
        err = math.atan2(math.sin(sup.theta_d - theta), math.cos(sup.theta_d - theta))
        parts.append(f"Heading error to theta_d = {sup.theta_d:.3f}: {err:+.3f} rad.")
    else:
        path = sum(math.hypot(s["x"][k + 1] - s["x"][k], s["y"][k + 1] - s["y"][k]) for k in range(n))
        parts.append(f"Distance driven: {path:.2f} m.")
    if "switches" in week.summary:
        # what grade counts (several in one step too), so the README's figures can be checked here
        seen = getattr(sup, "switches_seen", None)
        if isinstance(seen, int):
            rate = seen / trace.seconds if trace.seconds > 0 else 0.0
            parts.append(f"Switches: {seen} ({rate:.1f} per second).")
    if gate is not None:
        parts.append(count_laps(s["x"], s["y"], s["t"], gate).words())
    return " ".join(parts)
