"""Wrong pieces of `simiam migrate`, kept as test data: tests/course/test_migrate.py swaps each in and
checks that the test written against it fails."""

from pathlib import Path


def write_in_place(folder: Path, texts: dict) -> list:
    """Writes each file directly: a failure half-way leaves some files changed and others not."""
    import os

    done = []
    for name, text in texts.items():
        with open(folder / name, "w") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        done.append(name)
    return done


def check_body_verbatim(stub_text, stub_blocks, target, sub_block, file):
    """Takes the body without re-indenting it (and without checking that it parses)."""
    return sub_block.body, None
