#pragma once
// A batch's wrist rows read inside a parallel loop, private to the library (grasp/contact_quality.cpp,
// grasp/grasp_depth.cpp): a bad row is recorded, not thrown, since an exception must not leave an OpenMP region.
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "graspmix/core/se3.hpp"
#include "graspmix/core/types.hpp"

namespace graspmix {

/// Row i of wrists (N, 7) as a pose in W; false, with "wrists row i: ..." in `error` (one bad row's, whichever thread
/// wrote last), when it is no pose (pose_from_vector's check). Safe to call from the threads of one parallel loop.
inline bool wrist_of_row(const Eigen::Ref<const PoseArray>& wrists, Eigen::Index i, Eigen::Isometry3d& W,
                         std::string& error) {
  try {
    W = pose_from_vector(wrists.row(i).transpose());
    return true;
  } catch (const std::invalid_argument& e) {
#pragma omp critical
    error = "wrists row " + std::to_string(i) + ": " + e.what();
    return false;
  }
}

}  // namespace graspmix
