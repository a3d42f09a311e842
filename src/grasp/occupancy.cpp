// The occupancy map: OctoMap ray insertion clipped to the region of interest, or a visibility model's views, baked
// into a dense grid.
#include "graspmix/grasp/occupancy.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>

#include <octomap/OcTree.h>

#include "graspmix/core/plane.hpp"

namespace graspmix {

namespace {

void check_settings(const OccupancySettings& s) {
  if (!(s.resolution > 0) || !std::isfinite(s.resolution)) {
    throw std::invalid_argument("occupancy: resolution must be finite and > 0 (m), got " +
                                std::to_string(s.resolution));
  }
  if (!(s.margin >= 0) || !std::isfinite(s.margin)) {
    throw std::invalid_argument("occupancy: margin must be finite and >= 0 (m), got " + std::to_string(s.margin));
  }
  if (s.max_cells <= 0) throw std::invalid_argument("occupancy: max_cells must be > 0");
}

void check_inputs(const Eigen::Ref<const Vec3Array>& points, const Eigen::Ref<const Vec3Array>& viewpoints,
                  const Eigen::Ref<const Vec3Array>& objects) {
  if (points.rows() == 0) throw std::invalid_argument("occupancy: the cloud is empty");
  if (!points.allFinite()) throw std::invalid_argument("occupancy: points contain NaN or infinite values");
  if (viewpoints.rows() != 1 && viewpoints.rows() != points.rows()) {
    throw std::invalid_argument("occupancy: viewpoints must be one (1, 3) or one per point (" +
                                std::to_string(points.rows()) + ", 3), got " + std::to_string(viewpoints.rows()) +
                                " rows");
  }
  if (!viewpoints.allFinite()) throw std::invalid_argument("occupancy: viewpoints contain NaN or infinite values");
  if (!objects.allFinite()) throw std::invalid_argument("occupancy: object points contain NaN or infinite values");
}

/// Clips the segment a -> b to the box [lo, hi]: the part t in [t0, t1] of a + t (b - a) (Liang-Barsky).
bool clip_segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& lo,
                  const Eigen::Vector3d& hi, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const Eigen::Vector3d d = b - a;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-15) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

octomap::point3d to_point(const Eigen::Vector3d& p) {
  return octomap::point3d(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
}

/// Every ray's cells inside [lo, hi]: crossed cells free, the cell of its point (when inside) occupied.
/// One ray per (point's half cell, viewpoint): the cloud is voxelised on the way in.
struct RayCells {
  octomap::KeySet free, occupied;
  std::int64_t n_rays = 0;
};

RayCells cast_rays(const octomap::OcTree& tree, const Eigen::Ref<const Vec3Array>& points,
                   const Eigen::Ref<const Vec3Array>& viewpoints, const Eigen::Vector3d& lo,
                   const Eigen::Vector3d& hi) {
  RayCells out;
  std::map<std::array<double, 3>, std::uint64_t> origin_ids;
  std::unordered_set<std::uint64_t> seen;
  octomap::KeyRay ray;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    const Eigen::Vector3d o = viewpoints.row(viewpoints.rows() == 1 ? 0 : i).transpose();
    double t0 = 0, t1 = 1;
    if (!clip_segment(o, p, lo, hi, t0, t1)) continue;
    octomap::OcTreeKey end_key;
    const bool end_in_tree = tree.coordToKeyChecked(to_point(p), end_key);
    const std::uint64_t origin =
        origin_ids.emplace(std::array<double, 3>{o.x(), o.y(), o.z()}, origin_ids.size()).first->second;
    // De-duplicated on half cells: one ray per whole cell leaves cells between neighbouring rays unvisited
    // (a ray crosses a cell row obliquely), half cells leave none at the density of a depth image.
    if (end_in_tree && origin < (1u << 15)) {
      // The point's cell key (OctoMap's) and which half of the cell it is in, per axis.
      const octomap::point3d q = to_point(p);
      std::uint64_t id = origin;
      for (int k = 0; k < 3; ++k) {
        const double f = static_cast<double>(q(static_cast<unsigned>(k))) / tree.getResolution();
        const std::uint64_t half = f - std::floor(f) >= 0.5 ? 1 : 0;
        id = (id << 17) | (std::uint64_t{end_key[static_cast<unsigned>(k)]} << 1) | half;
      }
      if (!seen.insert(id).second) continue;
    }
    ++out.n_rays;
    const Eigen::Vector3d a = o + t0 * (p - o), b = o + t1 * (p - o);
    if (tree.computeRayKeys(to_point(a), to_point(b), ray)) out.free.insert(ray.begin(), ray.end());
    if (t1 >= 1.0 && end_in_tree) {
      out.occupied.insert(end_key);
    } else {
      octomap::OcTreeKey k;
      if (tree.coordToKeyChecked(to_point(b), k)) out.free.insert(k);  // the ray leaves the region there
    }
  }
  return out;
}

using Dims = Eigen::Matrix<std::int64_t, 3, 1>;

/// Whether a cell's centre c lies less than one cell (h) above the plane: such cells are free (the plane has an
/// exact term of its own in the collision expert, and the table's points would otherwise make the layer just above
/// it solid).
bool in_table_layer(const std::optional<Eigen::Vector4d>& plane, const Eigen::Vector3d& c, double h) {
  return plane && plane->head<3>().dot(c) + (*plane)[3] < h;
}

/// The cells in_table_layer made free.
void free_above_plane(std::vector<std::uint8_t>& cells, const Eigen::Vector3d& origin, double h, const Dims& dims,
                      const std::optional<Eigen::Vector4d>& plane) {
  if (!plane) return;
  for (std::int64_t k = 0; k < dims.z(); ++k)
    for (std::int64_t j = 0; j < dims.y(); ++j)
      for (std::int64_t i = 0; i < dims.x(); ++i) {
        if (in_table_layer(plane, origin + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5), h)) {
          cells[static_cast<std::size_t>((k * dims.y() + j) * dims.x() + i)] =
              static_cast<std::uint8_t>(CellState::Free);
        }
      }
}

/// A plane normalised (throws for a degenerate one).
Eigen::Vector4d normalised_plane(const Eigen::Vector4d& p) {
  const double n = p.head<3>().norm();
  if (!p.allFinite() || !(n > 1e-12)) throw std::invalid_argument("occupancy: the plane's normal must be non-zero");
  return p / n;
}

/// The dense grid over [origin, origin + h dims] from the tree's leaves (a pruned leaf fills all its
/// cells): never reached is unknown. Cells whose centre is less than one cell above the plane are free.
std::vector<std::uint8_t> bake_cells(const octomap::OcTree& tree, const Eigen::Vector3d& origin, double h,
                                     const Dims& dims, const std::optional<Eigen::Vector4d>& plane) {
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(dims.prod()), static_cast<std::uint8_t>(CellState::Unknown));
  const Eigen::Vector3d top = origin + h * dims.cast<double>();
  const octomap::point3d pmin = to_point(origin.array() + 0.25 * h), pmax = to_point(top.array() - 0.25 * h);
  for (auto it = tree.begin_leafs_bbx(pmin, pmax), end = tree.end_leafs_bbx(); it != end; ++it) {
    const auto state = static_cast<std::uint8_t>(tree.isNodeOccupied(*it) ? CellState::Occupied : CellState::Free);
    const double size = it.getSize();
    const Eigen::Vector3d c(it.getX(), it.getY(), it.getZ());
    const Eigen::Array3d first = ((c.array() - 0.5 * size - origin.array()) / h).round();
    const auto n = static_cast<std::int64_t>(std::llround(size / h));
    const Dims f = first.cast<std::int64_t>().matrix();
    const Dims l0 = f.cwiseMax(0), l1 = (f.array() + n).matrix().cwiseMin(dims);
    for (std::int64_t k = l0.z(); k < l1.z(); ++k)
      for (std::int64_t j = l0.y(); j < l1.y(); ++j)
        for (std::int64_t i = l0.x(); i < l1.x(); ++i)
          cells[static_cast<std::size_t>((k * dims.y() + j) * dims.x() + i)] = state;
  }
  free_above_plane(cells, origin, h, dims, plane);
  return cells;
}

}  // namespace

OccupancyMap::OccupancyMap(const Eigen::Ref<const Vec3Array>& points, const Eigen::Ref<const Vec3Array>& viewpoints,
                           const Eigen::Ref<const Vec3Array>& objects, const std::optional<Eigen::Vector4d>& plane,
                           OccupancySettings settings)
    : settings_(settings), h_(settings.resolution) {
  const auto t_start = std::chrono::steady_clock::now();
  check_settings(settings_);
  check_inputs(points, viewpoints, objects);
  const Eigen::Ref<const Vec3Array>& obj = objects.rows() > 0 ? objects : points;
  objects_lo_ = obj.colwise().minCoeff().transpose();
  objects_hi_ = obj.colwise().maxCoeff().transpose();
  for (Eigen::Index i = 0; i < viewpoints.rows(); ++i) {
    const Eigen::Vector3d v = viewpoints.row(i).transpose();
    if ((v.array() > objects_lo_.array()).all() && (v.array() < objects_hi_.array()).all()) {
      throw std::invalid_argument("occupancy: viewpoint " + std::to_string(i) +
                                  " lies inside the objects' bounding box (a camera sees them from outside; is the "
                                  "cloud in the camera's frame, or the viewpoint missing?)");
    }
  }
  if (plane) plane_ = orient_plane(normalised_plane(*plane), viewpoints, PlaneSide::Mean);  // the cameras' side
  set_region();
  octomap::OcTree tree(h_);
  const RayCells rays = cast_rays(tree, points, viewpoints, region_min(), region_max());
  stats_.n_rays = rays.n_rays;
  // One scan: a cell a ray ends in is occupied, whatever other rays cross it.
  for (const octomap::OcTreeKey& k : rays.free) {
    if (!rays.occupied.count(k)) tree.updateNode(k, false, true);
  }
  for (const octomap::OcTreeKey& k : rays.occupied) tree.updateNode(k, true, true);
  tree.updateInnerOccupancy();
  cells_ = bake_cells(tree, origin_, h_, dims_, plane_);
  finish_cells();
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
}

OccupancyMap::OccupancyMap(const VisibilityModel& visibility, const Eigen::Ref<const Vec3Array>& objects,
                           const std::optional<Eigen::Vector4d>& plane, OccupancySettings settings)
    : settings_(settings), h_(settings.resolution) {
  const auto t_start = std::chrono::steady_clock::now();
  check_settings(settings_);
  if (visibility.n_views() == 0) throw std::invalid_argument("occupancy: the visibility model has no view");
  if (objects.rows() == 0) throw std::invalid_argument("occupancy: no object points to map the region around");
  if (!objects.allFinite()) throw std::invalid_argument("occupancy: object points contain NaN or infinite values");
  objects_lo_ = objects.colwise().minCoeff().transpose();
  objects_hi_ = objects.colwise().maxCoeff().transpose();
  if (plane) {
    Vec3Array sensors(visibility.n_views(), 3);
    for (int i = 0; i < visibility.n_views(); ++i) sensors.row(i) = visibility.view(i).T_world_sensor.translation();
    plane_ = orient_plane(normalised_plane(*plane), sensors, PlaneSide::Mean);  // the sensors' side is free
  }
  set_region();
  // Only the cells above the table's layer are asked about (the others are free); each cell's centre asked where
  // it is made (no table of centres: a region holds up to millions of cells).
  cells_.assign(static_cast<std::size_t>(dims_.prod()), static_cast<std::uint8_t>(CellState::Free));
  const double tol = visibility.settings().surface_tolerance;
  const std::int64_t slices = dims_.z() * dims_.y();
#pragma omp parallel if (dims_.prod() >= 4096)
  {
    // A row of cells along x at a time: the centres above the table's layer, then their distances in one call.
    Vec3Array centres(dims_.x(), 3);
    std::vector<std::int64_t> column(static_cast<std::size_t>(dims_.x()));
    Eigen::VectorXd x(dims_.x());
#pragma omp for schedule(static)
    for (std::int64_t kj = 0; kj < slices; ++kj) {
      const std::int64_t k = kj / dims_.y(), j = kj % dims_.y();
      Eigen::Index m = 0;
      for (std::int64_t i = 0; i < dims_.x(); ++i) {
        const Eigen::Vector3d c = origin_ + h_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        if (in_table_layer(plane_, c, h_)) continue;
        centres.row(m) = c.transpose();
        column[static_cast<std::size_t>(m++)] = i;
      }
      visibility.signed_distances_into(centres.topRows(m), x.data());
      for (Eigen::Index r = 0; r < m; ++r) {
        // No view says anything (NaN): free, see the header; else the visibility model's state of the distance.
        const SpaceState st = std::isnan(x[r]) ? SpaceState::SeenFree : state_of_distance(x[r], tol);
        cells_[static_cast<std::size_t>(kj * dims_.x() + column[static_cast<std::size_t>(r)])] =
            static_cast<std::uint8_t>(st == SpaceState::SeenFree  ? CellState::Free
                                      : st == SpaceState::Surface ? CellState::Occupied
                                                                  : CellState::Unknown);
      }
    }
  }
  finish_cells();
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
}

void OccupancyMap::set_region() {
  // The grown box, its corners on OctoMap's cell boundaries (multiples of h).
  const Eigen::Vector3d lo = ((objects_lo_.array() - settings_.margin) / h_).floor() * h_;
  const Eigen::Vector3d hi = ((objects_hi_.array() + settings_.margin) / h_).ceil() * h_;
  dims_ = ((hi - lo) / h_).array().round().cast<std::int64_t>().max(1);
  const double n_cells =
      static_cast<double>(dims_.x()) * static_cast<double>(dims_.y()) * static_cast<double>(dims_.z());
  if (n_cells > static_cast<double>(settings_.max_cells)) {
    throw std::invalid_argument("occupancy: the region needs " + std::to_string(static_cast<std::int64_t>(n_cells)) +
                                " cells at resolution " + std::to_string(h_) + " m, more than max_cells = " +
                                std::to_string(settings_.max_cells) + " (coarsen the resolution or the margin)");
  }
  origin_ = lo;
}

void OccupancyMap::finish_cells() {
  for (const std::uint8_t c : cells_) {
    if (c > static_cast<std::uint8_t>(CellState::Unknown)) throw std::invalid_argument("occupancy: a cell state > 2");
    const auto st = static_cast<CellState>(c);
    (st == CellState::Free ? stats_.n_free : st == CellState::Occupied ? stats_.n_occupied : stats_.n_unknown) += 1;
  }
  build_blocked_sums();
}

OccupancyMap::OccupancyMap(const Eigen::Vector3d& origin, const Eigen::Vector3i& dims, std::vector<std::uint8_t> cells,
                           const Eigen::Vector3d& objects_lo, const Eigen::Vector3d& objects_hi,
                           const std::optional<Eigen::Vector4d>& plane, OccupancySettings settings)
    : settings_(settings),
      h_(settings.resolution),
      origin_(origin),
      objects_lo_(objects_lo),
      objects_hi_(objects_hi),
      cells_(std::move(cells)) {
  const auto t_start = std::chrono::steady_clock::now();
  check_settings(settings_);
  if (!origin.allFinite() || !objects_lo.allFinite() || !objects_hi.allFinite()) {
    throw std::invalid_argument("occupancy: the origin and the objects' box must be finite");
  }
  if ((dims.array() < 1).any()) throw std::invalid_argument("occupancy: dims must be >= 1 along every axis");
  dims_ = dims.cast<std::int64_t>();
  if (static_cast<std::int64_t>(cells_.size()) != dims_.prod()) {
    throw std::invalid_argument("occupancy: " + std::to_string(cells_.size()) + " cells given for dims of " +
                                std::to_string(dims_.prod()));
  }
  if (plane) plane_ = normalised_plane(*plane);
  finish_cells();
  stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
}

template <class Count>
std::vector<std::int64_t> OccupancyMap::summed(Count count) const {
  const std::int64_t nx = dims_.x(), ny = dims_.y(), nz = dims_.z();
  const std::int64_t sx = nx + 1, sy = ny + 1;
  std::vector<std::int64_t> sums(static_cast<std::size_t>(sx * sy * (nz + 1)), 0);
  auto at = [&](std::int64_t i, std::int64_t j, std::int64_t k) -> std::int64_t& {
    return sums[static_cast<std::size_t>((k * sy + j) * sx + i)];
  };
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i) {
        const bool b = count(static_cast<CellState>(cells_[static_cast<std::size_t>((k * ny + j) * nx + i)]));
        at(i + 1, j + 1, k + 1) = (b ? 1 : 0) + at(i, j + 1, k + 1) + at(i + 1, j, k + 1) + at(i + 1, j + 1, k) -
                                  at(i, j, k + 1) - at(i, j + 1, k) - at(i + 1, j, k) + at(i, j, k);
      }
  return sums;
}

void OccupancyMap::build_blocked_sums() {
  blocked_sums_ = summed([this](CellState s) { return blocked(s); });
  unknown_sums_ = summed([](CellState s) { return s == CellState::Unknown; });
}

bool OccupancyMap::any_blocked(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  return any_in(blocked_sums_, lo, hi);
}

bool OccupancyMap::any_unknown(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  return any_in(unknown_sums_, lo, hi);
}

bool OccupancyMap::any_in(const std::vector<std::int64_t>& sums, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi) const {
  // The cells the box touches, clipped to the region (outside it every cell is free).
  const Eigen::Vector3d a = ((lo - origin_) / h_).array().floor(), b = ((hi - origin_) / h_).array().floor();
  std::int64_t l[3], u[3];
  for (int d = 0; d < 3; ++d) {
    if (b[d] < 0 || a[d] >= static_cast<double>(dims_[d])) return false;
    l[d] = static_cast<std::int64_t>(std::max(a[d], 0.0));
    u[d] = static_cast<std::int64_t>(std::min(b[d], static_cast<double>(dims_[d] - 1))) + 1;
  }
  const std::int64_t sx = dims_.x() + 1, sy = dims_.y() + 1;
  auto s = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return sums[static_cast<std::size_t>((k * sy + j) * sx + i)];
  };
  const std::int64_t n = s(u[0], u[1], u[2]) - s(l[0], u[1], u[2]) - s(u[0], l[1], u[2]) - s(u[0], u[1], l[2]) +
                         s(l[0], l[1], u[2]) + s(l[0], u[1], l[2]) + s(u[0], l[1], l[2]) - s(l[0], l[1], l[2]);
  return n > 0;
}

}  // namespace graspmix
