"""WRONG points rule: a fast path that hands back the brain's own row lists (no copy) and trusts the rows'
sum alone, so a row holding a float subclass or a bool passes, and the brain can change a recorded row
after the step."""
from simiam import signals


def _points(p, n):
    if type(p) is list and len(p) == 2 and n <= signals.MAX_POINTS:
        xs, ys = p
        if isinstance(xs, list) and isinstance(ys, list) and len(xs) == n == len(ys):
            tx, ty = sum(xs), sum(ys)
            return [xs, ys] if tx - tx == 0.0 and ty - ty == 0.0 else None
    return None


def install(monkeypatch) -> None:
    monkeypatch.setitem(signals._CLEAN, "points", _points)
