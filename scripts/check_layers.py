"""Checks the C++ layering of docs/design.md: a file of layer L (include/graspmix/L/, src/L/, tests/cpp/L/)
includes graspmix headers (public ones as graspmix/<layer>/..., private ones of src/ as <layer>/...) of L and of
earlier layers only, and no public header includes a third-party
library other than Eigen. Prints every violation and exits 1 if there is one."""

from __future__ import annotations

import re
import sys
from pathlib import Path

LAYERS = ["core", "density", "perception", "robot", "grasp", "sim"]
# What each layer may use besides itself (docs/design.md, "Layers").
ALLOWED = {
    "core": set(),
    "density": {"core"},
    "perception": {"core"},
    "robot": {"core"},
    "grasp": {"core", "density", "perception", "robot"},
    "sim": {"core", "robot"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
STANDARD_OR_EIGEN = re.compile(r"^(Eigen/|[a-z_]+$|[a-z_]+\.h$)")


def violations(root: Path) -> list[str]:
    out = []
    for top in ("include/graspmix", "src", "tests/cpp"):
        for path in sorted((root / top).rglob("*.[ch]pp")):
            layer = path.relative_to(root / top).parts[0]
            if layer not in ALLOWED:
                out.append(f"{path.relative_to(root)}: not in a layer folder ({', '.join(LAYERS)})")
                continue
            for name in INCLUDE.findall(path.read_text()):
                # graspmix/<layer>/x.hpp, or a private header of src/ as <layer>/x.hpp
                parts = name.split("/")
                private = top != "include/graspmix" and len(parts) > 1 and parts[0] in ALLOWED
                if name.startswith("graspmix/") or private:
                    used = parts[0] if private else parts[1]
                    if used != layer and used not in ALLOWED[layer]:
                        out.append(f"{path.relative_to(root)}: layer '{layer}' includes {name}")
                elif top == "include/graspmix" and not STANDARD_OR_EIGEN.match(name):
                    out.append(f"{path.relative_to(root)}: public header includes third-party <{name}>")
    return out


if __name__ == "__main__":
    found = violations(Path(__file__).resolve().parent.parent)
    for line in found:
        print(line)
    print(f"layers: {len(found)} violation(s)")
    sys.exit(1 if found else 0)
