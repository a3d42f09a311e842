#pragma once
// What the cameras saw of a scene, as occupancy (the collision expert's model of the scene; perception's
// VisibilityModel answers the same question per view from the depth images): OctoMap's ray insertion of the cloud, each
// point from its own viewpoint (the camera that saw it), baked into a dense grid over a region of interest for O(1)
// queries.
//
// Each ray marks the cells it crosses free and the cell of its point occupied (a cell a ray ends in stays
// occupied whatever other rays cross it: OctoMap's own rule within one scan); every cell no ray reached is
// unknown. Only the region of interest is mapped: the box around the objects' points grown by `margin`,
// rays clipped to it. Outside the region every cell is free, and so is every cell whose centre is less
// than one cell above the support plane (the plane has an exact term of its own in the collision expert,
// and the table's points would otherwise make the layer just above it solid).
//
// The rule a hand is checked against: unknown counts as occupied (unknown_is_occupied). From one camera
// the shadow behind every object, up to the region's edge, is then solid: a hand must fit in space some
// camera saw free. With four cameras around the objects the shadow shrinks to what is enclosed by their
// surfaces, i.e. the objects' insides.
//
// Resolution: 5 mm by default, above the clean-up's 3 mm voxels (so the points of one surface leave no
// free gap between their cells for a ray to slip through) and under half a finger's thickness (the WSG 50's
// fingers are 23 mm by 30 mm, so a finger covers several cells). Finer maps cost cells as 1/h^3.
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/visibility.hpp"

namespace graspmix {

struct OccupancySettings {
  double resolution = 0.005;  ///< m: the cell size of the map (OctoMap's resolution), > 0
  double margin = 0.10;       ///< m: the region of interest is the objects' bounding box grown by this (>= 0)
  /// Unknown cells count as obstacles ("space the cameras did not see is not free"); false: as free.
  bool unknown_is_occupied = true;
  /// The dense grid's largest size (cells): a bigger region or a finer resolution is an error.
  std::int64_t max_cells = 50'000'000;
};

enum class CellState : std::uint8_t { Free = 0, Occupied = 1, Unknown = 2 };

/// Diagnostics of a map's construction.
struct OccupancyStats {
  std::int64_t n_rays = 0;  ///< rays inserted after de-duplication (one per half cell and viewpoint)
  std::int64_t n_free = 0;  ///< cells of the dense grid by state
  std::int64_t n_occupied = 0;
  std::int64_t n_unknown = 0;
  double seconds = 0.0;  ///< wall time of insertion and baking
};

class OccupancyMap {
 public:
  /// points (N, 3): the whole cloud (table included: its rays clear the space around the objects), each
  /// seen from viewpoints (1, 3) for all or (N, 3) one per point; objects (M, 3): the points whose box,
  /// grown by settings.margin, is the region (0 rows: all points); plane: the support plane, [n, d] with n
  /// pointing towards the cameras (n . x + d > 0 free side), or none.
  /// Throws std::invalid_argument for empty or non-finite points or viewpoints, viewpoints of the wrong
  /// shape, a viewpoint inside the objects' bounding box (no camera sees an object from inside it), a
  /// degenerate plane, and bad settings (resolution <= 0, margin < 0, a region of more than max_cells).
  OccupancyMap(const Eigen::Ref<const Vec3Array>& points, const Eigen::Ref<const Vec3Array>& viewpoints,
               const Eigen::Ref<const Vec3Array>& objects, const std::optional<Eigen::Vector4d>& plane = std::nullopt,
               OccupancySettings settings = {});

  /// The same region and rules from a visibility model's views (perception/visibility.hpp) instead of OctoMap's rays:
  /// each cell by the state of its centre, SeenFree -> Free, Surface -> Occupied, Unseen behind an observed surface ->
  /// Unknown (so a cell is occupied within the model's surface_tolerance of a seen surface, not only where a point
  /// ends). A cell no view says anything about (outside every image, on a pixel with no return, an empty bin of an
  /// unorganized cloud's range image) is Free: what is unknown is the shadow behind what the cameras saw. An
  /// unorganized cloud keeps no record of the rays that returned nothing, so a cloud cropped to its objects (no
  /// table) would otherwise leave all the space around them unknown. The views are already built, so this reads
  /// their images, O(1) a cell, where the rays cost O(points x cells along a ray).
  /// objects (M >= 1, 3): the points whose box, grown by settings.margin, is the region; plane as above (oriented
  /// towards the views' sensors). Throws std::invalid_argument for a model of no view, no or non-finite object
  /// points, a degenerate plane and bad settings, as the rays' constructor.
  OccupancyMap(const VisibilityModel& visibility, const Eigen::Ref<const Vec3Array>& objects,
               const std::optional<Eigen::Vector4d>& plane = std::nullopt, OccupancySettings settings = {});

  /// A map of given cells (grasp/solid_volume.hpp builds one): `cells`, a CellState per cell with x fastest,
  /// `dims` cells of `resolution` from `origin`; objects_lo/hi the box of what it maps; plane as above (normalised
  /// here, its sign kept). Throws std::invalid_argument for a cell count other than dims' product, a state out of
  /// range, dims < 1, a non-finite origin or bad settings.
  OccupancyMap(const Eigen::Vector3d& origin, const Eigen::Vector3i& dims, std::vector<std::uint8_t> cells,
               const Eigen::Vector3d& objects_lo, const Eigen::Vector3d& objects_hi,
               const std::optional<Eigen::Vector4d>& plane, OccupancySettings settings);

  /// The state of the cell holding p (Free outside the region).
  CellState state(const Eigen::Vector3d& p) const {
    Eigen::Vector3d c;
    return cell(p, c);
  }
  /// The state of the cell holding p, and that cell's centre in `centre` (set only inside the region).
  CellState cell(const Eigen::Vector3d& p, Eigen::Vector3d& centre) const {
    const Eigen::Vector3d f = (p - origin_) / h_;
    const double fx = std::floor(f.x()), fy = std::floor(f.y()), fz = std::floor(f.z());
    if (fx < 0 || fy < 0 || fz < 0 || fx >= dims_.x() || fy >= dims_.y() || fz >= dims_.z()) return CellState::Free;
    const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy), k = static_cast<std::int64_t>(fz);
    centre = origin_ + h_ * Eigen::Vector3d(fx + 0.5, fy + 0.5, fz + 0.5);
    return static_cast<CellState>(cells_[static_cast<std::size_t>((k * dims_.y() + j) * dims_.x() + i)]);
  }
  /// Occupied, or unknown when unknown cells are obstacles.
  bool blocked(CellState s) const {
    return s == CellState::Occupied || (s == CellState::Unknown && settings_.unknown_is_occupied);
  }

  /// Whether any blocked cell touches the axis-aligned box [lo, hi] (world): O(1), from a summed-volume table of
  /// the blocked cells built with the map. A false answer means the box lies wholly in free cells.
  bool any_blocked(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;
  /// Whether any unknown cell touches the box [lo, hi] (world), in O(1) likewise.
  bool any_unknown(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;

  double resolution() const { return h_; }
  /// The region of interest: [lo, hi] corners of the dense grid (aligned to the OctoMap's cells).
  Eigen::Vector3d region_min() const { return origin_; }
  Eigen::Vector3d region_max() const { return origin_ + h_ * dims_.cast<double>(); }
  Eigen::Vector3i dims() const { return dims_.cast<int>(); }
  const OccupancySettings& settings() const { return settings_; }
  const OccupancyStats& stats() const { return stats_; }
  bool has_plane() const { return plane_.has_value(); }
  /// The support plane, normalised, its normal towards the cameras (zero without a plane).
  Eigen::Vector4d plane() const { return plane_.value_or(Eigen::Vector4d::Zero()); }
  /// The objects' bounding box (before the margin).
  Eigen::Vector3d objects_min() const { return objects_lo_; }
  Eigen::Vector3d objects_max() const { return objects_hi_; }

 private:
  OccupancySettings settings_;
  std::optional<Eigen::Vector4d> plane_;
  double h_ = 0.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d objects_lo_ = Eigen::Vector3d::Zero(), objects_hi_ = Eigen::Vector3d::Zero();
  Eigen::Matrix<std::int64_t, 3, 1> dims_ = Eigen::Matrix<std::int64_t, 3, 1>::Zero();
  std::vector<std::uint8_t> cells_;  ///< CellState per cell, x fastest
  /// blocked cells in [0, i) x [0, j) x [0, k), (dims + 1) per axis, x fastest: any_blocked's table
  std::vector<std::int64_t> blocked_sums_;
  std::vector<std::int64_t> unknown_sums_;  ///< the same of the unknown cells: any_unknown's table
  void build_blocked_sums();
  /// The region of interest around objects_lo_/hi_ (grown by the margin, its corners on multiples of the
  /// resolution) into origin_ and dims_; throws past max_cells.
  void set_region();
  /// Counts the cells by state into stats_ and builds the summed-volume tables.
  void finish_cells();
  /// The summed-volume table of the cells for which `count` is true.
  template <class Count>
  std::vector<std::int64_t> summed(Count count) const;
  bool any_in(const std::vector<std::int64_t>& sums, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;
  OccupancyStats stats_;
};

}  // namespace graspmix
