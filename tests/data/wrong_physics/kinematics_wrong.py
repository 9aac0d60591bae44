"""WRONG uni_to_diff / diff_to_uni: algebraically equal or plainly wrong variants."""


def uni_to_diff_reordered(R, L, v, w):
    """Algebraically equal, different operation order: differs in the last bits."""
    return v / R + w * L / (2 * R), v / R - w * L / (2 * R)


def uni_to_diff_swapped(R, L, v, w):
    """Left and right swapped."""
    return (2 * v - w * L) / (2 * R), (2 * v + w * L) / (2 * R)


def diff_to_uni_reordered(R, L, vel_r, vel_l):
    """R*(r-l)/L instead of R/L*(r-l): differs in the last bits."""
    return R / 2 * (vel_r + vel_l), R * (vel_r - vel_l) / L


def diff_to_uni_no_half(R, L, vel_r, vel_l):
    """Forgets the 1/2 in v."""
    return R * (vel_r + vel_l), R / L * (vel_r - vel_l)
