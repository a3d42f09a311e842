#pragma once
// Surface normals of compute_surface_features (private to the library): the radius grid every stage
// searches, PCA normals within the radius, their outward orientation, and the neighbour cap.
#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/uniform_grid.hpp"
#include "graspmix/perception/surface.hpp"

namespace graspmix::surface_detail {

[[noreturn]] inline void bad(const std::string& m) { throw std::invalid_argument("compute_surface_features: " + m); }

/// The radius search of every stage: a grid of cells one radius wide (see core/uniform_grid.hpp: its
/// canonical order makes neighbour lists, every sum over them and hence the results the same for any
/// permutation of the input; and on surfaces it is several times faster than a sorted kd-tree search).
using RadiusGrid = detail::UniformGrid;

/// Normals (unoriented) in canonical order, which points have one, and (for propagation) each
/// point's k nearest neighbours.
struct Normals {
  std::vector<Eigen::Vector3d> n;
  std::vector<char> valid;
  std::vector<char> degenerate;  ///< no normal because the neighbourhood's points coincide or lie on a line
  std::vector<std::vector<int>> knn;
};

/// Watches the neighbourhood sizes of a parallel stage against max_neighbours: the first one over the
/// cap stops the stage (the remaining iterations skip), and throw_if_hit() then refuses the cloud. The
/// message names no point, so it is the same for any thread count.
class NeighbourCap {
 public:
  explicit NeighbourCap(const SurfaceFeatureSettings& s) : s_(s) {}
  /// True (and remembered) if nn is over the cap.
  bool over(std::size_t n) {
    if (s_.max_neighbours == 0 || n <= static_cast<std::size_t>(s_.max_neighbours)) return false;
    hit_.store(true, std::memory_order_relaxed);
    return true;
  }
  bool hit() const { return hit_.load(std::memory_order_relaxed); }
  void throw_if_hit() const {
    if (!hit()) return;
    bad("a neighbourhood holds more than max_neighbours = " + std::to_string(s_.max_neighbours) +
        " points within radius " + std::to_string(s_.radius) +
        " m: the cloud is far denser than the radius needs (time grows with every neighbour); voxel-downsample it "
        "first (e.g. a leaf of radius / 3), or raise max_neighbours (0: no cap)");
  }

 private:
  const SurfaceFeatureSettings& s_;
  std::atomic<bool> hit_{false};
};

/// The caller's normals or estimated ones, and the k-NN graph when the orientation propagates.
Normals estimate_normals(const RadiusGrid& grid, const SurfaceFeatureSettings& s, const Vec3Array& normals_in,
                         bool propagate, int n_threads);

/// Outward orientation by the rule: before the curvatures, whose projected normals need consistent signs.
void orient_normals(NormalOrientation rule, const RadiusGrid& grid, const Vec3Array& viewpoints, Normals& normals);

}  // namespace graspmix::surface_detail
