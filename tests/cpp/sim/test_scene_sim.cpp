// Several objects in one Bullet world: which object a grasp lifts, two at once, settling, bad input.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspmix/robot/hand.hpp"
#include "graspmix/sim/scene_sim.hpp"
#include "graspmix/sim/sim.hpp"
#include "sim_test_support.hpp"

namespace fs = std::filesystem;
using namespace graspmix;
using namespace graspmix::sim_test;

namespace {

/// A box URDF of the given size (m) and 100 g, written once per test into a temporary folder.
SimObject box(const std::string& name, double sx, double sy, double sz) {
  const fs::path dir = fs::temp_directory_path() / "graspmix_test_scene_sim";
  fs::create_directories(dir);
  const fs::path path = dir / (name + ".urdf");
  std::ofstream(path) << "<?xml version=\"1.0\"?><robot name=\"" << name << "\"><link name=\"" << name
                      << "\"><contact><lateral_friction value=\"0.8\"/></contact>"
                      << "<inertial><mass value=\"0.1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" "
                         "izz=\"1\"/></inertial><collision><geometry><box size=\""
                      << sx << " " << sy << " " << sz << "\"/></geometry></collision></link></robot>";
  return SimObject::from_urdf(path.string());
}

}  // namespace

TEST(SceneSim, GraspOnOneOfTwoObjectsLiftsItAlone) {
  const SimObject a = box("cube_a", 0.04, 0.04, 0.04), b = box("cube_b", 0.04, 0.04, 0.04);
  const std::vector<const SimObject*> objects{&a, &b};
  const std::vector<Eigen::Isometry3d> poses{a.rest_pose(0, 0), b.rest_pose(0, 0.1)};
  const SimSettings s;
  const SceneSimResult r = execute_scene(wsg50(), objects, poses, top_wrist(0, 0, 0.01), q(0.035), q(0.018), s);
  EXPECT_TRUE(r.result.success) << r.result.reason;
  ASSERT_EQ(r.lifted, std::vector<int>{0});
  EXPECT_NEAR(r.rise[0], s.lift_height, 0.02);
  EXPECT_NEAR(r.result.lift_height, r.rise[0], 1e-12);
  EXPECT_NEAR(r.moved[0], s.lift_height, 0.02);
  EXPECT_LT(r.moved[1], 1e-3);  // the neighbour stays where it was
  EXPECT_NEAR(r.T_world_objects[1].translation().z(), 0.02, 1e-3);
  // The same grasp on the other object (the scene shifted by its offset) lifts that one.
  const SceneSimResult r1 = execute_scene(wsg50(), objects, poses, top_wrist(0, 0.1, 0.01), q(0.035), q(0.018), s);
  EXPECT_EQ(r1.lifted, std::vector<int>{1});
  EXPECT_LT(r1.moved[0], 1e-3);
}

TEST(SceneSim, GraspAcrossTwoTouchingBoxesLiftsBoth) {
  // Two 2 x 4 x 4 cm boxes side by side along x: together a 4 cm cube, the fingers close on both.
  const SimObject a = box("half_a", 0.02, 0.04, 0.04), b = box("half_b", 0.02, 0.04, 0.04);
  const std::vector<const SimObject*> objects{&a, &b};
  const std::vector<Eigen::Isometry3d> poses{a.rest_pose(-0.01, 0), b.rest_pose(0.01, 0)};
  const SceneSimResult r = execute_scene(wsg50(), objects, poses, top_wrist(0, 0, 0.01), q(0.035), q(0.018));
  EXPECT_FALSE(r.result.success);
  EXPECT_EQ(r.result.reason, "two objects lifted");
  EXPECT_EQ(r.lifted, (std::vector<int>{0, 1}));
}

TEST(SceneSim, OneObjectIsExecuteBitForBit) {
  const SimObject a = box("cube_one", 0.04, 0.04, 0.04);
  const Hand hand = wsg50();
  Eigen::Isometry3d W = top_wrist(0.004, -0.003, 0.012);
  W.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  for (double closed : {0.02, 0.045}) {  // lifted; too wide to hold
    const SimResult one = execute(hand, a, a.rest_pose(0, 0), W, q(0.05), q(closed));
    const SceneSimResult scene = execute_scene(hand, {&a}, {a.rest_pose(0, 0)}, W, q(0.05), q(closed));
    EXPECT_EQ(one.reason, scene.result.reason);
    EXPECT_EQ(one.steps, scene.result.steps);
    EXPECT_EQ(one.contact_count, scene.result.contact_count);
    EXPECT_EQ(one.lift_height, scene.result.lift_height);
    EXPECT_TRUE(one.T_world_object_final.matrix() == scene.result.T_world_object_final.matrix());
  }
}

TEST(SceneSim, StartInCollisionWithTheNeighbour) {
  const SimObject a = box("cube_c", 0.04, 0.04, 0.04), b = box("cube_d", 0.04, 0.04, 0.04);
  // A finger of the open hand (fingers at +-3.5 cm along x) inside the neighbour 4 cm away.
  const SceneSimResult r = execute_scene(wsg50(), {&a, &b}, {a.rest_pose(0, 0), b.rest_pose(0.045, 0)},
                                         top_wrist(0, 0, 0.01), q(0.035), q(0.018));
  EXPECT_EQ(r.result.reason, "start in collision");
  EXPECT_EQ(r.result.steps, 0);
  EXPECT_TRUE(r.lifted.empty());
}

TEST(SceneSim, SettledBoxRestsAtItsAnalyticHeight) {
  const SimObject a = box("settle", 0.06, 0.04, 0.02);
  Eigen::Isometry3d start = a.rest_pose(0.05, -0.02);
  start.translation().z() += 0.10;
  const SettleResult r = settle_scene({&a}, {start}, SimSettings{}, 3.0);
  EXPECT_TRUE(r.at_rest);
  EXPECT_LT(r.simulated_time, 3.0);
  ASSERT_EQ(r.T_world_objects.size(), 1u);
  const Eigen::Isometry3d& T = r.T_world_objects[0];
  EXPECT_NEAR(T.translation().z(), 0.01, 1e-3);  // half its height, on z = 0
  EXPECT_NEAR(T.translation().x(), 0.05, 1e-3);
  EXPECT_NEAR(T.translation().y(), -0.02, 1e-3);
  EXPECT_GT((T.linear() * Eigen::Vector3d::UnitZ()).z(), 0.9999);  // still flat
  // The settled scene is at rest: settling it again moves nothing.
  const SettleResult again = settle_scene({&a}, r.T_world_objects, SimSettings{}, 1.0);
  EXPECT_LT((again.T_world_objects[0].translation() - T.translation()).norm(), 1e-4);
}

TEST(SceneSim, WallsKeepAPileInside) {
  const SimObject a = box("wall_a", 0.04, 0.04, 0.04), b = box("wall_b", 0.04, 0.04, 0.04);
  // b dropped onto a's edge tips over beside it (centre near x = 4.7 cm); a wall at x = 4.2 cm stops it.
  Eigen::Isometry3d pb = b.rest_pose(0.025, 0);
  pb.translation().z() += 0.05;
  const std::vector<Eigen::Isometry3d> start{a.rest_pose(0, 0), pb};
  SettleWalls walls;
  walls.min = Eigen::Vector2d(-0.03, -0.03);
  walls.max = Eigen::Vector2d(0.042, 0.03);
  walls.height = 0.2;
  const SettleResult free = settle_scene({&a, &b}, start, SimSettings{}, 5.0);
  EXPECT_GT(free.T_world_objects[1].translation().x(), walls.max.x());
  const SettleResult boxed = settle_scene({&a, &b}, start, SimSettings{}, 5.0, &walls);
  for (const auto& T : boxed.T_world_objects) {
    EXPECT_GT(T.translation().x(), walls.min.x());
    EXPECT_LT(T.translation().x(), walls.max.x());
  }
}

TEST(SceneSim, ErrorsNameTheInput) {
  const SimObject a = box("cube_e", 0.04, 0.04, 0.04);
  const Hand hand = wsg50();
  EXPECT_THROW(execute_scene(hand, {}, {}, top_wrist(0, 0, 0.01), q(0.035), q(0.018)), std::invalid_argument);
  EXPECT_THROW(execute_scene(hand, {&a}, {}, top_wrist(0, 0, 0.01), q(0.035), q(0.018)), std::invalid_argument);
  Eigen::Isometry3d bad = a.rest_pose(0, 0);
  bad.translation().x() = std::nan("");
  EXPECT_THROW(settle_scene({&a}, {bad}), std::invalid_argument);
  EXPECT_THROW(settle_scene({&a}, {a.rest_pose(0, 0)}, SimSettings{}, -1.0), std::invalid_argument);
  SettleWalls flat;
  flat.max = Eigen::Vector2d(0.1, 0.1);  // height 0
  EXPECT_THROW(settle_scene({&a}, {a.rest_pose(0, 0)}, SimSettings{}, 1.0, &flat), std::invalid_argument);
}
