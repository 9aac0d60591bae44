"""The trusted step loop: one QuickBot in a World, driven by a Brain (docs/design.md, Seam 1).

Step order (weeks 2-4, the original's `Simulator.step`):
  (a) move the true pose with the wheel speeds applied last step (exact arc), then the encoders with
      those same limited speeds;
  (b) `brain.step(readings)` with the new ticks and the IR values computed at the end of the previous step;
  (c) `limit_speeds` on the command, stored for the next move;
  (d) physics: collision check; only if there is no collision, recompute the IR ranges.
One IR update runs at construction, so step 1 sees the start pose. Week 1 runs the brain before the move
(its supervisor never moves the robot anyway).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

from simiam.brain import Brain, BrainError, Command, ConstantBrain, Readings, validate_command
from simiam.physics.robot_surfaces import RobotSurfaces
from simiam.physics.segments import ObstacleEdges
from simiam.physics.transform import transform_fast
from simiam.robot.dynamics import move
from simiam.robot.quickbot import RobotSpec, limit_speeds
from simiam.robot.wheel_encoder import WheelEncoder
from simiam.signals import WEEKS_1_TO_4, debug_plan, declared, headers
from simiam.trace import Ending, EndReason, Trace
from simiam.world.world import World

__all__ = ["Brain", "BrainError", "Command", "ConstantBrain", "Ending", "EndReason", "Readings", "Simulator",
           "StepRecord", "add_row", "run_steps", "validate_command"]

Pose = tuple[float, float, float]
_new_tuple = tuple.__new__


class StepRecord(NamedTuple):
    """The state after one step. `vel_r`/`vel_l` are the limited wheel speeds set at this step (they move
    the robot during the next step); `ir_raw`/`ir_range` are the values at the end of this step.
    Immutable; a NamedTuple rather than a frozen dataclass, whose construction took a sixth of a step."""

    step: int
    t: float
    pose: Pose
    ticks: tuple[int, int]
    ir_raw: tuple[int, ...]
    ir_range: tuple[float, ...]
    vel_r: float
    vel_l: float
    command: Command | None
    collided: bool


class Simulator:
    """One QuickBot in `world`, stepped at a fixed dt and driven by `brain`.

    `signals` names the debug signals the brain reports (simiam.signals; default: weeks 1-4's). The IR
    sensors are the spec's `ir_mounts`, however many.

    >>> sim = Simulator(load_world("week3"), ConstantBrain(5, 5), spec_for_week(3))
    >>> rec = sim.step(); trace = sim.run(seconds=10); trace.ending.reason
    """

    def __init__(self, world: World, brain: Brain, spec: RobotSpec, dt: float = 0.033,
                 start: Pose | None = None, signals: Sequence[str] = WEEKS_1_TO_4) -> None:
        if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a positive number of seconds, got {dt!r}")
        self.signals = declared(signals)
        self._n_ir = len(spec.ir_mounts)
        self._plan = debug_plan(self.signals, self._n_ir)
        self._brain_exception: BaseException | None = None  # what the brain itself raised, for run()
        self.world = world
        self.brain = brain
        self.spec = spec
        self.dt = float(dt)
        start = world.start if start is None else start
        self.start: Pose = (float(start[0]), float(start[1]), float(start[2]))
        self._x, self._y, self._theta = self.start
        self._enc_r = WheelEncoder(spec.ticks_per_rev)
        self._enc_l = WheelEncoder(spec.ticks_per_rev)
        self._vel_r = 0.0
        self._vel_l = 0.0
        self._k = 0
        self._collided = False
        self._first_collision: dict | None = None
        self._surfaces = RobotSurfaces(spec, world.obstacles)
        # what every step reads of the spec, looked up once
        self._wheels = (spec.wheel_radius, spec.wheel_base_length)
        self._brain_first = spec.brain_first
        self._limits = (spec.max_vel, spec.min_vel)
        # the IR values are tuples (RobotSurfaces.sense's): records and properties share them uncopied
        self._ir_range: tuple[float, ...] = (spec.ir_max_range,) * self._n_ir
        self._ir_raw: tuple[int, ...] = (0,) * self._n_ir
        self._update_ir()
        self._last: StepRecord = self._record(None)

    # --- read-only views of the true state (never handed to student code) ---
    @property
    def pose(self) -> Pose:
        """The true pose (x, y, theta); theta is never wrapped."""
        return (self._x, self._y, self._theta)

    @property
    def ticks(self) -> tuple[int, int]:
        """Cumulative encoder ticks (right, left)."""
        return (self._enc_r.ticks, self._enc_l.ticks)

    @property
    def ir_raw(self) -> tuple[int, ...]:
        """The raw IR values (one per sensor) computed at the end of the last step."""
        return self._ir_raw

    @property
    def ir_range(self) -> tuple[float, ...]:
        """The true IR ranges (m) behind `ir_raw`."""
        return self._ir_range

    @property
    def wheel_speeds(self) -> tuple[float, float]:
        """The limited wheel speeds (right, left) that the next step applies."""
        return (self._vel_r, self._vel_l)

    @property
    def collided(self) -> bool:
        """Whether the last step ended in a collision."""
        return self._collided

    @property
    def first_collision(self) -> dict | None:
        """{"step", "t", "pose"} of the first collision, or None."""
        return self._first_collision

    @property
    def t(self) -> float:
        """Simulated time: steps taken times dt."""
        return self._k * self.dt

    @property
    def steps_taken(self) -> int:
        """How many steps have run since construction."""
        return self._k

    @property
    def last(self) -> StepRecord:
        """The record of the last step (or of the start, before any step)."""
        return self._last

    def sensor_positions(self) -> list[tuple[float, float]]:
        """World positions of the IR sensors (the cone apexes) at the current true pose."""
        xs, ys = transform_fast((self._x, self._y, self._theta), [cone[0] for cone in self._surfaces.cones])
        return list(zip(xs, ys, strict=True))

    def set_pose(self, pose: Pose) -> None:
        """Put the robot at `pose` before the first step, without a physics pass.

        This is what the original's week-6 tests did after building the world (`robot_s.pose.set_pose`):
        the IR readings stay those of the world file's pose until the end of step 1, so the first
        controller call sees stale readings. To start at a pose with fresh readings, pass `start=`.
        """
        if self._k:
            raise ValueError("set_pose is only for the start, before the first step")
        self.start = (float(pose[0]), float(pose[1]), float(pose[2]))
        self._x, self._y, self._theta = self.start
        self._last = self._record(None)

    def touches_obstacle(self) -> bool:
        """The collision test at the current true pose (what the next physics pass would report)."""
        return self._check_collision()

    # --- physics ---
    def _update_ir(self, others: Sequence[ObstacleEdges] = ()) -> None:
        """Recompute the IR ranges at the true pose; `others` are other robots' base plates (a Fleet)."""
        self._ir_range, self._ir_raw = self._surfaces.sense((self._x, self._y, self._theta), others)

    def _check_collision(self, others: Sequence[ObstacleEdges] = ()) -> bool:
        return self._surfaces.collides((self._x, self._y, self._theta), others)

    def _move(self) -> None:
        R, L = self._wheels
        vel_r, vel_l, dt = self._vel_r, self._vel_l, self.dt
        self._x, self._y, self._theta = move(self._x, self._y, self._theta, vel_r, vel_l, R, L, dt)
        self._enc_r.update(vel_r, dt)
        self._enc_l.update(vel_l, dt)

    def _think(self, t: float) -> Command:
        readings: Readings = {"t": t, "dt": self.dt, "ticks": [self._enc_r.ticks, self._enc_l.ticks],
                              "ir_raw": list(self._ir_raw)}
        try:
            answer = self.brain.step(readings)
        except BaseException as exc:
            self._brain_exception = exc  # run() ends on this one; anything else raised in a step is a bug
            raise
        command = validate_command(answer, self.signals, self._n_ir, self._plan)
        max_vel, min_vel = self._limits
        self._vel_r, self._vel_l = limit_speeds(command["vel_r"], command["vel_l"], max_vel, min_vel)
        return command

    def _record(self, command: Command | None) -> StepRecord:
        # tuple.__new__ builds the same StepRecord as StepRecord(...) without its Python-level __new__
        return _new_tuple(StepRecord, (self._k, self._k * self.dt, (self._x, self._y, self._theta),
                                       (self._enc_r.ticks, self._enc_l.ticks), self._ir_raw, self._ir_range,
                                       self._vel_r, self._vel_l, command, self._collided))

    def step(self) -> StepRecord:
        """Advance one time step in the original's order; returns the new state."""
        command = self._advance()
        # `_collide` then `_update_ir`, in one physics pass (a Fleet's robots take the two apart)
        collided, ranges, raws = self._surfaces.step((self._x, self._y, self._theta))
        if not self._hit(collided):
            self._ir_range, self._ir_raw = ranges, raws
        return self._finish(command)

    # The three phases of a step, separate so that a Fleet can run the physics of all robots together.
    def _advance(self) -> Command:
        """Move and run the brain (week 1: the brain first); returns the validated command."""
        self._k += 1
        t = self._k * self.dt
        if self._brain_first:
            command = self._think(t)
            self._move()
        else:
            self._move()
            command = self._think(t)
        return command

    def _collide(self, others: Sequence[ObstacleEdges] = ()) -> bool:
        """The collision check at the new pose; remembers the first collision."""
        return self._hit(self._check_collision(others))

    def _hit(self, collided: bool) -> bool:
        """Keep the collision verdict at the new pose (and the first collision); returns it."""
        self._collided = collided
        if collided and self._first_collision is None:
            self._first_collision = {"step": self._k, "t": self._k * self.dt,
                                     "pose": [self._x, self._y, self._theta]}
        return collided

    def _finish(self, command: Command | None) -> StepRecord:
        self._last = self._record(command)
        return self._last

    def plate_polygon(self) -> ObstacleEdges:
        """The base plate at the current true pose, as an obstacle for other robots (a Fleet)."""
        return self._surfaces.plate_at((self._x, self._y, self._theta))

    def run(self, seconds: float, stop_on_collision: bool = True,
            until: Callable[[StepRecord], bool] | None = None,
            stuck: tuple[type[BaseException], ...] = ()) -> Trace:
        """Step for `seconds` of simulated time and return the Trace, row 0 being the state before this
        run's first step. The run ends early at a collision (unless `stop_on_collision` is false), once
        `until(record)` is true, or when the brain breaks: it raises (`stuck` lists the exception types
        that mean it did not answer in time) or returns an invalid command. `trace.ending` says which
        (simiam.trace.Ending, with the brain's exception in `.error`); the failed step is not recorded."""
        test = None if until is None else (lambda records: until(records[0]))
        return run_steps([self], lambda: [self.step()], seconds, stop_on_collision, test, stuck)[0]

    def new_trace(self) -> Trace:
        """An empty Trace with this run's header (week, dt, world, robot, start, goal)."""
        spec = self.spec
        robot = {"base_plate": [list(p) for p in spec.base_plate],
                 "ir_mounts": [list(m) for m in spec.ir_mounts],
                 "ir_min_range": spec.ir_min_range, "ir_max_range": spec.ir_max_range,
                 "ir_spread": spec.ir_spread, "wheel_radius": spec.wheel_radius,
                 "wheel_base_length": spec.wheel_base_length}
        goal = None if self.world.goal is None else list(self.world.goal)
        return Trace(week=spec.week, dt=self.dt, world=self.world.to_json(), robot=robot,
                     start=list(self.start), goal=goal, signals=headers(self.signals, self._n_ir))


def run_steps(sims: Sequence[Simulator], step: Callable[[], list[StepRecord]], seconds: float,
              stop_on_collision: bool = True, until: Callable[[list[StepRecord]], bool] | None = None,
              stuck: tuple[type[BaseException], ...] = ()) -> list[Trace]:
    """THE step loop, for one Simulator (`Simulator.run`) or a Fleet (`Fleet.run`): call `step()` (one
    record per robot) for `seconds` of the first robot's dt, record every robot's trace and end them all
    with the same Ending. Only what a brain itself raised, or its invalid command, ends a run quietly;
    any other exception is a bug of the caller or the simulator and propagates."""
    lead = sims[0]
    traces = []
    for sim in sims:
        trace = sim.new_trace()
        add_row(trace, sim.last, sim.start if sim.steps_taken == 0 else None)
        traces.append(trace)
    ending = None
    for _ in range(int(round(seconds / lead.dt))):
        try:
            records = step()
        except BaseException as exc:
            ending = _broken(sims, exc, stuck)
            break
        hit = False
        for trace, rec in zip(traces, records, strict=True):
            add_row(trace, rec)
            hit = hit or rec.collided
        if hit and stop_on_collision:
            ending = Ending(EndReason.COLLISION, lead.steps_taken, lead.t)
            break
        if until is not None and until(records):
            ending = Ending(EndReason.UNTIL, lead.steps_taken, lead.t)
            break
    if ending is None:
        ending = Ending(EndReason.TIME_UP, lead.steps_taken, lead.t)
    for sim, trace in zip(sims, traces, strict=True):
        trace.collision = sim.first_collision
        trace.ending = ending
    return traces


def _broken(sims: Sequence[Simulator], exc: BaseException, stuck: tuple[type[BaseException], ...]) -> Ending:
    """How a step that raised `exc` ended the run; re-raises what no brain raised (and Ctrl-C)."""
    lead = sims[0]
    robot = next((i for i, sim in enumerate(sims) if sim._brain_exception is exc), None)
    which = f"robot {robot + 1}: " if robot is not None and len(sims) > 1 else ""
    if isinstance(exc, KeyboardInterrupt):
        raise exc
    if robot is not None:
        reason = EndReason.STUCK if stuck and isinstance(exc, stuck) else EndReason.BRAIN_ERROR
        text = str(exc)
        words = which + type(exc).__name__ + (f": {text}" if text else "")
        return Ending(reason, lead.steps_taken, lead.t, words, exc)
    if isinstance(exc, BrainError):
        return Ending(EndReason.INVALID_COMMAND, lead.steps_taken, lead.t, which + str(exc), exc)
    raise exc


def add_row(trace: Trace, rec: StepRecord, estimate: Pose | None = None) -> None:
    """Append one StepRecord to the trace's columns (the estimate and debug values come from its command)."""
    s = trace.steps
    cmd: Any = rec.command or {}
    est = cmd.get("estimate") or estimate
    debug = cmd.get("debug") or {}
    s["t"].append(rec.t)
    s["x"].append(rec.pose[0])
    s["y"].append(rec.pose[1])
    s["theta"].append(rec.pose[2])
    s["x_est"].append(None if est is None else est[0])
    s["y_est"].append(None if est is None else est[1])
    s["theta_est"].append(None if est is None else est[2])
    s["ticks_r"].append(rec.ticks[0])
    s["ticks_l"].append(rec.ticks[1])
    s["vel_r"].append(rec.vel_r)
    s["vel_l"].append(rec.vel_l)
    s["ir_raw"].append(list(rec.ir_raw))
    s["ir_range"].append(list(rec.ir_range))
    for name in trace.signal_names:
        s[name].append(debug.get(name))
    s["state"].append(cmd.get("state"))
    s["collided"].append(rec.collided)
