"""Attack: form feeds in the last block's indentation (Python resets the column at a form feed), so the
block's second half lands at module level and takes the stub's own `return vel` with it.

Fixture stub for the block tests: two classes and a function, four code blocks."""

import math


class Steer:
    def __init__(self):
        # START CODE BLOCK [week 3: gains]
        self.Kp = 4.0
        # END CODE BLOCK
        self.E_k = 0.0

    def execute(self, x, y, x_g, y_g, theta, dt):
        # START CODE BLOCK [week 3: theta_g]
        theta_g = math.atan2(y_g - y, x_g - x)
        # END CODE BLOCK
        # START CODE BLOCK [week 3: error]
        e_k = theta_g - theta
        e_k = math.atan2(math.sin(e_k), math.cos(e_k))
        # END CODE BLOCK
        self.theta_g = theta_g
        return self.Kp * e_k


def wheel_speed(v, R):
    # START CODE BLOCK
    vel = v / R
    def wheel_speed(v, R):
        vel = 99.0
    # END CODE BLOCK
    return vel
