"""What differs between a grading's verdict and the one expected, in words a failing test prints whole:
every check's [status, points] as graded, then, for each check that differs, the expected verdict, the one
given and that check's message (so an intermittent failure can be told from CI's log alone)."""

from __future__ import annotations

import json


def verdicts(result: dict) -> dict[str, list]:
    """{check id: [status, points]}, as tests/data/verdicts/seed2014.json holds them."""
    return {c["id"]: [c["status"], round(c["points"], 9)] for c in result["checks"]}


def differences(result: dict, expected: dict[str, list]) -> str:
    """"" when the result's verdicts are `expected`; else the whole verdict and each changed check."""
    got = verdicts(result)
    if got == expected:
        return ""
    messages = {c["id"]: c.get("message", "") for c in result["checks"]}
    lines = [f"the verdict of {result.get('submission')} (week {result.get('week')}, seed "
             f"{result.get('seed')}, status {result.get('status')}): {json.dumps(got)}"]
    for check in sorted(set(got) | set(expected)):
        if got.get(check) != expected.get(check):
            lines.append(f"  {check}: expected {expected.get(check)}, got {got.get(check)}: "
                         f"{messages.get(check, '(not run)')}")
    for key in ("message", "under_load", "time_budget", "numerics"):
        if result.get(key):
            lines.append(f"  result {key}: {json.dumps(result[key])[:1500]}")
    return "\n".join(lines)
