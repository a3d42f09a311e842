// split_object_near: the split rule tried again on the segment a point target names (segmentation.hpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "graspmix/perception/segmentation.hpp"
#include "graspmix/perception/targets.hpp"
#include "pile_split.hpp"
#include "segmentation_steps.hpp"

namespace graspmix {

std::size_t split_object_near(Segmentation& scene, const Vec3Array& viewpoints, const Eigen::Vector3d& point,
                              const SegmentationSettings& settings) {
  detail::check_segmentation_settings(settings);
  if (!point.allFinite()) throw std::invalid_argument("split_object_near: the point must be finite");
  if (viewpoints.rows() > 1 && viewpoints.rows() != scene.points.rows())
    throw std::invalid_argument("split_object_near: viewpoints must be one row, or one per point of the scene");
  if (scene.objects.empty() || viewpoints.rows() == 0) return 0;
  Target target;
  target.kind = Target::Kind::Point;
  target.point = point;
  const auto named = static_cast<std::size_t>(select_targets(scene, Vec3Array(0, 3), target).front());
  const Eigen::VectorXi& rows = scene.objects[named].rows;  // objects are indexed in order (segment_scene)
  std::vector<std::vector<int>> pieces = {std::vector<int>(rows.data(), rows.data() + rows.size())};
  std::sort(pieces.front().begin(), pieces.front().end());
  const SegmentationSettings& s = settings;
  const std::size_t added = detail::split_touching(
      scene.points, viewpoints, pieces,
      detail::SplitRule{std::max(s.split_voxel_resolution, s.voxel_size), s.split_seed_resolution,
                        s.split_concavity_tolerance, s.split_min_points, s.split_named_max_size});
  if (added == 0) return 0;
  std::vector<std::vector<int>> groups;
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    if (k == named) continue;
    const Eigen::VectorXi& r = scene.objects[k].rows;
    groups.emplace_back(r.data(), r.data() + r.size());
  }
  for (auto& piece : pieces) groups.push_back(std::move(piece));
  const std::size_t n_split = scene.n_split + added;
  detail::regroup(scene, std::move(groups), settings);
  scene.n_split = n_split;
  return added;
}

}  // namespace graspmix
