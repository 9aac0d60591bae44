"""Wrong version of grader.inside.record_writer.writer_source: it does not check that the state is exactly a
str, so a state whose __str__ gives a str subclass is packed into a record, where the encoder (and so JSON,
as before records) gives what the grader's validation reads from a plain dict. tests/sandbox/
test_record_writer.py must catch it."""

from __future__ import annotations

from typing import Any

from grader.inside.record_writer import writer_source

_CHECK = "    if len(est) != 3 or type(state) is not str:"


def careless_source(layout: Any) -> str:
    source = writer_source(layout)
    assert _CHECK in source, "the honest writer changed: update this wrong version"
    return source.replace(_CHECK, "    if len(est) != 3:")
