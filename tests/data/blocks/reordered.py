"""Fixture stub for the block tests: two classes and a function, four code blocks."""

import math


def wheel_speed(v, R):
    # START CODE BLOCK
    vel = v / R
    # END CODE BLOCK
    return vel


class Steer:
    def execute(self, x, y, x_g, y_g, theta, dt):
        # START CODE BLOCK [week 3: error]
        e_k = math.atan2(math.sin(theta_g - theta), math.cos(theta_g - theta))
        # END CODE BLOCK
        # START CODE BLOCK [week 3: theta_g]
        theta_g = math.atan2(y_g - y, x_g - x)
        # END CODE BLOCK
        self.theta_g = theta_g
        return self.Kp * e_k

    def __init__(self):
        # START CODE BLOCK [week 3: gains]
        self.Kp = 4.0
        # END CODE BLOCK
        self.E_k = 0.0
