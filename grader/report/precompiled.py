"""The report's templates (and the replay page it embeds) precompiled: simiam.viewer.precompiled says how
and when stored code is used. The report loads them through grader.report.loader; this module
regenerates them all:

    python -m grader.report.precompiled          # regenerate grader/report/compiled, simiam/viewer/compiled
    python -m grader.report.precompiled --check  # exit 1 if a stored module is out of date
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from grader.report.html import _env
from grader.report.loader import COMPILED, TEMPLATES, PrecompiledLoader, module_name
from simiam.viewer import precompiled

__all__ = ["COMPILED", "TEMPLATES", "PrecompiledLoader", "main", "module_name"]


def main(argv: list[str] | None = None) -> int:
    """`python -m grader.report.precompiled [--check]`."""
    from simiam.viewer import replay

    parser = argparse.ArgumentParser(prog="python -m grader.report.precompiled",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="change nothing; exit 1 if out of date")
    args = parser.parse_args(argv)
    env = _env()
    assert env.loader is not None
    wanted: list[tuple[Path, str]] = []
    for template in TEMPLATES:
        source, filename, _ = env.loader.get_source(env, template)
        text = precompiled.module_source(env, source, template, filename,
                                         f"grader/report/templates/{template}")
        wanted.append((COMPILED / (module_name(template).rsplit(".", 1)[1] + ".py"), text))
    wanted.append((replay.COMPILED, precompiled.module_source(
        replay._env(), replay._asset(replay.TEMPLATE), None, None, f"simiam/viewer/{replay.TEMPLATE}")))
    root = COMPILED.parents[2]
    stale = [path for path, text in wanted if precompiled.write_if_changed(path, text, args.check)]
    for path in stale:
        print(f"{'out of date' if args.check else 'wrote'}: {path.relative_to(root)}")
    if args.check and stale:
        print("run `python -m grader.report.precompiled` to regenerate")
    return 1 if args.check and stale else 0


if __name__ == "__main__":
    sys.exit(main())
