"""Writes data/examples/contacts.npy: seeded synthetic contact data x = (p, log q, r) in two clusters,
the shape of what a finger's contact model is fitted to (a face cluster and an edge cluster).

    python3 scripts/make_example_data.py
"""

from pathlib import Path

import numpy as np

rng = np.random.default_rng(2019)
face = np.hstack(
    [
        rng.normal([0.0, 0.0, 0.02], 0.004, (300, 3)),
        rng.normal([0.0, 0.0, 0.1], 0.05, (300, 3)),
        rng.normal([0.003, 0.001], 0.001, (300, 2)),
    ]
)
edge = np.hstack(
    [
        rng.normal([0.03, 0.0, 0.015], 0.003, (120, 3)),
        rng.normal([0.3, -0.2, 0.1], 0.05, (120, 3)),
        rng.normal([0.035, 0.004], 0.004, (120, 2)),
    ]
)
X = np.vstack([face, edge])
rng.shuffle(X)
out = Path(__file__).resolve().parent.parent / "data" / "examples" / "contacts.npy"
out.parent.mkdir(parents=True, exist_ok=True)
np.save(out, X)
print(f"wrote {out} {X.shape}")
