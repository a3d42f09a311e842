"""scripts/named_table.py on hand-made named-object runs: its counts, Wilson interval and paired McNemar p against
the closed form and scipy, attempts of other scenes never paired, and a folder that is no run refused with one
line and exit 2."""

import csv
import gzip
import math
import subprocess
import sys
from pathlib import Path

from graspmix.clutter.named import NAMED_CSV, NAMED_CSV_NAME, NO_TARGET
from scipy.stats import binomtest, norm

REPO = Path(__file__).resolve().parents[3]


def write_run(folder: Path, outcomes: list[str], seed_offset: int = 0, gz: bool = False) -> Path:
    """A named-object run's attempts in the runner's schema (every column; those the table does not read blank)."""
    folder.mkdir()
    path = folder / (NAMED_CSV_NAME + (".gz" if gz else ""))
    with gzip.open(path, "wt", newline="") if gz else open(path, "w", newline="") as f:
        w = csv.DictWriter(f, NAMED_CSV.columns, restval="")
        w.writeheader()
        for i, o in enumerate(outcomes):
            w.writerow(
                dict(
                    mode="packed",
                    scene=i,
                    method="gmm",
                    pick=0,
                    scene_seed=1000 + i + seed_offset,
                    target=2,
                    point="0.1,0.2,0.03",
                    outcome=o,
                    success=int(o == "success"),
                )
            )
    return folder


def table(*runs: str) -> dict:
    out = subprocess.run(
        [sys.executable, str(REPO / "scripts/named_table.py"), *runs], capture_output=True, text=True, check=True
    ).stdout
    return {
        line.split("|")[1].strip(): [c.strip() for c in line.strip("|").split("|")] for line in out.splitlines()[2:]
    }


def wilson(k: int, n: int) -> tuple[float, float]:
    z = norm.ppf(0.975)
    centre = (k + z * z / 2) / (n + z * z)
    half = z * math.sqrt(k * (n - k) / n + z * z / 4) / (n + z * z)
    return centre - half, centre + half


def test_counts_interval_and_pairs_against_the_closed_forms(tmp_path):
    s, h, w, t = "success", "not held", "wrong object", "two objects lifted"
    base = write_run(tmp_path / "base", [s, h, h, h, h, h, s, s, w, t, NO_TARGET])  # the last: no attempt
    # against base: attempts 1-5 and 8 gained, 0 lost, 6 and 7 lifted in both, 9 in neither
    new = write_run(tmp_path / "new", [h, s, s, s, s, s, s, s, s, w], gz=True)
    other = write_run(tmp_path / "other", [s] * 10, seed_offset=100)  # other scenes: no pairs
    rows = table(f"base={base}", f"new={new}", f"other={other}")
    lo, hi = wilson(8, 10)
    assert rows["new"][1] == rows["base"][1] == "10"  # the pick with no target is no attempt
    assert rows["new"][2] == f"8, 80.0% [{100 * lo:.1f}, {100 * hi:.1f}]"
    assert rows["base"][3] == "2" and rows["new"][3] == "1"  # a neighbour lifted, alone or with the target
    assert rows["new"][5] == f"+6 / -1, p = {binomtest(1, 7, 0.5).pvalue:.2g}"
    assert rows["other"][5] == "no shared attempts (other scenes)"
    assert rows["base"][5] == ""


def test_a_folder_without_named_attempts_is_one_line_and_exit_2(tmp_path):
    (tmp_path / "empty").mkdir()
    r = subprocess.run(
        [sys.executable, str(REPO / "scripts/named_table.py"), f"x={tmp_path / 'empty'}"],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "named_attempts" in r.stderr
    (tmp_path / "bad").mkdir()
    (tmp_path / "bad" / (NAMED_CSV_NAME + ".gz")).write_bytes(b"not gzip")
    r = subprocess.run(
        [sys.executable, str(REPO / "scripts/named_table.py"), f"x={tmp_path / 'bad'}"], capture_output=True, text=True
    )
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "not a gzip file" in r.stderr
    r = subprocess.run(
        [sys.executable, str(REPO / "scripts/named_table.py"), "noequals"], capture_output=True, text=True
    )
    assert r.returncode == 2 and "NAME=RUN" in r.stderr
