// The collision expert against analytic penetration depths.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "graspmix/core/se3.hpp"
#include "graspmix/grasp/collision.hpp"
#include "graspmix/robot/hand.hpp"

using graspmix::CollisionExpert;
using graspmix::CollisionSettings;
using graspmix::Hand;
using graspmix::Vec3Array;

namespace {

// A "finger": a free box link 2 x 4 x 6 cm centred on its frame, and a child sphere and cylinder that
// sit far away along +z (so that they never touch the object unless a test moves them there).
const char* kFinger = R"(<robot name="finger">
  <link name="finger"><collision><geometry><box size="0.02 0.04 0.06"/></geometry></collision></link>
  <link name="ball"><collision><geometry><sphere radius="0.01"/></geometry></collision></link>
  <link name="rod"><collision><origin rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.01" length="0.04"/></geometry></collision></link>
  <joint name="to_ball" type="prismatic"><parent link="finger"/><child link="ball"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="to_rod" type="fixed"><parent link="finger"/><child link="rod"/><origin xyz="0 0 2"/></joint>
</robot>)";

std::shared_ptr<const Hand> finger() { return std::make_shared<Hand>(Hand::from_urdf_string(kFinger, ".")); }

/// These tests measure exact depths: no contact tolerance.
/// The paper's expert at exact depths: the points and the plane alone (no solid volume: test_solid_volume's).
CollisionSettings exact() {
  CollisionSettings s;
  s.contact_tolerance = 1e-9;
  s.volume = false;
  return s;
}

/// Points on the surface of the box [0, 0.1] x [-0.05, 0.05] x [-0.05, 0.05] on a 2.5 mm grid.
Vec3Array box_surface() {
  std::vector<Eigen::Vector3d> pts;
  const double s = 0.0025;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j)
      for (int k = 0; k <= 40; ++k) {
        if (i != 0 && i != 40 && j != 0 && j != 40 && k != 0 && k != 40) continue;
        pts.emplace_back(i * s, -0.05 + j * s, -0.05 + k * s);
      }
  Vec3Array out(static_cast<Eigen::Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return out;
}

Eigen::Isometry3d at(double x, double y = 0, double z = 0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

}  // namespace

TEST(Collision, DepthOfAFingerPushedIntoABoxIsAnalytic) {
  const CollisionExpert expert(finger(), box_surface(), std::nullopt, exact());
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1);
  double previous = -1;
  for (int step = 0; step <= 8; ++step) {
    const double depth = 0.001 * step;  // the finger's +x face at x = depth, inside the box's x = 0 face
    const auto r = expert.evaluate(at(depth - 0.01), q);
    // The deepest points are those of the face x = 0 under the finger: depth from the finger's +x face.
    EXPECT_NEAR(r.cloud_depth[0], depth, 1e-12) << depth;
    EXPECT_NEAR(r.total_depth, depth, 1e-12);
    EXPECT_NEAR(r.log_w, -expert.settings().beta * depth, 1e-9);
    EXPECT_EQ(r.collision_free, step == 0);
    EXPECT_GE(r.total_depth, previous);
    previous = r.total_depth;
  }
  // Clear of the box: zero, and free.
  const auto clear = expert.evaluate(at(-0.0101), q);
  EXPECT_EQ(clear.total_depth, 0.0);
  EXPECT_TRUE(clear.collision_free);
  EXPECT_EQ(clear.w, 1.0);
  // Half-way through the face the deepest points lie on the finger's mid-plane: its half-thickness.
  EXPECT_NEAR(expert.evaluate(at(0.0), q).cloud_depth[0], 0.01, 1e-12);
  // A cloud is a surface: a finger wholly inside the hollow box touches no point (see collision.hpp).
  EXPECT_EQ(expert.evaluate(at(0.05), q).cloud_depth[0], 0.0);
}

TEST(Collision, PointRadiusInflatesPoints) {
  CollisionSettings s = exact();
  s.point_radius = 0.002;
  const CollisionExpert expert(finger(), box_surface(), std::nullopt, s);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1);
  EXPECT_NEAR(expert.evaluate(at(-0.01 - 0.001), q).cloud_depth[0], 0.001, 1e-12);
  EXPECT_TRUE(expert.evaluate(at(-0.01 - 0.0021), q).collision_free);
}

TEST(Collision, SphereAndCylinderDepthsAreAnalytic) {
  const CollisionExpert expert(finger(), box_surface(), std::nullopt, exact());
  const Hand& hand = expert.hand();
  // The ball (radius 1 cm, at wrist + (0, 0, 1 + q)) with its centre at x = -0.01 + d reaches d into
  // the face x = 0; the finger box is then 1.5 m below the object.
  Eigen::VectorXd q(1);
  q[0] = 0.5;
  for (double d : {0.0005, 0.002, 0.006}) {
    const auto r = expert.evaluate(at(-0.01 + d, 0, -1.5), q);
    EXPECT_NEAR(r.cloud_depth[hand.link_index("ball")], d, 1e-12) << d;
    EXPECT_NEAR(r.total_depth, d, 1e-12);
  }
  // The rod (radius 1 cm, 4 cm long along x, at wrist + (0, 0, 2)) with its +x cap at x = d.
  for (double d : {0.001, 0.004}) {
    const auto r = expert.evaluate(at(d - 0.02, 0, -2), Eigen::VectorXd::Zero(1));
    EXPECT_NEAR(r.cloud_depth[hand.link_index("rod")], d, 1e-12) << d;
    EXPECT_NEAR(r.total_depth, d, 1e-12);
  }
}

TEST(Collision, SupportPlaneBlocksAHandBelowTheTable) {
  // A table z = 0 under the box; plane given with the normal pointing down: it is reoriented so the
  // cloud (above) is on the free side.
  Vec3Array cloud = box_surface();
  cloud.col(2).array() += 0.05 + 1e-9;
  const CollisionExpert expert(finger(), cloud, Eigen::Vector4d(0, 0, -2, 0), exact());
  EXPECT_LT((expert.plane() - Eigen::Vector4d(0, 0, 1, 0)).norm(), 1e-12);
  const Hand& hand = expert.hand();
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1);
  // Finger (6 cm tall box) beside the object, its bottom at z = -d.
  for (double d : {0.0, 0.001, 0.005, 0.02}) {
    const auto r = expert.evaluate(at(-0.2, 0, 0.03 - d), q);
    EXPECT_NEAR(r.plane_depth[0], d, 1e-9) << d;
    EXPECT_EQ(r.cloud_depth.sum(), 0.0);
    EXPECT_EQ(r.collision_free, d == 0.0);
  }
  // Sphere and cylinder links below the table: their lowest points at z = -d (FCL's half-space tests).
  for (double d : {0.002, 0.01}) {
    Eigen::VectorXd qb(1);
    qb[0] = -1.0;  // the ball at the wrist: compare the ball link's depth only
    const auto r = expert.evaluate(at(-0.2, 0, 0.01 - d), qb);
    EXPECT_NEAR(r.plane_depth[hand.link_index("ball")], d, 1e-9);
    const auto rr = expert.evaluate(at(-0.2, 0, -2 + 0.01 - d), q);
    EXPECT_NEAR(rr.plane_depth[hand.link_index("rod")], d, 1e-9);
  }
  // A tilted box: its lowest corner decides.
  Eigen::Isometry3d T = at(-0.2, 0, 0.0);
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double lowest = (T.linear().cwiseAbs() * Eigen::Vector3d(0.01, 0.02, 0.03)).z();
  EXPECT_NEAR(expert.evaluate(T, q).plane_depth[0], lowest, 1e-9);
  // A margin raises the plane.
  CollisionSettings s = exact();
  s.plane_margin = 0.004;
  const CollisionExpert raised(finger(), cloud, Eigen::Vector4d(0, 0, 1, 0), s);
  EXPECT_NEAR(raised.evaluate(at(-0.2, 0, 0.03 + 0.001), q).plane_depth[0], 0.003, 1e-9);
}

TEST(Collision, BatchEqualsSingleAndBruteForce) {
  const Vec3Array cloud = box_surface();
  const CollisionExpert expert(finger(), cloud, Eigen::Vector4d(0, 0, 1, 0.05), exact());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  const int N = 200;
  graspmix::PoseArray W(N, 7);
  graspmix::RowMatrixXd Q(N, 1);
  for (int i = 0; i < N; ++i) {
    Eigen::Vector4d qv(U(rng), U(rng), U(rng), U(rng));
    qv.normalize();
    W.row(i) << 0.05 + 0.07 * U(rng), 0.07 * U(rng), 0.07 * U(rng), qv[0], qv[1], qv[2], qv[3];
    Q(i, 0) = -1.0;  // ball onto the finger's centre
  }
  const auto batch = expert.evaluate_batch(W, Q);
  int colliding = 0;
  for (int i = 0; i < N; ++i) {
    const Eigen::Isometry3d T = graspmix::pose_from_vector(W.row(i).transpose());
    const auto r = expert.evaluate(T, Q.row(i).transpose());
    EXPECT_DOUBLE_EQ(batch.total_depth[i], r.total_depth);
    EXPECT_EQ(batch.collision_free[i], r.collision_free);
    // Brute force over every point for the finger box.
    double deepest = 0;
    for (Eigen::Index p = 0; p < cloud.rows(); ++p) {
      const Eigen::Vector3d x = T.inverse() * Eigen::Vector3d(cloud.row(p).transpose());
      const Eigen::Vector3d inside = Eigen::Vector3d(0.01, 0.02, 0.03) - x.cwiseAbs();
      if (inside.minCoeff() > 0) deepest = std::max(deepest, inside.minCoeff());
    }
    EXPECT_NEAR(r.cloud_depth[0], deepest, 1e-12);
    colliding += r.collision_free ? 0 : 1;
  }
  EXPECT_GT(colliding, 20);
  EXPECT_LT(colliding, N);
}

TEST(Collision, BadInputThrows) {
  Vec3Array bad = box_surface();
  bad(3, 1) = std::nan("");
  EXPECT_THROW(CollisionExpert(finger(), bad), std::invalid_argument);
  EXPECT_THROW(CollisionExpert(finger(), box_surface(), Eigen::Vector4d(0, 0, 0, 1)), std::invalid_argument);
  CollisionSettings s = exact();
  s.point_radius = -1;
  EXPECT_THROW(CollisionExpert(finger(), box_surface(), std::nullopt, s), std::invalid_argument);
  // A hand read without mesh geometry cannot feed the expert (the file need only exist).
  graspmix::HandLoadSettings no_meshes;
  no_meshes.load_meshes = false;
  const auto dir = std::filesystem::temp_directory_path();
  std::ofstream(dir / "graspmix_test_unread.stl") << "solid x\nendsolid x\n";
  const auto mesh_hand = std::make_shared<Hand>(Hand::from_urdf_string(
      R"(<robot name="m"><link name="a"><collision><geometry><mesh filename="graspmix_test_unread.stl"/></geometry></collision></link></robot>)",
      dir.string(), no_meshes));
  EXPECT_THROW(CollisionExpert(mesh_hand, box_surface()), std::invalid_argument);
  std::filesystem::remove(dir / "graspmix_test_unread.stl");
  const CollisionExpert e(finger(), box_surface(), std::nullopt, exact());
  EXPECT_THROW(e.evaluate(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(2)), std::invalid_argument);
}

TEST(Collision, BatchBroadcastsASingleWristOrConfiguration) {
  const CollisionExpert expert(finger(), box_surface(), std::nullopt, exact());
  graspmix::PoseArray one(1, 7);
  one << 0.005 - 0.01, 0, -1.5, 0, 0, 0, 1;
  graspmix::RowMatrixXd qs(3, 1);
  qs << 0.5, 0.0, 0.5;  // the ball at the object's face, 0.5 m away from it, at the face again
  const auto r = expert.evaluate_batch(one, qs);
  ASSERT_EQ(r.total_depth.size(), 3);
  EXPECT_NEAR(r.total_depth[0], 0.005, 1e-12);
  EXPECT_EQ(r.total_depth[1], 0.0);
  EXPECT_NEAR(r.total_depth[2], 0.005, 1e-12);
  EXPECT_THROW(expert.evaluate_batch(graspmix::PoseArray(2, 7), qs), std::invalid_argument);
}

TEST(Collision, InsideWeightAddsPerPenetratingPoint) {
  CollisionSettings s = exact();
  s.inside_weight = 0.0005;
  const CollisionExpert weighted(finger(), box_surface(), std::nullopt, s);
  const CollisionExpert plain(finger(), box_surface(), std::nullopt, exact());
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1);
  for (double x : {-0.0101, -0.006, 0.0}) {
    const auto a = weighted.evaluate(at(x), q), b = plain.evaluate(at(x), q);
    EXPECT_EQ(a.points_inside.sum(), b.points_inside.sum());
    EXPECT_NEAR(a.total_depth, b.total_depth + 0.0005 * b.points_inside.sum(), 1e-12) << x;
    EXPECT_EQ(a.collision_free, b.collision_free);
  }
  // Past the face's mid-plane the deepest depth falls again (the finger is nearly through the sheet of
  // points); the number of points inside does not.
  const double through_plain = plain.evaluate(at(0.008), q).total_depth;
  EXPECT_LT(through_plain, 0.0021);
  EXPECT_GT(weighted.evaluate(at(0.008), q).total_depth, 10.0 * through_plain);
  s.inside_weight = -1.0;
  EXPECT_THROW(CollisionExpert(finger(), box_surface(), std::nullopt, s), std::invalid_argument);
}

// ---- the occupancy model -------------------------------------------------------------------------

namespace {

/// box_surface() seen from outside every face: each point's camera 0.5 m out along its face's normal,
/// so the box's inside is what no ray reached (unknown) and the space around it was seen free.
std::shared_ptr<const graspmix::OccupancyMap> box_seen_all_round() {
  const Vec3Array pts = box_surface();
  Vec3Array views(pts.rows(), 3);
  const Eigen::Vector3d centre(0.05, 0, 0);
  for (Eigen::Index i = 0; i < pts.rows(); ++i) {
    const Eigen::Vector3d d = pts.row(i).transpose() - centre;
    Eigen::Index axis = 0;
    (d.cwiseAbs().array() / Eigen::Array3d(0.05, 0.05, 0.05)).maxCoeff(&axis);
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[axis] = d[axis] > 0 ? 1.0 : -1.0;
    views.row(i) = (pts.row(i).transpose() + 0.5 * n).transpose();
  }
  return std::make_shared<const graspmix::OccupancyMap>(pts, views, pts);
}

double occupancy_charge(const CollisionExpert& e, double x) {
  return e.evaluate(at(x), Eigen::VectorXd::Zero(1)).cloud_depth[0];
}

}  // namespace

TEST(CollisionOccupancy, ChargeGrowsWithDepthAndDoesNotSaturate) {
  const Vec3Array none(0, 3);
  const CollisionExpert occ(finger(), box_seen_all_round(), none);
  EXPECT_EQ(occ.settings().model, graspmix::CollisionModel::Occupancy);
  // The finger (2 cm thick along x) enters the face x = 0 by d: centred at x = d - 0.01.
  EXPECT_EQ(occupancy_charge(occ, -0.0105), 0.0);  // 0.5 mm off the face
  EXPECT_EQ(occupancy_charge(occ, -0.0095), 0.0);  // touching, 0.5 mm in: within the tolerance
  // It grows with depth in steps of the map's cells (the erosion hides the first few millimetres).
  std::vector<double> c;
  for (double d : {0.01, 0.015, 0.02, 0.03}) c.push_back(occupancy_charge(occ, d - 0.01));
  EXPECT_GT(c[0], 0.0);
  EXPECT_GT(c[1], c[0]);
  EXPECT_GE(c[2], c[1]);
  EXPECT_GE(c[3], c[2]);
  // Wholly inside: at least any partial entry, at most the link's volume over the reference area.
  const double inside = occupancy_charge(occ, 0.05);
  EXPECT_GE(inside, c[3]);
  EXPECT_GT(inside, 10 * 0.003);  // ten times what a 3 mm surface penetration costs
  EXPECT_LE(inside, 0.02 * 0.04 * 0.06 / occ.settings().reference_area + 1e-12);
  const graspmix::CollisionResult r = occ.evaluate(at(0.05), Eigen::VectorXd::Zero(1));
  EXPECT_FALSE(r.collision_free);
  EXPECT_NEAR(r.log_w, -occ.settings().beta * r.total_depth, 1e-9);
  // The surface model sees no point inside the same finger: the gap the occupancy model closes.
  const CollisionExpert surface(finger(), box_surface());
  EXPECT_EQ(surface.evaluate(at(0.05), Eigen::VectorXd::Zero(1)).cloud_depth[0], 0.0);
  // Given the cloud too, the occupancy model also charges shallow penetrations by their exact depth.
  const CollisionExpert both(finger(), box_seen_all_round(), box_surface(), std::nullopt, exact());
  EXPECT_EQ(occupancy_charge(occ, 0.003 - 0.01), 0.0);
  EXPECT_NEAR(occupancy_charge(both, 0.003 - 0.01), 0.003, 1e-9);
  // The batch agrees with single evaluations.
  graspmix::PoseArray W(3, 7);
  for (int i = 0; i < 3; ++i) W.row(i) = graspmix::pose_to_vector(at(-0.01 + 0.02 * i)).transpose();
  const auto b = occ.evaluate_batch(W, graspmix::RowMatrixXd::Zero(1, 1));
  for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(b.cloud_depth(i, 0), occupancy_charge(occ, -0.01 + 0.02 * i));
}

TEST(CollisionOccupancy, BehindAnObjectFromOneCameraIsCharged) {
  // One camera at -x sees only the face x = 0 of the box.
  Vec3Array face(41 * 41, 3);
  for (int j = 0; j <= 40; ++j)
    for (int k = 0; k <= 40; ++k) face.row(j * 41 + k) << 0.0, -0.05 + 0.0025 * j, -0.05 + 0.0025 * k;
  auto map = std::make_shared<const graspmix::OccupancyMap>(face, Eigen::RowVector3d(-0.5, 0, 0), face);
  const CollisionExpert occ(finger(), map, Vec3Array(0, 3));
  EXPECT_TRUE(occ.evaluate(at(-0.04), Eigen::VectorXd::Zero(1)).collision_free);  // in front: seen free
  EXPECT_GT(occupancy_charge(occ, 0.06), 0.0);                                    // behind: unseen
  // With unknown space taken as free, the same finger behind the face is not charged.
  graspmix::OccupancySettings free_unknown;
  free_unknown.unknown_is_occupied = false;
  const CollisionExpert lax(finger(),
                            std::make_shared<const graspmix::OccupancyMap>(face, Eigen::RowVector3d(-0.5, 0, 0), face,
                                                                           std::nullopt, free_unknown),
                            Vec3Array(0, 3));
  EXPECT_EQ(occupancy_charge(lax, 0.06), 0.0);
}

TEST(CollisionOccupancy, ModelNamesAndBadInput) {
  EXPECT_EQ(graspmix::collision_model_from_string("occupancy"), graspmix::CollisionModel::Occupancy);
  EXPECT_EQ(graspmix::to_string(graspmix::CollisionModel::Surface), "surface");
  EXPECT_THROW(graspmix::collision_model_from_string("voxels"), std::invalid_argument);
  CollisionSettings s;
  s.model = graspmix::CollisionModel::Occupancy;
  EXPECT_THROW(CollisionExpert(finger(), box_surface(), std::nullopt, s), std::invalid_argument);
  EXPECT_THROW(CollisionExpert(finger(), std::shared_ptr<const graspmix::OccupancyMap>(), box_surface()),
               std::invalid_argument);
  s = CollisionSettings{};
  s.reference_area = 0.0;
  EXPECT_THROW(CollisionExpert(finger(), box_seen_all_round(), box_surface(), std::nullopt, s), std::invalid_argument);
}

namespace {

// A hand of every shape kind, offset and rotated in its links: a long flat palm box (rotated about z and
// off its link's origin), a finger with two boxes on a prismatic joint, a sphere and a cylinder on a
// revolute one.
const char* kMixedHand = R"(<robot name="mixed">
  <link name="palm"><collision><origin xyz="0.01 -0.005 0.03" rpy="0 0 0.4"/><geometry><box size="0.146 0.05 0.0725"/></geometry></collision></link>
  <link name="finger">
    <collision><origin xyz="-0.0115 0 0.0445"/><geometry><box size="0.023 0.03 0.073"/></geometry></collision>
    <collision><origin xyz="-0.012 0 0.012" rpy="0.2 0 0"/><geometry><box size="0.018 0.03 0.024"/></geometry></collision>
  </link>
  <link name="knob">
    <collision><origin xyz="0 0.02 0"/><geometry><sphere radius="0.012"/></geometry></collision>
    <collision><origin xyz="0 -0.02 0.01" rpy="0.7 0.3 0"/><geometry><cylinder radius="0.01" length="0.05"/></geometry></collision>
  </link>
  <joint name="slide" type="prismatic"><parent link="palm"/><child link="finger"/><origin xyz="0 0 0.07"/><axis xyz="1 0 0"/><limit lower="-0.06" upper="0.06" effort="1" velocity="1"/></joint>
  <joint name="turn" type="revolute"><parent link="palm"/><child link="knob"/><origin xyz="0.05 0 0.08"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
</robot>)";

/// Brute-force signed distance (shape frame), from the shapes' definitions.
double reference_distance(const graspmix::CollisionShape& s, const Eigen::Vector3d& p) {
  using graspmix::ShapeType;
  if (s.type == ShapeType::Sphere) return p.norm() - s.size.x();
  Eigen::Vector3d q;
  if (s.type == ShapeType::Box) {
    q = p.cwiseAbs() - 0.5 * s.size;
  } else {  // cylinder: radial and axial excess, with a zero third
    q = Eigen::Vector3d(std::sqrt(p.x() * p.x() + p.y() * p.y()) - s.size.x(), std::abs(p.z()) - 0.5 * s.size.y(),
                        -1e300);
  }
  const double outside =
      std::sqrt(std::pow(std::max(q[0], 0.0), 2) + std::pow(std::max(q[1], 0.0), 2) + std::pow(std::max(q[2], 0.0), 2));
  return q.maxCoeff() > 0 ? outside : q.maxCoeff();
}

/// Brute-force depth of the lowest point of a shape posed at T below the plane n . x + d = margin.
double reference_plane_depth(const graspmix::CollisionShape& s, const Eigen::Isometry3d& T, const Eigen::Vector4d& pl,
                             double margin) {
  using graspmix::ShapeType;
  const Eigen::Vector3d n = pl.head<3>();
  const Eigen::Matrix3d& R = T.linear();
  double reach = 0;  // how far the shape reaches from its centre along -n
  if (s.type == ShapeType::Sphere) reach = s.size.x();
  if (s.type == ShapeType::Box) {
    for (int k = 0; k < 3; ++k) reach += 0.5 * s.size[k] * std::abs(n.dot(R.col(k)));
  }
  if (s.type == ShapeType::Cylinder) {
    const double c = std::abs(n.dot(R.col(2)));
    reach = 0.5 * s.size.y() * c + s.size.x() * std::sqrt(std::max(0.0, 1 - c * c));
  }
  return margin - (n.dot(T.translation()) + pl[3] - reach);
}

}  // namespace

TEST(Collision, ColumnCullingAndPlaneFormulaMatchBruteForceOnRandomHands) {
  // A mug-like cloud (a cylinder's side and top, 4000 points) on a tilted table; random hands around it, over
  // automatic and fine grids and point radii: every term equals a brute force over all points and shapes.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  Vec3Array cloud(4000, 3);
  for (Eigen::Index i = 0; i < cloud.rows(); ++i) {
    const double a = 2 * M_PI * U(rng), top = i % 5 == 0, rr = top ? 0.04 * std::sqrt(U(rng)) : 0.04;
    cloud.row(i) << rr * std::cos(a), rr * std::sin(a), top ? 0.12 : 0.12 * U(rng);
  }
  Eigen::Vector4d plane(0.05, -0.03, 1, 0.002);
  plane /= plane.head<3>().norm();
  const auto hand = std::make_shared<Hand>(Hand::from_urdf_string(kMixedHand, "."));
  const int N = 300;
  graspmix::PoseArray W(N, 7);
  graspmix::RowMatrixXd Q(N, 2), Q2(N, 2);
  for (int i = 0; i < N; ++i) {
    Eigen::Vector4d qv(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
    qv.normalize();
    W.row(i) << 0.16 * (U(rng) - 0.5), 0.16 * (U(rng) - 0.5), 0.16 * U(rng) - 0.02, qv[0], qv[1], qv[2], qv[3];
    Q.row(i) << 0.12 * (U(rng) - 0.5), 3 * (U(rng) - 0.5);
    Q2.row(i) << 0.12 * (U(rng) - 0.5), Q(i, 1);  // the knob stays put: its terms are reused by log_w_pair
  }
  for (const double cell : {0.0, 0.003}) {
    for (const double radius : {0.0, 0.002}) {
      CollisionSettings s;
      s.volume = false;  // the points' and the plane's terms against brute force
      s.cell_size = cell;
      s.point_radius = radius;
      s.plane_margin = 0.001;
      const CollisionExpert expert(hand, cloud, plane, s);
      const auto batch = expert.evaluate_batch(W, Q);
      int hits = 0;
      for (int i = 0; i < N; ++i) {
        const auto poses = hand->fk(graspmix::pose_from_vector(W.row(i).transpose()), Q.row(i).transpose());
        for (int l = 0; l < hand->n_links(); ++l) {
          double deepest = 0, below = 0;
          for (const auto& sh : hand->links()[l].collisions) {
            const Eigen::Isometry3d T = poses[l] * sh.T_link_shape;
            for (Eigen::Index p = 0; p < cloud.rows(); ++p) {
              const double d = radius - reference_distance(sh, T.inverse() * Eigen::Vector3d(cloud.row(p).transpose()));
              if (d > s.contact_tolerance) deepest = std::max(deepest, d);
            }
            const double pd = reference_plane_depth(sh, T, plane, s.plane_margin);
            if (pd > s.contact_tolerance) below = std::max(below, pd);
          }
          EXPECT_NEAR(batch.cloud_depth(i, l), deepest, 1e-9) << i << " " << l << " cell " << cell;
          EXPECT_NEAR(batch.plane_depth(i, l), below, 1e-9) << i << " " << l << " cell " << cell;
          hits += deepest > 0;
        }
      }
      EXPECT_GT(hits, N / 5);
      // The pair equals two batches, exactly.
      const auto [w1, w2] = expert.log_w_pair(W, Q, Q2);
      const auto batch2 = expert.evaluate_batch(W, Q2);
      for (int i = 0; i < N; ++i) {
        EXPECT_EQ(w1[i], batch.log_w[i]);
        EXPECT_EQ(w2[i], batch2.log_w[i]);
      }
    }
  }
}
