#pragma once
// complete_object's private parts: the object in the table's frame, its footprint, and the three shapes the
// hypotheses are made of (perception/completion.hpp).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/completion.hpp"

namespace graspmix::detail {

/// The observed points in the support plane's frame: u = (p.e1, p.e2) on the table, h = n.p + d above it.
struct TableFrame {
  Eigen::Vector3d n, e1, e2;
  double d = 0;
  Eigen::Matrix<double, Eigen::Dynamic, 2> u;  ///< (N, 2) footprint coordinates
  Eigen::VectorXd h;                           ///< (N,) heights over the plane
  Eigen::Vector2d camera;                      ///< the nearest viewpoint, projected onto the table

  TableFrame(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector4d& plane, const Eigen::Vector3d& viewpoint);
  /// The world point at footprint coordinates u and height h.
  Eigen::Vector3d world(const Eigen::Vector2d& uv, double height) const {
    return uv.x() * e1 + uv.y() * e2 + (height - d) * n;
  }
  Eigen::Vector3d world_dir(const Eigen::Vector2d& uv, double vertical) const {
    return uv.x() * e1 + uv.y() * e2 + vertical * n;
  }
};

/// The footprint rasterised at cell size s: occupied cells, and the outline (occupied cells 4-adjacent to a cell
/// reachable from outside the grid, so holes inside the footprint are not outline).
struct Footprint {
  double cell = 0;
  Eigen::Vector2d origin;
  int nx = 0, ny = 0;
  std::vector<std::int8_t> state;  ///< per cell: 0 empty inside, 1 occupied, 2 outside
  std::vector<int> top;            ///< per cell: the row of its highest point, -1 if empty
  std::vector<int> outline;        ///< cell indices on the outline

  Footprint(const TableFrame& f, double cell_size);
  int index(int ix, int iy) const { return iy * nx + ix; }
  bool outside(int ix, int iy) const { return ix < 0 || iy < 0 || ix >= nx || iy >= ny || state[index(ix, iy)] == 2; }
};

/// Points with their outward normals.
struct Shape {
  Vec3Array points, normals;
};

/// Unit outward normals of the observed points: the least-variance direction of the points within radius,
/// turned towards the viewpoint (a visible surface faces its camera). With `rows`, only those rows' normals are
/// worked out (the others are 0): each the same as among all.
Vec3Array observed_normals(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector3d& viewpoint, double radius,
                           const std::vector<Eigen::Index>* rows = nullptr);

/// The observed points and normals mirrored through the plane m.p = o (m unit).
Shape mirror_shape(const Eigen::Ref<const Vec3Array>& P, const Vec3Array& N, const Eigen::Vector3d& m, double o);

/// A circle fitted to the outline: centre (footprint coordinates), radius, inlier fraction and inlier RMS.
struct Circle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0, inliers = 0, rms = 0;
  bool ok = false;
};
Circle fit_outline_circle(const TableFrame& f, const Footprint& fp, const CompletionSettings& s);

/// The observed profile (height, radius, normal) in bins of `spacing`, the bins within the circle's radius plus
/// two bins, swept around the circle's vertical axis at about `spacing` between samples. N may be empty
/// (points only, for scoring).
Shape revolution_shape(const TableFrame& f, const Circle& c, const Vec3Array& N, double spacing);

/// Walls down from the outline (header comment, rule 3), as unclipped columns: column k is rows
/// [starts[k], starts[k + 1]) from the top down.
Shape extrusion_shape(const TableFrame& f, const Footprint& fp, double spacing, std::vector<Eigen::Index>& starts);

}  // namespace graspmix::detail
