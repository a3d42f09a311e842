#pragma once
// How far a support plane's own points scatter about it, private to perception: segment_scene uses it to tell
// a noisy table's fragments from objects, and a lone table from a scene (segmentation.hpp states the rules).
#include <Eigen/Core>

namespace graspmix::detail {

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

}  // namespace graspmix::detail
