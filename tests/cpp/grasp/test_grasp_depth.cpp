// The grasp-depth expert against exact geometry: the WSG 50 (palm z the approach, fingers closing along x, their far
// end 153.5 mm above the flange) straight down over a sampled box whose top face is at z = 0.14 m: the depth is the
// top's height above the fingertips' far end.
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <gtest/gtest.h>

#include "graspmix/grasp/grasp_depth.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {
const fs::path kRepo = GRASPMIX_SOURCE_DIR;  // set by CMakeLists.txt for the tests
constexpr double kTipReach = 0.1535;         // m: the WSG 50's fingertips' far end along its palm z
constexpr double kTop = 0.14;

std::shared_ptr<const Hand> wsg50() {
  return std::make_shared<Hand>(Hand::from_urdf((kRepo / "data" / "hands" / "wsg50.urdf").string()));
}

/// The surface of the 60 x 100 x 140 mm box standing on z = 0, on a 5 mm grid (its top face at z = kTop).
Vec3Array box() {
  std::vector<Eigen::Vector3d> pts;
  const Eigen::Vector3d half(0.03, 0.05, 0.07), centre(0, 0, 0.07);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int nu = static_cast<int>(std::round(2 * half[u] / 0.005)),
                nv = static_cast<int>(std::round(2 * half[v] / 0.005));
      for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) {
          Eigen::Vector3d x;
          x[axis] = side * half[axis];
          x[u] = -half[u] + 2 * half[u] * i / nu;
          x[v] = -half[v] + 2 * half[v] * j / nv;
          pts.push_back(centre + x);
        }
    }
  Vec3Array out(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return out;
}

/// Straight down (palm z to -z) at (x, y), the fingertips' far end `below` under the box's top, the fingers at 30 mm.
std::pair<PoseArray, RowMatrixXd> top_grasp(double below, double x = 0.0, double y = 0.0) {
  PoseArray w(1, 7);
  w << x, y, kTop - below + kTipReach, 1.0, 0.0, 0.0, 0.0;
  return {w, RowMatrixXd::Constant(1, 1, 0.03)};
}

double log_e(const GraspDepthExpert& e, const std::pair<PoseArray, RowMatrixXd>& g) {
  return e.log_value(GraspBatch{g.first, g.second})[0];
}
}  // namespace

TEST(GraspDepth, IsTheTopsHeightAboveTheFingertipsCappedAtTheMinimum) {
  const GraspDepthExpert e(wsg50(), box());  // min_depth 20 mm, 1000 nats per metre short
  for (const double below : {0.0, 0.005, 0.012, 0.0199}) {
    const auto g = top_grasp(below);
    EXPECT_NEAR(e.depths(g.first, g.second)[0], below, 1e-12) << below;
    EXPECT_NEAR(log_e(e, g), -1000.0 * (0.02 - below), 1e-9) << below;
  }
  for (const double below : {0.02, 0.03, 0.1}) {
    const auto g = top_grasp(below);
    EXPECT_NEAR(e.depths(g.first, g.second)[0], 0.02, 1e-12) << below;
    EXPECT_NEAR(log_e(e, g), 0.0, 1e-9) << below;
  }
}

TEST(GraspDepth, FingertipsAboveTheObjectCountNegativeAndNothingBetweenThemCountsZero) {
  const GraspDepthExpert e(wsg50(), box());
  EXPECT_NEAR(log_e(e, top_grasp(-0.01)), -30.0, 1e-9);  // 10 mm above the top: 30 mm short
  // Beside the box (its nearest point 0.27 m from the cylinder's axis): no point between the fingers.
  EXPECT_NEAR(log_e(e, top_grasp(0.03, 0.3)), -20.0, 1e-9);
}

TEST(GraspDepth, SettingsScaleTheChargeAndBadInputIsRefused) {
  GraspDepthSettings s;
  s.min_depth = 0.01;
  s.penalty = 500.0;
  const GraspDepthExpert e(wsg50(), box(), s);
  EXPECT_NEAR(log_e(e, top_grasp(0.004)), -500.0 * 0.006, 1e-9);
  EXPECT_EQ(e.max_log_value(), 0.0);
  s.penalty = -1.0;
  EXPECT_THROW(GraspDepthExpert(wsg50(), box(), s), std::invalid_argument);
  EXPECT_THROW(GraspDepthExpert(nullptr, box()), std::invalid_argument);
  Vec3Array bad = box();
  bad(3, 1) = std::nan("");
  EXPECT_THROW(GraspDepthExpert(wsg50(), bad), std::invalid_argument);
  EXPECT_THROW(GraspDepthExpert(wsg50(), Vec3Array(0, 3)), std::invalid_argument);
  const auto g = top_grasp(0.01);
  EXPECT_THROW(e.depths(g.first, RowMatrixXd::Zero(1, 2)), std::invalid_argument);
  EXPECT_THROW(e.depths(g.first, RowMatrixXd::Constant(1, 1, std::nan(""))), std::invalid_argument);
  PoseArray none(0, 7);
  EXPECT_EQ(e.depths(none, RowMatrixXd(0, 1)).size(), 0);
}
