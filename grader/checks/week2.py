"""Week 2 checks: uni_to_diff, odometry, IR conversion (week-2 divider), go-to-angle.

Each property judges the student's answers by what they must do (grader.reference: the provided
diff_to_uni, the simulator's encoders, the manual's IR table); the go-to-angle
scenario runs the student's supervisor in the trusted simulator and judges the true heading.
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterator

from grader import reference as ref
from grader import scenarios
from grader.checks import Check, Context, Mismatch, Outcome
from grader.checks.answers import amount, fmt, off_by, vector
from grader.checks.odometry import ODOMETRY_CHECKS
from grader.domains import Floats
from grader.margins import Limit, Margins
from grader.properties import run_property

DRIVE = ("differential_drive.py",)
IR = ("quickbot.py",)

# The reference solution and its correct variants end within 0.0054 rad of theta_d after 8 s (every
# visible angle and 45 hidden ones); a uni_to_diff that turns at half the asked w ends 0.03 rad away.
ANGLE_TOLERANCE = 0.02
HEADING_ERROR = Limit("final heading error", "rad", ANGLE_TOLERANCE, above=False)
ANGLE_PLOTS = ("trajectory", "angle")  # the report: the path, and theta against theta_d
ANGLE_HINT = (
    "Hint: the robot turns with the w GoToAngle asks from your odometry's theta: check that uni_to_diff "
    "really turns at w (its own checks) and that update_odometry's theta follows the wheels"
)

speeds = Floats(-0.3, 0.3)
turns = Floats(-5.0, 5.0)


def _wheels(ctx: Context, v: float, w: float) -> tuple[float, float]:
    answer = ctx.probe("uni_to_diff", v=v, w=w)
    vel_r, vel_l = vector(answer, 2, f"with v = {fmt(v)}, w = {fmt(w)} your uni_to_diff result")
    return vel_r, vel_l


def _close(a: float, b: float, scale: float = 1.0) -> bool:
    return abs(a - b) <= 1e-6 * max(1.0, abs(b), scale)


def _ratio(got: float, asked: float) -> float | None:
    return got / asked if abs(asked) > 1e-9 else None


def _near(a: float | None, b: float) -> bool:
    return a is not None and abs(a - b) <= 1e-6 * max(1.0, abs(b))


def round_trip_hint(v: float, w: float, got_v: float, got_w: float) -> str:
    """What the numbers of one failed round trip show (issue 31): v and w scaled alike point at a factor
    both wheels share (R, the 2 of 2R); only w reversed at the wheels' order; only w doubled or halved at
    L/2 vs L. Otherwise it says how each came out, and guesses nothing."""
    k_v, k_w = _ratio(got_v, v), _ratio(got_w, w)
    if k_v is not None and k_w is not None and _near(k_v, k_w) and not _near(k_v, 1.0):
        return (f"v and w both came out {fmt(k_v)} times the asked: a factor both wheels share is off, "
                "such as R or the 2 of (2v +- wL)/(2R), not which wheel is which")
    v_right = k_v is None and _close(got_v, v) or _near(k_v, 1.0)
    if v_right and _near(k_w, -1.0):
        return "v is right and w reversed: check which wheel is which (vel_r = (2v + wL)/(2R))"
    if v_right and k_w is not None and (_near(k_w, 2.0) or _near(k_w, 0.5)):
        return f"v is right and w came out {fmt(k_w)} times the asked: check L/2 vs L"
    said = [f"{name} came out {fmt(k)} times the asked" if k is not None else f"{name} came out {fmt(got)}"
            for name, k, got in (("v", k_v, got_v), ("w", k_w, got_w))]
    return " and ".join(said) + ": write vel_r and vel_l from the manual's (2v + wL)/(2R) and (2v - wL)/(2R)"


def round_trip(ctx: Context) -> Outcome:
    """The wheels must drive the robot at the (v, w) asked, through the provided diff_to_uni (the
    simulator's own): no expected wheel speeds are needed, and (diff_to_uni being one-to-one) nothing else
    passes."""

    def case(ctx: Context, v: float, w: float) -> None:
        vel_r, vel_l = _wheels(ctx, v, w)
        got_v, got_w = ref.diff_to_uni(ctx.spec, vel_r, vel_l)
        if not (_close(got_v, v) and _close(got_w, w)):
            raise Mismatch(
                f"with v = {fmt(v)}, w = {fmt(w)} your vel_r was {fmt(vel_r)} and vel_l {fmt(vel_l)}: "
                f"these wheels drive the robot at v = {fmt(got_v)}, w = {fmt(got_w)} (diff_to_uni), not at "
                f"the v = {fmt(v)}, w = {fmt(w)} asked ({round_trip_hint(v, w, got_v, got_w)})"
            )

    return run_property(
        ctx,
        "week2.uni_to_diff.round_trip",
        {"v": speeds, "w": turns},
        case,
        examples=[{"v": 0.1, "w": 0.5}, {"v": 0.0, "w": 1.0}],
        passed="diff_to_uni(uni_to_diff(v, w)) gives back (v, w)",
    )


def straight(ctx: Context) -> Outcome:
    def case(ctx: Context, v: float) -> None:
        vel_r, vel_l = _wheels(ctx, v, 0.0)
        if not _close(vel_r, vel_l) or not _close(vel_r, v / ctx.spec.wheel_radius):
            raise Mismatch(
                f"with v = {fmt(v)}, w = 0 your wheels were {fmt(vel_r)} and {fmt(vel_l)}; driving "
                f"straight needs both at v/R = {fmt(v / ctx.spec.wheel_radius)} rad/s"
            )

    return run_property(
        ctx,
        "week2.uni_to_diff.straight",
        {"v": speeds.filter(lambda v: abs(v) > 1e-3)},
        case,
        examples=[{"v": 0.1}],
        passed="w = 0 gives equal wheels",
    )


def spin(ctx: Context) -> Outcome:
    def case(ctx: Context, w: float) -> None:
        vel_r, vel_l = _wheels(ctx, 0.0, w)
        if not _close(vel_r, -vel_l) or abs(vel_r) < 1e-9:
            raise Mismatch(
                f"with v = 0, w = {fmt(w)} your wheels were {fmt(vel_r)} and {fmt(vel_l)}; turning "
                "on the spot needs equal and opposite, non-zero wheel speeds (vel_l = -vel_r): "
                + _spin_fault(vel_r, vel_l)
            )

    return run_property(
        ctx,
        "week2.uni_to_diff.spin",
        {"w": turns.filter(lambda w: abs(w) > 1e-2)},
        case,
        examples=[{"w": 1.0}],
        passed="v = 0 gives opposite wheels",
    )


def _spin_fault(vel_r: float, vel_l: float) -> str:
    """Which part of "equal and opposite, non-zero" the two wheels miss."""
    if abs(vel_r) < 1e-9 and abs(vel_l) < 1e-9:
        return "both are zero"
    if vel_r * vel_l > 0:
        return "both turn the same way"
    if vel_r * vel_l == 0:
        return "one of them is zero"
    return f"they are opposite but not equal (one {fmt(abs(vel_r / vel_l))} times the other)"


def linearity(ctx: Context) -> Outcome:
    def case(ctx: Context, v: float, w: float) -> None:
        unit_v = _wheels(ctx, 1.0, 0.0)
        unit_w = _wheels(ctx, 0.0, 1.0)
        if max(map(abs, unit_v)) < 1e-9 or max(map(abs, unit_w)) < 1e-9:
            raise Mismatch(
                "your uni_to_diff returns zero wheel speeds for v = 1 or for w = 1: is it filled in?"
            )
        got = _wheels(ctx, v, w)
        for i, side in enumerate(("vel_r", "vel_l")):
            expected = v * unit_v[i] + w * unit_w[i]
            if not _close(got[i], expected, 10.0):
                raise Mismatch(
                    f"with v = {fmt(v)}, w = {fmt(w)} your {side} was {fmt(got[i])}, but v times your "
                    f"answer for (1, 0) plus w times your answer for (0, 1) is {fmt(expected)}: "
                    "uni_to_diff must be linear in v and w"
                )

    return run_property(
        ctx,
        "week2.uni_to_diff.linearity",
        {"v": speeds, "w": turns},
        case,
        passed="uni_to_diff is linear in v and w",
    )


def _distances(ctx: Context, raws: list[list[int]]) -> Iterator[list[float]]:
    """get_ir_distances of each set of five raw values, probed in one request, checked one by one."""
    answers = ctx.probe_each("ir_distances", [{"raw": raw} for raw in raws])
    for raw, answer in zip(raws, answers, strict=False):
        yield vector(answer, 5, f"with raw values {raw} your get_ir_distances result")


def ir_table(ctx: Context) -> Outcome:
    """The manual's table (Figure 2b), read through this week's divider, within 5 % or 3 mm."""
    divider = ref.ir_divider(ctx.spec)
    rows = list(ref.IR_TABLE)
    worst = 0.0
    chunks = [rows[start : start + 5] for start in range(0, len(rows), 5)]
    chunks = [chunk + [rows[-1]] * (5 - len(chunk)) for chunk in chunks]
    raws = [[ref.table_raw(ctx.spec, v) for _, v in chunk] for chunk in chunks]
    misses: list[tuple[float, float, int, float]] = []
    for chunk, raw, answer in zip(chunks, raws, _distances(ctx, raws), strict=False):
        for (d, v), r, got in zip(chunk, raw, answer, strict=False):
            err = abs(got - d)
            worst = max(worst, err / d)
            if err > max(0.05 * d, 0.003) and (d, v) not in [m[:2] for m in misses]:
                misses.append((d, v, r, got))
    if misses:
        d, v, r, got = misses[0]
        raise Mismatch(
            f"for raw value {r} (the table's {fmt(v)} V at {fmt(d)} m) your distance was "
            f"{amount(got, 'm', 10.0)}, expected about {fmt(d)} m ({_table_hint(misses, len(rows), divider)})"
        )
    return Outcome(1.0, f"every table row within 5 % (worst {worst:.1%})", {"worst_relative_error": worst})


def _table_hint(misses: list[tuple[float, float, int, float]], rows: int, divider: float) -> str:
    """The divider hint only where the numbers point at the volts (issue 31): when most of the table's rows
    come out right, raw -> volts works (a wrong divider moves every row) and the polynomial misses some."""
    fit = rows - len(misses)
    if fit * 2 > rows:
        at = ", ".join(f"{fmt(v)} V" for _, v, _, _ in misses)
        return (f"{fit} of the {rows} table rows are within 5 %, so your volts are right: the polynomial "
                f"misses at {at}; check coeff, a degree-5 fit with every digit kept")
    return (f"{len(misses)} of the {rows} table rows are off: check that you divide by {fmt(divider)} to get "
            "volts, then that coeff is the table's degree-5 fit")


def ir_simulator(ctx: Context) -> Outcome:
    """The simulator's own readings at distances 4..30 cm (and some drawn from the seed), within 8 %."""
    import random

    rng = random.Random(ctx.seed)
    distances = [0.04 + 0.005 * i for i in range(53)] + [rng.uniform(0.04, 0.3) for _ in range(7)]
    worst, at = 0.0, None
    chunks = [distances[start : start + 5] for start in range(0, len(distances), 5)]
    raws = [[ref.ir_raw(ctx.spec, d) for d in chunk] for chunk in chunks]
    for chunk, raw, answer in zip(chunks, raws, _distances(ctx, raws), strict=False):
        for d, r, got in zip(chunk, raw, answer, strict=False):
            rel = abs(got - d) / d
            if rel > worst:
                worst, at = rel, (d, r, got)
            if rel > 0.08:
                raise Mismatch(
                    f"an obstacle {fmt(d)} m away reads {r}; your distance was {amount(got, 'm', 10.0)}"
                    + (f", {off_by(rel)}" if abs(got) <= 10.0 else "") + " (at most 8 % off expected)"
                )
    return Outcome(
        1.0,
        f"{len(distances)} readings within 8 % (worst {worst:.1%})",
        {"worst_relative_error": worst, "worst_at": at},
    )


def go_to_angle_check(hidden: bool):
    """Week 2: go-to-angle turns the TRUE heading to theta_d (within ANGLE_TOLERANCE after the week's
    run length, 8 s; no collision), at the week's v."""

    def go_to_angle(ctx: Context) -> Outcome:
        if hidden:
            rng = random.Random(f"{ctx.seed}:go_to_angle")
            angles = [rng.choice((-1, 1)) * rng.uniform(0.3, 2.8) for _ in range(3)]
        else:
            angles = [math.pi / 4, -2.0]
        good, lines, runs, margins = 0, [], [], Margins()
        details: dict[str, list] = {"runs": []}
        for theta_d in angles:
            settings = ctx.config.settings.with_changes(theta_d=theta_d).as_dict()
            r = scenarios.run(ctx, f"theta_d = {theta_d:.3f}", settings, ctx.config.seconds)
            runs.append(r)
            scenarios.keep(ctx, "week2.go_to_angle." + ("other_angles" if hidden else "reaches_theta_d"), r)
            err = ref.angle_diff(r.final_pose[2], theta_d)
            scenarios.add_margins(margins, r)
            if not r.problem:
                margins.add(HEADING_ERROR, err, r.label)
            ok = not r.problem and r.collision is None and err <= ANGLE_TOLERANCE
            good += ok
            why = r.problem or (
                f"it collided at t = {r.collision['t']:.2f} s"
                if r.collision
                else f"the true heading ended {err:.3f} rad away (at most {ANGLE_TOLERANCE:g} rad)"
            )
            lines.append(f"theta_d = {theta_d:.2f}: " + ("reached" if ok else why))
            details["runs"].append(
                {"theta_d": theta_d, "heading_error": err, **r.metrics, "problem": r.problem}
            )
        missed = good < len(angles) and not any(r.problem for r in runs)
        return Outcome(
            good / len(angles),
            "; ".join(lines) + (f". {ANGLE_HINT}" if missed else ""),
            {**details, "traces": scenarios.trace_keys(runs), "margins": margins.to_json()},
            status=scenarios.status_of(runs),
        )

    return go_to_angle


CHECKS = [
    Check(
        "week2.uni_to_diff.round_trip",
        "uni_to_diff: the wheels drive the robot at (v, w)",
        "property",
        1.5,
        round_trip,
        DRIVE,
    ),
    Check(
        "week2.uni_to_diff.straight", "uni_to_diff: w = 0 drives straight", "property", 0.5, straight, DRIVE
    ),
    Check("week2.uni_to_diff.spin", "uni_to_diff: v = 0 turns on the spot", "property", 0.5, spin, DRIVE),
    Check("week2.uni_to_diff.linearity", "uni_to_diff: linear in v and w", "property", 0.5, linearity, DRIVE),
    *ODOMETRY_CHECKS,
    Check("week2.ir.table", "IR: the manual's table (week-2 divider)", "property", 1.0, ir_table, IR),
    Check(
        "week2.ir.simulator",
        "IR: the simulator's readings from 4 to 30 cm",
        "property",
        1.0,
        ir_simulator,
        IR,
    ),
    Check(
        "week2.go_to_angle.reaches_theta_d",
        "go-to-angle reaches theta_d",
        "scenario",
        1.5,
        go_to_angle_check(hidden=False),
        ("differential_drive.py", "quickbot.py", "go_to_angle.py", "qb_supervisor.py"),
        plots=ANGLE_PLOTS,
    ),
    Check(
        "week2.go_to_angle.other_angles",
        "go-to-angle reaches angles drawn per seed",
        "scenario",
        1.0,
        go_to_angle_check(hidden=True),
        ("differential_drive.py", "quickbot.py", "go_to_angle.py", "qb_supervisor.py"),
        visibility="hidden",
        plots=ANGLE_PLOTS,
    ),
]
