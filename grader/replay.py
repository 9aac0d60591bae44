"""What `grade weekN --check ID --case ...` shows besides the verdict, to debug one failing case.

The traceback of the student's own code (only frames in their files), what their code printed, and a
short Python snippet that calls their function with exactly the failing inputs, to paste into a Python
prompt or a file next to their folder. The snippet mirrors what the probe did in the worker
(grader/inside/probes_weekN.py) with the public simiam API a student has installed.
"""

from __future__ import annotations

import json
import sys
from typing import Any, TextIO

from grader.sandbox.errors import StudentError
from grader.untrusted import printable

_HEAD = """from simiam.control import Pose2D, RobotView
from simiam.control.controller import Inputs
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week

sub = load_submission({folder!r}, {week})
robot = RobotView(get_week({week}).spec, sub)
"""


def traceback_text(exc: StudentError) -> str:
    """The traceback through the student's files, as Python prints one (innermost call last)."""
    lines = ["Traceback (your code, most recent call last):"]
    for f in exc.frames:
        lines.append(f'  File "{f["file"]}", line {f["line"]}, in {f["function"]}')
        if f["code"]:
            lines.append(f"    {f['code']}")
    lines.append(f"{exc.type_name}: {exc.message}" if exc.type_name else exc.message)
    return "\n".join(lines)


def _value(x: Any) -> str:
    return json.dumps(x)


def _body(name: str, args: dict[str, Any]) -> str | None:
    """The lines after _HEAD that repeat probe `name` with `args` (None for a probe it does not know)."""
    if name == "uni_to_diff":
        return f"print(sub.module('differential_drive').uni_to_diff(robot, {args['v']!r}, {args['w']!r}))\n"
    if name == "ensure_w":
        return (
            "sup = sub.module('qb_supervisor').QBSupervisor()\n"
            "sup.attach_robot(robot, Pose2D(0.0, 0.0, 0.0))\n"
            f"print(sup.ensure_w(robot, {args['v']!r}, {args['w']!r}))\n"
        )
    if name == "odometry":
        return (
            "sup = sub.module('qb_supervisor').QBSupervisor()\n"
            f"sup.attach_robot(robot, Pose2D(*{_value(args.get('start', [0.0, 0.0, 0.0]))}))\n"
            f"for right, left in {_value(args['ticks'])}:  # cumulative encoder ticks\n"
            "    robot.encoders[0].ticks, robot.encoders[1].ticks = right, left\n"
            "    sup.update_odometry()\n"
            "    print(sup.state_estimate.unpack())\n"
        )
    if name == "ir_distances":
        return (
            f"for sensor, raw in zip(robot.ir_array, {_value(args['raw'])}):\n"
            "    sensor._raw = raw  # what the IR sensor reads\n"
            "print(robot.get_ir_distances())\n"
        )
    if name == "go_to_goal":
        lines = []
        for k, call in enumerate(args["calls"]):
            if k == 0 or args.get("fresh"):
                lines.append("ctrl = sub.module('go_to_goal').GoToGoal()")
                lines += [f"ctrl.{g} = {v!r}" for g, v in args["gains"].items()]
            lines += [f"ctrl.{m} = {v!r}" for m, v in (call.get("memory") or {}).items()]
            x_g, y_g = call["goal"]
            lines.append(
                f"print(ctrl.execute(robot, Pose2D(*{_value(call['pose'])}), "
                f"Inputs(v={call['v']!r}, x_g={x_g!r}, y_g={y_g!r}, theta_d=0.0), {call['dt']!r}))"
            )
        return "\n".join(lines) + "\n"
    if name == "transformation_matrix":
        return (
            "ctrl = sub.module('avoid_obstacles').AvoidObstacles()\n"
            f"print(ctrl.get_transformation_matrix({args['x']!r}, {args['y']!r}, {args['theta']!r}))\n"
        )
    if name == "sensor_geometry":
        return (
            "ctrl = sub.module('avoid_obstacles').AvoidObstacles()\n"
            f"print(ctrl.apply_sensor_geometry(robot, {_value(args['distances'])}, "
            f"Pose2D(*{_value(args['pose'])})))\n"
        )
    if name == "avoid_obstacles":
        return (
            "ctrl = sub.module('avoid_obstacles').AvoidObstacles()\n"
            f"robot.get_ir_distances = lambda: {_value(args['distances'])}\n"
            f"print(ctrl.execute(robot, Pose2D(*{_value(args['pose'])}), "
            f"Inputs(v={args.get('v', 0.2)!r}, x_g=0.0, y_g=0.0, theta_d=0.0), {args.get('dt', 0.033)!r}))\n"
            "print('u_ao =', ctrl.u_ao)\n"
        )
    if name == "blend":  # week 5: AOandGTG with the u_ao the grader chose (its AvoidObstacles stood in for)
        lines = ["class GivenAvoid:  # hands AOandGTG the u_ao of the failing case",
                 "    def __init__(self, u_ao):",
                 "        self.u_ao, self.ir_distances_wf = u_ao, None",
                 "    def execute(self, robot, state_estimate, inputs, dt):",
                 "        return inputs.v, 0.0"]
        for call in args["calls"]:
            x_g, y_g = call["goal"]
            lines += ["ctrl = sub.module('ao_and_gtg').AOandGTG()",
                      f"ctrl.avoid = GivenAvoid({_value(call['u_ao'])})",
                      f"ctrl.execute(robot, Pose2D(*{_value(call['pose'])}), "
                      f"Inputs(v=0.15, x_g={x_g!r}, y_g={y_g!r}, theta_d=0.0), 0.05)",
                      "print('u_gtg =', ctrl.u_gtg, 'u_ao =', ctrl.u_ao, 'u_ao_gtg =', ctrl.u_ao_gtg)"]
        return "\n".join(lines) + "\n"
    if name == "switching":  # week 5: one step of the switching from a state, with chosen IR distances
        lines = []
        for case in args["cases"]:
            goal = (0.0, 0.0) if case["at_goal"] else (1.0, 0.0)
            lines += [f"robot.get_ir_distances = lambda: {_value(case['distances'])}",
                      "sup = sub.module('qb_supervisor').QBSupervisor()",
                      "sup.attach_robot(robot, Pose2D(0.0, 0.0, 0.0))",
                      f"sup.is_blending = False\nsup.goal = {goal!r}",
                      f"sup.switch_to_state({case['state']!r})",
                      "sup.execute(0.05)",
                      "print('state after one step:', sup.current_state)"]
        return "\n".join(lines) + "\n"
    if name == "follow_wall":
        return (
            "ctrl = sub.module('follow_wall').FollowWall()\n"
            f"robot.get_ir_distances = lambda: {_value(args['distances'])}\n"
            f"inputs = Inputs(v={args.get('v', 0.15)!r}, direction={args['direction']!r}, "
            f"d_fw={args['d_fw']!r})\n"
            f"print(ctrl.execute(robot, Pose2D(*{_value(args['pose'])}), inputs, {args.get('dt', 0.05)!r}))\n"
            "for name in ('p_1', 'p_2', 'u_fw_t', 'u_fw_tp', 'u_fw_p', 'u_fw_pp', 'u_fw'):\n"
            "    print(name, '=', getattr(ctrl, name))\n"
        )
    if name == "wall_settings":
        return (
            "sup = sub.module('qb_supervisor').QBSupervisor()\n"
            "print('d_fw =', sup.d_fw, ' fw_direction =', repr(sup.fw_direction))\n"
        )
    return _week7_body(name, args)


def _week7_body(name: str, args: dict[str, Any]) -> str | None:
    """Week 7's probes (grader/inside/probes_week7.py) as Python a student can run."""
    head = ["import numpy as np",
            "sup = sub.module('qb_supervisor').QBSupervisor()",
            f"sup.attach_robot(robot, Pose2D(*{_value(args.get('estimate') or [0.0, 0.0, 0.0])}))"]
    if name == "week7_sliding":
        vectors = ", ".join(f"np.array({_value(args[k])})" for k in ("u_gtg", "u_ao", "u_fw"))
        return "\n".join(head + [
            f"sup.sliding_vectors = lambda side: ({vectors})  # u_gtg, u_ao, u_fw of the failing case",
            f"print('sliding:', sup.check_event({'sliding_' + args['direction']!r}), "
            f"'sigma:', sup.sigma_{args['direction']})"]) + "\n"
    if name in ("week7_progress", "week7_progress_point"):
        call = ("print('progress_made:', sup.check_event('progress_made'))" if name == "week7_progress"
                else "sup.set_progress_point()\nprint('d_prog:', sup.d_prog)")
        return "\n".join(head + [f"sup.goal = tuple({_value(args['goal'])})",
                                  f"sup.d_prog = {args['d_prog']!r}", call]) + "\n"
    if name == "week7_step":
        events = {k: bool(v) for k, v in args["events"].items()}
        return "\n".join(head + [
            f"robot.get_ir_distances = lambda: np.array({_value(args['distances'])})",
            f"sup.switch_to_state({args['state']!r})",
            f"sup.fw_direction = {args['fw_direction']!r}",
            f"events = {events!r}  # what each check_event(name) answers",
            "sup.events = {name: (lambda value=value: value) for name, value in events.items()}",
            f"sup.execute({args.get('dt', 0.05)!r})",
            "print('state after one step:', sup.current_state, 'fw_direction:', repr(sup.fw_direction))",
        ]) + "\n"
    return None


def snippet(folder: str, probe: tuple[str, dict[str, Any]] | None) -> str | None:
    """Python that calls the student's function as the last probe did, or None."""
    if probe is None:
        return None
    name, args = probe
    args = dict(args)
    week = args.pop("week", None)
    try:
        body = _body(name, args)
    except (KeyError, TypeError, ValueError):  # a probe called in a way this module does not know
        return None
    return None if body is None or week is None else _HEAD.format(folder=folder, week=week) + body


def print_replay(result: dict, out: TextIO | None = None) -> None:
    """After a replayed case: what the student's code printed, its traceback and the snippet."""
    out = out or sys.stdout
    printed = printable(str(result.get("student_output") or "").strip())
    if printed:
        print("\nyour code printed:", file=out)
        print("\n".join("  | " + line for line in printed.splitlines()), file=out)
    for c in result.get("checks", []):
        details = c.get("details") or {}
        if details.get("traceback"):
            print(f"\n{printable(str(details['traceback']))}", file=out)
        if details.get("snippet"):
            print("\nto try this case yourself, run this Python next to your folder:\n", file=out)
            print(details["snippet"], file=out)
