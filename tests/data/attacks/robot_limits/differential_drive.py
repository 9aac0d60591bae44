"""Attack: change the robot's limits and pose from student code."""



def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


class _Robot:
    wheel_radius = 0.0325
    wheel_base_length = 0.09925


def honest():
    return uni_to_diff(_Robot(), 0.1, 0.5)


def attack(**args):
    import simiam.course.weeks as weeks

    spec = weeks.spec_for_week(3)
    for name in ('max_vel', 'min_vel'):
        try:
            object.__setattr__(spec, name, 1e9)
        except Exception:
            pass
    weeks.spec_for_week = lambda week: spec
    return {'max_vel': spec.max_vel}
