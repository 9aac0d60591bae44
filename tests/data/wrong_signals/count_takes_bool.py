"""WRONG: a count is any int, True and -5 and 10**100 included."""

from _kinds import with_rule

clean_debug = with_rule("count", lambda x, n: x if isinstance(x, int) else None)
