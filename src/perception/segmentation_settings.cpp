// SegmentationSettings checked and turned into the settings of the steps that take them (the visibility model's),
// and the workspace's error: what segment_scene and segment_depth share before they look at a point.
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "segmentation_steps.hpp"

namespace graspmix {

namespace {

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument("segment_scene: " + m); }

bool finite_ge(double v, double lo) { return std::isfinite(v) && v >= lo; }

}  // namespace

VisibilitySettings detail::visibility_settings(const SegmentationSettings& s) {
  VisibilitySettings vs;
  vs.surface_tolerance = s.visibility_tolerance;
  vs.angular_resolution = s.visibility_resolution;
  return vs;
}

void detail::nothing_in_workspace(const SegmentationSettings& s, const char* what) {
  std::ostringstream box;
  for (std::size_t k = 0; k < s.workspace.size(); ++k) box << (k ? ", " : "") << s.workspace[k];
  throw std::invalid_argument(std::string(what) + ": nothing inside the workspace [" + box.str() +
                              "] (x_min, y_min, z_min, x_max, y_max, z_max in the world frame, m)");
}

void detail::check_segmentation_settings(const SegmentationSettings& s) {
  if (!s.workspace.empty()) {
    const auto& w = s.workspace;
    if (w.size() != 6) bad("workspace must be empty or [x_min, y_min, z_min, x_max, y_max, z_max] (6 numbers, m)");
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(k);
      if (!std::isfinite(w[a]) || !std::isfinite(w[a + 3]) || !(w[a] < w[a + 3]))
        bad("workspace: each minimum must be finite and below its maximum ([x_min, y_min, z_min, x_max, y_max, "
            "z_max])");
    }
  }
  if (!finite_ge(s.voxel_size, 0)) bad("voxel_size must be a finite size >= 0 (m; 0 switches it off)");
  if (!(finite_ge(s.plane_distance, 0) && s.plane_distance > 0)) bad("plane_distance must be > 0 (m)");
  if (s.plane_max_iterations < 1) bad("plane_max_iterations must be >= 1");
  if (s.plane_candidates < 1) bad("plane_candidates must be >= 1");
  if (!(finite_ge(s.plane_min_fraction, 0) && s.plane_min_fraction <= 1)) bad("plane_min_fraction must be in [0, 1]");
  if (!finite_ge(s.plane_behind_distance, 0)) bad("plane_behind_distance must be a finite distance >= 0 (m)");
  if (!(finite_ge(s.plane_max_behind_fraction, 0) && s.plane_max_behind_fraction <= 1)) {
    bad("plane_max_behind_fraction must be in [0, 1]");
  }
  if (!finite_ge(s.plane_margin, 0)) bad("plane_margin must be a finite distance >= 0 (m)");
  if (!finite_ge(s.table_clearance, 0)) bad("table_clearance must be a finite distance >= 0 (m)");
  if (s.remove_outliers &&
      (s.outlier_neighbours < 1 || !(finite_ge(s.outlier_std_ratio, 0) && s.outlier_std_ratio > 0))) {
    bad("outlier_neighbours must be >= 1 and outlier_std_ratio > 0");
  }
  if (!(finite_ge(s.cluster_tolerance, 0) && s.cluster_tolerance > 0)) bad("cluster_tolerance must be > 0 (m)");
  if (s.min_cluster_size < 1) bad("min_cluster_size must be >= 1");
  if (!(finite_ge(s.merge_through_fraction, 0) && s.merge_through_fraction <= 1)) {
    bad("merge_through_fraction must be in [0, 1]");
  }
  if (!finite_ge(s.merge_inset, 0)) bad("merge_inset must be a finite distance >= 0 (m)");
  if (!finite_ge(s.join_max_gap, 0)) bad("join_max_gap must be a finite distance >= 0 (m)");
  if (!std::isfinite(s.join_seen_margin)) bad("join_seen_margin must be a finite distance (m)");
  if (!(finite_ge(s.join_max_size, 0) && s.join_max_size > 0)) bad("join_max_size must be a finite size > 0 (m)");
  if (s.split_touching &&
      !(finite_ge(s.split_voxel_resolution, 0) && s.split_voxel_resolution > 0 &&
        finite_ge(s.split_seed_resolution, 0) && s.split_seed_resolution > s.split_voxel_resolution &&
        finite_ge(s.split_concavity_tolerance, 0) && s.split_concavity_tolerance < M_PI / 2 &&
        s.split_min_points >= 1 && finite_ge(s.split_max_size, 0) && s.split_max_size > 0)) {
    bad("split_voxel_resolution must be > 0 (m), split_seed_resolution larger (m), split_concavity_tolerance in "
        "[0, pi/2) rad, split_min_points >= 1 and split_max_size > 0 (m)");
  }
  if (!(finite_ge(s.split_named_max_size, 0) && s.split_named_max_size > 0))
    bad("split_named_max_size must be a finite size > 0 (m)");
  try {
    check_visibility_settings(visibility_settings(s));
  } catch (const std::invalid_argument&) {
    bad("visibility_tolerance must be a finite distance >= 0 (m) and visibility_resolution in (0, 0.5] rad");
  }
  if (s.max_cluster_size < 0 || (s.max_cluster_size > 0 && s.max_cluster_size < s.min_cluster_size)) {
    bad("max_cluster_size must be 0 (no limit) or >= min_cluster_size");
  }
  if (s.visibility_median_window < 0 || s.visibility_median_window > 5)
    bad("visibility_median_window must be in [0, 5] px");
  if (s.image_stride < 0) bad("image_stride must be >= 0 (0: chosen from voxel_size)");
  if (s.plane_image_stride < 1) bad("plane_image_stride must be >= 1");
}

}  // namespace graspmix
