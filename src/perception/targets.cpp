#include "graspmix/perception/targets.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace graspmix {

std::vector<int> select_targets(const Segmentation& scene, const Vec3Array& viewpoints, const Target& target) {
  const auto& objects = scene.objects;
  const int n = static_cast<int>(objects.size());
  if (viewpoints.rows() > 1 && viewpoints.rows() != scene.points.rows())
    throw std::invalid_argument("target: " + std::to_string(viewpoints.rows()) + " viewpoints for " +
                                std::to_string(scene.points.rows()) + " points (one per point, one, or none)");
  if (objects.empty() && target.kind != Target::Kind::All)
    throw std::invalid_argument("target: the scene has no object");
  if (target.camera && !target.camera->allFinite())
    throw std::invalid_argument("camera: expected a finite (3,) position");
  switch (target.kind) {
    case Target::Kind::All: {
      std::vector<int> all;
      for (const auto& o : objects) all.push_back(o.index);
      return all;
    }
    case Target::Kind::Index:
      if (target.index < 0 || target.index >= n)
        throw std::invalid_argument("target: no object " + std::to_string(target.index) + " (the scene has " +
                                    std::to_string(n) + ": 0.." + std::to_string(n - 1) + ")");
      return {target.index};
    case Target::Kind::Largest: {
      const auto best = std::max_element(objects.begin(), objects.end(), [](const auto& a, const auto& b) {
        return a.n_points != b.n_points ? a.n_points < b.n_points : a.index > b.index;
      });
      return {best->index};
    }
    case Target::Kind::Point: {
      double best = std::numeric_limits<double>::infinity();
      int which = 0;
      for (const auto& o : objects) {
        double d = std::numeric_limits<double>::infinity();
        for (Eigen::Index r = 0; r < o.rows.size(); ++r)
          d = std::min(d, (scene.points.row(o.rows[r]).transpose() - target.point).norm());
        if (d < best) best = d, which = o.index;
      }
      if (best > kPointTargetMaxDistance) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "target: the point point:%g,%g,%g is %.3f m from the nearest object (more than %g m): it names "
                      "no object",
                      target.point.x(), target.point.y(), target.point.z(), best, kPointTargetMaxDistance);
        throw std::invalid_argument(text);
      }
      return {which};
    }
    case Target::Kind::Nearest: {
      double best = std::numeric_limits<double>::infinity();
      int which = 0;
      for (const auto& o : objects) {
        double d = std::numeric_limits<double>::infinity();
        for (Eigen::Index r = 0; r < o.rows.size(); ++r) {
          const Eigen::Index i = o.rows[r];
          const Eigen::Vector3d from = target.camera            ? *target.camera
                                       : viewpoints.rows() == 1 ? Eigen::Vector3d(viewpoints.row(0).transpose())
                                       : viewpoints.rows() > 0  ? Eigen::Vector3d(viewpoints.row(i).transpose())
                                                                : Eigen::Vector3d::Zero();
          d = std::min(d, (scene.points.row(i).transpose() - from).norm());
        }
        if (d < best) best = d, which = o.index;
      }
      return {which};
    }
  }
  throw std::invalid_argument("target: unknown kind");
}

}  // namespace graspmix
