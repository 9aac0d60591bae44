"""WRONG limit_speeds variants."""


def no_dead_zone(vel_r, vel_l, max_vel, min_vel):
    """Forgets the dead zone."""
    return max(min(vel_r, max_vel), -max_vel), max(min(vel_l, max_vel), -max_vel)


def non_strict(vel_r, vel_l, max_vel, min_vel):
    """Zeroes a wheel at |w| <= min_vel (the original keeps |w| == min_vel)."""
    vel_r = max(min(vel_r, max_vel), -max_vel)
    vel_l = max(min(vel_l, max_vel), -max_vel)
    return (0.0 if abs(vel_r) <= min_vel else vel_r), (0.0 if abs(vel_l) <= min_vel else vel_l)


def dead_zone_first(vel_r, vel_l, max_vel, min_vel):
    """Applies the dead zone before the clamp and rounds min_vel to math.pi."""
    import math
    min_vel = math.pi
    vel_r = 0.0 if abs(vel_r) < min_vel else vel_r
    vel_l = 0.0 if abs(vel_l) < min_vel else vel_l
    return max(min(vel_r, max_vel), -max_vel), max(min(vel_l, max_vel), -max_vel)
