// The unseen side of one object, completed by the rule of perception/completion.hpp.
#include "graspmix/perception/completion.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/parallel_rows.hpp"
#include "perception/completion_shapes.hpp"

namespace graspmix {

namespace {

using detail::Shape;
using detail::TableFrame;

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("complete_object: " + what); }

/// The viewpoint nearest to the points' centroid; throws unless every view's sensor is above the plane.
Eigen::Vector3d check_input(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector4d& plane,
                            const VisibilityModel& vis) {
  if (P.rows() == 0) bad("points: no point");
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    if (!P.row(i).allFinite()) bad("points: row " + std::to_string(i) + " is not finite");
  if (!plane.allFinite()) bad("plane: not finite");
  if (std::abs(plane.head<3>().norm() - 1.0) > 1e-6) bad("plane: (a, b, c) is not a unit normal (degenerate plane?)");
  if (vis.n_views() == 0) bad("visibility: the model has no view");
  const Eigen::Vector3d centroid = P.colwise().mean().transpose();
  Eigen::Vector3d nearest = Eigen::Vector3d::Zero();
  double best = std::numeric_limits<double>::infinity();
  for (int v = 0; v < vis.n_views(); ++v) {
    const Eigen::Vector3d e = vis.view(v).T_world_sensor.translation();
    const double height = plane.head<3>().dot(e) + plane[3];
    if (!(height > 0))
      bad("plane: the viewpoint of view " + std::to_string(v) + " is in or below the plane (height " +
          std::to_string(height) + " m); the plane must face the cameras");
    if ((e - centroid).norm() < best) best = (e - centroid).norm(), nearest = e;
  }
  std::vector<double> h(static_cast<std::size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) h[static_cast<std::size_t>(i)] = P.row(i).dot(plane.head<3>()) + plane[3];
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
  if (h[h.size() / 2] < 0) bad("points: most lie below the plane (the plane must face the cameras, the object on it)");
  return nearest;
}

/// The warning for an object the border of a pinhole view's image cuts (empty if none does).
std::string border_warning(const Eigen::Ref<const Vec3Array>& P, const VisibilityModel& vis, double margin) {
  for (int v = 0; v < vis.n_views(); ++v) {
    const ViewInfo& info = vis.view(v);
    if (!info.camera) continue;
    const Eigen::Isometry3d T_camera_world = info.T_world_sensor.inverse();
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector2d uv = info.camera->project(T_camera_world * Eigen::Vector3d(P.row(i).transpose()));
      if (!uv.allFinite()) continue;
      const bool inside = uv.x() >= margin - 0.5 && uv.y() >= margin - 0.5 &&
                          uv.x() <= info.camera->width() - 0.5 - margin &&
                          uv.y() <= info.camera->height() - 0.5 - margin;
      if (!inside)
        return "the object touches the image border of view " + std::to_string(v) +
               ": completed only where the image could have seen";
    }
  }
  return {};
}

/// Fills the fractions, score and acceptance of h from the signed distances d[0, n) of its scored points.
void tally(CompletionHypothesis& h, const double* d, Eigen::Index n, double tol, const CompletionSettings& s) {
  double free = 0, surface = 0, unseen = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isnan(d[i])) continue;
    const SpaceState st = state_of_distance(d[i], tol);
    (st == SpaceState::SeenFree ? free : st == SpaceState::Surface ? surface : unseen) += 1;
  }
  const double known = free + surface + unseen;
  h.known_fraction = n ? known / static_cast<double>(n) : 0.0;
  h.free_fraction = known ? free / known : 0.0;
  h.surface_fraction = known ? surface / known : 0.0;
  h.unseen_fraction = known ? unseen / known : 0.0;
  h.score = h.surface_fraction - s.free_weight * h.free_fraction;
  h.accepted = known > 0 && h.known_fraction >= 0.5 && h.free_fraction <= s.max_free_fraction &&
               h.unseen_fraction >= s.min_unseen_fraction;
}

/// An even subsample of at most k rows.
Vec3Array subsample(const Eigen::Ref<const Vec3Array>& P, int k) {
  const Eigen::Index stride = (P.rows() + k - 1) / k;
  Vec3Array S((P.rows() + stride - 1) / stride, 3);
  for (Eigen::Index i = 0; i < S.rows(); ++i) S.row(i) = P.row(i * stride);
  return S;
}

struct MirrorCandidate {
  double angle, offset;
  CompletionHypothesis h;
};

Eigen::Vector3d mirror_normal(const TableFrame& f, double angle, const Eigen::Vector2d& away) {
  Eigen::Vector2d m(std::cos(angle), std::sin(angle));
  if (m.dot(away) < 0) m = -m;
  return f.world_dir(m, 0.0);
}

/// Scores every (angle, offset) candidate's mirror of the scoring points S in one batch of queries.
void score_mirrors(std::vector<MirrorCandidate>& cands, const TableFrame& f, const Vec3Array& S,
                   const Eigen::Vector2d& away, const VisibilityModel& vis, const CompletionSettings& s) {
  Vec3Array batch(static_cast<Eigen::Index>(cands.size()) * S.rows(), 3);
  for (std::size_t c = 0; c < cands.size(); ++c) {
    const Eigen::Vector3d m = mirror_normal(f, cands[c].angle, away);
    batch.middleRows(static_cast<Eigen::Index>(c) * S.rows(), S.rows()) =
        detail::mirror_shape(S, Vec3Array(), m, cands[c].offset).points;
  }
  const Eigen::VectorXd d = vis.signed_distances(batch);
  for (std::size_t c = 0; c < cands.size(); ++c) {
    tally(cands[c].h, d.data() + static_cast<Eigen::Index>(c) * S.rows(), S.rows(), vis.settings().surface_tolerance,
          s);
    const Eigen::Vector3d m = mirror_normal(f, cands[c].angle, away);
    cands[c].h.kind = CompletionKind::Mirror;
    cands[c].h.plane_or_axis << m, -cands[c].offset;
  }
}

/// The best mirror about either principal axis of the footprint (one per axis), coarse then fine; on a run of
/// equal best offsets the middle one.
std::vector<CompletionHypothesis> search_mirrors(const TableFrame& f, const Vec3Array& S, const VisibilityModel& vis,
                                                 const CompletionSettings& s) {
  const Eigen::Vector2d mid = f.u.colwise().mean().transpose();
  const Eigen::Vector2d away = mid - f.camera;
  const Eigen::Matrix<double, Eigen::Dynamic, 2> c = f.u.rowwise() - mid.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(c.transpose() * c);
  std::vector<CompletionHypothesis> out;
  for (int axis = 0; axis < 2; ++axis) {
    const double a0 = std::atan2(es.eigenvectors()(1, axis), es.eigenvectors()(0, axis));
    const auto offsets = [&](double angle, std::vector<MirrorCandidate>& into, double lo, double hi, double step) {
      for (double o = lo; o <= hi + 1e-12; o += step) into.push_back({angle, o, {}});
    };
    const auto range = [&](double angle) {
      const Eigen::Vector3d m = mirror_normal(f, angle, away);
      const Eigen::Vector2d m2(m.dot(f.e1), m.dot(f.e2));
      const Eigen::VectorXd t = f.u * m2;
      return std::make_pair((t.minCoeff() + t.maxCoeff()) / 2, t.maxCoeff() + s.mirror_max_depth);
    };
    std::vector<MirrorCandidate> coarse;
    for (int k = -s.mirror_angle_steps; k <= s.mirror_angle_steps; ++k) {
      const auto [lo, hi] = range(a0 + k * s.mirror_angle_step);
      offsets(a0 + k * s.mirror_angle_step, coarse, lo, hi, 2 * s.spacing);
    }
    score_mirrors(coarse, f, S, away, vis, s);
    const auto better = [](const MirrorCandidate& x, const MirrorCandidate& y) { return x.h.score < y.h.score; };
    const MirrorCandidate best = *std::max_element(coarse.begin(), coarse.end(), better);
    std::vector<MirrorCandidate> fine;
    for (const double da : {-0.5, 0.0, 0.5})
      offsets(best.angle + da * s.mirror_angle_step, fine, best.offset - 2 * s.spacing, best.offset + 2 * s.spacing,
              s.spacing / 2);
    score_mirrors(fine, f, S, away, vis, s);
    const auto top = std::max_element(fine.begin(), fine.end(), better);
    auto first = top, last = top;  // the run of equal scores at the best angle around the best offset
    while (first != fine.begin() && (first - 1)->angle == top->angle && (first - 1)->h.score >= top->h.score - 1e-9)
      --first;
    while (last + 1 != fine.end() && (last + 1)->angle == top->angle && (last + 1)->h.score >= top->h.score - 1e-9)
      ++last;
    out.push_back(first[(last - first) / 2].h);
  }
  return out;
}

/// The extrusion's columns cut at their first seen-free sample; the hypothesis scored on what is left.
Shape clipped_extrusion(const TableFrame& f, const detail::Footprint& fp, const VisibilityModel& vis,
                        const CompletionSettings& s, CompletionHypothesis& h) {
  std::vector<Eigen::Index> starts;
  const Shape raw = detail::extrusion_shape(f, fp, s.spacing, starts);
  const Eigen::VectorXd d = vis.signed_distances(raw.points);
  const double tol = vis.settings().surface_tolerance;
  std::vector<Eigen::Index> keep;
  for (std::size_t k = 0; k + 1 < starts.size(); ++k)
    for (Eigen::Index i = starts[k]; i < starts[k + 1] && !(d[i] > tol); ++i) keep.push_back(i);
  Shape out;
  out.points.resize(static_cast<Eigen::Index>(keep.size()), 3);
  out.normals.resize(out.points.rows(), 3);
  Eigen::VectorXd dk(out.points.rows());
  for (Eigen::Index j = 0; j < out.points.rows(); ++j) {
    const Eigen::Index i = keep[static_cast<std::size_t>(j)];
    out.points.row(j) = raw.points.row(i);
    out.normals.row(j) = raw.normals.row(i);
    dk[j] = d[i];
  }
  h.kind = CompletionKind::Extrusion;
  tally(h, dk.data(), dk.size(), tol, s);
  // The fallback needs only to add something without a contradiction.
  h.accepted = h.known_fraction > 0 && h.free_fraction <= s.max_free_fraction && h.unseen_fraction > 0;
  return out;
}

/// The cell of p at cell size `spacing`: its indices along x, y and z, offset to stay positive.
std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& p, double spacing) {
  const auto c = [spacing](double x) { return std::llround(x / spacing) + (std::int64_t{1} << 20); };
  return {c(p.x()), c(p.y()), c(p.z())};
}

/// The key of the cell `c` moved by (dx, dy, dz) cells.
std::uint64_t cell_key(const std::array<std::int64_t, 3>& c, int dx = 0, int dy = 0, int dz = 0) {
  return (static_cast<std::uint64_t>(c[0] + dx) << 42) ^ (static_cast<std::uint64_t>(c[1] + dy) << 21) ^
         static_cast<std::uint64_t>(c[2] + dz);
}

/// Whether an observed point (indexed by cells of size `radius`) lies within `radius` of p.
bool near_observed(const Eigen::Vector3d& p, const std::unordered_multimap<std::uint64_t, Eigen::Index>& cells,
                   const Eigen::Ref<const Vec3Array>& P, double radius) {
  const std::array<std::int64_t, 3> c = cell_of(p, radius);  // once: its 27 neighbours are offsets of it
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const auto range = cells.equal_range(cell_key(c, dx, dy, dz));
        for (auto it = range.first; it != range.second; ++it)
          if ((P.row(it->second).transpose() - p).squaredNorm() < radius * radius) return true;
      }
  return false;
}

/// The rows of a winner's points `Q` kept: where the views say Unseen or Surface, min_height above the plane, one per
/// spacing cell, none within observed_clearance of an observed point (P).
std::vector<Eigen::Index> completed_rows(const Vec3Array& Q, const Eigen::Ref<const Vec3Array>& P, const TableFrame& f,
                                         const VisibilityModel& vis, const CompletionSettings& s) {
  std::unordered_multimap<std::uint64_t, Eigen::Index> observed;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    observed.emplace(cell_key(cell_of(P.row(i).transpose(), s.observed_clearance)), i);
  std::unordered_set<std::uint64_t> taken;
  const Eigen::VectorXd d = vis.signed_distances(Q);
  const double tol = vis.settings().surface_tolerance;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < Q.rows(); ++i) {
    const Eigen::Vector3d p = Q.row(i).transpose();
    if (!(std::isfinite(d[i]) && d[i] <= tol) || f.n.dot(p) + f.d < s.min_height) continue;
    if (near_observed(p, observed, P, s.observed_clearance) || !taken.insert(cell_key(cell_of(p, s.spacing))).second)
      continue;
    keep.push_back(i);
  }
  return keep;
}

/// out's points and normals (normalised): the rows `keep` of shape.
void take_rows(const Shape& shape, const std::vector<Eigen::Index>& keep, Completion& out) {
  out.points.resize(static_cast<Eigen::Index>(keep.size()), 3);
  out.normals.resize(out.points.rows(), 3);
  for (Eigen::Index j = 0; j < out.points.rows(); ++j) {
    out.points.row(j) = shape.points.row(keep[static_cast<std::size_t>(j)]);
    out.normals.row(j) = shape.normals.row(keep[static_cast<std::size_t>(j)]).normalized();
  }
}

/// The winner's completed points with their normals (completed_rows). A mirror is made twice: first its points
/// alone, to choose the rows kept, then those rows with their observed points' normals (a mirror keeps a fraction
/// of its points: most of an object's normals would be made for nothing).
void keep_completed(const CompletionHypothesis& win, const Shape& walls, const detail::Circle& circle,
                    const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector3d& viewpoint, const TableFrame& f,
                    const VisibilityModel& vis, const CompletionSettings& s, Completion& out) {
  if (win.kind == CompletionKind::Extrusion) {
    take_rows(walls, completed_rows(walls.points, P, f, vis, s), out);
  } else if (win.kind == CompletionKind::Rotation) {
    const Shape rev =
        detail::revolution_shape(f, circle, detail::observed_normals(P, viewpoint, s.normal_radius), s.spacing);
    take_rows(rev, completed_rows(rev.points, P, f, vis, s), out);
  } else {
    const Eigen::Vector3d m = win.plane_or_axis.head<3>();
    const double o = -win.plane_or_axis[3];
    const std::vector<Eigen::Index> keep =
        completed_rows(detail::mirror_shape(P, Vec3Array(), m, o).points, P, f, vis, s);
    const Vec3Array N = detail::observed_normals(P, viewpoint, s.normal_radius, &keep);
    const Shape kept = detail::mirror_shape(P(keep, Eigen::all), N(keep, Eigen::all), m, o);
    std::vector<Eigen::Index> all(keep.size());
    std::iota(all.begin(), all.end(), 0);
    take_rows(kept, all, out);
  }
}

}  // namespace

void check_completion_settings(const CompletionSettings& s) {
  const auto in = [](double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; };
  const auto need = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("CompletionSettings: ") + what);
  };
  need(in(s.spacing, 1e-4, 0.1), "spacing must be in [0.0001, 0.1] m");
  need(in(s.max_free_fraction, 0, 1), "max_free_fraction must be in [0, 1]");
  need(in(s.min_unseen_fraction, 0, 1), "min_unseen_fraction must be in [0, 1]");
  need(in(s.free_weight, 0, 1e6), "free_weight must be a finite number >= 0");
  need(in(s.mirror_angle_step, 1e-4, 1.0), "mirror_angle_step must be in [0.0001, 1] rad");
  need(s.mirror_angle_steps >= 0 && s.mirror_angle_steps <= 20, "mirror_angle_steps must be in [0, 20]");
  need(in(s.mirror_max_depth, 0, 1.0), "mirror_max_depth must be in [0, 1] m");
  need(in(s.circle_max_rms, 1e-6, 1.0), "circle_max_rms must be in (0, 1] m");
  need(in(s.circle_min_inliers, 0, 1), "circle_min_inliers must be in [0, 1]");
  need(in(s.max_radius, 1e-6, 10.0), "max_radius must be in (0, 10] m");
  need(in(s.normal_radius, s.spacing * (1 + 1e-9), 1.0), "normal_radius must be larger than spacing (and <= 1 m)");
  need(s.max_scoring_points >= 16 && s.max_scoring_points <= 1'000'000, "max_scoring_points must be in [16, 1e6]");
  need(in(s.border_margin, 0, 1e4), "border_margin must be in [0, 10000] px");
  need(in(s.min_height, 0, 1.0), "min_height must be in [0, 1] m");
  need(in(s.rotation_margin, 0, 1.0), "rotation_margin must be in [0, 1]");
  need(in(s.observed_clearance, 1e-4, 0.1), "observed_clearance must be in [0.0001, 0.1] m");
}

Completion complete_object(const Eigen::Ref<const Vec3Array>& points, const Eigen::Vector4d& plane,
                           const VisibilityModel& visibility, const CompletionSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  check_completion_settings(settings);
  const Eigen::Vector3d viewpoint = check_input(points, plane, visibility);
  Completion out;
  out.warning = border_warning(points, visibility, settings.border_margin);
  const TableFrame f(points, plane, viewpoint);
  const detail::Footprint fp(f, 1.5 * settings.spacing);  // coarser than the points: no holes between them
  const Vec3Array S = subsample(points, settings.max_scoring_points);

  std::vector<CompletionHypothesis> mirrors = search_mirrors(f, S, visibility, settings);
  CompletionHypothesis rotation;
  rotation.kind = CompletionKind::Rotation;
  const detail::Circle circle = detail::fit_outline_circle(f, fp, settings);
  if (circle.ok) {
    const Shape rev = detail::revolution_shape(f, circle, Vec3Array(), settings.spacing);
    const Vec3Array R = subsample(rev.points, settings.max_scoring_points);
    const Eigen::VectorXd d = visibility.signed_distances(R);
    tally(rotation, d.data(), d.size(), visibility.settings().surface_tolerance, settings);
    rotation.plane_or_axis << f.world(circle.centre, 0.0), circle.radius;
  }
  CompletionHypothesis extrusion;
  const Shape walls = clipped_extrusion(f, fp, visibility, settings, extrusion);

  const auto by_score = [](const CompletionHypothesis& a, const CompletionHypothesis& b) { return a.score > b.score; };
  std::sort(mirrors.begin(), mirrors.end(), by_score);
  // The rotation wins unless an accepted mirror explains the views better by more than rotation_margin.
  const auto best_mirror = std::find_if(mirrors.begin(), mirrors.end(), [](const auto& m) { return m.accepted; });
  const bool rotation_first = rotation.accepted && (best_mirror == mirrors.end() ||
                                                    rotation.score >= best_mirror->score - settings.rotation_margin);
  if (rotation_first) out.hypotheses.push_back(rotation);
  for (const auto& m : mirrors) out.hypotheses.push_back(m);
  if (circle.ok && !rotation_first) out.hypotheses.push_back(rotation);
  out.hypotheses.push_back(extrusion);
  std::stable_partition(out.hypotheses.begin(), out.hypotheses.end(),
                        [](const CompletionHypothesis& h) { return h.accepted; });
  const CompletionHypothesis& win = out.hypotheses.front();
  if (win.accepted) {
    keep_completed(win, walls, circle, points, viewpoint, f, visibility, settings, out);
    out.kind = win.kind;
    out.score = win.score;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

SceneCompletion complete_scene(const Segmentation& scene, const CompletionSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  SceneCompletion out;
  out.completions.assign(scene.objects.size(), std::nullopt);
  check_completion_settings(settings);  // bad settings are the caller's error, even where nothing is completed
  if (!scene.visibility) {
    out.notes.push_back("no viewpoint given: the unseen side of the objects is not completed");
    return out;
  }
  if (!(scene.plane_found || scene.plane_given)) {
    out.notes.push_back("no support plane: the unseen side of the objects is not completed");
    return out;
  }
  // The objects on threads of their own, largest first (the scene's order) as threads come free; each object's note
  // kept in its own slot, so the notes come in the objects' order.
  const auto n = static_cast<std::int64_t>(scene.objects.size());
  std::vector<std::string> notes(scene.objects.size());
  detail::parallel_rows<detail::NoState>(
      n,
      [&](detail::NoState&, std::int64_t i) {
        const SceneObject& o = scene.objects[static_cast<std::size_t>(i)];
        Vec3Array points(o.rows.size(), 3);
        for (Eigen::Index r = 0; r < o.rows.size(); ++r) points.row(r) = scene.points.row(o.rows[r]);
        std::string& note = notes[static_cast<std::size_t>(i)];
        try {
          Completion c = complete_object(points, scene.plane, *scene.visibility, settings);
          if (!c.warning.empty()) note = "object " + std::to_string(o.index) + ": " + c.warning;
          out.completions[static_cast<std::size_t>(o.index)] = std::move(c);
        } catch (const std::invalid_argument& e) {  // e.g. a camera in the support plane: that object stays as seen
          note = "object " + std::to_string(o.index) + " is not completed: " + e.what();
        }
      },
      detail::RowOrder::AsThreadsFree);
  for (std::string& note : notes)
    if (!note.empty()) out.notes.push_back(std::move(note));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace graspmix
