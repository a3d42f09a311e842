// Hand: URDF loading (urdfdom), mesh loading (assimp) and fk against analytic answers.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspmix/core/se3.hpp"
#include "graspmix/robot/hand.hpp"

namespace fs = std::filesystem;
using graspmix::Hand;
using graspmix::kMaxUrdfLinks;

namespace {

// A planar arm: base -(revolute z, at x=0)- l1 -(revolute z, at x=0.3)- l2 -(fixed, x=0.2)- tip,
// plus a prismatic slider on l1 along its y, a continuous wheel on the base, and a mimic of joint a.
const char* kArm = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="l1"><collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.02 0.02"/></geometry></collision></link>
  <link name="l2"><collision><origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/><geometry><cylinder radius="0.01" length="0.2"/></geometry></collision></link>
  <link name="tip"><collision><geometry><sphere radius="0.015"/></geometry></collision></link>
  <link name="slider"/>
  <link name="wheel"/>
  <link name="twin"/>
  <joint name="a" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.3 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="c" type="fixed"><parent link="l2"/><child link="tip"/><origin xyz="0.2 0 0"/></joint>
  <joint name="d" type="prismatic"><parent link="l1"/><child link="slider"/><axis xyz="0 2 0"/><limit lower="0" upper="0.1" effort="1" velocity="1"/></joint>
  <joint name="e" type="continuous"><parent link="base"/><child link="wheel"/><origin xyz="0 0 0.1" rpy="1.5707963267948966 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="m" type="revolute"><parent link="base"/><child link="twin"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="a" multiplier="-2" offset="0.5"/></joint>
</robot>)";

struct TempDir {
  fs::path path;
  TempDir() {
    std::mt19937_64 rng(std::random_device{}());
    path = fs::temp_directory_path() / ("graspmix_test_" + std::to_string(rng()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    fs::create_directories((path / name).parent_path());
    std::ofstream(path / name) << text;
    return path / name;
  }
};

Hand arm() { return Hand::from_urdf_string(kArm, "."); }

std::string cube_obj() {
  std::string s;
  for (int i = 0; i < 8; ++i)
    s += "v " + std::to_string((i & 1) ? 0.5 : -0.5) + " " + std::to_string((i & 2) ? 0.5 : -0.5) + " " +
         std::to_string((i & 4) ? 0.5 : -0.5) + "\n";
  const int f[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& t : f)
    s += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return s;
}

std::string tetra_stl() {  // ascii STL of the unit corner tetrahedron
  const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string s = "solid t\n";
  for (const auto& t : f) {
    s += "facet normal 0 0 0\nouter loop\n";
    for (int k : t)
      s += "vertex " + std::to_string(v[k][0]) + " " + std::to_string(v[k][1]) + " " + std::to_string(v[k][2]) + "\n";
    s += "endloop\nendfacet\n";
  }
  return s + "endsolid t\n";
}

}  // namespace

TEST(Hand, NamesLimitsAndOrder) {
  const Hand h = arm();
  EXPECT_EQ(h.name(), "arm");
  EXPECT_EQ(h.link_names().front(), "base");
  EXPECT_EQ(h.n_links(), 7);
  // Independent joints only: the fixed c and the mimic m are not degrees of freedom.
  ASSERT_EQ(h.n_dofs(), 4);
  for (const auto& n : {"a", "b", "d", "e"}) EXPECT_NO_THROW(h.dof_index(n));
  EXPECT_THROW(h.dof_index("m"), std::invalid_argument);
  const auto lim = h.joint_limits();
  EXPECT_DOUBLE_EQ(lim(h.dof_index("a"), 0), -1.0);
  EXPECT_DOUBLE_EQ(lim(h.dof_index("d"), 1), 0.1);
  EXPECT_TRUE(std::isinf(lim(h.dof_index("e"), 0)));
  // Parents come before children.
  for (const auto& j : h.joints()) EXPECT_LT(j.parent_link, j.child_link);
}

TEST(Hand, FkMatchesPlanarArmAnalytically) {
  const Hand h = arm();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd q(4);
    for (int i = 0; i < 4; ++i) q[i] = U(rng);
    const double a = q[h.dof_index("a")], b = q[h.dof_index("b")], d = q[h.dof_index("d")], e = q[h.dof_index("e")];
    Eigen::Isometry3d W = Eigen::Isometry3d::Identity();
    W.translation() = Eigen::Vector3d(U(rng), U(rng), U(rng));
    W.linear() = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
    const auto P = h.fk(W, q);
    auto local = [&](const std::string& link) { return W.inverse() * P[static_cast<size_t>(h.link_index(link))]; };
    const Eigen::Vector3d tip(0.3 * std::cos(a) + 0.2 * std::cos(a + b), 0.3 * std::sin(a) + 0.2 * std::sin(a + b), 0);
    EXPECT_LT((local("tip").translation() - tip).norm(), 1e-12);
    EXPECT_NEAR(Eigen::AngleAxisd(local("tip").linear()).angle(), std::abs(std::remainder(a + b, 2 * M_PI)), 1e-9);
    // The prismatic axis (0 2 0) is normalised: the slider moves d along l1's y.
    EXPECT_LT((local("slider").translation() - d * Eigen::Vector3d(-std::sin(a), std::cos(a), 0)).norm(), 1e-12);
    // Continuous joint at a rotated origin: rotation about the joint frame's z = the base's -y.
    const Eigen::Matrix3d Rw = local("wheel").linear();
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                                     Eigen::AngleAxisd(e, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT((Rw - expected).norm(), 1e-12);
    // Mimic: value = -2 a + 0.5.
    EXPECT_NEAR(Eigen::AngleAxisd(local("twin").linear()).angle(), std::abs(-2 * a + 0.5), 1e-9);
  }
}

TEST(Hand, BatchedFkEqualsSingle) {
  const Hand h = arm();
  graspmix::PoseArray W(3, 7);
  W << 0, 0, 0, 0, 0, 0, 1, 1, 2, 3, 0, 0, 0.7071067811865476, 0.7071067811865476, -1, 0, 0.5, 0.5, 0.5, 0.5, 0.5;
  graspmix::RowMatrixXd Q(3, 4);
  Q << 0.1, 0.2, 0.03, 0.4, -0.5, 0.6, 0.07, -0.8, 0.9, -1.0, 0.01, 1.2;
  const graspmix::RowMatrixXd out = h.fk_batch(W, Q);
  ASSERT_EQ(out.rows(), 3);
  ASSERT_EQ(out.cols(), 7 * h.n_links());
  for (int i = 0; i < 3; ++i) {
    const auto P = h.fk(graspmix::pose_from_vector(W.row(i).transpose()), Q.row(i).transpose());
    for (int l = 0; l < h.n_links(); ++l) {
      const auto T = graspmix::pose_from_vector(out.block<1, 7>(i, 7 * l).transpose());
      EXPECT_LT((T.matrix() - P[static_cast<size_t>(l)].matrix()).norm(), 1e-12);
    }
  }
}

TEST(Hand, JointMapsAndErrors) {
  const Hand h = arm();
  const Eigen::VectorXd q = h.joints_from_map({{"a", 0.1}, {"b", 0.2}, {"d", 0.05}, {"e", 3.0}});
  EXPECT_DOUBLE_EQ(q[h.dof_index("e")], 3.0);
  // A consistent mimic value is accepted, an inconsistent one is not.
  EXPECT_NO_THROW(h.joints_from_map({{"a", 0.1}, {"b", 0.2}, {"d", 0.05}, {"e", 3.0}, {"m", 0.3}}));
  EXPECT_THROW(h.joints_from_map({{"a", 0.1}, {"b", 0.2}, {"d", 0.05}, {"e", 3.0}, {"m", 0.0}}), std::invalid_argument);
  try {
    h.joints_from_map({{"a", 0.1}, {"b", 0.2}, {"d", 0.05}, {"e", 3.0}, {"nope", 1.0}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos);
  }
  try {
    h.joints_from_map({{"a", 0.1}, {"b", 0.2}, {"d", 0.05}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'e' is missing"), std::string::npos);
  }
  try {
    h.fk(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(3));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected 4"), std::string::npos);
  }
  EXPECT_TRUE(h.within_limits(h.clamp(Eigen::VectorXd::Constant(4, 5.0))));
  EXPECT_FALSE(h.within_limits(Eigen::VectorXd::Constant(4, 5.0)));
}

TEST(Hand, LoadErrorsNameTheInput) {
  TempDir dir;
  auto message = [](const auto& fn) {
    try {
      fn();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  const std::string missing = (dir.path / "missing.urdf").string();
  EXPECT_NE(message([&] { Hand::from_urdf(missing); }).find(missing), std::string::npos);
  const auto empty = dir.write("empty.urdf", "<?xml version=\"1.0\"?><robot name=\"r\"></robot>");
  const std::string m = message([&] { Hand::from_urdf(empty.string()); });
  EXPECT_NE(m.find(empty.string()), std::string::npos) << m;
  EXPECT_NE(m.find("link"), std::string::npos) << m;
  const auto nomesh = dir.write(
      "nomesh.urdf",
      R"(<robot name="r"><link name="a"><collision><geometry><mesh filename="gone.stl"/></geometry></collision></link></robot>)");
  EXPECT_NE(message([&] { Hand::from_urdf(nomesh.string()); }).find("gone.stl"), std::string::npos);
  const auto floating = dir.write(
      "floating.urdf",
      R"(<robot name="r"><link name="a"/><link name="b"/><joint name="f" type="floating"><parent link="a"/><child link="b"/></joint></robot>)");
  EXPECT_NE(message([&] { Hand::from_urdf(floating.string()); }).find("'f'"), std::string::npos);
}

TEST(Hand, MeshesLoadFromObjAndStlWithScaleAndPackagePaths) {
  TempDir dir;
  dir.write("pkg/meshes/cube.obj", cube_obj());
  dir.write("pkg/meshes/tetra.stl", tetra_stl());
  const auto urdf = dir.write("pkg/urdf/h.urdf", R"(<robot name="r">
    <link name="a"><collision><origin xyz="1 0 0"/><geometry><mesh filename="package://pkg/meshes/cube.obj" scale="0.1 0.2 0.3"/></geometry></collision></link>
    <link name="b"><collision><geometry><mesh filename="../meshes/tetra.stl"/></geometry></collision></link>
    <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>)");
  const Hand h = Hand::from_urdf(urdf.string());
  const auto& cube = h.links()[static_cast<size_t>(h.link_index("a"))].collisions.at(0);
  ASSERT_EQ(cube.type, graspmix::ShapeType::Mesh);
  ASSERT_TRUE(cube.mesh);
  EXPECT_EQ(cube.mesh->triangles.rows(), 12);
  EXPECT_LT((cube.mesh->vertices.colwise().maxCoeff() - Eigen::RowVector3d(0.05, 0.1, 0.15)).norm(), 1e-9);
  // The hull of a box has six distinct face planes n . x <= offset.
  ASSERT_TRUE(cube.hull_planes);
  EXPECT_EQ(cube.hull_planes->rows(), 6);
  const auto& tetra = h.links()[static_cast<size_t>(h.link_index("b"))].collisions.at(0);
  EXPECT_EQ(tetra.mesh->triangles.rows(), 4);
  EXPECT_EQ(tetra.hull_planes->rows(), 4);
  // The diagonal face x + y + z <= 1 is one of them.
  bool found = false;
  for (Eigen::Index i = 0; i < tetra.hull_planes->rows(); ++i) {
    const Eigen::Vector4d p = tetra.hull_planes->row(i).transpose();
    found = found || (p - Eigen::Vector4d(1, 1, 1, 1) / std::sqrt(3.0)).norm() < 1e-9;
  }
  EXPECT_TRUE(found);
  const auto mesh = h.collision_mesh(h.link_index("a"));
  EXPECT_NEAR(mesh.vertices.col(0).minCoeff(), 0.95, 1e-9);
}

TEST(Hand, MeshProxiesBoundTheHullAnalytically) {
  TempDir dir;
  dir.write("cube.obj", cube_obj());
  dir.write("tetra.stl", tetra_stl());
  const auto urdf = dir.write("h.urdf", R"(<robot name="r">
    <link name="a"><collision><geometry><mesh filename="cube.obj" scale="0.1 0.2 0.3"/></geometry></collision></link>
    <link name="b"><collision><geometry><mesh filename="tetra.stl"/></geometry></collision></link>
    <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>)");
  const Hand h = Hand::from_urdf(urdf.string());
  // A box's proxy is the box itself, grown by exactly g, its inner box nearly the whole of it.
  const auto& cube = h.links()[static_cast<size_t>(h.link_index("a"))].collisions.at(0);
  const Eigen::Vector3d half(0.05, 0.1, 0.15);
  EXPECT_LT((cube.T_shape_box.translation()).norm(), 1e-12);
  EXPECT_LT((cube.T_shape_box.linear().cwiseAbs() * cube.box_half - half).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_NEAR(cube.box_growth, 1.0, 1e-8);
  EXPECT_LT((cube.T_shape_box.linear().cwiseAbs() * cube.box_inner - half).cwiseAbs().maxCoeff(), 1e-6);
  // The unit corner tetrahedron's hull grown by g (every plane moved out by g) has the corners (-g, -g, -g) and
  // e_k (1 + (2 + sqrt 3) g) - g (1 - e_k): each lies in the proxy box grown by box_growth * g.
  const auto& tetra = h.links()[static_cast<size_t>(h.link_index("b"))].collisions.at(0);
  const double g = 0.01, s = 2.0 + std::sqrt(3.0);
  std::vector<Eigen::Vector3d> corners{Eigen::Vector3d::Constant(-g)};
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d c = Eigen::Vector3d::Constant(-g);
    c[k] = 1.0 + s * g;
    corners.push_back(c);
  }
  const Eigen::Isometry3d inv = tetra.T_shape_box.inverse();
  for (const Eigen::Vector3d& c : corners) {
    const Eigen::Vector3d q = (inv * c).cwiseAbs() - tetra.box_half;
    EXPECT_LE(q.maxCoeff(), tetra.box_growth * g + 1e-12) << c.transpose();
  }
  for (int k = 0; k < 4; ++k) {  // and the vertices themselves in the box
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    if (k > 0) v[k - 1] = 1.0;
    EXPECT_LE(((inv * v).cwiseAbs() - tetra.box_half).maxCoeff(), 1e-12);
  }
  // Its box is the unit cube (smaller than the principal axes' one) and the bound is tight: the corner
  // (1 + (2 + sqrt 3) g, -g, -g) lies on the grown box. Its centre is outside the hull: no inner box.
  EXPECT_LT((tetra.T_shape_box.translation() - Eigen::Vector3d::Constant(0.5)).norm(), 1e-9);
  EXPECT_NEAR(tetra.box_growth, s, 1e-6);
  EXPECT_EQ(tetra.box_inner, Eigen::Vector3d::Zero());
  // The hull's planes come largest facet first: the diagonal face (area sqrt(3) / 2) leads.
  EXPECT_LT((tetra.hull_planes->row(0).transpose() - Eigen::Vector4d(1, 1, 1, 1) / std::sqrt(3.0)).norm(), 1e-9);
}

TEST(Hand, CollisionMeshOfPrimitivesIsClosedAndOutward) {
  const Hand h = arm();
  for (const auto& link : {"l1", "l2", "tip"}) {
    const auto mesh = h.collision_mesh(h.link_index(link));
    ASSERT_GT(mesh.triangles.rows(), 0);
    // Divergence theorem: sum over triangles of (a . (b x c)) / 6 is the enclosed volume (> 0 if outward).
    double volume = 0;
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(t, 0)).transpose();
      const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(t, 1)).transpose();
      const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(t, 2)).transpose();
      volume += a.dot(b.cross(c)) / 6.0;
    }
    const double expected = std::string(link) == "l1"   ? 0.3 * 0.02 * 0.02
                            : std::string(link) == "l2" ? M_PI * 0.01 * 0.01 * 0.2
                                                        : 4.0 / 3.0 * M_PI * std::pow(0.015, 3);
    EXPECT_NEAR(volume, expected, 0.05 * expected) << link;
  }
}

TEST(Hand, MimicChainsResolveToTheirIndependentJoint) {
  const Hand h = Hand::from_urdf_string(R"(<robot name="r">
    <link name="a"/><link name="b"/><link name="c"/><link name="d"/>
    <joint name="j1" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="j2" type="prismatic"><parent link="a"/><child link="c"/><axis xyz="1 0 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/><mimic joint="j1" multiplier="2" offset="0.1"/></joint>
    <joint name="j3" type="prismatic"><parent link="a"/><child link="d"/><axis xyz="1 0 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/><mimic joint="j2" multiplier="-3" offset="0.5"/></joint>
  </robot>)",
                                        ".");
  ASSERT_EQ(h.n_dofs(), 1);
  const auto P = h.fk(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Constant(1, 0.2));
  EXPECT_NEAR(P[static_cast<size_t>(h.link_index("c"))].translation().x(), 2 * 0.2 + 0.1, 1e-12);
  EXPECT_NEAR(P[static_cast<size_t>(h.link_index("d"))].translation().x(), -3 * (2 * 0.2 + 0.1) + 0.5, 1e-12);
  try {
    Hand::from_urdf_string(R"(<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="ghost"/></joint></robot>)",
                           ".");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'ghost'"), std::string::npos);
  }
}

namespace {

std::string load_error(const std::string& xml, const std::string& base_dir = ".") {
  try {
    Hand::from_urdf_string(xml, base_dir);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

/// A chain of n links joined by revolute z joints 1 mm apart along x.
std::string chain(int n) {
  std::string s = "<robot name=\"chain\">\n";
  for (int i = 0; i < n; ++i) s += "<link name=\"l" + std::to_string(i) + "\"/>\n";
  for (int i = 1; i < n; ++i) {
    s += "<joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"l" + std::to_string(i - 1) +
         "\"/><child link=\"l" + std::to_string(i) +
         "\"/><origin xyz=\"0.001 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" "
         "velocity=\"1\"/></joint>\n";
  }
  return s + "</robot>\n";
}

/// A two-link gripper whose finger carries `finger` (collision elements and more) and whose joint
/// carries `joint` (axis, limit, origin, mimic).
std::string gripper(const std::string& finger, const std::string& joint) {
  return R"(<robot name="g"><link name="palm"><collision><geometry><box size="0.1 0.05 0.05"/></geometry></collision></link>
<link name="finger">)" +
         finger + R"(</link>
<joint name="slide" type="prismatic"><parent link="palm"/><child link="finger"/>)" +
         joint + "</joint></robot>";
}

const std::string kGoodBox = R"(<collision><geometry><box size="0.02 0.02 0.06"/></geometry></collision>)";
const std::string kGoodJoint = R"(<axis xyz="1 0 0"/><limit lower="0" upper="0.05" effort="1" velocity="1"/>)";

}  // namespace

TEST(HandUrdf, LongChainsLoadIterativelyUpToTheLimitAndFailCleanlyBeyond) {
  const Hand h = Hand::from_urdf_string(chain(kMaxUrdfLinks), ".");
  ASSERT_EQ(h.n_links(), kMaxUrdfLinks);
  EXPECT_EQ(h.link_names().back(), "l" + std::to_string(kMaxUrdfLinks - 1));
  const auto poses = h.fk(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(h.n_dofs()));
  EXPECT_NEAR(poses.back().translation().x(), 0.001 * (kMaxUrdfLinks - 1), 1e-9);
  const std::string m = load_error(chain(10000));
  EXPECT_NE(m.find("10000 links"), std::string::npos) << m;
}

TEST(HandUrdf, DeepXmlNestingAndTruncatedOrMismatchedXmlAreRefused) {
  std::string deep = "<robot name=\"r\"><link name=\"a\">";
  for (int i = 0; i < 100000; ++i) deep += "<x>";
  EXPECT_NE(load_error(deep).find("nested more than"), std::string::npos);
  const std::string good = gripper(kGoodBox, kGoodJoint);
  ASSERT_NO_THROW(Hand::from_urdf_string(good, "."));
  // Cut anywhere inside, urdfdom (TinyXML) would read the part before the cut as a smaller robot.
  for (const std::size_t cut : {good.size() / 3, good.size() / 2, good.size() - 10}) {
    const std::string m = load_error(good.substr(0, cut));
    EXPECT_NE(m.find("malformed XML"), std::string::npos) << cut << ": " << m;
  }
  std::string mismatched = good;
  mismatched.replace(mismatched.find("</collision>"), 12, "</colision>");
  EXPECT_NE(load_error(mismatched).find("</colision>"), std::string::npos) << load_error(mismatched);
}

TEST(HandUrdf, AMalformedShapeNamesTheLinkInsteadOfDroppingItsCollisions) {
  // urdfdom alone logs these and returns the finger without any collision shape.
  for (const std::string bad :
       {R"(<box size="0.02 0.06"/>)", R"(<box size="nan 0.02 0.06"/>)", R"(<box size="inf 0.02 0.06"/>)",
        R"(<box size="1e999 0.02 0.06"/>)", R"(<cylinder radius="x" length="0.1"/>)",
        R"(<mesh filename="m.stl" scale="1 1"/>)", R"(<boxx size="1 1 1"/>)"}) {
    const std::string m =
        load_error(gripper(kGoodBox + "<collision><geometry>" + bad + "</geometry></collision>", kGoodJoint));
    EXPECT_NE(m.find("finger"), std::string::npos) << bad << ": " << m;
    EXPECT_NE(m.find("collision"), std::string::npos) << bad << ": " << m;
  }
  // A bad <visual> comes before the collisions in urdfdom and drops them all.
  const std::string visual =
      load_error(gripper(R"(<visual><geometry><box size="1 1"/></geometry></visual>)" + kGoodBox, kGoodJoint));
  EXPECT_NE(visual.find("finger"), std::string::npos) << visual;
  // Values urdfdom accepts but no shape has.
  for (const std::string bad :
       {R"(<box size="-0.02 0.02 0.06"/>)", R"(<box size="0 0.02 0.06"/>)", R"(<box size="1e300 0.02 0.06"/>)",
        R"(<sphere radius="-1"/>)", R"(<cylinder radius="0.01" length="0"/>)"}) {
    const std::string m =
        load_error(gripper(kGoodBox + "<collision><geometry>" + bad + "</geometry></collision>", kGoodJoint));
    EXPECT_NE(m.find("link 'finger' <collision> 2 of 2"), std::string::npos) << bad << ": " << m;
  }
  TempDir dir;
  dir.write("cube.obj", cube_obj());
  for (const std::string scale : {"0 1 1", "1e300 1 1"}) {
    const std::string m = load_error(
        gripper("<collision><geometry><mesh filename=\"cube.obj\" scale=\"" + scale + "\"/></geometry></collision>",
                kGoodJoint),
        dir.path.string());
    EXPECT_NE(m.find("link 'finger' <collision> 1 of 1"), std::string::npos) << scale << ": " << m;
  }
  const std::string far = load_error(gripper(
      R"(<collision><origin xyz="1e5 0 0"/><geometry><sphere radius="0.01"/></geometry></collision>)", kGoodJoint));
  EXPECT_NE(far.find("link 'finger'"), std::string::npos) << far;
}

TEST(HandUrdf, JointNumbersAreCheckedAndNamed) {
  const std::string lower_upper =
      load_error(gripper(kGoodBox, R"(<axis xyz="1 0 0"/><limit lower="0.05" upper="0" effort="1" velocity="1"/>)"));
  EXPECT_NE(lower_upper.find("joint 'slide': <limit> lower 0.05 > upper 0"), std::string::npos) << lower_upper;
  EXPECT_NE(
      load_error(gripper(kGoodBox, R"(<axis xyz="0 0 0"/><limit lower="0" upper="0.05" effort="1" velocity="1"/>)"))
          .find("'slide' has a zero axis"),
      std::string::npos);
  for (const std::string& bad :
       std::vector<std::string>{R"(<axis xyz="nan 0 1"/><limit lower="0" upper="0.05" effort="1" velocity="1"/>)",
                                R"(<axis xyz="1 0 0"/><limit lower="nan" upper="0.05" effort="1" velocity="1"/>)",
                                R"(<origin xyz="0 inf 0"/>)" + kGoodJoint}) {
    const std::string m = load_error(gripper(kGoodBox, bad));
    EXPECT_NE(m.find("slide"), std::string::npos) << bad << ": " << m;
  }
  const std::string mimic = load_error(gripper(kGoodBox, kGoodJoint + R"(<mimic joint="slide" multiplier="nan"/>)"));
  EXPECT_NE(mimic.find("not a valid URDF"), std::string::npos) << mimic;
  const std::string mass = load_error(gripper(
      R"(<inertial><mass value="-1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>)" + kGoodBox,
      kGoodJoint));
  EXPECT_NE(mass.find("link 'finger' <inertial>: negative mass"), std::string::npos) << mass;
}
