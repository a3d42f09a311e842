// The collision expert W(h): exact point-in-shape depths against a grid index of the cloud, and the
// support plane and the occupancy map through each link shape (grasp/collision_shapes.hpp).
#include "graspmix/grasp/collision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/uniform_grid.hpp"
#include "grasp/collision_geometry.hpp"
#include "grasp/collision_shapes.hpp"
#include "graspmix/core/plane.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/grasp/solid_volume.hpp"

namespace graspmix {

using detail::BoxColumns;
using detail::signed_distance;
using detail::signed_distance_within;

/// The cloud's points in a grid over their bounding box [lo, hi].
struct CollisionExpert::Index {
  Index(const Eigen::Ref<const Vec3Array>& cloud, double cell_size);
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  detail::UniformGrid grid;
};

namespace {

void check_settings(const CollisionSettings& s) {
  if (!(s.beta >= 0) || !std::isfinite(s.beta)) throw std::invalid_argument("beta must be finite and >= 0");
  if (!(s.point_radius >= 0) || !std::isfinite(s.point_radius)) {
    throw std::invalid_argument("point_radius must be finite and >= 0");
  }
  if (!std::isfinite(s.plane_margin)) throw std::invalid_argument("plane_margin must be finite");
  if (!(s.inside_weight >= 0) || !std::isfinite(s.inside_weight)) {
    throw std::invalid_argument("inside_weight must be finite and >= 0");
  }
  if (!(s.contact_tolerance >= 0) || !std::isfinite(s.contact_tolerance)) {
    throw std::invalid_argument("contact_tolerance must be finite and >= 0");
  }
  if (!(s.reference_area > 0) || !std::isfinite(s.reference_area)) {
    throw std::invalid_argument("reference_area must be finite and > 0 (m^2)");
  }
  if (!(s.volume_resolution > 0) || !std::isfinite(s.volume_resolution)) {
    throw std::invalid_argument("volume_resolution must be finite and > 0 (m)");
  }
  if (!(s.unseen_weight >= 0) || !std::isfinite(s.unseen_weight)) {
    throw std::invalid_argument("unseen_weight must be finite and >= 0");
  }
  if (!(s.unseen_margin >= 0) || !std::isfinite(s.unseen_margin)) {
    throw std::invalid_argument("unseen_margin must be finite and >= 0 (m)");
  }
  if (!(s.cell_size >= 0) || !std::isfinite(s.cell_size)) {
    throw std::invalid_argument("cell_size must be finite and >= 0 (0 = automatic)");
  }
}

/// The grid over the cloud's bounding box [lo, hi]: cells of cell_size, or of about one point per cell
/// over the bounding box (a surface cloud then fills a few per cell); at most 4 million cells.
detail::UniformGrid cloud_grid(const Eigen::Ref<const Vec3Array>& cloud, const Eigen::Vector3d& lo,
                               const Eigen::Vector3d& hi, double cell_size) {
  using Grid = detail::UniformGrid;
  const Eigen::Index N = cloud.rows();
  if (N == 0) return Grid(cloud, Eigen::Vector3d::Zero(), 1.0, {1, 1, 1}, Grid::Layout::Dense);
  const Eigen::Vector3d ext = (hi - lo).cwiseMax(1e-6);
  // Thin sides count as 5% of the longest so a flat cloud does not get a needlessly fine grid.
  const Eigen::Vector3d thick = ext.cwiseMax(0.05 * ext.maxCoeff());
  double h = cell_size > 0 ? cell_size : std::cbrt(thick.prod() / static_cast<double>(N));
  h = std::max(h, 1e-4 * ext.maxCoeff());
  auto dims_for = [&](double hh) { return ((ext / hh).array().floor().cast<int>() + 1).matrix().eval(); };
  Eigen::Vector3i dims = dims_for(h);
  while (static_cast<double>(dims[0]) * dims[1] * dims[2] > 4e6) dims = dims_for(h *= 1.5);
  return Grid(cloud, lo, h, {dims[0], dims[1], dims[2]}, Grid::Layout::Dense);
}

/// The plane normalised and, if asked, oriented so the cloud's mean height over it is >= 0 (PlaneSide::Mean).
Eigen::Vector4d checked_plane(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& cloud, bool orient) {
  Eigen::Vector4d p = plane;
  if (!p.allFinite()) throw std::invalid_argument("plane: must be finite");
  const double n = p.head<3>().norm();
  if (!(n > 1e-12)) throw std::invalid_argument("plane: the normal [a, b, c] is zero");
  p /= n;
  return orient ? orient_plane(p, cloud, PlaneSide::Mean) : p;
}

}  // namespace

std::string to_string(CollisionModel model) { return model == CollisionModel::Occupancy ? "occupancy" : "surface"; }

CollisionModel collision_model_from_string(const std::string& name) {
  if (name == "surface") return CollisionModel::Surface;
  if (name == "occupancy") return CollisionModel::Occupancy;
  throw std::invalid_argument("collision model must be 'surface' or 'occupancy', got '" + name + "'");
}

namespace {

/// m: the widest cloud a collision expert indexes. Its grid measures points from the cloud's corner, so over a
/// span of S metres a point's place is known to S * 1e-16 m; 10 km keeps that below a nanometre. A wider cloud
/// is no scene a hand reaches (millimetres read as metres, a stray point): an error.
constexpr double kMaxCloudExtent = 1e4;

/// The cloud's corners, checked to span at most kMaxCloudExtent.
Eigen::Vector3d checked_corner(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const double extent = (hi - lo).maxCoeff();
  if (extent > kMaxCloudExtent) {
    std::ostringstream os;
    os.precision(3);
    os << "cloud: its points span " << extent << " m (more than " << kMaxCloudExtent / 1000
       << " km: are its units metres? is a point far astray?)";
    throw std::invalid_argument(os.str());
  }
  return hi;
}

}  // namespace

CollisionExpert::Index::Index(const Eigen::Ref<const Vec3Array>& cloud, double cell_size)
    : lo(cloud.rows() > 0 ? Eigen::Vector3d(cloud.colwise().minCoeff().transpose()) : Eigen::Vector3d::Zero()),
      hi(cloud.rows() > 0 ? checked_corner(lo, cloud.colwise().maxCoeff().transpose()) : Eigen::Vector3d::Zero()),
      grid(cloud_grid(cloud, lo, hi, cell_size)) {}

/// The hand's collision shapes with their local bounding boxes and (with a plane) their FCL geometry,
/// and the plane as an FCL half-space.

CollisionExpert::CollisionExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& cloud,
                                 const std::optional<Eigen::Vector4d>& plane, CollisionSettings settings,
                                 std::shared_ptr<const OccupancyMap> unseen)
    : hand_(std::move(hand)), settings_(settings), unseen_(std::move(unseen)) {
  if (!hand_) throw std::invalid_argument("hand: expected a Hand, got none");
  check_settings(settings_);
  if (settings_.model != CollisionModel::Surface) {
    throw std::invalid_argument(
        "collision model 'occupancy' is built from an OccupancyMap (the cloud with its "
        "viewpoints), not from points alone");
  }
  require_finite(cloud, "cloud");
  index_ = std::make_shared<const Index>(cloud, settings_.cell_size);
  if (plane) plane_ = checked_plane(*plane, cloud, settings_.orient_plane);
  build_volume(cloud);
}

namespace {

/// The volume's occupied cells kept only where the map of what the cameras saw calls them unknown (behind what they
/// saw): where a camera saw through a column (under a mug's handle, through it) or saw its surface (within the map's
/// tolerance: the points' own depths charge that band), it is free.
OccupancyMap carve_seen_free(const OccupancyMap& volume, const OccupancyMap& seen) {
  const Eigen::Vector3i d = volume.dims();
  const double h = volume.resolution();
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(d.prod()));
  for (int k = 0; k < d.z(); ++k)
    for (int j = 0; j < d.y(); ++j)
      for (int i = 0; i < d.x(); ++i) {
        const Eigen::Vector3d c = volume.region_min() + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        const bool inside =
            (c.array() >= seen.region_min().array()).all() && (c.array() < seen.region_max().array()).all();
        CellState st = volume.state(c);
        if (st == CellState::Occupied && inside && seen.state(c) != CellState::Unknown) st = CellState::Free;
        cells[static_cast<std::size_t>((k * d.y() + j) * d.x() + i)] = static_cast<std::uint8_t>(st);
      }
  return OccupancyMap(volume.region_min(), d, std::move(cells), volume.objects_min(), volume.objects_max(),
                      volume.has_plane() ? std::optional<Eigen::Vector4d>(volume.plane()) : std::nullopt,
                      volume.settings());
}

}  // namespace

void CollisionExpert::build_volume(const Eigen::Ref<const Vec3Array>& cloud) {
  if (settings_.volume && plane_ && cloud.rows() > 0) {
    SolidVolumeSettings vs;
    vs.resolution = settings_.volume_resolution;
    volume_ = std::make_shared<const OccupancyMap>(solid_volume(cloud, *plane_, vs));
    if (unseen_) volume_ = std::make_shared<const OccupancyMap>(carve_seen_free(*volume_, *unseen_));
  }
  auto shapes = std::make_shared<Shapes>(hand_, plane_, settings_.plane_margin);
  if (occupancy_ || volume_ || unseen_) {
    // One set of interior samples for every map: at the finest of their cells.
    constexpr double none = std::numeric_limits<double>::infinity();
    const double h = std::min({occupancy_ ? occupancy_->resolution() : none, volume_ ? volume_->resolution() : none,
                               unseen_ ? unseen_->resolution() : none});
    shapes->sample_interiors(h);
  }
  shapes_ = std::move(shapes);
}

CollisionExpert::CollisionExpert(std::shared_ptr<const Hand> hand, std::shared_ptr<const OccupancyMap> occupancy,
                                 const Eigen::Ref<const Vec3Array>& cloud, const std::optional<Eigen::Vector4d>& plane,
                                 CollisionSettings settings)
    : hand_(std::move(hand)), settings_(settings), occupancy_(std::move(occupancy)), unseen_(occupancy_) {
  if (!hand_) throw std::invalid_argument("hand: expected a Hand, got none");
  if (!occupancy_) throw std::invalid_argument("occupancy: expected an OccupancyMap, got none");
  settings_.model = CollisionModel::Occupancy;
  check_settings(settings_);
  // A map that counts unknown cells as obstacles charges them in full: no soft charge on top.
  if (occupancy_->settings().unknown_is_occupied) unseen_.reset();
  require_finite(cloud, "cloud");
  index_ = std::make_shared<const Index>(cloud, settings_.cell_size);
  if (plane) {
    const Vec3Array centre = (0.5 * (occupancy_->objects_min() + occupancy_->objects_max())).transpose();
    plane_ = checked_plane(*plane, cloud.rows() > 0 ? Vec3Array(cloud) : centre, settings_.orient_plane);
  }
  build_volume(cloud);
}

Eigen::Index CollisionExpert::n_points() const { return index_->grid.size(); }
double CollisionExpert::cell_size() const { return index_->grid.cell_size(); }

namespace {

/// The surface model's D_l term of one shape posed at T (its world box: centre, half): the deepest penetrating point
/// (into `deepest`, a running maximum) and their count (added to `inside`). kFirst: stop at the first penetrating
/// point (`inside` then says whether there is one).
template <bool kFirst = false>
void cloud_term(const CollisionExpert::Index& ix, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                const WorldBox& box_w, double r, double tol, double& deepest, int& inside) {
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d &centre = box_w.centre, &half = box_w.half;
  // The cells under the shape's world box (grown by r), each column cut to the cells its oriented box meets.
  const Eigen::Vector3d lo = (centre - half).array() - r, hi = (centre + half).array() + r;
  if (!((lo.array() <= ix.hi.array()).all() && (hi.array() >= ix.lo.array()).all())) return;
  const detail::UniformGrid::Cell c0 = ix.grid.cell_of(lo), c1 = ix.grid.cell_of(hi);
  const BoxColumns columns(ix.lo, ix.grid.cell_size(), centre, R, sh.half, r);
  // A box's points inside it by more than r need no distance: it is minus their largest excess (the same
  // arithmetic as signed_distance's).
  const bool box = sh.src->type == ShapeType::Box, mesh = sh.src->type == ShapeType::Mesh;
  const bool point_box = box && r == 0.0 && tol >= 0.0;  // then depth > tol implies inside: depth = -excess
  // Order-free: a maximum and a count (kept in locals: the points could alias the outputs).
  double best = deepest;
  int count = 0;
  for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
    for (std::int64_t y = c0[1]; y <= c1[1]; ++y) {
      const auto [b0, e0] = ix.grid.z_run(x, y, c0[2], c1[2]);
      if (b0 == e0) continue;  // no point under the world box in this column: no need to cut it
      std::int64_t z0, z1;
      if (!columns.column(x, y, c0[2], c1[2], z0, z1)) continue;
      const auto [b, e] = ix.grid.z_run(x, y, z0, z1);
      if (point_box) {
        // A box against points: depth = -excess inside; branch-free (the same values as below).
        for (Eigen::Index i = b; i < e; ++i) {
          const Eigen::Vector3d p = R.transpose() * (ix.grid.point(static_cast<int>(i)) - t);
          const double depth = -(p.cwiseAbs() - sh.half).maxCoeff();
          const bool in = depth > tol;
          count += in;
          best = std::max(best, in ? depth : best);
        }
        if (kFirst && count > 0) {
          inside += count;
          return;
        }
        continue;
      }
      for (Eigen::Index i = b; i < e; ++i) {
        const Eigen::Vector3d p = R.transpose() * (ix.grid.point(static_cast<int>(i)) - t);
        // Cheap rejection against the local box before the exact distance.
        const double excess = ((p - sh.centre).cwiseAbs() - sh.half).maxCoeff();
        if (excess >= r) continue;
        if (mesh) {
          // Counted for sure inside the inner proxy; and, inside the proxy box, no deeper than r - its excess:
          // such a point cannot raise the deepest one found, so the hull is not needed for it.
          const detail::ProxyView v = detail::proxy_view(*sh.src, p);
          if (r - v.inner > tol && v.excess <= 0.0 && (kFirst || r - v.excess <= best)) {
            ++count;
            if (kFirst) break;
            continue;
          }
        }
        // Only a distance below r - tol counts: the mesh's proxy and early exit decide the rest (the same values).
        const double depth = r - (box && excess < 0 ? excess : signed_distance_within(*sh.src, p, r - tol));
        if (depth > tol) {
          ++count;
          best = std::max(best, depth);
          if (kFirst) break;
        }
      }
      if (kFirst && count > 0) {
        inside += count;
        return;
      }
    }
  deepest = best;
  inside += count;
}

/// The total of collision.hpp ("total = sum_l (D_l + P_l + inside_weight * n_l)") from its per-link terms.
double total_depth(const Eigen::VectorXd& cloud_depth, const Eigen::VectorXd& plane_depth,
                   const std::vector<int>& inside, double inside_weight) {
  return cloud_depth.sum() + plane_depth.sum() + inside_weight * std::accumulate(inside.begin(), inside.end(), 0);
}

}  // namespace

void CollisionExpert::evaluate_into(const Eigen::Isometry3d* link_poses, double* cloud_depth, double* plane_depth,
                                    int* points_inside, double* unseen_depth, const bool* skip) const {
  const double tol = settings_.contact_tolerance;
  const Eigen::Index N = index_->grid.size();
  for (const Shapes::Shape& sh : shapes_->shapes) {
    if (skip && skip[sh.link]) continue;
    const Eigen::Isometry3d T = link_poses[sh.link] * sh.src->T_link_shape;
    // The maps' terms, each when the shape's world box touches a cell it charges (else every sample is free).
    const WorldBox box_w = world_box(sh, T);
    const Eigen::Vector3d lo = box_w.centre - box_w.half, hi = box_w.centre + box_w.half;
    if (occupancy_ && settings_.occupied_cells && occupancy_->any_blocked(lo, hi)) {
      cloud_depth[sh.link] +=
          blocked_volume(*occupancy_, sh, T, tol, points_inside[sh.link]) / settings_.reference_area;
    }
    if (unseen_ && settings_.unseen_weight > 0 && unseen_->any_unknown(lo, hi)) {
      unseen_depth[sh.link] += settings_.unseen_weight *
                               unseen_volume(*unseen_, volume_.get(), settings_.unseen_margin, sh, T, tol) /
                               settings_.reference_area;
    }
    if (volume_ && volume_->any_blocked(lo, hi)) {
      cloud_depth[sh.link] += blocked_volume(*volume_, sh, T, tol, points_inside[sh.link]) / settings_.reference_area;
    }
    if (N > 0) {
      cloud_term(*index_, sh, T, box_w, settings_.point_radius, tol, cloud_depth[sh.link], points_inside[sh.link]);
    }
    if (plane_) {
      const double depth = plane_term(*shapes_, sh, T, box_w, *plane_, settings_.plane_margin);
      if (depth > tol) plane_depth[sh.link] = std::max(plane_depth[sh.link], depth);
    }
  }
}

bool CollisionExpert::penetrates(const Eigen::Isometry3d* link_poses) const {
  const double tol = settings_.contact_tolerance;
  const Eigen::Index N = index_->grid.size();
  // evaluate_into's hard terms (the unseen charge never refuses), each stopping at its first penetration.
  for (const Shapes::Shape& sh : shapes_->shapes) {
    const Eigen::Isometry3d T = link_poses[sh.link] * sh.src->T_link_shape;
    const WorldBox box_w = world_box(sh, T);
    const Eigen::Vector3d lo = box_w.centre - box_w.half, hi = box_w.centre + box_w.half;
    if (plane_ && plane_term(*shapes_, sh, T, box_w, *plane_, settings_.plane_margin) > tol) return true;
    if (N > 0) {
      double deepest = 0.0;
      int inside = 0;
      cloud_term<true>(*index_, sh, T, box_w, settings_.point_radius, tol, deepest, inside);
      if (inside > 0) return true;
    }
    if (occupancy_ && settings_.occupied_cells && occupancy_->any_blocked(lo, hi) &&
        any_blocked_sample(*occupancy_, sh, T, tol)) {
      return true;
    }
    if (volume_ && volume_->any_blocked(lo, hi) && any_blocked_sample(*volume_, sh, T, tol)) return true;
  }
  return false;
}

Eigen::Matrix<bool, Eigen::Dynamic, 1> CollisionExpert::collision_free_batch(
    const Eigen::Ref<const PoseArray>& T_world_wrist, const Eigen::Ref<const RowMatrixXd>& q) const {
  Eigen::Matrix<bool, Eigen::Dynamic, 1> out(std::max(T_world_wrist.rows(), q.rows()));
  const Eigen::Index parallel_from = index_->grid.size() == 0 && !occupancy_ && !volume_ ? 4096 : 64;
  const Eigen::Index N = hand_->fk_each(
      T_world_wrist, q, parallel_from,
      [&](Eigen::Index i, const Eigen::VectorXd&, const Eigen::Isometry3d* poses) { out[i] = !penetrates(poses); });
  out.conservativeResize(N);
  return out;
}

CollisionResult CollisionExpert::evaluate(const Eigen::Isometry3d& T_world_wrist,
                                          const Eigen::Ref<const Eigen::VectorXd>& q) const {
  hand_->check_configuration(q);
  const int L = hand_->n_links();
  std::vector<Eigen::Isometry3d> poses(static_cast<size_t>(L));
  const Eigen::VectorXd qq = q;
  hand_->fk_into(T_world_wrist, qq.data(), poses.data());
  CollisionResult res;
  res.cloud_depth = Eigen::VectorXd::Zero(L);
  res.plane_depth = Eigen::VectorXd::Zero(L);
  res.points_inside = Eigen::VectorXi::Zero(L);
  res.unseen_depth = Eigen::VectorXd::Zero(L);
  evaluate_into(poses.data(), res.cloud_depth.data(), res.plane_depth.data(), res.points_inside.data(),
                res.unseen_depth.data());
  const double hard = res.cloud_depth.sum() + res.plane_depth.sum() + settings_.inside_weight * res.points_inside.sum();
  res.total_depth = hard + res.unseen_depth.sum();
  res.log_w = -settings_.beta * res.total_depth;
  res.w = std::exp(res.log_w);
  res.collision_free = hard <= 0.0;
  return res;
}

CollisionBatchResult CollisionExpert::evaluate_batch(const Eigen::Ref<const PoseArray>& T_world_wrist,
                                                     const Eigen::Ref<const RowMatrixXd>& q) const {
  const Eigen::Index n = std::max(T_world_wrist.rows(), q.rows());
  const int L = hand_->n_links();
  CollisionBatchResult out;
  out.cloud_depth = RowMatrixXd::Zero(n, L);
  out.plane_depth = RowMatrixXd::Zero(n, L);
  out.unseen_depth = RowMatrixXd::Zero(n, L);
  out.total_depth.resize(n);
  out.log_w.resize(n);
  out.w.resize(n);
  out.collision_free.resize(n);
  // Small batches (annealing scores ~10 hands at a time) stay on one thread: waking a team costs more
  // than it saves, and its spinning threads stall badly on a loaded machine.
  // A plane alone (the kinematic expert's test) is a fraction of a microsecond per hand: large batches only.
  const Eigen::Index parallel_from = index_->grid.size() == 0 && !occupancy_ && !volume_ && !unseen_ ? 4096 : 64;
  const Eigen::Index N = hand_->fk_each(
      T_world_wrist, q, parallel_from, [&](Eigen::Index i, const Eigen::VectorXd&, const Eigen::Isometry3d* poses) {
        std::vector<int> inside(static_cast<size_t>(L), 0);
        Eigen::VectorXd cd = Eigen::VectorXd::Zero(L), pd = Eigen::VectorXd::Zero(L), ud = Eigen::VectorXd::Zero(L);
        evaluate_into(poses, cd.data(), pd.data(), inside.data(), ud.data());
        out.cloud_depth.row(i) = cd.transpose();
        out.plane_depth.row(i) = pd.transpose();
        out.unseen_depth.row(i) = ud.transpose();
        const double hard = total_depth(cd, pd, inside, settings_.inside_weight);
        out.total_depth[i] = hard + ud.sum();
        out.log_w[i] = -settings_.beta * out.total_depth[i];
        out.w[i] = std::exp(out.log_w[i]);
        out.collision_free[i] = hard <= 0.0;
      });
  if (N != n) {  // an empty side broadcasts to no hands
    out.cloud_depth.conservativeResize(N, Eigen::NoChange);
    out.plane_depth.conservativeResize(N, Eigen::NoChange);
    out.unseen_depth.conservativeResize(N, Eigen::NoChange);
    out.total_depth.conservativeResize(N);
    out.log_w.conservativeResize(N);
    out.w.conservativeResize(N);
    out.collision_free.conservativeResize(N);
  }
  return out;
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> CollisionExpert::total_depth_pair(
    const Eigen::Ref<const PoseArray>& wrists, const Eigen::Ref<const RowMatrixXd>& q,
    const Eigen::Ref<const RowMatrixXd>& q2) const {
  const Eigen::Index n = wrists.rows();
  if (q.rows() != n || q2.rows() != n || q2.cols() != hand_->n_dofs()) {
    throw std::invalid_argument("total_depth_pair: wrists, q and q2 must have the same rows, q2 one column per joint");
  }
  const int L = hand_->n_links();
  std::pair<Eigen::VectorXd, Eigen::VectorXd> out{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  hand_->fk_each(wrists, q, 64, [&](Eigen::Index i, const Eigen::VectorXd&, const Eigen::Isometry3d* poses) {
    std::vector<int> inside(static_cast<size_t>(L), 0);
    Eigen::VectorXd cd = Eigen::VectorXd::Zero(L), pd = Eigen::VectorXd::Zero(L), ud = Eigen::VectorXd::Zero(L);
    evaluate_into(poses, cd.data(), pd.data(), inside.data(), ud.data());
    out.first[i] = total_depth(cd, pd, inside, settings_.inside_weight) + ud.sum();
    // The second configuration: a link posed exactly as in the first (the palm) keeps its terms.
    std::vector<Eigen::Isometry3d> poses2(static_cast<size_t>(L));
    const Eigen::VectorXd qi2 = q2.row(i).transpose();
    hand_->fk_into(pose_from_vector(wrists.row(i).transpose()), qi2.data(), poses2.data());
    std::unique_ptr<bool[]> same(new bool[static_cast<size_t>(L)]);
    for (int l = 0; l < L; ++l) {
      same[l] = poses2[l].matrix() == poses[l].matrix();
      if (!same[l]) cd[l] = pd[l] = ud[l] = inside[l] = 0;
    }
    evaluate_into(poses2.data(), cd.data(), pd.data(), inside.data(), ud.data(), same.get());
    out.second[i] = total_depth(cd, pd, inside, settings_.inside_weight) + ud.sum();
  });
  return out;
}

std::pair<Eigen::VectorXd, Eigen::VectorXd> CollisionExpert::log_w_pair(const Eigen::Ref<const PoseArray>& wrists,
                                                                        const Eigen::Ref<const RowMatrixXd>& q,
                                                                        const Eigen::Ref<const RowMatrixXd>& q2) const {
  auto depth = total_depth_pair(wrists, q, q2);
  depth.first *= -settings_.beta;
  depth.second *= -settings_.beta;
  return depth;
}

Eigen::VectorXd link_signed_distances(const Hand& hand, int link, const Eigen::Isometry3d& T_world_link,
                                      const Eigen::Ref<const Vec3Array>& points) {
  if (link < 0 || link >= hand.n_links()) {
    throw std::invalid_argument("link_signed_distances: link index " + std::to_string(link) + " outside [0, " +
                                std::to_string(hand.n_links()) + ")");
  }
  for (const CollisionShape& s : hand.links()[link].collisions) {
    if (s.type == ShapeType::Mesh && !s.hull_planes) {
      throw std::invalid_argument("link_signed_distances: link '" + hand.link_names()[link] +
                                  "' has a mesh read without geometry");
    }
  }
  Eigen::VectorXd out = Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  for (const CollisionShape& s : hand.links()[link].collisions) {
    const Eigen::Isometry3d T_shape_world = (T_world_link * s.T_link_shape).inverse();
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      out[i] = std::min(out[i], signed_distance(s, T_shape_world * Eigen::Vector3d(points.row(i).transpose())));
    }
  }
  return out;
}

}  // namespace graspmix
