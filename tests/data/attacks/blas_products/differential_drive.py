"""Not an attack: student-style numpy products (the kind weeks 4-7 compute every step), whose last bit
depends on the BLAS kernel and numpy's SIMD loops; the test compares them with the grading process's."""
import numpy as np


def uni_to_diff(robot, v, w):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return (2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)


def diff_to_uni(robot, vel_r, vel_l):
    R = robot.wheel_radius
    L = robot.wheel_base_length
    return R / 2 * (vel_r + vel_l), R / L * (vel_r - vel_l)


def attack(x=(), y=(), **args):
    x, y = np.array(x, dtype=float), np.array(y, dtype=float)
    T = np.array([[x[0], -x[1], 0.3], [x[1], x[0], -0.7], [0.0, 0.0, 1.0]])
    points = np.array([[y[0], y[1], 0.5, -0.25, 1.5], [y[1], -y[0], 0.75, 0.125, -1.0], [1.0] * 5])
    return {"dot": float(x @ y).hex(), "gemm": [float(v).hex() for v in (T @ points).ravel()],
            "atan2": float(np.arctan2(x[0] * 1.7, y[1] - 0.3)).hex()}
