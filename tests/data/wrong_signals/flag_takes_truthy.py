"""WRONG: a flag is bool(anything): "no" is True, a list is True."""

from _kinds import with_rule

clean_debug = with_rule("flag", lambda x, n: None if x is None else bool(x))
