"""QuickBot IR sensors: convert the raw ADC values to distances in metres.

From week 3 the ADC divider is fixed: raw = 1000 * V / 3 (the manual, section 2.1), so V = raw * 3 / 1000.
The coefficients map V to a distance: numpy.polyfit(table voltages, table distances, 5) on the manual's
table (Figure 2b), rounded to 4 decimals as the course shipped them.

Student block (week 2, shipped filled in) and the placeholder the stub would get:
  get_ir_distances: ir_voltages and coeff.
    Placeholder: `ir_voltages = ir_array_values` and `coeff = [0, 0, 0, 0, 0, 0]`.
"""

import numpy as np


def get_ir_distances(robot):
    """The five IR distances in metres (sensors 1..5 of the manual), from the raw ADC values."""
    ir_array_values = np.array([sensor.get_range() for sensor in robot.ir_array], dtype=float)

    # START CODE BLOCK
    ir_voltages = ir_array_values * 3 / 1000
    coeff = [-0.0182, 0.1690, -0.6264, 1.1853, -1.2104, 0.6293]
    # END CODE BLOCK

    ir_distances = np.polyval(coeff, ir_voltages)
    return ir_distances
