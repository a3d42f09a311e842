// The solid volume of objects on a table against the exact insides of a box and a cylinder, and the collision
// expert charging a finger inside a completed object that touches none of its points.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/solid_volume.hpp"
#include "graspmix/robot/hand.hpp"

using graspmix::CellState;
using graspmix::CollisionExpert;
using graspmix::CollisionSettings;
using graspmix::OccupancyMap;
using graspmix::Vec3Array;

namespace {

const Eigen::Vector4d kTable(0, 0, 1, 0);  // z = 0, objects above

Vec3Array to_array(const std::vector<Eigen::Vector3d>& pts) {
  Vec3Array out(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return out;
}

/// The box [x0, x0 + 0.1] x [-0.05, 0.05] x [0, 0.1] standing on the table: its five faces off the table on a
/// grid of step s (what a completed view of it gives).
std::vector<Eigen::Vector3d> box_points(double x0 = 0.0, double s = 0.003) {
  std::vector<Eigen::Vector3d> pts;
  const int n = static_cast<int>(std::round(0.1 / s));
  const double d = 0.1 / n;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        if (i != 0 && i != n && j != 0 && j != n && k != n) continue;  // faces only, no bottom
        pts.emplace_back(x0 + i * d, -0.05 + j * d, k * d);
      }
  return pts;
}

/// A cylinder of radius r and height H on the table about the z axis: its side and top, about 3 mm apart.
std::vector<Eigen::Vector3d> cylinder_points(double r, double H) {
  std::vector<Eigen::Vector3d> pts;
  const int na = static_cast<int>(2 * M_PI * r / 0.003), nz = static_cast<int>(H / 0.003);
  for (int a = 0; a < na; ++a)
    for (int k = 0; k <= nz; ++k) {
      const double t = 2 * M_PI * a / na;
      pts.emplace_back(r * std::cos(t), r * std::sin(t), H * k / nz);
    }
  for (double x = -r; x <= r; x += 0.003)
    for (double y = -r; y <= r; y += 0.003)
      if (x * x + y * y < r * r) pts.emplace_back(x, y, H);
  return pts;
}

/// Every random point of the box [lo, hi] more than `margin` inside or outside `inside_by` (signed: > 0 inside)
/// has the state the exact shape says.
void expect_states(const OccupancyMap& map, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double margin,
                   const std::function<double(const Eigen::Vector3d&)>& inside_by) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int n_in = 0, n_out = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    if (p.z() < 2 * map.resolution()) continue;  // the layer above the table is the plane's
    const double d = inside_by(p);
    if (d > margin) {
      ++n_in;
      EXPECT_EQ(map.state(p), CellState::Occupied) << p.transpose();
    } else if (d < -margin) {
      ++n_out;
      EXPECT_EQ(map.state(p), CellState::Free) << p.transpose();
    }
  }
  EXPECT_GT(n_in, 1000);
  EXPECT_GT(n_out, 1000);
}

// The test finger: a box link 2 x 4 x 6 cm centred on its frame.
const char* kFinger = R"(<robot name="finger">
  <link name="finger"><collision><geometry><box size="0.02 0.04 0.06"/></geometry></collision></link>
</robot>)";

std::shared_ptr<const graspmix::Hand> finger() {
  return std::make_shared<graspmix::Hand>(graspmix::Hand::from_urdf_string(kFinger, "."));
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

}  // namespace

TEST(SolidVolume, BoxInsideIsOccupiedOutsideFree) {
  const OccupancyMap map = graspmix::solid_volume(to_array(box_points()), kTable);
  const double h = map.resolution();
  // Exact within a cell's diagonal (a cell is occupied by its centre).
  expect_states(map, Eigen::Vector3d(-0.05, -0.1, 0), Eigen::Vector3d(0.15, 0.1, 0.15), std::sqrt(3.0) * h,
                [](const Eigen::Vector3d& p) {
                  return -Eigen::Vector3d(std::abs(p.x() - 0.05) - 0.05, std::abs(p.y()) - 0.05,
                                          std::abs(p.z() - 0.05) - 0.05)
                              .maxCoeff();
                });
  EXPECT_EQ(map.state(Eigen::Vector3d(0.05, 0, 0.05)), CellState::Occupied);  // the middle: no point within 5 cm
}

TEST(SolidVolume, CylinderInsideIsOccupiedOutsideFree) {
  const double r = 0.04, H = 0.11;
  const OccupancyMap map = graspmix::solid_volume(to_array(cylinder_points(r, H)), kTable);
  expect_states(map, Eigen::Vector3d(-0.08, -0.08, 0), Eigen::Vector3d(0.08, 0.08, 0.15),
                std::sqrt(3.0) * map.resolution(),
                [&](const Eigen::Vector3d& p) { return std::min(r - p.head<2>().norm(), std::min(H - p.z(), p.z())); });
}

TEST(SolidVolume, SparseTopIsClosedGapBetweenObjectsIsNot) {
  // Two boxes 2 cm apart, their points 4.5 mm apart (holes in the half-cell footprint).
  std::vector<Eigen::Vector3d> pts = box_points(0.0, 0.0045), right = box_points(0.12, 0.0045);
  pts.insert(pts.end(), right.begin(), right.end());
  const OccupancyMap map = graspmix::solid_volume(to_array(pts), kTable);
  int holes = 0;
  for (double x = 0.01; x < 0.09; x += 0.0011)
    for (double y = -0.04; y < 0.04; y += 0.0013)
      holes += map.state(Eigen::Vector3d(x, y, 0.05)) != CellState::Occupied;
  EXPECT_EQ(holes, 0);
  for (double y = -0.04; y < 0.04; y += 0.001)
    for (double z = 0.02; z < 0.09; z += 0.005) EXPECT_EQ(map.state(Eigen::Vector3d(0.11, y, z)), CellState::Free);
}

TEST(SolidVolume, TiltedPlaneAndTablePoints) {
  // The same box on a table tilted by 0.3 rad about x: the map is the rotated box's.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  std::vector<Eigen::Vector3d> pts = box_points();
  for (auto& p : pts) p = R * p;
  for (double x = -0.1; x < 0.2; x += 0.003) pts.push_back(R * Eigen::Vector3d(x, -0.08, 0.0005));  // the table's
  const Eigen::Vector3d n = R.col(2);
  const OccupancyMap map = graspmix::solid_volume(to_array(pts), Eigen::Vector4d(-n.x(), -n.y(), -n.z(), 0));
  EXPECT_EQ(map.state(R * Eigen::Vector3d(0.05, 0, 0.05)), CellState::Occupied);
  EXPECT_EQ(map.state(R * Eigen::Vector3d(0.05, 0, 0.12)), CellState::Free);
  EXPECT_EQ(map.state(R * Eigen::Vector3d(0.05, -0.08, 0.02)), CellState::Free);   // above the table's points
  EXPECT_EQ(map.state(R * Eigen::Vector3d(0.05, -0.08, -0.02)), CellState::Free);  // under the table
}

TEST(SolidVolume, BadInput) {
  const Vec3Array pts = to_array(box_points());
  EXPECT_THROW(graspmix::solid_volume(pts, Eigen::Vector4d::Zero()), std::invalid_argument);
  Vec3Array bad = pts;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(graspmix::solid_volume(bad, kTable), std::invalid_argument);
  graspmix::SolidVolumeSettings s;
  s.resolution = 0;
  EXPECT_THROW(graspmix::solid_volume(pts, kTable, s), std::invalid_argument);
  s = {};
  s.gap = -1;
  EXPECT_THROW(graspmix::solid_volume(pts, kTable, s), std::invalid_argument);
  s = {};
  s.max_cells = 100;
  EXPECT_THROW(graspmix::solid_volume(pts, kTable, s), std::invalid_argument);
  // No point above the table: nothing solid.
  const OccupancyMap none = graspmix::solid_volume(Vec3Array(0, 3), kTable);
  EXPECT_EQ(none.stats().n_occupied, 0);
}

TEST(CollisionVolume, AFingerInsideACompletedObjectIsChargedOneOutsideIsNot) {
  // The box's points; the finger (2 x 4 x 6 cm) in its middle is more than 2 cm from every one of them.
  const Vec3Array pts = to_array(box_points());
  CollisionSettings with, without;
  with.volume = true;  // the default
  without.volume = false;
  const CollisionExpert surface(finger(), pts, kTable, without), volume(finger(), pts, kTable, with);
  ASSERT_TRUE(volume.has_volume());
  EXPECT_FALSE(surface.has_volume());
  const Eigen::VectorXd q(0);
  const auto in_surface = surface.evaluate(at(0.05, 0, 0.05), q), in_volume = volume.evaluate(at(0.05, 0, 0.05), q);
  EXPECT_TRUE(in_surface.collision_free);  // the gap: no point near the finger
  EXPECT_FALSE(in_volume.collision_free);
  // Wholly inside: at most the finger's volume over the reference area, and at least its core's (the samples whose
  // cells lie deeper than the erosion, 3.5 mm, plus half a cell).
  const double full = 0.02 * 0.04 * 0.06 / with.reference_area, core = 0.01 * 0.03 * 0.05 / with.reference_area;
  EXPECT_LE(in_volume.total_depth, full + 1e-12);
  EXPECT_GE(in_volume.total_depth, core);
  // Outside, clear of the box, or touching its face (0.5 mm in, within the contact tolerance): not charged.
  EXPECT_EQ(volume.evaluate(at(-0.02, 0, 0.05), q).total_depth, 0.0);
  EXPECT_TRUE(volume.evaluate(at(-0.0095, 0, 0.05), q).collision_free);
  EXPECT_TRUE(volume.evaluate(at(0.05, 0, 0.1295), q).collision_free);  // on the top face, from above
  // Half inside: charged, less than wholly inside.
  const double half = volume.evaluate(at(0.0, 0, 0.05), q).total_depth;
  EXPECT_GT(half, 0.0);
  EXPECT_LT(half, in_volume.total_depth);
  // Without a plane there is no volume.
  EXPECT_FALSE(CollisionExpert(finger(), pts, std::nullopt, with).has_volume());
  with.volume_resolution = 0;
  EXPECT_THROW(CollisionExpert(finger(), pts, kTable, with), std::invalid_argument);
}

namespace {

/// The box of box_points seen by one camera at -x (its face x = 0) and completed (its other faces), and the map of
/// what the camera saw, unknown space not an obstacle.
struct OneView {
  Vec3Array seen, completed;
  std::shared_ptr<const OccupancyMap> map;
};
OneView box_seen_from_minus_x() {
  std::vector<Eigen::Vector3d> face;
  for (const auto& p : box_points())
    if (p.x() == 0.0) face.push_back(p);
  OneView v{to_array(face), to_array(box_points()), nullptr};
  graspmix::OccupancySettings free_unknown;
  free_unknown.unknown_is_occupied = false;
  v.map = std::make_shared<const OccupancyMap>(v.seen, Eigen::RowVector3d(-0.5, 0, 0.05), v.completed, kTable,
                                               free_unknown);
  return v;
}

}  // namespace

TEST(CollisionUnseen, SpaceBehindASeenFaceIsChargedSoftlyOutsideTheVolume) {
  // One camera at -x sees the box's face x = 0; the completion gives its other faces (box_points).
  const OneView view = box_seen_from_minus_x();
  const Vec3Array &seen = view.seen, &completed = view.completed;
  const auto& map = view.map;
  CollisionSettings s;
  s.volume = false;  // first the charge alone, no margin
  s.unseen_margin = 0.0;
  s.unseen_weight = 0.1;
  const CollisionExpert soft(finger(), map, seen, kTable, s);
  const Eigen::VectorXd q(0);
  // In front of the face: seen free, no charge. Behind it (in the box, unseen): charged, yet collision-free.
  EXPECT_EQ(soft.evaluate(at(-0.03, 0, 0.05), q).total_depth, 0.0);
  const graspmix::CollisionResult behind = soft.evaluate(at(0.05, 0, 0.05), q);
  EXPECT_GT(behind.unseen_depth.sum(), 0.0);
  EXPECT_DOUBLE_EQ(behind.total_depth, behind.unseen_depth.sum());
  EXPECT_TRUE(behind.collision_free);
  // Linear in the weight.
  s.unseen_weight = 0.2;
  const CollisionExpert twice(finger(), map, seen, kTable, s);
  EXPECT_NEAR(twice.evaluate(at(0.05, 0, 0.05), q).unseen_depth.sum(), 2 * behind.unseen_depth.sum(), 1e-12);
  // With the completed box's volume, its inside is solid (hard) and no longer unseen; beyond its back face
  // (x > 0.1), the unseen is still charged softly.
  s.volume = true;
  const CollisionExpert both(finger(), map, completed, kTable, s);
  const graspmix::CollisionResult inside = both.evaluate(at(0.05, 0, 0.05), q);
  EXPECT_EQ(inside.unseen_depth.sum(), 0.0);
  EXPECT_FALSE(inside.collision_free);
  const graspmix::CollisionResult beyond = both.evaluate(at(0.13, 0, 0.05), q);
  EXPECT_GT(beyond.unseen_depth.sum(), 0.0);
  EXPECT_TRUE(beyond.collision_free);
  // With a margin, unseen cells near the volume are exempt: the finger 2-4 cm beyond the back face, within 5 cm.
  s.unseen_margin = 0.05;
  EXPECT_EQ(CollisionExpert(finger(), map, completed, kTable, s).evaluate(at(0.13, 0, 0.05), q).unseen_depth.sum(),
            0.0);
  // 1 cm exempts the part of a finger 0-2 cm beyond the back face that lies within 1 cm of it.
  const double no_margin = both.evaluate(at(0.11, 0, 0.05), q).unseen_depth.sum();
  s.unseen_margin = 0.01;
  const double near =
      CollisionExpert(finger(), map, completed, kTable, s).evaluate(at(0.11, 0, 0.05), q).unseen_depth.sum();
  EXPECT_GT(near, 0.0);
  EXPECT_LT(near, no_margin);
  s.unseen_margin = -0.01;
  EXPECT_THROW(CollisionExpert(finger(), map, completed, kTable, s), std::invalid_argument);
  s.unseen_margin = 0.0;
  // Pressed 1 cm into the seen face: the occupied cells' volume and the points' depth; without the cells, the depth.
  s.unseen_weight = 0.1;
  s.volume = false;
  const graspmix::CollisionResult pressed = CollisionExpert(finger(), map, seen, kTable, s).evaluate(at(0, 0, 0.05), q);
  s.occupied_cells = false;
  const graspmix::CollisionResult points_only =
      CollisionExpert(finger(), map, seen, kTable, s).evaluate(at(0, 0, 0.05), q);
  EXPECT_NEAR(points_only.cloud_depth.sum(), 0.01, 1e-9);
  EXPECT_GT(pressed.cloud_depth.sum(), points_only.cloud_depth.sum());
  EXPECT_DOUBLE_EQ(pressed.unseen_depth.sum(), points_only.unseen_depth.sum());
  // Unknown cells counted as obstacles by the map: charged in full as blocked, not softly on top.
  const auto hard = std::make_shared<const OccupancyMap>(seen, Eigen::RowVector3d(-0.5, 0, 0.05), seen, kTable);
  s.occupied_cells = true;
  const CollisionExpert blocked(finger(), hard, seen, kTable, s);
  EXPECT_EQ(blocked.unseen(), nullptr);
  const graspmix::CollisionResult in_hard = blocked.evaluate(at(0.05, 0, 0.05), q);
  EXPECT_EQ(in_hard.unseen_depth.sum(), 0.0);
  EXPECT_GT(in_hard.cloud_depth.sum(), 0.0);
  EXPECT_FALSE(in_hard.collision_free);
  s.unseen_weight = -1;
  EXPECT_THROW(CollisionExpert(finger(), map, seen, kTable, s), std::invalid_argument);
}

TEST(CollisionVolume, WhatTheCamerasSawThroughIsNotSolid) {
  // A plate 8 cm above the table (a shelf) on no visible legs, and a wall behind it that a camera at 4 cm height sees
  // under the plate: the plate's columns fill the space under it down to the table, which the camera saw free.
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      pts.emplace_back(0.0025 * i, -0.05 + 0.0025 * j, 0.08);      // the plate
      pts.emplace_back(0.3, -0.05 + 0.0025 * j, 0.07 * i / 40.0);  // the wall behind it
      pts.emplace_back(0.1 + 0.005 * i, -0.05 + 0.0025 * j, 0.0);  // the table between them
    }
  const Vec3Array P = to_array(pts);
  // The wall is a block's front face; its top (x 0.3 to 0.36, unseen from below) comes from a completion.
  for (int i = 0; i <= 24; ++i)
    for (int j = 0; j <= 40; ++j) pts.emplace_back(0.3 + 0.0025 * i, -0.05 + 0.0025 * j, 0.07);
  const Vec3Array solid = to_array(pts);
  graspmix::OccupancySettings free_unknown;
  free_unknown.unknown_is_occupied = false;
  const auto seen = std::make_shared<const OccupancyMap>(P, Eigen::RowVector3d(-0.5, 0, 0.04), P, kTable, free_unknown);
  const Eigen::VectorXd q(0);
  CollisionSettings s;  // the defaults: the volume and the unseen charge
  const CollisionExpert columns(finger(), solid, kTable, s), carved(finger(), solid, kTable, s, seen);
  // Under the plate (the finger from 1 to 7 cm high): solid by the columns alone, seen free with the camera's map.
  const graspmix::CollisionResult under = columns.evaluate(at(0.05, 0, 0.04), q);
  EXPECT_FALSE(under.collision_free);
  const graspmix::CollisionResult seen_under = carved.evaluate(at(0.05, 0, 0.04), q);
  EXPECT_TRUE(seen_under.collision_free);
  EXPECT_EQ(seen_under.total_depth, 0.0);
  // In the block behind the wall, where the camera did not see: still solid.
  EXPECT_FALSE(carved.evaluate(at(0.33, 0, 0.035), q).collision_free);
  EXPECT_FALSE(columns.evaluate(at(0.33, 0, 0.035), q).collision_free);
  EXPECT_TRUE(carved.has_volume());
}

namespace {

/// A frustum as an OBJ mesh (the hull the expert uses is the mesh itself): its base 2 x 4 cm at z = 0, its top
/// 1 x 2 cm at z = 6 cm: a mesh link whose proxy boxes are not its hull.
std::string frustum_obj() {
  std::string s;
  for (int i = 0; i < 8; ++i) {
    const double k = (i & 4) ? 0.5 : 1.0;
    s += "v " + std::to_string(((i & 1) ? 0.01 : -0.01) * k) + " " + std::to_string(((i & 2) ? 0.02 : -0.02) * k) +
         " " + std::to_string((i & 4) ? 0.06 : 0.0) + "\n";
  }
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f)
    s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return s;
}

}  // namespace

TEST(CollisionFreeBatch, GivesTheFullEvaluationsVerdictOnRandomHands) {
  // A mesh link (the frustum) and a box finger that slides from it, posed at random around a box seen from one
  // camera and completed: collision_free_batch (no unseen charge, first penetration ends a hand) says what
  // evaluate_batch's collision_free says, for the surface model with and without the volume and the occupancy model.
  const auto dir = std::filesystem::temp_directory_path() / "graspmix_test_collision_free_batch";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "frustum.obj") << frustum_obj();
  const auto hand = std::make_shared<graspmix::Hand>(graspmix::Hand::from_urdf_string(R"(<robot name="m">
    <link name="palm"><collision><geometry><mesh filename="frustum.obj"/></geometry></collision></link>
    <link name="finger"><collision><geometry><box size="0.01 0.02 0.05"/></geometry></collision></link>
    <joint name="slide" type="prismatic"><parent link="palm"/><child link="finger"/><origin xyz="0 0 0.06"/>
      <axis xyz="1 0 0"/><limit lower="-0.04" upper="0.04" effort="1" velocity="1"/></joint></robot>)",
                                                                                      dir.string()));
  std::filesystem::remove_all(dir);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  const OneView view = box_seen_from_minus_x();
  const Vec3Array &seen = view.seen, &completed = view.completed;
  const auto& map = view.map;
  const int N = 600;
  graspmix::PoseArray W(N, 7);
  graspmix::RowMatrixXd Q(N, 1);
  for (int i = 0; i < N; ++i) {
    Eigen::Vector4d qv(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
    qv.normalize();
    W.row(i) << 0.2 * U(rng) - 0.05, 0.16 * (U(rng) - 0.5), 0.15 * U(rng), qv[0], qv[1], qv[2], qv[3];
    Q(i, 0) = 0.08 * (U(rng) - 0.5);
  }
  CollisionSettings s;
  s.unseen_weight = 0.1;
  const CollisionExpert volume_unseen(hand, completed, kTable, s, map), occupancy(hand, map, completed, kTable, s);
  s.volume = false;
  const CollisionExpert surface(hand, completed, kTable, s);
  for (const CollisionExpert* e : {&volume_unseen, &occupancy, &surface}) {
    const graspmix::CollisionBatchResult full = e->evaluate_batch(W, Q);
    const Eigen::Matrix<bool, Eigen::Dynamic, 1> fast = e->collision_free_batch(W, Q);
    ASSERT_EQ(fast.size(), N);
    int free = 0, soft = 0;
    for (int i = 0; i < N; ++i) {
      EXPECT_EQ(fast[i], full.collision_free[i]) << "hand " << i;
      free += fast[i];
      soft += fast[i] && full.unseen_depth.row(i).sum() > 0;
    }
    EXPECT_GT(free, N / 5);  // both verdicts well represented
    EXPECT_LT(free, 4 * N / 5);
    if (e != &surface) EXPECT_GT(soft, 10);  // hands in unseen space only: charged, yet free
  }
}
