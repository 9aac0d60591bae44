"""WRONG: a scalar is anything float() accepts: True, "1.5", NaN (JSON cannot even hold NaN)."""

from _kinds import with_rule


def _loose(x, n):
    try:
        return float(x)
    except (TypeError, ValueError, OverflowError):
        return None


clean_debug = with_rule("scalar", _loose)
