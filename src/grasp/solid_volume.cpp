// The solid columns of objects standing on a plane, baked into an OccupancyMap (the rule: solid_volume.hpp).
#include "graspmix/grasp/solid_volume.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "graspmix/core/plane.hpp"

namespace graspmix {

namespace {

void check_settings(const SolidVolumeSettings& s) {
  if (!(s.resolution > 0) || !std::isfinite(s.resolution)) {
    throw std::invalid_argument("solid_volume: resolution must be finite and > 0 (m), got " +
                                std::to_string(s.resolution));
  }
  if (!(s.gap >= 0) || !std::isfinite(s.gap)) {
    throw std::invalid_argument("solid_volume: gap must be finite and >= 0 (m), got " + std::to_string(s.gap));
  }
  if (s.max_cells <= 0) throw std::invalid_argument("solid_volume: max_cells must be > 0");
}

constexpr double kEmpty = -std::numeric_limits<double>::infinity();

/// The footprint: cells of size f over [u0, u0 + nu f) x [v0, v0 + nv f) in the plane's frame (e1, e2), each
/// with the top height of its column (kEmpty: no column).
struct Footprint {
  Eigen::Vector3d e1, e2;
  double u0 = 0, v0 = 0, f = 0;
  std::int64_t nu = 0, nv = 0;
  std::vector<double> top;
  double at(std::int64_t i, std::int64_t j) const { return top[static_cast<std::size_t>(j * nu + i)]; }
  /// The top over the plane point with coordinates (u, v), kEmpty outside.
  double top_at(double u, double v) const {
    const double fi = std::floor((u - u0) / f), fj = std::floor((v - v0) / f);
    if (fi < 0 || fj < 0 || fi >= static_cast<double>(nu) || fj >= static_cast<double>(nv)) return kEmpty;
    return at(static_cast<std::int64_t>(fi), static_cast<std::int64_t>(fj));
  }
};

/// The nearest solid top from cell (i, j) stepping (di, dj), at most g cells away; kEmpty if none.
double nearest_top(const Footprint& fp, std::int64_t i, std::int64_t j, int di, int dj, std::int64_t g) {
  for (std::int64_t s = 1; s <= g; ++s) {
    const std::int64_t a = i + s * di, b = j + s * dj;
    if (a < 0 || b < 0 || a >= fp.nu || b >= fp.nv) return kEmpty;
    if (fp.at(a, b) != kEmpty) return fp.at(a, b);
  }
  return kEmpty;
}

/// Fills each empty cell between solid cells within g on both sides along its row or its column, up to the lower
/// of their tops (the higher of the two axes' when both close it).
void close_holes(Footprint& fp, std::int64_t g) {
  if (g <= 0) return;
  std::vector<double> filled = fp.top;
  for (std::int64_t j = 0; j < fp.nv; ++j)
    for (std::int64_t i = 0; i < fp.nu; ++i) {
      if (fp.at(i, j) != kEmpty) continue;
      const double row = std::min(nearest_top(fp, i, j, 1, 0, g), nearest_top(fp, i, j, -1, 0, g));
      const double column = std::min(nearest_top(fp, i, j, 0, 1, g), nearest_top(fp, i, j, 0, -1, g));
      filled[static_cast<std::size_t>(j * fp.nu + i)] = std::max(row, column);  // kEmpty when neither closes it
    }
  fp.top.swap(filled);
}

}  // namespace

OccupancyMap solid_volume(const Eigen::Ref<const Vec3Array>& points, const Eigen::Vector4d& plane,
                          const SolidVolumeSettings& settings) {
  check_settings(settings);
  if (!points.allFinite()) throw std::invalid_argument("solid_volume: points contain NaN or infinite values");
  const double pn = plane.head<3>().norm();
  if (!plane.allFinite() || !(pn > 1e-12))
    throw std::invalid_argument("solid_volume: the plane's normal must be non-zero");
  Eigen::Vector4d pl = plane / pn;
  if (points.rows() > 0) pl = orient_plane(pl, points, PlaneSide::Mean);
  const Eigen::Vector3d n = pl.head<3>();
  const double h = settings.resolution;
  OccupancySettings os;
  os.resolution = h;
  os.margin = 0.0;
  os.unknown_is_occupied = false;
  os.max_cells = settings.max_cells;
  // The points a cell or more above the plane make columns.
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (n.dot(points.row(i).transpose()) + pl[3] >= h) kept.push_back(i);
  if (kept.empty()) {
    return OccupancyMap(Eigen::Vector3d::Zero(), Eigen::Vector3i::Ones(), {0}, Eigen::Vector3d::Zero(),
                        Eigen::Vector3d::Zero(), pl, os);
  }
  Footprint fp;
  fp.e1 = n.unitOrthogonal();
  fp.e2 = n.cross(fp.e1);
  fp.f = 0.5 * h;
  // The points' box and their feet on the plane (the columns' extent in the world), and the footprint's range.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Eigen::Vector3d olo = lo, ohi = hi;
  double umin = lo.x(), umax = hi.x(), vmin = lo.x(), vmax = hi.x();
  for (const Eigen::Index i : kept) {
    const Eigen::Vector3d p = points.row(i).transpose();
    const Eigen::Vector3d foot = p - (n.dot(p) + pl[3]) * n;
    olo = olo.cwiseMin(p);
    ohi = ohi.cwiseMax(p);
    lo = lo.cwiseMin(p).cwiseMin(foot);
    hi = hi.cwiseMax(p).cwiseMax(foot);
    umin = std::min(umin, fp.e1.dot(p));
    umax = std::max(umax, fp.e1.dot(p));
    vmin = std::min(vmin, fp.e2.dot(p));
    vmax = std::max(vmax, fp.e2.dot(p));
  }
  fp.u0 = umin;
  fp.v0 = vmin;
  fp.nu = static_cast<std::int64_t>(std::floor((umax - umin) / fp.f)) + 1;
  fp.nv = static_cast<std::int64_t>(std::floor((vmax - vmin) / fp.f)) + 1;
  if (static_cast<double>(fp.nu) * static_cast<double>(fp.nv) > static_cast<double>(settings.max_cells)) {
    throw std::invalid_argument("solid_volume: the footprint needs more than max_cells cells");
  }
  fp.top.assign(static_cast<std::size_t>(fp.nu * fp.nv), kEmpty);
  for (const Eigen::Index i : kept) {
    const Eigen::Vector3d p = points.row(i).transpose();
    const auto a = std::min(fp.nu - 1, static_cast<std::int64_t>(std::floor((fp.e1.dot(p) - fp.u0) / fp.f)));
    const auto b = std::min(fp.nv - 1, static_cast<std::int64_t>(std::floor((fp.e2.dot(p) - fp.v0) / fp.f)));
    double& t = fp.top[static_cast<std::size_t>(b * fp.nu + a)];
    t = std::max(t, n.dot(p) + pl[3]);
  }
  // Twice: the first pass fills holes along rows and columns, the second the cells where two such lines cross.
  for (int pass = 0; pass < 2; ++pass)
    close_holes(fp, static_cast<std::int64_t>(std::floor(settings.gap / fp.f + 1e-9)));
  // The map's cells: its corners on multiples of h, one cell beyond the columns.
  const Eigen::Vector3d origin = ((lo.array() - h) / h).floor() * h;
  const Eigen::Vector3d corner = ((hi.array() + h) / h).ceil() * h;
  const Eigen::Array3d dd = ((corner - origin) / h).array().round().max(1.0);
  if (dd.prod() > static_cast<double>(settings.max_cells)) {
    throw std::invalid_argument("solid_volume: the region needs " +
                                std::to_string(static_cast<std::int64_t>(dd.prod())) + " cells at resolution " +
                                std::to_string(h) + " m, more than max_cells = " + std::to_string(settings.max_cells));
  }
  const Eigen::Vector3i dims = dd.cast<int>();
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(dims.prod()), static_cast<std::uint8_t>(CellState::Free));
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) {
        const Eigen::Vector3d c = origin + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        const double z = n.dot(c) + pl[3];
        if (z < h || z > fp.top_at(fp.e1.dot(c), fp.e2.dot(c))) continue;
        cells[(static_cast<std::size_t>(k) * dims.y() + j) * dims.x() + i] =
            static_cast<std::uint8_t>(CellState::Occupied);
      }
  return OccupancyMap(origin, dims, std::move(cells), olo, ohi, pl, os);
}

}  // namespace graspmix
