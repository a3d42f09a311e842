#pragma once
// What the simulation's tests share: the bundled WSG 50 and its top grasps.
#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>

#include "graspmix/robot/hand.hpp"

namespace graspmix::sim_test {

inline Hand wsg50() {
  return Hand::from_urdf((std::filesystem::path(GRASPMIX_SOURCE_DIR) / "data" / "hands" / "wsg50.urdf").string());
}

/// A top grasp of the WSG 50 (palm z pointing down, fingers closing along world x): fingertips `tip_z`
/// above the plane at (x, y).
inline Eigen::Isometry3d top_wrist(double x, double y, double tip_z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, tip_z + 0.0725 + 0.081);
  return T;
}

/// A one-joint configuration.
inline Eigen::VectorXd q(double v) { return Eigen::VectorXd::Constant(1, v); }

}  // namespace graspmix::sim_test
