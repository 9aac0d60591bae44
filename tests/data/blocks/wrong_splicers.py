"""Wrong splice implementations kept as test data: each must be caught by tests/course/test_splice.py.

They share the real `splice`'s signature and return a SpliceResult-like object (only `.text`, `.errors`,
`.outside_edits`, `.blocks_taken` are looked at).
"""

from types import SimpleNamespace

from simiam.course.blocks import find_blocks, replace_bodies


def by_ordinal(stub_text, submission_text, filename):
    """Pairs blocks by their position in the file only: moving a function around swaps bodies."""
    stub = find_blocks(stub_text, filename)
    sub = find_blocks(submission_text, filename)
    bodies = {s.ordinal: b.body for s, b in zip(stub, sub)}
    return SimpleNamespace(text=replace_bodies(stub_text, stub, bodies), errors=[], outside_edits=[],
                           blocks_taken=[s.describe() for s in stub])


def no_reindent(stub_text, submission_text, filename):
    """Copies the bodies verbatim: a file re-indented by the student no longer compiles."""
    stub = find_blocks(stub_text, filename)
    sub = {b.key: b for b in find_blocks(submission_text, filename)}
    bodies = {s.ordinal: sub[s.key].body for s in stub if s.key in sub}
    return SimpleNamespace(text=replace_bodies(stub_text, stub, bodies), errors=[], outside_edits=[],
                           blocks_taken=[s.describe() for s in stub])


def whole_file(stub_text, submission_text, filename):
    """Trusts the submission entirely: edits outside the blocks run."""
    return SimpleNamespace(text=submission_text, errors=[], outside_edits=[], blocks_taken=[])


def no_syntax_check(stub_text, submission_text, filename):
    """Matches and re-indents correctly but never checks that a body parses on its own."""
    from simiam.course.blocks import dedent_body, indent_body

    stub = find_blocks(stub_text, filename)
    sub = {b.key: b for b in find_blocks(submission_text, filename)}
    bodies = {s.ordinal: indent_body(dedent_body(sub[s.key].body), s.indent) for s in stub if s.key in sub}
    return SimpleNamespace(text=replace_bodies(stub_text, stub, bodies), errors=[], outside_edits=[],
                           blocks_taken=[s.describe() for s in stub])


def no_whitespace_check(stub_text, submission_text, filename):
    """The real splice without the indentation check: a form feed in a block's indentation lets the block
    leave its function (Python resets the column at a form feed)."""
    from simiam.course import splice as splice_module

    check, splice_module.odd_indent = splice_module.odd_indent, lambda body: None
    try:
        return splice_module.splice(stub_text, submission_text, filename)
    finally:
        splice_module.odd_indent = check


WRONG = {"by_ordinal": by_ordinal, "no_reindent": no_reindent, "whole_file": whole_file,
         "no_syntax_check": no_syntax_check, "no_whitespace_check": no_whitespace_check}
