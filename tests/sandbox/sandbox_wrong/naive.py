"""Naive versions a first attempt might write, each with the hole the real one closes."""

import json


def decode(line: bytes) -> dict:
    """Plain json.loads: accepts NaN/Infinity tokens, duplicate keys, any size, non-objects."""
    return json.loads(line)


def as_float(x, what="the value"):
    """float(x): accepts bools, numeric strings, NaN, and calls a student's __float__."""
    return float(x)


def to_json(value, depth=0):
    """Trusts __float__ of anything number-like: a lying object crosses as a 'number'."""
    if isinstance(value, (list, tuple)):
        return [to_json(v) for v in value]
    if hasattr(value, "__float__"):
        return float(value)
    return value


def find_stuck(dump: bytes, folder: str):
    """A loose reading of a faulthandler dump: any `File "...", line N in F` under the folder, unchecked
    (trusts the file name, the line number and the function name the untrusted dump gives)."""
    import re

    for m in re.finditer(r'File "([^"]*)", line (\d+) in (.*)', dump.decode(errors="replace")):
        if m.group(1).startswith(folder):
            return m.group(1)[len(folder):].lstrip("/"), int(m.group(2)), m.group(3)
    return None


def student_error_fields(error: dict) -> tuple:
    """The earlier rebuild of a worker error: message and type cut, but the file name taken whole."""
    return (str(error.get("message"))[:1000], str(error.get("type"))[:100], error.get("file"),
            error.get("line"))


def check_load(value: dict) -> dict:
    """The earlier load report check: types only, every name, error and message kept whole."""
    return {"modules": value.get("modules", {}), "errors": value.get("errors", [])}
