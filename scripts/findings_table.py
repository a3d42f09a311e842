"""Renders the findings of an experiment run (summary.json, and benchmark.json if given) as markdown,
and optionally writes it into a markdown page (docs/experiment.md, its findings) between the markers

    <!-- findings:begin -->
    <!-- findings:end -->

so the page's numbers always come from a run, never from a hand.

    python scripts/findings_table.py results/paper/summary.json [--benchmark results/paper/benchmark.json]
                                     [--extra results/paper-learnt-closing/summary.json] [--doc docs/experiment.md]
(--benchmark and --extra can be given more than once.)
"""

import argparse
import json
import re
import sys
from pathlib import Path

from graspmix.experiment.report import findings_table, md_table
from graspmix.model.grasps import STAGE_LABELS, STAGES


def success_table(summary: dict) -> str:
    return md_table(findings_table(summary))


def runtime_table_md(bench: dict) -> str:
    med, ratio = bench["median_s"], bench["ratio_kde_over_gmm"]
    rows = [["stage (median over %d objects)" % len(bench["objects"]), "GMM (ms)", "KDE (ms)", "KDE / GMM"]]
    for s in (*STAGES, "total"):
        rows.append(
            [
                STAGE_LABELS.get(s, "total of the three"),
                f"{med['gmm'][s] * 1e3:.1f}",
                f"{med['kde'][s] * 1e3:.1f}",
                f"{ratio[s]:.2f}",
            ]
        )
    return md_table(rows)


def verdict(summary: dict) -> str:
    """Whether the run agrees with the paper's claim: GMM at least 10 points above KDE, p < 0.05, in every
    condition."""
    parts = []
    for c, tt in summary["ttest_gmm_vs_kde"].items():
        if "mean_difference" not in tt:
            parts.append(f"{c}: no test ({tt.get('note', '')})")
            continue
        d, p = 100 * tt["mean_difference"], tt["p"]
        ok = d >= 10 and p is not None and p < 0.05
        parts.append(f"{c}: {d:+.1f} points, p = {p:.2g} -> {'agrees' if ok else 'does not agree'}")
    return "; ".join(parts)


def render(summary_path: Path, bench_paths: list[Path], extra: list[Path]) -> str:
    s = json.loads(summary_path.read_text())
    prov = s["provenance"]
    out = [
        f"Run: `{prov.get('command', '?')}` on commit `{prov.get('commit', '?')}` "
        f"({s['attempts']['done']} of {s['attempts']['expected']} attempts).",
        "",
        success_table(s),
        "",
        f"Against the paper's claim (GMM at least 10 points above KDE with p < 0.05 in every condition): {verdict(s)}.",
        "",
    ]
    rt = s["runtime"]
    if rt.get("median_s"):
        g, k = rt["median_s"]["gmm"], rt["median_s"]["kde"]
        out += [
            f"Synthesis time in the run (conditions {','.join(rt['conditions'])}, two jobs sharing two cores; "
            f"median over objects): GMM {g['total'] * 1e3:.0f} ms, KDE {k['total'] * 1e3:.0f} ms, "
            f"KDE / GMM = {rt['ratio_kde_over_gmm']['total']:.2f}.",
            "",
        ]
    for bench_path in bench_paths:
        b = json.loads(bench_path.read_text())
        m = b.get("machine", {})
        threads = m.get("OMP_NUM_THREADS") or f"unset (OpenMP's default: {m.get('cpu_count', '?')} threads)"
        load = m.get("load_average_before", [None])[0]
        out += [
            f"`graspmix_cli benchmark` ({bench_path.parent.name}/{bench_path.name}): one process, "
            f"OMP_NUM_THREADS {threads}, machine load average {load:.1f} at the start, commit "
            f"`{b.get('commit', '?')}`:"
            if load is not None
            else f"`graspmix_cli benchmark` ({bench_path}):",
            "",
            runtime_table_md(b),
            "",
            f"The paper: GMM nearly 5x faster. Here: {b['ratio_kde_over_gmm']['total']:.2f}x in total.",
            "",
        ]
    for e in extra:
        x = json.loads(e.read_text())
        xp = x["provenance"]
        out += [
            f"With `--closing {x['protocol'].get('closing', 'full')}` (`{xp.get('command', '?')}`, commit "
            f"`{xp.get('commit', '?')}`, {x['attempts']['done']} of {x['attempts']['expected']} attempts):",
            "",
            success_table(x),
            "",
            f"Against the paper's claim: {verdict(x)}.",
            "",
        ]
    return "\n".join(out).rstrip() + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("summary", type=Path)
    ap.add_argument("--benchmark", type=Path, action="append", default=[], help="benchmark.json files to list")
    ap.add_argument("--extra", type=Path, action="append", default=[], help="more runs' summary.json to list")
    ap.add_argument("--doc", type=Path, help="write the text between the findings markers of this markdown page")
    args = ap.parse_args()
    text = render(args.summary, args.benchmark, args.extra)
    if args.doc:
        doc = args.doc.read_text()
        pattern = re.compile(r"(<!-- findings:begin -->\n).*?(<!-- findings:end -->)", re.S)
        if not pattern.search(doc):
            sys.exit(f"{args.doc}: no findings markers")
        args.doc.write_text(pattern.sub(lambda m: m.group(1) + text + m.group(2), doc))
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
