"""Fixture stub for the block tests: two classes and a function, four code blocks."""

import math


class Steer:
    def __init__(self):
        # START CODE BLOCK [week 3: gains]
        self.Kp = 4.0
        # START CODE BLOCK
        self.Ki = 0.0
        # END CODE BLOCK
        # END CODE BLOCK
        self.E_k = 0.0
