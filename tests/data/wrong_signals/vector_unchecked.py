"""WRONG: a vector is any two-element list, NaN, strings and nested lists included."""

from _kinds import with_rule

clean_debug = with_rule("vector2",
                        lambda x, n: list(x) if isinstance(x, (list, tuple)) and len(x) == 2 else None)
