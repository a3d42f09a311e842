// The contact-quality expert against analytic contacts: the WSG 50 (palm z the approach, fingers closing
// along x, inner faces at x = -+q, 80.5-153.5 mm above the flange) closing on sampled boxes, spheres and
// cylinders with exact normals.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "graspmix/grasp/contact_quality.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {
const fs::path kRepo = GRASPMIX_SOURCE_DIR;   // set by CMakeLists.txt for the tests
constexpr double kCone = 0.4636476090008061;  // atan(0.5)

std::shared_ptr<const Hand> wsg50() {
  return std::make_shared<Hand>(Hand::from_urdf((kRepo / "data" / "hands" / "wsg50.urdf").string()));
}

/// The pre-grasp opens each grasp by 20 mm (clamped to the 55 mm limit).
ConfigModel opening() {
  RowMatrixXd limits(1, 2);
  limits << 0.0, 0.055;
  return ConfigModel(Eigen::VectorXd::Constant(1, 0.05), Eigen::VectorXd::Constant(1, 0.03), limits);
}

struct Cloud {
  Vec3Array p, n;
  void add(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
    p.conservativeResize(p.rows() + 1, 3);
    n.conservativeResize(n.rows() + 1, 3);
    p.row(p.rows() - 1) = point.transpose();
    n.row(n.rows() - 1) = normal.transpose();
  }
};

/// The surface of the box centre +- half, rotated by R about its centre, on a grid of about `step`.
Cloud box(const Eigen::Vector3d& centre, const Eigen::Vector3d& half, double step,
          const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Cloud c;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int nu = static_cast<int>(std::round(2 * half[u] / step)),
              nv = static_cast<int>(std::round(2 * half[v] / step));
    for (int side = -1; side <= 1; side += 2)
      for (int i = 1; i < nu; ++i)  // face interiors: the edges belong to no face's normal
        for (int j = 1; j < nv; ++j) {
          Eigen::Vector3d x, n = Eigen::Vector3d::Zero();
          x[axis] = side * half[axis];
          x[u] = -half[u] + 2 * half[u] * i / nu;
          x[v] = -half[v] + 2 * half[v] * j / nv;
          n[axis] = side;
          c.add(centre + R * x, R * n);
        }
  }
  return c;
}

/// n points of a sphere (Fibonacci lattice).
Cloud sphere(const Eigen::Vector3d& centre, double r, int n) {
  Cloud c;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, rho = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d u(rho * std::cos(golden * i), rho * std::sin(golden * i), z);
    c.add(centre + r * u, u);
  }
  return c;
}

/// The side of a cylinder of radius r, axis along y, length len.
Cloud cylinder(const Eigen::Vector3d& centre, double r, double len, int around, int along) {
  Cloud c;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j <= along; ++j) {
      const double a = 2 * M_PI * (i + 0.5) / around;
      const Eigen::Vector3d u(std::cos(a), 0.0, std::sin(a));
      c.add(centre + r * u + Eigen::Vector3d(0, -0.5 * len + len * j / along, 0), u);
    }
  return c;
}

PoseArray wrist(const Eigen::Vector3d& at, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  PoseArray w(1, 7);
  w << at.x(), at.y(), at.z(), q.x(), q.y(), q.z(), q.w();
  return w;
}
RowMatrixXd joint(double q) { return RowMatrixXd::Constant(1, 1, q); }

const Eigen::Vector3d kCentre(0, 0, 0.12);  // between the fingers of a wrist at the origin
}  // namespace

TEST(ContactQuality, BoxAcrossParallelFacesHoldsAndContactsWhereTheGapIsItsWidth) {
  const Cloud c = box(kCentre, Eigen::Vector3d(0.02, 0.02, 0.02), 0.002);
  const ContactQualityExpert e(wsg50(), c.p, c.n, opening());
  ASSERT_EQ(e.finger_links().size(), 2u);
  // q = 15 mm, pre-grasp 35 mm: a finger meets its face (20 mm out) when it is within the 1 mm tolerance,
  // at joint 21 mm: t = (35 - 21) / 35.
  const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.015));
  EXPECT_NEAR(r.log_value[0], 0.0, 1e-12);
  for (int f = 0; f < 2; ++f) {
    EXPECT_NEAR(r.t(0, f), 0.4, 1e-9) << f;
    EXPECT_NEAR(r.joints(0, f), 0.021, 1e-9) << f;
    EXPECT_NEAR(std::abs(r.points(0, 3 * f)), 0.02, 1e-3) << f;  // on the face x = -+20 mm
    EXPECT_NEAR(std::abs(r.normals(0, 3 * f)), 1.0, 1e-9) << f;
    EXPECT_NEAR(r.angles(0, f), 0.0, 1e-6) << f;
    EXPECT_GT(r.patch_size(0, f), 100) << f;
  }
  // The normals point towards their fingers: finger_left on -x.
  EXPECT_LT(r.normals(0, 0), 0.0);
  EXPECT_GT(r.normals(0, 3), 0.0);
  EXPECT_EQ(e.log_value({wrist(Eigen::Vector3d::Zero()), joint(0.015)})[0], r.log_value[0]);
  // Fully open, the pre-grasp clamps to q itself: the hand still closes, the demonstration's way.
  const ContactQualityResult open = e.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.055));
  EXPECT_NEAR(open.log_value[0], 0.0, 1e-12);
  for (int f = 0; f < 2; ++f) EXPECT_NEAR(open.t(0, f), (0.055 - 0.021) / 0.055, 1e-9) << f;
}

TEST(ContactQuality, SphereThroughItsCentreHoldsAndShallowGraspsFailPastTheCone) {
  const double R = 0.03;
  const Cloud c = sphere(kCentre, R, 4000);
  // The cone term alone: the fingertips' edges below press on a few points each, which the patch term charges
  // (SmallPatchesAreChargedByTheirShortfall).
  ContactQualitySettings cone_only;
  cone_only.patch_points = 0.0;
  const ContactQualityExpert e(wsg50(), c.p, c.n, opening(), cone_only);
  EXPECT_NEAR(e.log_value({wrist(Eigen::Vector3d::Zero()), joint(0.02)})[0], 0.0, 1e-12);
  // Centre h above the fingertips (153.5 mm): their edges touch the sphere where its normal is tilted by
  // asin((h - tol) / R) from the closing axis.
  double last = 1.0;
  for (const double deg : {15.0, 35.0, 45.0, 60.0}) {
    const double alpha = deg * M_PI / 180.0, h = R * std::sin(alpha) + 1e-3;
    const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d(0, 0, kCentre.z() - 0.1535 - h)), joint(0.02));
    for (int f = 0; f < 2; ++f) EXPECT_NEAR(r.angles(0, f), alpha, 0.05) << deg;
    const double expected = -10.0 * 2.0 * std::max(0.0, alpha - kCone);
    EXPECT_NEAR(r.log_value[0], expected, 1.5) << deg;
    if (deg > 30) {
      EXPECT_LT(r.log_value[0], last) << deg;
    }
    last = r.log_value[0];
  }
}

TEST(ContactQuality, FrictionWidensTheCone) {
  const double R = 0.03, alpha = 35.0 * M_PI / 180.0, h = R * std::sin(alpha) + 1e-3;
  const Cloud c = sphere(kCentre, R, 4000);
  const PoseArray w = wrist(Eigen::Vector3d(0, 0, kCentre.z() - 0.1535 - h));
  double last = -1e9;
  for (const double mu : {0.3, 0.5, 0.7, 1.0}) {
    ContactQualitySettings s;
    s.friction = mu;
    s.patch_points = 0.0;  // the cone term alone (the fingertips' edges touch few points)
    const double v = ContactQualityExpert(wsg50(), c.p, c.n, opening(), s).log_value({w, joint(0.02)})[0];
    EXPECT_GE(v, last) << mu;
    if (mu <= 0.5) {
      EXPECT_LT(v, -0.5) << mu;  // atan(0.5) = 26.6 degrees < 35
    }
    if (mu >= 1.0) {
      EXPECT_EQ(v, 0.0) << mu;  // atan(1) = 45 degrees > 35
    }
    last = v;
  }
}

TEST(ContactQuality, CylinderAcrossItsAxisHolds) {
  const double R = 0.025;
  const Cloud c = cylinder(kCentre, R, 0.08, 120, 40);
  const ContactQualityExpert e(wsg50(), c.p, c.n, opening());
  const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.02));
  EXPECT_NEAR(r.log_value[0], 0.0, 1e-12);
  // The points nearest the fingers lie at R cos(pi / 120) from the axis; contact 1 mm before them.
  const double reach = R * std::cos(M_PI / 120) + 1e-3;
  for (int f = 0; f < 2; ++f) EXPECT_NEAR(r.t(0, f), (0.04 - reach) / 0.04, 1e-9) << f;
}

TEST(ContactQuality, CornerPinchScoresLow) {
  // A box with a vertical edge at the origin (x, y <= 0); the fingers close along (1, -1) / sqrt(2) through
  // that edge, so each meets one face 45 degrees off the grasp line: 2 * 10 * (pi / 4 - atan 0.5) nats.
  const Cloud c = box(Eigen::Vector3d(-0.02, -0.02, 0.12), Eigen::Vector3d(0.02, 0.02, 0.02), 0.002);
  const ContactQualityExpert e(wsg50(), c.p, c.n, opening());
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(-M_PI / 4, Eigen::Vector3d::UnitZ()));
  const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d::Zero(), turn), joint(0.02));
  EXPECT_NEAR(r.log_value[0], -20.0 * (M_PI / 4 - kCone), 0.3);
  for (int f = 0; f < 2; ++f) EXPECT_NEAR(r.angles(0, f), M_PI / 4, 0.02) << f;
  // The same box across two faces holds.
  const ContactQualityResult across = e.evaluate(wrist(Eigen::Vector3d(-0.02, -0.02, 0.0)), joint(0.015));
  EXPECT_NEAR(across.log_value[0], 0.0, 1e-12);
}

TEST(ContactQuality, NothingBetweenTheFingersCostsTwoAirPenalties) {
  const Cloud c = box(Eigen::Vector3d(0.5, 0.0, 0.12), Eigen::Vector3d(0.02, 0.02, 0.02), 0.002);
  ContactQualitySettings s;
  s.air_penalty = 3.5;
  const ContactQualityExpert e(wsg50(), c.p, c.n, opening(), s);
  const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.02));
  EXPECT_EQ(r.log_value[0], -7.0);
  EXPECT_TRUE(std::isnan(r.t(0, 0)) && std::isnan(r.t(0, 1)));
  // One finger only: a box beside the left finger's path.
  const Cloud side = box(Eigen::Vector3d(-0.02, 0.0, 0.12), Eigen::Vector3d(0.01, 0.02, 0.02), 0.002);
  const ContactQualityExpert one(wsg50(), side.p, side.n, opening(), s);
  EXPECT_EQ(one.log_value({wrist(Eigen::Vector3d(0.0, 0.0, 0.0)), joint(0.02)})[0], -3.5);
}

TEST(ContactQuality, SmallPatchesAreChargedByTheirShortfall) {
  // A box across two parallel faces: each finger presses a face of about 17 x 19 points (the face's 2 mm grid
  // under the 30 mm wide finger, the 2 tol band around it), far more than the default patch_points: no charge.
  const Cloud flat = box(kCentre, Eigen::Vector3d(0.02, 0.02, 0.02), 0.002);
  const ContactQualityExpert on_faces(wsg50(), flat.p, flat.n, opening());
  const ContactQualityResult faces = on_faces.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.015));
  ASSERT_GT(faces.patch_size.minCoeff(), ContactQualitySettings{}.patch_points);
  EXPECT_EQ(faces.log_value[0], 0.0);
  // A sphere through its centre: antipodal contacts (angle 0), each on a small cap. With the patch term off the
  // grasp scores 0; with it on, exactly patch_penalty * (1 - n_f / reference_f) a finger, n_f its cap's points and
  // reference_f = min(patch_points, what the pad meets of a flat face at the cloud's spacing; PatchReference...).
  const Cloud ball = sphere(kCentre, 0.03, 4000);
  ContactQualitySettings s;
  s.patch_points = 0.0;
  const ContactQualityResult off =
      ContactQualityExpert(wsg50(), ball.p, ball.n, opening(), s).evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.02));
  EXPECT_EQ(off.log_value[0], 0.0);
  s.patch_points = 1000.0;
  s.patch_penalty = 3.0;
  const ContactQualityExpert on_ball(wsg50(), ball.p, ball.n, opening(), s);
  const ContactQualityResult on = on_ball.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.02));
  ASSERT_EQ(on.patch_size, off.patch_size);
  double expected = 0.0;
  for (int f = 0; f < 2; ++f) {
    const double reference = on_ball.patch_reference()[static_cast<size_t>(f)];
    ASSERT_GT(on.patch_size(0, f), 0);
    ASSERT_LT(on.patch_size(0, f), reference);
    ASSERT_LE(reference, 1000.0);
    expected -= 3.0 * (1.0 - on.patch_size(0, f) / reference);
  }
  EXPECT_NEAR(on.log_value[0], expected, 1e-12);
  // A finger on nothing pays the air penalty only (no patch term for it): the one-finger box of the air test.
  const Cloud side = box(Eigen::Vector3d(-0.02, 0.0, 0.12), Eigen::Vector3d(0.01, 0.02, 0.02), 0.002);
  s.air_penalty = 3.5;
  const ContactQualityResult one =
      ContactQualityExpert(wsg50(), side.p, side.n, opening(), s).evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.02));
  ASSERT_EQ(one.patch_size(0, 1), 0);
  const ContactQualityExpert on_side(wsg50(), side.p, side.n, opening(), s);
  const double reference = on_side.patch_reference()[0];
  EXPECT_NEAR(one.log_value[0], -3.5 - 3.0 * std::max(0.0, 1.0 - one.patch_size(0, 0) / reference), 1e-12);
}

namespace {
/// The WSG 50 with its fingers' 23 x 30 x 73 mm boxes cut to `pad` (x, y, z sizes, m), same origin.
std::shared_ptr<const Hand> wsg50_with_pads(const std::string& pad) {
  std::ifstream in((kRepo / "data" / "hands" / "wsg50.urdf").string());
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const std::string from = "<box size=\"0.023 0.03 0.073\"/>", to = "<box size=\"" + pad + "\"/>";
  int replaced = 0;
  for (size_t at = xml.find(from); at != std::string::npos; at = xml.find(from, at), ++replaced)
    xml.replace(at, from.size(), to);
  EXPECT_EQ(replaced, 4);  // each finger's visual and collision
  return std::make_shared<Hand>(Hand::from_urdf_string(xml, (kRepo / "data" / "hands").string()));
}
}  // namespace

TEST(ContactQuality, PatchReferenceIsWhatThePadMeetsOfAFlatFace) {
  // A 3 x 10 x 10 cm slab on a 3 mm grid, wider than the 30 x 73 mm pads: each finger's patch on its face is the
  // pad's face grown by the patch band (2 tol = 2 mm) each side, (34 x 77 mm) / (3 mm)^2 = 291 points give or take
  // the grid's phase. The reference, a flat wall at the cloud's spacing (3 mm, measured) facing the other finger,
  // must find the same, and with the default patch_points (30, less) the reference is patch_points: the WSG 50's
  // charge is what it was.
  // The slab at `step`, patch_points raised above any pad: each finger's reference against its patch on the slab's
  // face in the top grasp (within a row of points either way) and against `expected`.
  const auto reference_on_slab = [](double step, double expected) {
    const Cloud slab = box(kCentre, Eigen::Vector3d(0.015, 0.05, 0.05), step);
    ContactQualitySettings s;
    s.patch_points = 5000.0;
    const ContactQualityExpert e(wsg50(), slab.p, slab.n, opening(), s);
    const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.01));
    for (int f = 0; f < 2; ++f) {
      const double reference = e.patch_reference()[static_cast<size_t>(f)];
      EXPECT_NEAR(reference, r.patch_size(0, f), 0.1 * r.patch_size(0, f)) << step << " " << f;
      EXPECT_NEAR(reference, expected, 0.1 * expected) << step << " " << f;
    }
    return e.patch_reference();
  };
  const std::vector<double> at_3mm = reference_on_slab(0.003, 34.0 * 77.0 / 9.0);
  // A cloud twice as dense: four times the points under a pad (the wall stays at 3 mm and is counted up by the
  // squared ratio of the spacings, so a dense cloud costs no more).
  const std::vector<double> at_1_5mm = reference_on_slab(0.0015, 4.0 * at_3mm[0]);
  EXPECT_NEAR(at_1_5mm[1], 4.0 * at_3mm[1], 0.05 * at_1_5mm[1]);
  const Cloud slab = box(kCentre, Eigen::Vector3d(0.015, 0.05, 0.05), 0.003);
  const ContactQualityExpert defaults(wsg50(), slab.p, slab.n, opening());
  EXPECT_EQ(defaults.patch_reference(), std::vector<double>(2, ContactQualitySettings{}.patch_points));
  // Pads of 6 x 6 mm: (10 mm)^2 / (3 mm)^2 = 11 points, fewer than patch_points. Pressed flat on the slab's faces
  // they meet all they can and are not charged; on the sphere's small caps they are, by their shortfall from
  // that reference (with it at 30 they would pay on the flat faces too).
  const auto small = wsg50_with_pads("0.023 0.006 0.006");
  const ContactQualityExpert small_on_slab(small, slab.p, slab.n, opening());
  for (const double reference : small_on_slab.patch_reference()) EXPECT_NEAR(reference, 100.0 / 9.0, 4.0);
  const ContactQualityResult flat = small_on_slab.evaluate(wrist(Eigen::Vector3d(0, 0, -0.04)), joint(0.01));
  ASSERT_GT(flat.patch_size.minCoeff(), 0);
  EXPECT_EQ(flat.log_value[0], 0.0);
  ContactQualitySettings at_30;
  at_30.patch_points = 30.0;
  EXPECT_LT(ContactQualityExpert(small, slab.p, slab.n, opening(), at_30).patch_reference()[0], 30.0);
}

TEST(ContactQuality, SteppedClosingAgreesWithTheExactOne) {
  // The finger's box replaced by a sphere of radius 10 mm: not all boxes, so closing steps and bisects.
  std::ifstream in((kRepo / "data" / "hands" / "wsg50.urdf").string());
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const std::string from =
      "<collision>\n      <origin xyz=\"-0.0115 0 0.0445\" rpy=\"0 0 0\"/>\n      "
      "<geometry><box size=\"0.023 0.03 0.073\"/></geometry>";
  const std::string to =
      "<collision>\n      <origin xyz=\"-0.0115 0 0.0445\" rpy=\"0 0 0\"/>\n      "
      "<geometry><sphere radius=\"0.01\"/></geometry>";
  for (size_t at = xml.find(from); at != std::string::npos; at = xml.find(from, at)) xml.replace(at, from.size(), to);
  const auto hand = std::make_shared<Hand>(Hand::from_urdf_string(xml, (kRepo / "data" / "hands").string()));
  const Cloud c = box(kCentre, Eigen::Vector3d(0.02, 0.02, 0.03), 0.001);
  const ContactQualityExpert e(hand, c.p, c.n, opening());
  // The sphere reaches 1.5 mm short of the old face: contact at joint 20 - 1.5 + 1 mm.
  const ContactQualityResult r = e.evaluate(wrist(Eigen::Vector3d::Zero()), joint(0.015));
  EXPECT_NEAR(r.log_value[0], 0.0, 1e-9);
  for (int f = 0; f < 2; ++f) EXPECT_NEAR(r.joints(0, f), 0.0195, 1e-6) << f;
}

TEST(ContactQuality, BadInputThrows) {
  const Cloud c = box(kCentre, Eigen::Vector3d(0.02, 0.02, 0.02), 0.004);
  auto make = [&](ContactQualitySettings s) { return ContactQualityExpert(wsg50(), c.p, c.n, opening(), s); };
  ContactQualitySettings s;
  for (const double mu : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    s = {};
    s.friction = mu;
    EXPECT_THROW(make(s), std::invalid_argument) << mu;
  }
  s = {};
  s.concentration = -1;
  EXPECT_THROW(make(s), std::invalid_argument);
  s = {};
  s.air_penalty = -1;
  EXPECT_THROW(make(s), std::invalid_argument);
  s = {};
  s.closing_steps = 0;
  EXPECT_THROW(make(s), std::invalid_argument);
  for (const double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    s = {};
    s.patch_points = bad;
    EXPECT_THROW(make(s), std::invalid_argument) << bad;
    s = {};
    s.patch_penalty = bad;
    EXPECT_THROW(make(s), std::invalid_argument) << bad;
  }
  EXPECT_THROW(ContactQualityExpert(wsg50(), c.p, c.n.topRows(3), opening()), std::invalid_argument);
  Vec3Array zero = c.n;
  zero.row(2).setZero();
  EXPECT_THROW(ContactQualityExpert(wsg50(), c.p, zero, opening()), std::invalid_argument);
  Vec3Array nan = c.p;
  nan(1, 1) = std::nan("");
  EXPECT_THROW(ContactQualityExpert(wsg50(), nan, c.n, opening()), std::invalid_argument);
  const ContactQualityExpert e(wsg50(), c.p, c.n, opening());
  EXPECT_THROW(e.evaluate(wrist(Eigen::Vector3d::Zero()), RowMatrixXd::Zero(2, 1)), std::invalid_argument);
}
