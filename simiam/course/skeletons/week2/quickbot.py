"""QuickBot IR sensors: convert the raw ADC values to distances in metres.

Week 2: the ADC reads the sensor voltage through a divider, raw = 500 * V (the manual's week-2 note),
and a 5th-order polynomial fitted to the manual's table (Figure 2b) maps V to a distance.

The coefficients below were computed once, as the manual says, with
    numpy.polyfit([2.750, 2.350, 2.050, 1.750, 1.550, 1.400, 1.275, 1.075, 0.925, 0.805, 0.725, 0.650,
                   0.500, 0.400],                                   # table voltages (V)
                  [0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12, 0.14, 0.16, 0.18, 0.20, 0.25, 0.30],
                  5)                                                # table distances (m), degree 5
and pasted here (highest power first).

Student block (week 2) and the placeholder the stub gets:
  get_ir_distances: ir_voltages and coeff.
    Placeholder: `ir_voltages = ir_array_values` and `coeff = [0, 0, 0, 0, 0, 0]` (all distances read 0).
"""

import numpy as np


def get_ir_distances(robot):
    """The five IR distances in metres (sensors 1..5 of the manual), from the raw ADC values."""
    ir_array_values = np.array([sensor.get_range() for sensor in robot.ir_array], dtype=float)

    # START CODE BLOCK
    # TODO (week 2): raw ADC values -> volts (this week's divider: raw / 500), then coeff,
    # the degree-5 polynomial (highest power first) fitted once to the table of Figure 2b with
    # numpy.polyfit(voltages, distances, 5), pasted here as numbers. Until then every distance
    # reads 0.
    ir_voltages = ir_array_values
    coeff = [0, 0, 0, 0, 0, 0]
    # END CODE BLOCK

    ir_distances = np.polyval(coeff, ir_voltages)
    return ir_distances
