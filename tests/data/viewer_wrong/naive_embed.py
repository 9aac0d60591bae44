"""Wrong on purpose: how a replay page goes wrong when the trace is pasted in raw.

Kept as test data: tests/viewer/test_replay_page.py proves its checks catch both mistakes.
"""

import json


def naive_script_json(data: dict) -> str:
    """No escaping: a '</script>' inside any string ends the data element and runs what follows."""
    return json.dumps(data)


def naive_page(trace: dict) -> str:
    """The whole trace unrounded, row-oriented as given, with json.dumps' default separators."""
    return "<!doctype html><script>var TRACE = " + json.dumps(trace) + ";</script>" + "x" * 30_000
