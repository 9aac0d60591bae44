"""WRONG: the state timeline pastes state names into the SVG as they are (the way a hand-built picture
forgets): a student's state "<script>..." becomes markup in the instructor's report."""

import grader.report.signal_plots as real


def states_svg(trace, width=460):
    saved = real.escape
    real.escape = lambda text: text
    try:
        return real.states_svg(trace, width)
    finally:
        real.escape = saved
