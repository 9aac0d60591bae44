"""Every benchmark prints the machine line, a baseline from the same run and its ratio to it (tiny sizes;
the figures themselves are never asserted: they depend on the machine and its load)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

from grader.sandbox import bench as sandbox_bench
from simiam.bench import baseline_steps, main

ROOT = Path(__file__).resolve().parents[2]
MACHINE = re.compile(r"^machine: .+ \(\d+ cores.*\), .*Python \d+\.\d+\.\d+; sandbox: .+; "
                     r"load average before ", re.M)
LOAD_AFTER = re.compile(r"^load average after ", re.M)


def _ratios(text: str, label: str) -> list[float]:
    return [float(x) for x in re.findall(r"([0-9.]+)x " + label, text)]


def test_simiam_bench_prints_machine_baseline_and_ratio(capsys):
    assert main(SimpleNamespace(json=False, seconds=0.33)) == 0
    out = capsys.readouterr().out
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    assert "baseline (a step's arithmetic in one flat loop)" in out
    cpu_ratio = re.search(r"simulator / baseline: ([0-9.]+)x by CPU time \(([0-9.]+)x by wall time\)", out)
    assert cpu_ratio and float(cpu_ratio.group(1)) > 0 and float(cpu_ratio.group(2)) > 0


def test_simiam_bench_baseline_does_the_work():
    # the checksum depends on the steps run: a loop that skipped its body would return the same for all n
    assert baseline_steps(10) != baseline_steps(20)


def test_sandbox_bench_prints_machine_baselines_and_ratios(capsys):
    sandbox_bench.main(["--starts", "1", "--calls", "5"])
    out = capsys.readouterr().out
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    assert re.search(r"^baseline +interpreter start .* echo round trip ", out, re.M)
    assert _ratios(out, "an interpreter start") and _ratios(out, "the echo round trip")


def _script(*args: str) -> str:
    done = subprocess.run([sys.executable, *args], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


def test_grade_bench_prints_machine_baseline_and_ratios():
    out = _script("benchmarks/grade_bench.py", "--repeat", "1", "--weeks", "1", "--cli-week", "1",
                  "--no-hidden")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    assert "baseline: python -c 'import grader.grading'" in out and "baseline: bare worker start" in out
    assert re.search(r"^grade week1 --solutions \(fresh process\): wall .* CPU ", out, re.M)
    assert len(_ratios(out, "baseline CPU")) == 2  # the fresh process and the warm grade_submission
    assert re.search(r"^baseline CPU before the runs \d+ ms, after \d+ ms", out, re.M)  # the two averaged
    # each run over a baseline taken just before it: one ratio per run, their median first
    assert len(re.findall(r"paired \d+\.\dx \(\d+\.\d\)", out)) == 2


def test_pages_bench_prints_machine_sizes_and_the_same_run_baseline():
    out = _script("benchmarks/pages_bench.py", "--week", "1", "--n", "2", "--jobs", "1")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    rows = dict((name, (float(size), float(x))) for name, size, x in re.findall(
        r"^(self-contained \(baseline\)|shared assets) +([0-9.]+) +([0-9.]+) ", out, re.M))
    assert set(rows) == {"self-contained (baseline)", "shared assets"}, out
    assert rows["self-contained (baseline)"][1] == 1.0 and 0 < rows["shared assets"][1] < 1.0
    assert re.search(r"^shared assets .* [0-9.]+ +[0-9.]+ +[0-9.]+$", out, re.M)  # pages/s, x base, CPU


def test_batch_bench_prints_machine_baseline_and_ratios():
    out = _script("benchmarks/batch_bench.py", "--weeks", "1", "--jobs", "1", "--n", "1")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    row = re.search(r"^ +1 +1 +1 +[0-9.]+ +[0-9.]+ +([0-9.]+) +([0-9.]+) ", out, re.M)
    assert row and float(row.group(1)) > 0 and float(row.group(2)) > 0  # CPU s/sub and its ratio
    # cores busy, how often the grading process stalled, the tail, the end
    busy = re.search(r"^ +1 +1 +1 .* (\d+)% +([0-9.]+) +([0-9.]+) +([0-9.]+)  \S+$", out, re.M)
    assert busy and int(busy.group(1)) > 0 and float(busy.group(2)) >= 0
    assert float(busy.group(3)) == 0 and float(busy.group(4)) > 0


def test_beyond_step_prints_each_part_alone_and_against_another_checkout():
    out = _script("benchmarks/beyond_step.py", "--weeks", "7", "--repeat", "1")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    total = re.search(r"^  grading process in all \(grade_submission\) +([0-9.]+)$", out, re.M)
    part = re.search(r"^  scenario metric: min_clearance +([0-9.]+) +([0-9.]+)%$", out, re.M)
    assert total and part and 0 < float(part.group(1)) < float(total.group(1)), out
    out = _script("benchmarks/beyond_step.py", "--weeks", "7", "--repeat", "1", "--rounds", "1",
                  "--against", str(ROOT))  # A and B the same checkout: the ratios are about 1
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    ratio = re.search(r"^  report: JSON and HTML \(write_outputs\) +A +[0-9.]+ +B +[0-9.]+ +([0-9.]+) ",
                      out, re.M)
    assert ratio and 0.2 < float(ratio.group(1)) < 5, out


def test_grade_profile_prints_every_phase():
    # The profile wraps grader functions by name (grading._splice, write_outputs, scenarios.run, ...): a
    # rename must break this test, not silently drop a row from docs/performance.md's source.
    out = _script("benchmarks/grade_profile.py", "--week", "2")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    assert re.search(r"^1\. imports of a fresh `grade week2 --solutions` .*: [0-9.]+ s in all", out, re.M)
    for row in ("splice (skeleton check included)", "worker start and load", "property checks",
                "probe round trips", "scenario runs", "report: JSON and HTML", "total grade_submission"):
        assert re.search(rf"^ +{re.escape(row)} +-?\d+ ", out, re.M), row
    assert re.search(r"drawing the cases costs -?\d+ us per case", out)


def test_grade_and_batch_bench_say_when_the_sandbox_asked_for_is_missing():
    env = dict(os.environ, PATH="/nonexistent")  # no bwrap on PATH; the interpreter is called by path
    for script in ("benchmarks/grade_bench.py", "benchmarks/batch_bench.py"):
        done = subprocess.run([sys.executable, script, "--sandbox", "bwrap"], cwd=ROOT, env=env,
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 2, done.stderr[-2000:]
        assert done.stderr.startswith("--sandbox bwrap: ") and "Traceback" not in done.stderr


def test_worker_start_prints_every_piece_or_says_why_not():
    """Needs root and a cpuacct cgroup: where either is missing it must say so and stop, not guess."""
    done = subprocess.run([sys.executable, "benchmarks/worker_start.py", "--runs", "1"], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        assert "cannot make a cpuacct cgroup" in done.stderr or "bubblewrap is not usable" in done.stderr
        assert "Traceback" not in done.stderr
        return
    assert MACHINE.search(done.stdout) and LOAD_AFTER.search(done.stdout)
    for piece in ("bubblewrap -- /bin/true", "bubblewrap -- python: import numpy",
                  "bubblewrap -- python: the worker's preloads", "fresh process: imports + a bare worker"):
        figure = re.search(rf"^{re.escape(piece)} +([0-9.]+) ms CPU median", done.stdout, re.M)
        assert figure and float(figure.group(1)) > 0, piece


def test_step_parts_prints_machine_baseline_and_each_part():
    out = _script("benchmarks/step_parts.py", "--steps", "30", "--repeat", "1")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    assert re.search(r"^step, CPU us .*: [0-9.]+ \([0-9.]+x the flat-loop baseline", out, re.M)
    for part in ("brain", "command validation", "physics pass", "the rest"):
        assert re.search(rf"^  {part}.*: -?[0-9.]+ us \(-?[0-9.]+x baseline\)", out, re.M), part


def test_step_identity_finds_one_changed_bit(tmp_path):
    """The comparison of issue 24: a recording compares identical with itself, and one trace value one
    bit off (a wrong version of the step, as the recording sees it) is found and named."""
    import gzip
    import json

    record = tmp_path / "before.json.gz"
    out = _script("benchmarks/step_identity.py", "record", str(record), "--only", "solution/week2/start")
    assert "1 scenarios" in out
    assert "identical" in _script("benchmarks/step_identity.py", "compare", str(record), "--only",
                                  "solution/week2/start")
    with gzip.open(record, "rt") as f:
        data = json.load(f)
    ts = data["solution/week2/start"][0]["steps"]["t"]
    k = len(ts) // 2  # t > 0 there
    ts[k] = float.hex(float.fromhex(ts[k]) * (1 + 2.0 ** -52))  # the last bit
    with gzip.open(record, "wt") as f:
        json.dump(data, f)
    done = subprocess.run([sys.executable, "benchmarks/step_identity.py", "compare", str(record), "--only",
                           "solution/week2/start"], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 1 and f"DIFFERS solution/week2/start[0].steps.t[{k}]" in done.stdout


def test_similarity_bench_prints_machine_baseline_and_ratio():
    out = _script("benchmarks/similarity_bench.py", "--n", "8", "--hostile-mb", "0.2")
    assert MACHINE.search(out) and LOAD_AFTER.search(out)
    assert re.search(r"^baseline: stdlib tokenize over the class's blocks \(\d+ tokens\): [0-9.]+ s CPU$",
                     out, re.M)
    row = re.search(r"^class of 8 .*\((\d+) pairs share a fingerprint, (\d+) at 60 % or more\), .* = "
                    r"([0-9.]+|nan)x baseline", out, re.M)
    assert row and int(row.group(1)) >= int(row.group(2)) > 0, out   # the copies of a variant pair up
    assert re.search(r"^hostile student, a 0.2 MB block: [0-9.]+ s CPU", out, re.M), out
