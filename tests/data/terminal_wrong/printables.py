"""Wrong on purpose: ways to "clean" untrusted text for a terminal that leave it dangerous.
tests/grader/test_terminal.py shows its check catches each of them."""

import re


def unchanged(text: str, multiline: bool = True) -> str:
    """Printed raw, as before."""
    return text


def strip_colour_codes(text: str, multiline: bool = True) -> str:
    """Removes CSI sequences only: OSC (window title), a bare CR, backspace and bidi overrides get through."""
    return re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", text)


def ascii_controls_only(text: str, multiline: bool = True) -> str:
    """Escapes C0 controls only: C1 controls (a one-byte CSI) and bidi overrides get through."""
    return re.sub(r"[\x00-\x09\x0b-\x1f\x7f]", lambda m: f"\\x{ord(m.group()):02x}", text)
