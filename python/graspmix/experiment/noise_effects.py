"""What depth noise does inside the pipeline (issue 16): per noise setting and method, the curvature features
of the query cloud, how the contact models' feature densities M_i(r) spread their weight over its points, the
spread of the query densities Q_i, and the frame jitter the weighted points carry.

Every cloud is acquired as the experiment acquires it (Protocol.acquisition_seed, crop_above_plane) with the
noise model on, off, or one of its two terms alone; the features, M_i(r) and Q_i are those the synthesis
computes (segment_query, the same segmentation and completion; object_surface, the synthesis' own
_core.object_surface; GraspSynthesizer.query_densities with the synthesis' settings and seed). A unit is one (object, trial, setting); the summary takes medians and quartiles over units.

    from graspmix.experiment import noise_effects as ne
    p = Protocol(objects=test_objects(), trials=2)
    result = ne.run_study(p, {"gmm": GraspModel.load(...), "kde": GraspModel.load(...)})
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .. import _core
from ..io.checks import check_float, check_int, quote
from ..model import GraspModel
from ..model.demonstration import Demonstration
from ..model.options import SynthesisOptions
from ..model.scene_synthesis import object_surface, segment_query
from .attempt import acquire_unit
from .protocol import SUPPORT_PLANE, Protocol, derive_seed

_FULL = Protocol  # its defaults: the paper's sigma_p (px) and sigma_d (m), read from AcquisitionSettings
# setting -> (pixel_noise_std, depth_noise_std), None: the noise model off (the experiment's clean clouds).
NOISE_SETTINGS = {
    "clean": None,
    "lateral": (_FULL.pixel_noise_std, 0.0),
    "depth": (0.0, _FULL.depth_noise_std),
    "full": (_FULL.pixel_noise_std, _FULL.depth_noise_std),
}
# The condition whose synthesis seed a setting's query densities use: the experiment's A (clean) and B (noise).
SEED_CONDITION = {"clean": "A", "lateral": "B", "depth": "B", "full": "B"}
TOP_FRACTION = 0.1  # the share of points whose weight top_weight_fraction sums
SPREAD_SAMPLES = 500  # poses drawn from each query density to measure its spread
MEASURES = (
    "effective_fraction",  # exp(entropy of M_i(r) over the points) / points
    "effective_points",  # exp(entropy of M_i(r) over the points): noise adds points, so the count too
    "top10_weight",  # the share of M_i(r)'s weight on the top 10% of points
    "jitter_mean",  # rad, the jitter angle's mean weighted by M_i(r)
    "jitter_undetermined",  # the share of M_i(r)'s weight on points with jitter angle > pi/2
    "weighted_k1",  # the median of k1 over the points weighted by M_i(r): which curvature M_i picks
    "max_log_density",  # max over the points of log M_i(r): how well the best point matches the demonstration
    "query_spread",  # m, RMS distance of the query density's samples from their mean
    "query_means_spread",  # m, weighted RMS distance of its components' (kernels') positions from their mean
    "query_components",  # exp(entropy of its component weights) (GMM; KDE: of its kernel weights)
)
# log10 of k1, k2 (dimensionless PCL curvatures; a synthetic flat face gives ~1e-11): smaller go in the first bin.
LOG_CURVATURE_BINS = np.linspace(-12.0, 0.0, 97)
FLAT_K1 = 1e-3  # query points with k1 below this count as flat (flat_fraction)
# log10 of the jitter angle (rad): it spans pi exp(-100) ~ 1e-43 to pi; smaller than 1e-8 rad go in the first bin.
LOG_JITTER_BINS = np.linspace(-8.0, math.log10(math.pi), 69)


# ---- measures of one weight vector / cloud -------------------------------------------------------------------


def normalised_weights(log_weights) -> np.ndarray:
    """Weights proportional to exp(log_weights), summing to 1 (all -inf: uniform, as the sampler does)."""
    lw = np.asarray(log_weights, dtype=float).ravel()
    if lw.size == 0:
        raise ValueError("log_weights: empty")
    if np.any(np.isnan(lw)) or np.any(lw == np.inf):
        raise ValueError("log_weights: contains NaN or +inf")
    m = lw.max()
    w = np.ones_like(lw) if not np.isfinite(m) else np.exp(lw - m)
    return w / w.sum()


def _checked_weights(weights) -> np.ndarray:
    w = np.asarray(weights, dtype=float).ravel()
    if w.size == 0:
        raise ValueError("weights: empty")
    if not np.all(np.isfinite(w)) or np.any(w < 0) or not w.sum() > 0:
        raise ValueError("weights: must be finite, non-negative and not all zero")
    return w / w.sum()


def effective_number(weights) -> float:
    """exp(entropy) of the normalised weights: N for N equal weights, 1 for one non-zero weight."""
    w = _checked_weights(weights)
    nz = w[w > 0]
    return float(np.exp(-np.sum(nz * np.log(nz))))


def effective_fraction(weights) -> float:
    """effective_number / the number of weights, in (0, 1]."""
    return effective_number(weights) / np.asarray(weights).size


def top_weight_fraction(weights, share: float = TOP_FRACTION) -> float:
    """The share of the total weight on the ceil(share * N) heaviest points (>= share; 1 when one point has it)."""
    check_float(share, "share", gt=0.0, hi=1.0)
    w = np.sort(_checked_weights(weights))[::-1]
    return float(w[: max(1, math.ceil(share * w.size))].sum())


def jitter_angles(curvatures, sharpness: float) -> np.ndarray:
    """The query densities' jitter size pi exp(-s ((k1 - k2) / k1)^2) per point (QuerySettings.jitter_sharpness;
    k1 <= 1e-12 counts as isotropic, angle pi, as the synthesiser does)."""
    k = np.asarray(curvatures, dtype=float)
    if k.ndim != 2 or k.shape[1] < 2:
        raise ValueError(f"curvatures: expected shape (N, 2), got {k.shape}")
    check_float(sharpness, "sharpness", 0.0)
    k1, k2 = k[:, 0], k[:, 1]
    rel = np.where(k1 > 1e-12, (k1 - k2) / np.where(k1 > 1e-12, k1, 1.0), 0.0)
    return math.pi * np.exp(-sharpness * rel**2)


def weighted_rms_spread(positions, weights=None) -> float:
    """sqrt(sum_j w_j |x_j - mean_w|^2): the RMS distance from the weighted mean (m)."""
    x = np.asarray(positions, dtype=float)
    if x.ndim != 2 or len(x) == 0:
        raise ValueError(f"positions: expected a non-empty (N, d) array, got shape {x.shape}")
    w = np.full(len(x), 1.0 / len(x)) if weights is None else _checked_weights(weights)
    if w.size != len(x):
        raise ValueError(f"weights: {w.size} for {len(x)} positions")
    mean = w @ x
    return float(np.sqrt(w @ np.sum((x - mean) ** 2, axis=1)))


# ---- one acquisition ----------------------------------------------------------------------------------------


def check_setting(setting: str) -> None:
    if setting not in NOISE_SETTINGS:
        raise ValueError(f"setting must be one of {', '.join(NOISE_SETTINGS)}, got {quote(setting)}")


def acquire_setting(p: Protocol, obj: str, trial: int, setting: str, stds: tuple | None = None):
    """The object's cloud as the experiment acquires it (attempt.acquire_unit: its seed and crop), under a noise
    setting; stds (pixel, depth) overrides the setting's standard deviations (for tests)."""
    check_setting(setting)
    stds = NOISE_SETTINGS[setting] if stds is None else stds
    if stds is not None:
        p = dataclasses.replace(p, pixel_noise_std=stds[0], depth_noise_std=stds[1])
    return acquire_unit(p, obj, trial, noise=stds is not None)


@dataclass
class QuerySurface:
    """The surface features the synthesis computes for its largest target, and how many targets there were."""

    surface: object  # _core.SurfaceCloud
    n_targets: int
    n_points: int  # of the acquired (cropped) cloud


def query_surface(model: GraspModel, acq, opts: SynthesisOptions) -> QuerySurface:
    """The scene and the surface features of its largest object as GraspModel.synthesize computes them (segment_query,
    object_surface)."""
    scene = segment_query((acq.points, acq.viewpoints), np.asarray(SUPPORT_PLANE), opts, model.features)
    if not scene.objects:
        raise ValueError("the segmentation found no object")
    largest = scene.select("largest")[0]
    return QuerySurface(object_surface(scene, largest, model.features), len(scene.objects), len(acq.points))


# ---- the measures of one model on one surface ---------------------------------------------------------------


def contact_log_densities(model: GraspModel, curvatures) -> dict:
    """link name -> log M_i(r) of every point (normalised: the query densities' resampling weights)."""
    r = np.asarray(curvatures, dtype=float)
    return {m.link_name: np.asarray(m.density.feature_log_density(r)) for m in model.synthesizer.contact_models}


def weighted_median(x, weights) -> float:
    """The smallest x whose cumulative weight reaches half the total."""
    x = np.asarray(x, dtype=float).ravel()
    w = _checked_weights(weights)
    if w.size != x.size:
        raise ValueError(f"weights: {w.size} for {x.size} values")
    order = np.argsort(x, kind="stable")
    c = np.cumsum(w[order])
    return float(x[order][min(np.searchsorted(c, 0.5 * c[-1]), x.size - 1)])


def query_measures(density, seed: int, n: int = SPREAD_SAMPLES) -> dict:
    """Spread of one query density: of n samples' positions, of its components' (kernels') positions, and
    the effective number of its components."""
    samples = np.asarray(density.sample(n, None, seed))
    if density.kind == "gmm":
        weights, centres = np.asarray(density.joint.weights_), np.asarray(density.joint.means_)[:, :3]
    else:
        weights, centres = np.asarray(density.weights), np.asarray(density.positions)
    return {
        "query_spread": weighted_rms_spread(samples[:, :3]),
        "query_means_spread": weighted_rms_spread(centres, weights),
        "query_components": effective_number(weights),
    }


def model_measures(model: GraspModel, surface, settings, seed: int, spread_seed: int) -> dict:
    """link -> every MEASURES value of one model on one query surface; settings: the synthesis'
    SynthesizerSettings (its query settings and seed give the query densities the synthesis fits). Also
    "_jitter": link -> (angles, weights) for the histograms."""
    frames, curv = np.asarray(surface.frames), np.asarray(surface.curvatures)
    angles = jitter_angles(curv, settings.query.jitter_sharpness)
    query = model.synthesizer.query_densities(frames, curv, settings.query, seed)
    out, jitter = {}, {}
    for (link, logm), q in zip(contact_log_densities(model, curv).items(), query):
        if q.link_name != link:
            raise RuntimeError(f"query density of {q.link_name} where {link} was expected")
        w = normalised_weights(logm)
        out[link] = {
            "effective_fraction": effective_fraction(w),
            "effective_points": effective_number(w),
            "top10_weight": top_weight_fraction(w),
            "jitter_mean": float(w @ angles),
            "jitter_undetermined": float(w[angles > math.pi / 2].sum()),
            "weighted_k1": weighted_median(curv[:, 0], w),
            "max_log_density": float(np.max(logm)),
            **query_measures(q.density, derive_seed(spread_seed, link)),
        }
        jitter[link] = (angles, w)
    out["_jitter"] = jitter
    return out


# ---- the demonstration's contact features -------------------------------------------------------------------


def demonstration_contacts(model: GraspModel, demo_path=None) -> dict:
    """link -> (features r (M, 2), contact weights (M,)) of the demonstration's contact points, through the
    features the model was learnt with (default: the model's first type's demonstration)."""
    path = demo_path or model.demo
    if path is None:
        raise ValueError("demo_path: the model names no demonstration; give one")
    d = Demonstration.load(path)
    ls = model.learn_settings
    surface, _ = model.features.surface(d.cloud, remove_plane=False, seed=int(ls.get("seed", 0)))
    contact = _core.ContactSettings()
    contact.max_distance = ls.get("max_distance", contact.max_distance)
    contact.lambda_ = ls.get("contact_lambda", contact.lambda_)
    out = {}
    for m in model.synthesizer.contact_models:
        cd = _core.contact_data(
            model.hand, m.link, d.T_world_wrist, d.grasp_joints, surface.frames, surface.curvatures, contact
        )
        out[m.link_name] = (np.asarray(cd.r), np.asarray(cd.weights))
    return out


# ---- the study ----------------------------------------------------------------------------------------------


def log_curvatures(curvatures) -> np.ndarray:
    """log10 of the first two features, clipped into LOG_CURVATURE_BINS (a zero into the first bin)."""
    k = np.maximum(np.asarray(curvatures, dtype=float)[:, :2], 1e-300)
    return np.clip(np.log10(k), LOG_CURVATURE_BINS[0], LOG_CURVATURE_BINS[-1] - 1e-9)


class Histograms:
    """Pooled histograms: k1 and k2 of the query points per setting (each unit's points weigh 1 in total) and
    the M_i(r)-weighted jitter angle per setting and method (each unit and link weighs 1)."""

    def __init__(self, settings, methods):
        n_k, n_j = len(LOG_CURVATURE_BINS) - 1, len(LOG_JITTER_BINS) - 1
        self.k = {s: np.zeros((2, n_k)) for s in settings}
        self.jitter = {s: {m: np.zeros(n_j) for m in methods} for s in settings}

    def add_features(self, setting: str, curvatures) -> None:
        k = log_curvatures(curvatures)
        for i in range(2):
            self.k[setting][i] += np.histogram(k[:, i], LOG_CURVATURE_BINS)[0] / len(k)

    def add_jitter(self, setting: str, method: str, angles, weights) -> None:
        a = np.clip(np.log10(np.maximum(angles, 1e-300)), LOG_JITTER_BINS[0], LOG_JITTER_BINS[-1] - 1e-12)
        self.jitter[setting][method] += np.histogram(a, LOG_JITTER_BINS, weights=weights)[0]

    def to_json(self) -> dict:
        return {
            "log10_curvature_bins": LOG_CURVATURE_BINS.tolist(),
            "log10_jitter_bins": LOG_JITTER_BINS.tolist(),
            "k1": {s: v[0].tolist() for s, v in self.k.items()},
            "k2": {s: v[1].tolist() for s, v in self.k.items()},
            "jitter": {s: {m: v.tolist() for m, v in d.items()} for s, d in self.jitter.items()},
        }


def unit_measures(p: Protocol, models: dict, obj: str, trial: int, setting: str, hist: Histograms) -> dict:
    """One unit's row: the cloud's and surface's sizes and, per method, per link and averaged over links,
    every MEASURES value; adds its features and jitter to hist."""
    acq = acquire_setting(p, obj, trial, setting)
    seed = p.synthesis_seed(obj, trial, SEED_CONDITION[setting])
    opts = p.attempt_options(obj, trial, SEED_CONDITION[setting])
    row = {"object": obj, "trial": trial, "setting": setting, "synthesis_seed": seed, "methods": {}}
    surfaces = {}
    for method, model in models.items():
        # The segmentation does not depend on the model (same features settings): computed once if shared.
        key = (model.features.voxel_size, model.features.radius)
        if key not in surfaces:
            surfaces[key] = query_surface(model, acq, opts)
        qs = surfaces[key]
        settings = model.synthesizer_settings(opts)
        spread_seed = derive_seed(p.seed, "noise_effects", obj, trial, setting, method)
        per_link = model_measures(model, qs.surface, settings, seed, spread_seed)
        for angles, w in per_link.pop("_jitter").values():
            hist.add_jitter(setting, method, angles, w / len(model.synthesizer.contact_models))
        mean = {k: float(np.mean([v[k] for v in per_link.values()])) for k in MEASURES}
        row["methods"][method] = {"mean_over_links": mean, "links": per_link}
    qs = next(iter(surfaces.values()))
    row.update(n_points=qs.n_points, n_surface=len(qs.surface.points), n_targets=qs.n_targets)
    hist.add_features(setting, qs.surface.curvatures)
    k = np.asarray(qs.surface.curvatures)
    row["median_k1"], row["median_k2"] = (float(x) for x in np.median(k[:, :2], axis=0))
    row["flat_fraction"] = float(np.mean(k[:, 0] < FLAT_K1))
    return row


def quartiles(values) -> dict:
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], dtype=float)
    if v.size == 0:
        return {"median": None, "q1": None, "q3": None, "n": 0}
    q1, med, q3 = np.percentile(v, [25, 50, 75])
    return {"median": float(med), "q1": float(q1), "q3": float(q3), "n": int(v.size)}


SURFACE_KEYS = ("n_points", "n_surface", "n_targets", "median_k1", "median_k2", "flat_fraction")


def summarise(rows: list[dict], settings, methods) -> dict:
    """setting -> method -> measure -> quartiles over units (of the mean over links), plus per link, and the
    surfaces' sizes and median curvatures per setting."""
    out = {}
    for s in settings:
        ok = [r for r in rows if r["setting"] == s and "error" not in r]
        entry = {k: quartiles([r[k] for r in ok]) for k in SURFACE_KEYS}
        entry["errors"] = sum(1 for r in rows if r["setting"] == s and "error" in r)
        for m in methods:
            mm = [r["methods"][m] for r in ok]
            links = sorted({lk for x in mm for lk in x["links"]})
            entry[m] = {k: quartiles([x["mean_over_links"][k] for x in mm]) for k in MEASURES}
            entry[m]["by_link"] = {
                lk: {k: quartiles([x["links"][lk][k] for x in mm if lk in x["links"]]) for k in MEASURES}
                for lk in links
            }
        out[s] = entry
    return out


def run_study(p: Protocol, models: dict, settings=tuple(NOISE_SETTINGS), progress=None) -> dict:
    """Every (object, trial, setting) unit of the protocol: {"units": rows, "summary", "histograms"}. A unit
    that fails (no object segmented, too few points) is a row with its "error". progress: called with 1
    after each unit."""
    if not models or any(not isinstance(m, GraspModel) for m in models.values()):
        raise ValueError(f"models must be a non-empty dict method -> GraspModel, got {quote(models)}")
    if isinstance(settings, str) or not settings:
        raise ValueError(f"settings must be a non-empty list of {', '.join(NOISE_SETTINGS)}")
    for s in settings:
        check_setting(s)
    check_int(p.trials, "trials", 1)
    hist, rows = Histograms(settings, models), []
    for obj in p.objects:
        for trial in range(p.trials):
            for s in settings:
                try:
                    rows.append(unit_measures(p, models, obj, trial, s, hist))
                except (ValueError, RuntimeError) as e:
                    rows.append({"object": obj, "trial": trial, "setting": s, "error": " ".join(str(e).split())})
                if progress is not None:
                    progress(1)
    return {
        "settings": list(settings),
        "methods": list(models),
        "units": rows,
        "summary": summarise(rows, settings, list(models)),
        "histograms": hist.to_json(),
    }
