// Grasp execution in Bullet: outcomes of hand-made grasps on a cube, determinism, input errors.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "graspmix/robot/hand.hpp"
#include "graspmix/sim/sim.hpp"
#include "sim_test_support.hpp"

namespace fs = std::filesystem;
using namespace graspmix;
using namespace graspmix::sim_test;

namespace {

const fs::path kRepo = GRASPMIX_SOURCE_DIR;  // set by CMakeLists.txt for the tests

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("graspmix_test_sim_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

// A 4 cm cube of 100 g with pybullet's <contact> friction extension.
const char* kCube = R"(<?xml version="1.0"?>
<robot name="cube">
  <link name="cube">
    <contact><lateral_friction value="0.8"/><inertia_scaling value="3"/></contact>
    <inertial><mass value="0.1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><box size="0.04 0.04 0.04"/></geometry></collision>
  </link>
</robot>)";

}  // namespace

TEST(SimObject, ReadsMassFrictionAndRestsOnThePlane) {
  TempDir dir;
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  EXPECT_DOUBLE_EQ(cube.mass(), 0.1);
  EXPECT_DOUBLE_EQ(cube.lateral_friction(), 0.8);
  EXPECT_DOUBLE_EQ(cube.inertia_scaling(), 3.0);
  const Eigen::Isometry3d T = cube.rest_pose(0.1, -0.2);
  EXPECT_NEAR(T.translation().x(), 0.1, 1e-12);
  EXPECT_NEAR(T.translation().y(), -0.2, 1e-12);
  EXPECT_NEAR(T.translation().z(), 0.02, 1e-12);
  // Rotated 45 degrees about x, the cube stands on an edge: centre at half the face diagonal.
  const Eigen::Quaterniond r(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(cube.rest_pose(0, 0, r).translation().z(), 0.02 * std::sqrt(2.0), 1e-12);
}

TEST(Sim, CubeGraspedAcrossTwoFacesIsLifted) {
  TempDir dir;
  const Hand hand = wsg50();
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  const SimSettings s;
  const SimResult r = execute(hand, cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.035), q(0.018), s);
  EXPECT_TRUE(r.success) << r.reason;
  EXPECT_EQ(r.reason, "success");
  EXPECT_NEAR(r.lift_height, s.lift_height, 0.02);
  EXPECT_GE(r.contact_count, 2);
  EXPECT_LT(r.start_penetration, s.start_penetration);
  EXPECT_GT(r.steps, 0);
  EXPECT_NEAR(r.simulated_time, r.steps * s.time_step, 1e-12);
  // Rotating the whole scene about z (grasp across the other pair of faces) changes nothing.
  Eigen::Isometry3d Rz = Eigen::Isometry3d::Identity();
  Rz.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const SimResult r2 =
      execute(hand, cube, Rz * cube.rest_pose(0, 0), Rz * top_wrist(0, 0, 0.01), q(0.035), q(0.018), s);
  EXPECT_TRUE(r2.success) << r2.reason;
}

TEST(Sim, GraspBesideTheObjectHasNoContact) {
  TempDir dir;
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  const SimResult r = execute(wsg50(), cube, cube.rest_pose(0, 0), top_wrist(0.0, 0.12, 0.01), q(0.035), q(0.018));
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.reason, "no contact");
  EXPECT_EQ(r.contact_count, 0);
  EXPECT_NEAR(r.lift_height, 0.0, 1e-3);
}

TEST(Sim, GraspStartingInsideTheObjectIsStartInCollision) {
  TempDir dir;
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  // Fingers nearly closed, reaching into the cube from above.
  const SimResult r = execute(wsg50(), cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.005), q(0.0));
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.reason, "start in collision");
  EXPECT_GT(r.start_penetration, 0.005);
  EXPECT_EQ(r.steps, 0);
  // Fingers through the support plane.
  const SimResult below = execute(wsg50(), cube, cube.rest_pose(0, 0), top_wrist(0, 0, -0.01), q(0.035), q(0.018));
  EXPECT_EQ(below.reason, "start in collision");
}

TEST(Sim, TooWideAGraspDoesNotHold) {
  TempDir dir;
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  // The motors' target stays wider than the cube: the fingers never squeeze it.
  const SimResult r = execute(wsg50(), cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.05), q(0.04));
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.reason, "start in collision");
}

TEST(Sim, Deterministic) {
  TempDir dir;
  const Hand hand = wsg50();
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  Eigen::Isometry3d W = top_wrist(0.004, -0.003, 0.012);
  W.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  const SimResult a = execute(hand, cube, cube.rest_pose(0, 0), W, q(0.04), q(0.02));
  const SimResult b = execute(hand, cube, cube.rest_pose(0, 0), W, q(0.04), q(0.02));
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.contact_count, b.contact_count);
  EXPECT_EQ(a.lift_height, b.lift_height);  // bit for bit
  EXPECT_TRUE(a.T_world_object_final.matrix() == b.T_world_object_final.matrix());
}

// Two 3 x 3 x 3 cm blocks 4 cm apart as the two parts ("o" groups) of one OBJ, like pybullet_data's
// random_urdfs: pybullet hulls each part, so the gap between them is free space.
std::string two_blocks_obj() {
  std::string out;
  int base = 0;
  for (double cx : {-0.035, 0.035}) {
    out += "o block_" + std::to_string(base) + "\n";
    for (int k = 0; k < 8; ++k) {
      out += "v " + std::to_string(cx + ((k & 1) ? 0.015 : -0.015)) + " " + std::to_string((k & 2) ? 0.015 : -0.015) +
             " " + std::to_string((k & 4) ? 0.015 : -0.015) + "\n";
    }
    const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                          {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& t : f) {
      out += "f " + std::to_string(base + t[0] + 1) + " " + std::to_string(base + t[1] + 1) + " " +
             std::to_string(base + t[2] + 1) + "\n";
    }
    base += 8;
  }
  return out;
}

TEST(Sim, MeshPartsAreSeparateHullsLikePybullet) {
  TempDir dir;
  dir.write("blocks.obj", two_blocks_obj());
  const std::string urdf = dir.write("blocks.urdf", R"(<?xml version="1.0"?>
<robot name="blocks"><link name="blocks">
  <inertial><mass value="0.1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  <collision><geometry><mesh filename="blocks.obj" scale="1 1 1"/></geometry></collision>
</link></robot>)");
  const SimObject blocks = SimObject::from_urdf(urdf);
  const Hand hand = wsg50();
  // Closed fingers turned 90 degrees (their 30 mm width along x) reach down into the 4 cm gap: free
  // between two hulls, deep inside one hull of everything.
  Eigen::Isometry3d W = top_wrist(0, 0, 0.01);
  W.prerotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const SimResult r = execute(hand, blocks, blocks.rest_pose(0, 0), W, q(0.0), q(0.0));
  EXPECT_EQ(r.reason, "no contact");
  // Across both blocks (outer faces 10 cm apart) the grasp holds them as one object.
  const SimResult across = execute(hand, blocks, blocks.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.055), q(0.04));
  EXPECT_TRUE(across.success) << across.reason;
}

TEST(Sim, ErrorsNameTheInput) {
  TempDir dir;
  const Hand hand = wsg50();
  EXPECT_THROW(SimObject::from_urdf((dir.path / "missing.urdf").string()), std::invalid_argument);
  // A hand is not an object (more than one link).
  try {
    SimObject::from_urdf((kRepo / "data" / "hands" / "wsg50.urdf").string());
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("one link"), std::string::npos) << e.what();
  }
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  try {
    execute(hand, cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), Eigen::VectorXd::Zero(2), q(0.0));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pregrasp_joints"), std::string::npos) << e.what();
  }
  SimSettings bad;
  bad.time_step = 0;
  EXPECT_THROW(execute(hand, cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.03), q(0.01), bad),
               std::invalid_argument);
}

namespace {

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

/// The cube with one line of its text replaced.
std::string cube_with(const std::string& from, const std::string& to) {
  std::string s = kCube;
  s.replace(s.find(from), from.size(), to);
  return s;
}

}  // namespace

TEST(Sim, TimesForcesAndSpeedsOutOfRangeAreRefusedByName) {
  TempDir dir;
  const Hand hand = wsg50();
  const SimObject cube = SimObject::from_urdf(dir.write("cube.urdf", kCube));
  auto run = [&](const SimSettings& s) {
    return error_of([&] { execute(hand, cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.03), q(0.01), s); });
  };
  // hold_time 1e7 s is 2.4e9 steps: the count overflowed an int, the hold was skipped and SUCCESS reported.
  SimSettings hold;
  hold.hold_time = 1e7;
  EXPECT_NE(run(hold).find("SimSettings.hold_time"), std::string::npos) << run(hold);
  const std::vector<std::pair<std::string, std::function<void(SimSettings&)>>> cases = {
      {"hold_time", [](SimSettings& s) { s.hold_time = kMaxPhaseTime * 1.01; }},
      {"hold_time", [](SimSettings& s) { s.hold_time = std::nan(""); }},
      {"close_time", [](SimSettings& s) { s.close_time = -1; }},
      {"close_time", [](SimSettings& s) { s.time_step = 1e-9; }},  // 0.5 s in 5e8 steps
      {"lift_height / lift_speed", [](SimSettings& s) { s.lift_speed = 1e-9; }},
      {"lift_height", [](SimSettings& s) { s.lift_height = 1e9; }},
      {"time_step", [](SimSettings& s) { s.time_step = 1.0; }},
      {"grip_force", [](SimSettings& s) { s.grip_force = std::numeric_limits<double>::infinity(); }},
      {"lift_force", [](SimSettings& s) { s.lift_force = 1e300; }},
      {"object_friction", [](SimSettings& s) { s.object_friction = std::nan(""); }},
      {"object_mass", [](SimSettings& s) { s.object_mass = -std::numeric_limits<double>::infinity(); }},
      {"success_fraction", [](SimSettings& s) { s.success_fraction = 1.5; }},
      {"solver_iterations", [](SimSettings& s) { s.solver_iterations = 2000000000; }},
  };
  for (const auto& [name, change] : cases) {
    SimSettings s;
    change(s);
    const std::string m = run(s);
    EXPECT_NE(m.find(name), std::string::npos) << name << ": " << m;
  }
  // Settings within the bounds run as before.
  SimSettings within;
  within.hold_time = 2.0;
  EXPECT_NO_THROW(execute(hand, cube, cube.rest_pose(0, 0), top_wrist(0, 0, 0.01), q(0.03), q(0.01), within));
}

TEST(SimObject, BadObjectUrdfsAreRefusedByName) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> cases = {
      // (change of the cube's text, what the message must hold)
      {cube_with(R"(<mass value="0.1"/>)", R"(<mass value="0"/>)"), "positive mass"},
      {cube_with(R"(<mass value="0.1"/>)", R"(<mass value="-0.1"/>)"), "negative mass"},
      {cube_with(R"(<mass value="0.1"/>)", R"(<mass value="nan"/>)"), "Inertial"},
      {cube_with(R"(<box size="0.04 0.04 0.04"/>)", R"(<box size="0.04 0.04"/>)"), "Link [cube]"},
      {cube_with(R"(<box size="0.04 0.04 0.04"/>)", R"(<mesh filename="gone.obj"/>)"), "gone.obj"},
      {cube_with(R"(<box size="0.04 0.04 0.04"/>)", R"(<mesh filename="gone.obj" scale="0 0 0"/>)"), "mesh scale"},
      {cube_with(R"(<lateral_friction value="0.8"/>)", R"(<lateral_friction value="nan"/>)"), "lateral_friction"},
      {cube_with(R"(<lateral_friction value="0.8"/>)", R"(<lateral_friction value="0.8abc"/>)"), "lateral_friction"},
      {cube_with(R"(<lateral_friction value="0.8"/>)", R"(<lateral_friction value="-1"/>)"), "lateral_friction"},
      {cube_with(R"(<inertia_scaling value="3"/>)", R"(<inertia_scaling value="inf"/>)"), "inertia_scaling"},
      {cube_with("</robot>", ""), "malformed XML"},
  };
  int k = 0;
  for (const auto& [text, mention] : cases) {
    const std::string path = dir.write("bad" + std::to_string(k++) + ".urdf", text);
    const std::string m = error_of([&] { SimObject::from_urdf(path); });
    EXPECT_NE(m.find(mention), std::string::npos) << mention << ": " << m;
    EXPECT_NE(m.find(path), std::string::npos) << m;
  }
  // 2 MB inside <contact>: read by a plain search (std::regex recursed per character and overflowed).
  std::string big = kCube;
  big.insert(big.find("<contact>") + 9, "<!--" + std::string(2000000, 'x') + "-->");
  EXPECT_NO_THROW(SimObject::from_urdf(dir.write("big.urdf", big)));
}
