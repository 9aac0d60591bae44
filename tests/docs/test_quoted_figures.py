"""The figures the handout READMEs quote from a run come from that run: each is read from the README and
from the summary `simiam run` prints for the same folder, and the two must agree (to the README's
precision). A README that quotes a figure the run no longer gives fails here, not in a student's hands."""

from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass

import pytest
from documented import ROOT, scripts


@dataclass(frozen=True)
class Quoted:
    """A figure a README quotes (`said`, its numbers as groups) and the same figure in the summary of
    `simiam run ARGS` (`ran`); `week` names the README."""

    week: int
    said: str
    args: tuple[str, ...]
    ran: str

    def disagreement(self, readme: str, summary: str) -> str | None:
        """None when the README's numbers are the run's (rounded as the README writes them)."""
        quoted = re.search(self.said, " ".join(readme.split()))
        measured = re.search(self.ran, summary)
        if quoted is None or measured is None:
            return f"week {self.week}: {'the README' if quoted is None else 'the run'} no longer says it"
        for q, m in zip(quoted.groups(), measured.groups(), strict=True):
            decimals = len(q.partition(".")[2])
            if round(float(m), decimals) != float(q):
                return f"week {self.week}: the README says {q}, the run gives {m}"
        return None


QUOTED = (
    Quoted(5, r"the summary's final pose is about \((-?[\d.]+), (-?[\d.]+)\)", ("week5", "--solutions"),
           r"Final true pose \(x, y, theta\) = \((-?[\d.]+), (-?[\d.]+),"),
    Quoted(7, r"hits the trap's top bar after ([\d.]+) s", ("week7",), r"COLLISION at t = ([\d.]+) s"),
    Quoted(7, r"reaches the goal after about (\d+) s with (\d+) switches", ("week7", "--solutions"),
           r"the robot stopped at t = ([\d.]+) s.*Switches: (\d+)"),
)


@pytest.fixture(scope="module")
def summaries(tmp_path_factory) -> dict[tuple[str, ...], str]:
    """The summary of each run the READMEs quote, run once (the handouts' commands, in the checkout:
    `week7` is the stub, as a student first runs it)."""
    out = {}
    for args in {q.args for q in QUOTED}:
        folder = tmp_path_factory.mktemp("runs")
        done = subprocess.run([str(scripts() / "simiam"), "run", *args, "--out", str(folder)], cwd=ROOT,
                              capture_output=True, text=True)
        out[args] = " ".join(done.stdout.split())
    return out


@pytest.mark.parametrize("quoted", QUOTED, ids=[f"week{q.week}-{k}" for k, q in enumerate(QUOTED)])
def test_a_quoted_figure_is_the_runs(quoted: Quoted, summaries: dict) -> None:
    readme = (ROOT / "assignments" / f"week{quoted.week}" / "README.md").read_text(encoding="utf-8")
    assert quoted.disagreement(readme, summaries[quoted.args]) is None


def test_a_stale_figure_is_caught(summaries: dict) -> None:
    """The same comparison on READMEs whose figures are off by the README's last digit."""
    for quoted, stale in zip(QUOTED, ("about (1.02, 0.95)", "after 1.55 s", "after about 28 s with 17"),
                             strict=True):
        readme = (ROOT / "assignments" / f"week{quoted.week}" / "README.md").read_text(encoding="utf-8")
        fresh = re.search(quoted.said, " ".join(readme.split())).group(0)
        wrong = re.sub(r"about \(.*?\)|after [\d.]+ s|after about \d+ s with \d+", stale, fresh, count=1)
        assert wrong != fresh
        assert quoted.disagreement(wrong, summaries[quoted.args]) is not None, stale


def test_each_readme_figure_has_one_source() -> None:
    """The figures are not restated elsewhere, where they could drift apart from the checked copy."""
    others = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
              *(ROOT / "assignments" / f"week{w}" / "README.md" for w in range(1, 8))]
    for quoted in QUOTED:
        found = [p for p in others if re.search(quoted.said, " ".join(p.read_text(encoding="utf-8").split()))]
        assert found == [ROOT / "assignments" / f"week{quoted.week}" / "README.md"]
