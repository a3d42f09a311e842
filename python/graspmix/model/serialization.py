"""Densities and configuration-model settings to and from the JSON of a model file."""

from __future__ import annotations

import numpy as np

from .. import _core

CONFIG_KEYS = ("beta", "n_kernels", "alpha", "bandwidth", "min_bandwidth")


def density_to_json(d) -> dict:
    if d.kind == "gmm":
        j = d.joint
        return {
            "kind": "gmm",
            "reference": d.reference.tolist(),
            "weights": j.weights_.tolist(),
            "means": j.means_.tolist(),
            "covariances": j.covariances_.tolist(),
        }
    return {
        "kind": "kde",
        "position_bandwidth": d.position_bandwidth,
        "orientation_bandwidth": d.orientation_bandwidth,
        "feature_bandwidth": d.feature_bandwidth.tolist(),
        "poses": np.hstack([d.positions, d.orientations]).tolist(),
        "features": d.features.tolist(),
        "weights": d.weights.tolist(),
    }


def density_from_json(data: dict, where: str):
    try:
        kind = data["kind"]
        if kind == "gmm":
            joint = _core.GaussianMixture.from_parameters(
                np.asarray(data["weights"], float),
                np.asarray(data["means"], float),
                np.asarray(data["covariances"], float),
            )
            return _core.PoseMixture.from_parameters(np.asarray(data["reference"], float), joint)
        if kind == "kde":
            kde = _core.PoseKDE(
                position_bandwidth=float(data["position_bandwidth"]),
                orientation_bandwidth=float(data["orientation_bandwidth"]),
                feature_bandwidth=np.asarray(data["feature_bandwidth"], float),
            )
            poses = np.asarray(data["poses"], float)
            feats = np.asarray(data["features"], float).reshape(len(poses), -1)
            return kde.fit(poses, feats, np.asarray(data["weights"], float))
        raise ValueError(f"unknown density kind {kind!r}")
    except KeyError as e:
        raise ValueError(f"{where}: density misses field {e}") from None
    except (TypeError, ValueError) as e:
        raise ValueError(f"{where}: {e}") from None


def config_settings(d: dict) -> "_core.ConfigModelSettings":
    s = _core.ConfigModelSettings()
    for k, v in d.items():
        if k not in CONFIG_KEYS:
            raise ValueError(f"unknown configuration-model setting {k!r} (known: {', '.join(CONFIG_KEYS)})")
        setattr(s, k, v)
    return s


def config_dict(s) -> dict:
    return {k: getattr(s, k) for k in CONFIG_KEYS}
