"""WRONG: every finite value on a plot's axis, as the report drew before issue 22: a student's debug value of
±1e308 makes the span of the axis overflow to infinity, and the ticks raise OverflowError (the report is
not written, and the batch marked the student `crashed`)."""

import grader.report.signal_plots as signal_plots
import grader.report.svg as real


def signals_svg(trace, names):
    saved = real._plottable, real._off_chart
    real._plottable, real._off_chart = real._finite, lambda v: False
    try:
        return signal_plots.signals_svg(trace, names)
    finally:
        real._plottable, real._off_chart = saved
