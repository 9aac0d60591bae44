"""Wrong version of the framed decoder's validated answers (grader.inside.record_codec._checked_lines): it
marks an answer as already validated without testing that its doubles are finite, so a NaN wheel speed
or a points row of an infinite sum would skip the validation. tests/sandbox/test_checked_answers.py
must catch it."""

from __future__ import annotations

from grader.inside import record_codec
from grader.inside.step_record import StepLayout
from simiam.course.weeks import get_week
from simiam.signals import week_signals

_TEST = "finite = total - total == 0.0"


def lax_layout(week: int) -> StepLayout:
    """The week's layout, its framed decoder compiled from the honest source without the finiteness test."""
    declaration = get_week(week)
    layout = StepLayout(week_signals(declaration), len(declaration.spec.ir_mounts))
    source = record_codec.source(layout)
    assert _TEST in source, "the honest decoder changed: update this wrong version"
    lax = source.replace(_TEST, "finite = True").replace("finite = xs", "ignored = xs")
    space = record_codec.namespace(layout, layout._caps)  # noqa: SLF001
    exec(compile(lax, "<lax decoder>", "exec"), space)  # noqa: S102
    layout._decode_frame = space["decode_frame"]  # noqa: SLF001
    return layout
