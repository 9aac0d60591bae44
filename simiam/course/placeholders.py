"""The code blocks of the course, as data: which week each block is new in, and what a stub holds instead.

Each block of `solutions/weekN` is looked up here by (file, enclosing function, position in that function).
In the week it is introduced its body is replaced by `hint` (comment lines) and `code` (a placeholder that
runs: the robot stays still or drives straight); in later weeks the solution's body ships filled in.

`revised_in` lists the weeks whose stubs ship a *changed* filled version (the course changed the robot or
the provided code around the block): `simiam migrate` keeps the shipped version there instead of carrying
the student's older one. `tunable` blocks (gains) may ship other values in later weeks and are carried
all the same. A test compares this table with the solutions, so it cannot silently drift.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Placeholder:
    """What the stub of `week` puts in the block `scope` (occurrence `occurrence`) of `file`."""

    file: str
    scope: str
    week: int
    hint: str
    code: str
    occurrence: int = 1
    revised_in: tuple[int, ...] = ()
    revised_why: str = ""
    tunable: bool = False  # numbers to tune: later weeks may ship other values, yet migrate carries yours

    @property
    def key(self) -> tuple[str, str, int]:
        return (self.file, self.scope, self.occurrence)

    def body(self, indent: str) -> str:
        """The placeholder as block body text at `indent`: the hint as comments, then the code."""
        lines = [f"# {ln}".rstrip() for ln in self.hint.strip().splitlines()]
        lines += self.code.strip().splitlines()
        return "".join(f"{indent}{ln}\n" if ln.strip() else "\n" for ln in lines)


PLACEHOLDERS: tuple[Placeholder, ...] = (
    # ------------------------------------------------------------------------------------------ week 2
    Placeholder(
        "differential_drive.py",
        "uni_to_diff",
        week=2,
        hint="""TODO (week 2): turn the unicycle command (v in m/s, w in rad/s) into the angular speeds
of the right and left wheels, vel_r and vel_l (rad/s). R is the wheel radius and L the
distance between the wheels (manual, section 2.2). Until then the wheels do not turn.""",
        code="vel_r = 0\nvel_l = 0",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.update_odometry",
        week=2,
        hint="""TODO (week 2): estimate how the pose changed since the last call.
A wheel covered (its ticks now - its ticks then) * m_per_tick metres. From the right and
left distances, L and theta, compute x_dt, y_dt and theta_dt. Until then the estimate
never leaves the start pose.""",
        code="x_dt = 0\ny_dt = 0\ntheta_dt = 0",
    ),
    Placeholder(
        "quickbot.py",
        "get_ir_distances",
        week=2,
        hint="""TODO (week 2): raw ADC values -> volts (this week's divider: raw / 500), then coeff,
the degree-5 polynomial (highest power first) fitted once to the table of Figure 2b with
numpy.polyfit(voltages, distances, 5), pasted here as numbers. Until then every distance
reads 0.""",
        code="ir_voltages = ir_array_values\ncoeff = [0, 0, 0, 0, 0, 0]",
        revised_in=(3,),
        revised_why="the IR sensors report a different raw value from week 3 (new divider and fit)",
    ),
    # ------------------------------------------------------------------------------------------ week 3
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.__init__",
        week=3,
        hint="""TODO (week 3, part 3): tune the PID gains so that theta settles on theta_g within 10%
in 3 s or less, overshooting by 10% at most. With zero gains the robot never turns.""",
        code="self.Kp = 0\nself.Ki = 0\nself.Kd = 0",
        tunable=True,
    ),
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.execute",
        week=3,
        occurrence=1,
        hint="""TODO (week 3, part 1): u_x, u_y = the vector from the robot (x, y) to the goal
(x_g, y_g); theta_g = the angle it makes with the x axis (math.atan2).""",
        code="u_x = 0\nu_y = 0\ntheta_g = 0",
    ),
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.execute",
        week=3,
        occurrence=2,
        hint="""TODO (week 3, part 2): e_k = theta_g - theta, brought back into [-pi, pi]
(the atan2 of its sine and cosine does that).""",
        code="e_k = 0",
    ),
    Placeholder(
        "go_to_goal.py",
        "GoToGoal.execute",
        week=3,
        occurrence=3,
        hint="""TODO (week 3, part 3): e_P is this step's error; e_I adds e_k * dt to the error
accumulated so far (self.E_k); e_D is the change since the last step's error
(self.e_k_1) divided by dt. The code below stores e_I and e_k for the next step.""",
        code="e_P = 0\ne_I = 0\ne_D = 0",
    ),
    Placeholder(
        "qb_supervisor.py",
        "QBSupervisor.ensure_w",
        week=3,
        hint="""TODO (week 3, part 4): if the faster wheel would turn faster than robot.max_vel, take
the excess off both wheels; if the slower one would turn backwards faster than max_vel,
add the shortfall to both. The same shift on both wheels keeps w and gives up some v.
Until then the speeds pass through unchanged (w is lost when a motor saturates).""",
        code="vel_r = vel_r_d\nvel_l = vel_l_d",
    ),
    # ------------------------------------------------------------------------------------------ week 4
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.__init__",
        week=4,
        hint="""Week 4: the PID gains that steer along u_ao. These values work; tune them if you like.""",
        code="self.Kp = 4\nself.Ki = 0.01\nself.Kd = 0.1",
        tunable=True,
    ),
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.execute",
        week=4,
        hint="""TODO (week 4, part 3): sensor_gains = one weight per sensor, the same on the left and
the right; u_i = column i is sensor_gains[i] times the vector from the robot (x, y) to
the IR point ir_distances_wf[:, i]; u_ao = the sum of the columns; theta_ao = its angle;
e_k = theta_ao - theta, kept in [-pi, pi]. Until then the robot drives straight.""",
        code=(
            "sensor_gains = [0, 0, 0, 0, 0]\nu_i = np.zeros((2, 5))\nu_ao = np.sum(u_i, axis=1)\n"
            "theta_ao = 0\ne_k = 0"
        ),
    ),
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.apply_sensor_geometry",
        week=4,
        hint="""TODO (week 4, parts 1 and 2): sensor i measured the point (ir_distances[i], 0) in its
own frame. Move it into the robot's frame with the sensor's mount pose
(robot.ir_array[i].location: x_s, y_s, theta_s), then into the world with the estimate
(x, y, theta), both with get_transformation_matrix. Column i of ir_distances_rf and of
ir_distances_wf holds that point as (x, y, 1).""",
        code="ir_distances_rf = np.zeros((3, 5))\nir_distances_wf = np.zeros((3, 5))",
    ),
    Placeholder(
        "avoid_obstacles.py",
        "AvoidObstacles.get_transformation_matrix",
        week=4,
        hint="""TODO (week 4, part 1): T = the 3x3 matrix that rotates a point (x, y, 1) by theta,
then translates it by (x, y).""",
        code="T = np.zeros((3, 3))",
    ),
)


def placeholder_for(file: str, scope: str, occurrence: int = 1) -> Placeholder | None:
    """The table's entry for a block, or None."""
    for p in PLACEHOLDERS:
        if p.key == (file, scope, occurrence):
            return p
    return None
