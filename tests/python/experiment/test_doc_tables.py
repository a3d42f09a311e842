"""The tables of docs/experiment.md and docs/one-view.md come from results/: the render commands each page gives
beside them, run again on the stored runs, write the page unchanged."""

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
# page -> the tables (markers) it holds
PAGES = {
    "docs/experiment.md": {"findings", "defaults", "ablation", "heldout", "heldout-paper"},
    "docs/one-view.md": {
        "dev",
        "heldout",
        "four-views",
        "paper",
        "clutter",
        "image-dev",
        "image-heldout",
        "volume-dev",
        "volume-heldout",
        "volume-four-views",
        "volume-clutter",
        "median-dev",
        "median-clutter-dev",
        "median-test60",
        "median-heldout",
        "median-four-views",
        "median-clutter",
        "air-test60",
        "air-dev",
        "air-heldout",
        "air-four-views",
        "air-clutter",
        "lever-test60",
        "lever-dev",
        "lever-clutter-dev",
        "split-clutter",
        "split-heldout",
        "patch-test60",
        "patch-test60-kde",
        "patch-dev",
        "patch-dev-four-views",
        "patch-clutter-dev",
        "patch-heldout",
        "patch-heldout-kde",
        "patch-four-views",
        "patch-clutter",
        "lift-test60",
        "lift-dev",
        "lift-clutter-dev",
        "seeds-test60",
        "seeds-dev",
        "seeds-clutter-dev",
        "seeds-heldout",
        "seeds-four-views",
        "seeds-clutter",
        "floor-test60",
        "floor-test60-kde",
        "floor-dev",
        "floor-four-views-dev",
        "floor-clutter-dev",
        "floor-heldout",
        "floor-four-views",
        "floor-clutter",
        "grasp-depth-heldout",
        "grasp-depth-four-views",
        "grasp-depth-clutter",
        "image-clutter",
    },
}
SCRIPTS = ("scripts/findings_table.py", "scripts/ablation_table.py", "scripts/clutter_table.py")


def render_commands(text: str) -> list[list[str]]:
    """The page's `python scripts/... --doc PAGE` commands, continuation lines joined and the
    shell variables its blocks set (NAME=value lines) expanded."""
    commands = []
    for block in re.findall(r"```bash\n(.*?)```", text, re.S):
        variables = {}
        for line in block.replace("\\\n", " ").splitlines():
            if m := re.fullmatch(r"(\w+)=(\S+)", line.strip()):
                variables[m.group(1)] = m.group(2)
                continue
            words = shlex.split(line.split("#")[0])
            if len(words) > 1 and words[0] == "python" and words[1] in SCRIPTS and "--doc" in words:
                commands.append([expand(w, variables) for w in words])
    return commands


def expand(word: str, variables: dict) -> str:
    return re.sub(r"\$(\w+)", lambda v: variables[v.group(1)], word)


@pytest.mark.parametrize("page", sorted(PAGES))
def test_the_render_commands_of_a_page_reproduce_its_tables(tmp_path, page):
    text = (REPO / page).read_text()
    commands = render_commands(text)
    markers = set(re.findall(r"<!-- ([\w-]+):begin -->", text))
    rendered = {c[c.index("--marker") + 1] if "--marker" in c else "findings" for c in commands}
    assert markers == PAGES[page] and rendered == markers
    copy = tmp_path / Path(page).name
    copy.write_text(text)
    for words in commands:
        assert words[words.index("--doc") + 1] == page
        words = [sys.executable, *words[1:]]
        words[words.index("--doc") + 1] = str(copy)
        subprocess.run(words, cwd=REPO, check=True, capture_output=True, text=True)
    assert copy.read_text() == text
