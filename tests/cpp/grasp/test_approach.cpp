// The clear-approach expert against exact geometry: the WSG 50's palm spans 0 to 72.5 mm along its approach
// axis from the flange (data/hands/wsg50.urdf), so where its path meets a slab of points or the support plane
// follows from the stand-off alone.
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "graspmix/grasp/approach.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {
const fs::path kRepo = GRASPMIX_SOURCE_DIR;  // set by CMakeLists.txt for the tests
constexpr double kRejected = -std::numeric_limits<double>::infinity();

std::shared_ptr<const Hand> wsg50() {
  return std::make_shared<Hand>(Hand::from_urdf((kRepo / "data" / "hands" / "wsg50.urdf").string()));
}
// Opens from a 3 cm grasp to a 5 cm pre-grasp (finger distances from the centre plane).
ConfigModel opening(const Hand& hand) {
  return ConfigModel(Eigen::VectorXd::Constant(1, 0.05), Eigen::VectorXd::Constant(1, 0.03), hand.joint_limits());
}
PoseArray wrist(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  PoseArray w(1, 7);
  w << p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w();
  return w;
}
// A 4 x 4 cm horizontal slab of points (2 mm apart) at height z centred on (x, y).
Vec3Array slab(double x, double y, double z) {
  Vec3Array pts(21 * 21, 3);
  for (int i = 0; i < 21; ++i)
    for (int j = 0; j < 21; ++j) pts.row(i * 21 + j) << x - 0.02 + 0.002 * i, y - 0.02 + 0.002 * j, z;
  return pts;
}
double value(const ClearApproachExpert& e, const PoseArray& w) {
  const RowMatrixXd q = RowMatrixXd::Constant(1, 1, 0.03);
  return e.log_value({w, q})[0];
}
ClearApproachExpert expert(std::shared_ptr<const CollisionExpert> c, double stand_off) {
  ClearApproachSettings s;
  s.stand_off = stand_off;
  return ClearApproachExpert(std::move(c), opening(c->hand()), s);
}
}  // namespace

TEST(ClearApproach, OffsetsRunFromThePregraspToTheStandOff) {
  const auto hand = wsg50();
  const auto c = std::make_shared<const CollisionExpert>(hand, Vec3Array(0, 3));
  EXPECT_EQ(expert(c, 0.10).offsets(), (std::vector<double>{0.0, 0.02, 0.04, 0.06, 0.08, 0.10}));
  EXPECT_EQ(expert(c, 0.05).offsets(), (std::vector<double>{0.0, 0.02, 0.04, 0.05}));
  EXPECT_EQ(expert(c, 0.0).offsets(), (std::vector<double>{0.0}));
}

TEST(ClearApproach, ANeighbourOnThePathRejectsTheGraspOnlyWithinTheStandOff) {
  const auto hand = wsg50();
  // Top-down (palm z along world -z, a rotation of pi about x), flange at 20 cm: backing off lifts the palm,
  // which spans [0.2 + s - 0.0725, 0.2 + s]; a slab at 26 cm enters it once s > 6 cm.
  const PoseArray w = wrist({0, 0, 0.20}, Eigen::Quaterniond(0, 1, 0, 0));
  const auto above = std::make_shared<const CollisionExpert>(hand, slab(0, 0, 0.26));
  EXPECT_EQ(value(expert(above, 0.10), w), kRejected);
  EXPECT_EQ(value(expert(above, 0.05), w), 0.0);
  // The same slab 20 cm to the side is never on the path.
  const auto aside = std::make_shared<const CollisionExpert>(hand, slab(0.2, 0, 0.26));
  EXPECT_EQ(value(expert(aside, 0.10), w), 0.0);
  // A slab through the open hand at the pre-grasp itself (between flange and fingertips).
  const auto inside = std::make_shared<const CollisionExpert>(hand, slab(0, 0, 0.17));
  EXPECT_EQ(value(expert(inside, 0.0), w), kRejected);
}

TEST(ClearApproach, APathThroughTheTableIsRejected) {
  const auto hand = wsg50();
  // Palm z along world +z with the flange 5 cm above the table z = 0: backing off lowers the flange to 5 cm - s.
  const PoseArray w = wrist({0, 0, 0.05}, Eigen::Quaterniond::Identity());
  const auto table = std::make_shared<const CollisionExpert>(hand, Vec3Array(0, 3), Eigen::Vector4d(0, 0, 1, 0));
  EXPECT_EQ(value(expert(table, 0.045), w), 0.0);
  EXPECT_EQ(value(expert(table, 0.055), w), kRejected);
  // A horizontal approach keeps its height: clear whatever the stand-off.
  const Eigen::Quaterniond side(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));  // palm z along +x
  EXPECT_EQ(value(expert(table, 0.5), wrist({0, 0, 0.10}, side)), 0.0);
}

TEST(ClearApproach, BadSettingsThrow) {
  const auto hand = wsg50();
  const auto c = std::make_shared<const CollisionExpert>(hand, Vec3Array(0, 3));
  ClearApproachSettings s;
  s.stand_off = -0.01;
  EXPECT_THROW(ClearApproachExpert(c, opening(*hand), s), std::invalid_argument);
  s = {};
  s.step = 0.0;
  EXPECT_THROW(ClearApproachExpert(c, opening(*hand), s), std::invalid_argument);
  s = {};
  s.stand_off = std::nan("");
  EXPECT_THROW(ClearApproachExpert(c, opening(*hand), s), std::invalid_argument);
  s = {};
  s.hand_axis = Eigen::Vector3d::Zero();
  EXPECT_THROW(ClearApproachExpert(c, opening(*hand), s), std::invalid_argument);
  EXPECT_THROW(ClearApproachExpert(nullptr, opening(*hand)), std::invalid_argument);
}
