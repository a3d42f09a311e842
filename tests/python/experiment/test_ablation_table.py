"""scripts/ablation_table.py on hand-made run folders: its paired counts and McNemar p against scipy's binomial
test, and a method the base run lacks paired with nothing."""

import csv
import subprocess
import sys
from pathlib import Path

from scipy.stats import binomtest

REPO = Path(__file__).resolve().parents[3]
FIELDS = ["object", "trial", "condition", "method", "success", "reason"]


def write_run(folder: Path, rows: list[tuple]) -> Path:
    folder.mkdir()
    with open(folder / "attempts.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FIELDS)
        w.writerows(rows)
    return folder


def attempts(method: str, successes: list[int]) -> list[tuple]:
    return [(f"obj{i}", 0, "A", method, s, "success" if s else "not held") for i, s in enumerate(successes)]


def test_pairs_each_method_with_the_base_run_and_says_when_it_cannot(tmp_path):
    base = write_run(tmp_path / "base", attempts("gmm", [1, 0, 0, 0, 0, 0, 1, 1]))
    # Against the base: five attempts gained, one lost; KDE only in this run.
    other = write_run(
        tmp_path / "other", attempts("gmm", [1, 1, 1, 1, 1, 1, 0, 1]) + attempts("kde", [1, 0, 1, 0, 1, 0, 1, 0])
    )
    out = subprocess.run(
        [sys.executable, str(REPO / "scripts/ablation_table.py"), f"base={base}", f"other={other}", "--base", "base"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    rows = {tuple(c.strip() for c in line.strip("|").split("|")[:2]): line for line in out.splitlines()[2:]}
    p = binomtest(1, 6, 0.5).pvalue  # McNemar's exact test: the discordant pairs, 1 of 6 one way
    assert rows[("other", "GMM")].rstrip(" |").endswith(f"+5 / -1, p = {p:.2g}")
    assert "87.5" in rows[("other", "GMM")] and "37.5" in rows[("base", "GMM")]  # 7 of 8, 3 of 8
    assert rows[("other", "KDE")].rstrip(" |").endswith("n/a (no such attempts in the base run)")
