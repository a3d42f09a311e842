#pragma once
// How far a support plane's own points scatter about it, private to perception: segment_scene uses it to tell
// a noisy table's fragments from objects, and a lone table from a scene (segmentation.hpp states the rules).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "graspmix/core/types.hpp"

namespace graspmix::detail {

/// Signed heights of P's points above a plane [a, b, c, d] with a unit normal (a x + b y + c z + d).
Eigen::VectorXd heights(const Vec3Array& P, const Eigen::Vector4d& plane);

struct TableNoise {
  /// Spreads above the centre that a table's own point reaches with a chance under 3e-7 (Gaussian noise).
  static constexpr double kSigmas = 5.0;
  double centre = 0.0;  ///< m, height of the table's points' median above the plane
  double spread = 0.0;  ///< m, 1.4826 x their median absolute deviation (sigma for Gaussian noise)
  bool known = false;   ///< false when the heights near the plane are no table's noise (table_noise)

  /// Whether a height is within the table's noise (kSigmas spreads of its centre), or within `band` of the plane.
  bool holds(double h, double band = 0.0) const {
    const double reach = known ? kSigmas * spread : 0.0;
    return (h - centre <= reach && centre - h <= reach) || (h <= band && -h <= band);
  }
};

/// The noise of the table a plane fits, from the heights `h` of a cloud's points above it. The first estimate
/// takes the plane's RANSAC band (|h| <= band); each next one the heights within centre +- 3 spread, until it
/// settles, so it follows noise wider or narrower than the band (what stands on the table adds only its base).
/// Known only when the heights look like a table's noise: some of the band's points lie behind the plane (the
/// base of what stands on a plane, with the table cropped away, lies above it only), and about as many points
/// lie between 1 and 3 spreads above the centre as below it (the face of a flat object seen without a table
/// has its sides close behind it and nothing in front).
TableNoise table_noise(const Eigen::VectorXd& h, double band);

/// The table's noise where a point stands: one camera sees the near table along steep rays and the far table
/// along grazing ones, so its depth noise lifts the near table's points about twice as far (a 45-degree view).
/// The plane is cut into square cells of kCell; a place's noise is table_noise of the sample's heights in
/// its cell and the 8 around it, measured on first use; unknown (holds nothing) where they are fewer than
/// kMinPoints or do not look like a table's noise.
class TableNoiseMap {
 public:
  static constexpr std::size_t kMinPoints = 50;
  static constexpr double kCell = 0.05;   ///< m, a cell's side: a place's noise is measured on 15 x 15 cm
  static constexpr double kReach = 0.04;  ///< m, no table's noise reaches further from its plane (8 mm sigma)
  /// `sample`: points of the view (the table's and what stands on it), `h` their heights above `plane`, `band` the
  /// plane's RANSAC band (table_noise's first estimate).
  TableNoiseMap(const Vec3Array& sample, const Eigen::VectorXd& h, const Eigen::Vector4d& plane, double band);
  const TableNoise& at(const Eigen::Vector3d& p);

 private:
  std::int64_t key(const Eigen::Vector3d& p) const;
  Eigen::Vector3d u_, v_;
  double band_;
  std::unordered_map<std::int64_t, std::vector<double>> heights_;
  std::unordered_map<std::int64_t, TableNoise> noise_;
};

/// Whether points of P rise above the own noise of the table a plane fits: above the whole table's noise and above
/// the noise of the table where they stand (TableNoiseMap; where that is not measured, the whole table's counts
/// alone). Every point rises when the table's noise is unknown (no table's: table_noise). The noise is measured on
/// `sample`'s points (P's when null); the local map is made at the first point above the whole table's noise.
class AboveTableNoise {
 public:
  AboveTableNoise(const Vec3Array& P, const Eigen::Vector4d& plane, double band, const Vec3Array* sample = nullptr);
  /// Whether any of `rows` of P rises above the table's noise.
  bool any(const std::vector<int>& rows);

 private:
  const Vec3Array& P_;
  const Vec3Array& sample_;
  Eigen::Vector4d plane_;
  double band_;
  Eigen::VectorXd h_, hs_;
  TableNoise noise_;
  std::optional<TableNoiseMap> local_;
};

}  // namespace graspmix::detail
