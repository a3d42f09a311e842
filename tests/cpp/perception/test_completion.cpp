// Completion against exact geometry: a box, a vertical cylinder and an L-shaped block on a table, each rendered by
// exact ray casting into a depth image from a camera 55 cm away looking down at 45 degrees; the observed points are
// the object's hits, voxelised at 3 mm. The completed points are compared with the true solid's surface and
// normals; no completed point may lie in seen-free space; bad input throws naming the cause.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "graspmix/perception/completion.hpp"
#include "raycast.hpp"

using namespace graspmix;
using graspmix::test::looking_at;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const PinholeCamera kCam(300.0, 300.0, 159.5, 119.5, 320, 240);

// 55 cm from the object's middle, 45 degrees above the table, in front (-y).
const Eigen::Vector3d kTarget(0.0, 0.0, 0.05);
const Eigen::Isometry3d kPose =
    looking_at(kTarget + 0.55 * Eigen::Vector3d(0, -std::sqrt(0.5), std::sqrt(0.5)), kTarget);
const Eigen::Vector4d kTable(0, 0, 1, 0);

/// A solid: its first ray hit (t along o + t d, inf for none), its signed distance and outward normal at p.
struct Solid {
  std::function<double(const Eigen::Vector3d&, const Eigen::Vector3d&)> hit;
  std::function<double(const Eigen::Vector3d&)> sdf;
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> normal;
};

/// A box of half extents `half`, its bottom centre at `foot` on the table, turned by yaw about z.
Solid box(const Eigen::Vector3d& foot, const Eigen::Vector3d& half, double yaw) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d c = foot + Eigen::Vector3d(0, 0, half.z());
  Solid s;
  s.hit = [=](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    const Eigen::Vector3d lo = R.transpose() * (o - c), ld = R.transpose() * d;
    double t0 = 0, t1 = kInf;
    for (int k = 0; k < 3; ++k) {
      double a = (-half[k] - lo[k]) / ld[k], b = (half[k] - lo[k]) / ld[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a), t1 = std::min(t1, b);
    }
    return t0 <= t1 && t0 > 0 ? t0 : kInf;
  };
  s.sdf = [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = (R.transpose() * (p - c)).cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  s.normal = [=](const Eigen::Vector3d& p) {
    const Eigen::Vector3d l = R.transpose() * (p - c);
    Eigen::Index k = 0;
    (l.cwiseAbs() - half).maxCoeff(&k);
    return Eigen::Vector3d(R.col(k) * (l[k] > 0 ? 1.0 : -1.0));
  };
  return s;
}

/// A vertical cylinder of radius r and height h standing at (x, y) on the table.
Solid cylinder(double x, double y, double r, double h) {
  const Eigen::Vector2d c(x, y);
  Solid s;
  s.hit = [=](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    double best = kInf;
    const Eigen::Vector2d oo = o.head<2>() - c, dd = d.head<2>();
    const double a = dd.squaredNorm(), b = 2 * oo.dot(dd), cc = oo.squaredNorm() - r * r, disc = b * b - 4 * a * cc;
    if (disc >= 0) {
      const double t = (-b - std::sqrt(disc)) / (2 * a);
      const double z = o.z() + t * d.z();
      if (t > 0 && z >= 0 && z <= h) best = t;
    }
    const double t = (h - o.z()) / d.z();  // the top cap
    if (t > 0 && (oo + t * dd).norm() <= r) best = std::min(best, t);
    return best;
  };
  s.sdf = [=](const Eigen::Vector3d& p) {
    const Eigen::Vector2d q((p.head<2>() - c).norm() - r, std::abs(p.z() - h / 2) - h / 2);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  s.normal = [=](const Eigen::Vector3d& p) {
    const Eigen::Vector2d radial = p.head<2>() - c;
    if (radial.norm() - r > p.z() - h) return Eigen::Vector3d(radial.x(), radial.y(), 0).normalized();
    return Eigen::Vector3d(0, 0, 1);
  };
  return s;
}

/// The union of two solids (its sdf exact outside, its normal that of the nearer part).
Solid join(const Solid& a, const Solid& b) {
  Solid s;
  s.hit = [=](const Eigen::Vector3d& o, const Eigen::Vector3d& d) { return std::min(a.hit(o, d), b.hit(o, d)); };
  s.sdf = [=](const Eigen::Vector3d& p) { return std::min(a.sdf(p), b.sdf(p)); };
  s.normal = [=](const Eigen::Vector3d& p) { return a.sdf(p) < b.sdf(p) ? a.normal(p) : b.normal(p); };
  return s;
}

struct Rendered {
  VisibilityModel model;
  Vec3Array points;  // the object's hits, voxelised at 3 mm
};

Rendered render(const Solid& solid, const Eigen::Isometry3d& T = kPose) {
  DepthImage depth(kCam.height(), kCam.width());
  std::map<std::tuple<long, long, long>, std::pair<Eigen::Vector3d, int>> voxels;
  for (int v = 0; v < kCam.height(); ++v)
    for (int u = 0; u < kCam.width(); ++u) {
      const Eigen::Vector3d d = T.linear() * kCam.back_project(u, v, 1.0), o = T.translation();
      const double t_obj = solid.hit(o, d), t_table = -o.z() / d.z();
      const double t = std::min(t_obj, t_table > 0 ? t_table : kInf);
      depth(v, u) = t;
      if (t_obj < kInf && t_obj <= t) {
        const Eigen::Vector3d p = o + t_obj * d;
        const auto key = std::make_tuple(std::lround(std::floor(p.x() / 0.003)), std::lround(std::floor(p.y() / 0.003)),
                                         std::lround(std::floor(p.z() / 0.003)));
        auto& cell = voxels.try_emplace(key, Eigen::Vector3d::Zero(), 0).first->second;
        cell.first += p, ++cell.second;
      }
    }
  Rendered r{VisibilityModel::from_depth(depth, kCam, T), Vec3Array(static_cast<Eigen::Index>(voxels.size()), 3)};
  Eigen::Index i = 0;
  for (const auto& [key, cell] : voxels) r.points.row(i++) = (cell.first / cell.second).transpose();
  return r;
}

/// The fraction of completed points within `tol` of the solid's surface, and the fraction whose normal is
/// within acos(0.7) of the true outward normal.
std::pair<double, double> agreement(const Completion& c, const Solid& s, double tol) {
  int near = 0, aligned = 0;
  for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
    const Eigen::Vector3d p = c.points.row(i).transpose();
    near += std::abs(s.sdf(p)) <= tol;
    aligned += c.normals.row(i).dot(s.normal(p).transpose()) > 0.7;
  }
  const double n = std::max<double>(1.0, static_cast<double>(c.points.rows()));
  return {near / n, aligned / n};
}

void expect_nothing_in_free_space(const Completion& c, const VisibilityModel& model) {
  for (const SpaceState st : model.classify(c.points)) EXPECT_NE(st, SpaceState::SeenFree);
  for (const auto& h : c.hypotheses) {
    if (!h.accepted) continue;
    EXPECT_LE(h.free_fraction, CompletionSettings{}.max_free_fraction);
  }
  for (Eigen::Index i = 0; i < c.normals.rows(); ++i) EXPECT_NEAR(c.normals.row(i).norm(), 1.0, 1e-9);
}

}  // namespace

TEST(Completion, ABoxIsMirroredOntoItsBackFace) {
  const Solid solid = box({0.01, 0.015, 0}, {0.045, 0.03, 0.05}, 0.25);
  const Rendered r = render(solid);
  ASSERT_GT(r.points.rows(), 300);
  const Completion c = complete_object(r.points, kTable, r.model);
  ASSERT_EQ(c.kind, CompletionKind::Mirror) << c.hypotheses.size();
  EXPECT_TRUE(c.warning.empty()) << c.warning;
  ASSERT_GT(c.points.rows(), 100);
  const auto [near, aligned] = agreement(c, solid, 0.004);
  EXPECT_GT(near, 0.9);
  EXPECT_GT(aligned, 0.85);
  // The back face (its outward normal away from the camera, local +y) is covered: completed points lie on it.
  const Eigen::Vector3d back = Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d back_centre = Eigen::Vector3d(0.01, 0.015, 0.05) + 0.03 * back;
  int on_back = 0;
  for (Eigen::Index i = 0; i < c.points.rows(); ++i)
    on_back += std::abs((c.points.row(i).transpose() - back_centre).dot(back)) < 0.004;
  EXPECT_GT(on_back, 0.5 * (0.09 * 0.1) / (0.003 * 0.003));  // half the face's 3 mm cells
  // The mirror plane passes through the box's middle, along its local x axis.
  const Eigen::Vector4d& plane = c.hypotheses.front().plane_or_axis;
  EXPECT_GT(std::abs(plane.head<3>().dot(back)), std::cos(0.05));
  EXPECT_NEAR(plane.head<3>().dot(Eigen::Vector3d(0.01, 0.015, 0.05)) + plane[3], 0.0, 0.003);
  expect_nothing_in_free_space(c, r.model);
}

TEST(Completion, AVerticalCylinderIsSweptAboutItsAxis) {
  const Solid solid = cylinder(0.01, 0.02, 0.035, 0.11);
  const Rendered r = render(solid);
  const Completion c = complete_object(r.points, kTable, r.model);
  ASSERT_EQ(c.kind, CompletionKind::Rotation);
  ASSERT_GT(c.points.rows(), 100);
  const auto [near, aligned] = agreement(c, solid, 0.004);
  EXPECT_GT(near, 0.9);
  EXPECT_GT(aligned, 0.9);
  const Eigen::Vector4d& axis = c.hypotheses.front().plane_or_axis;
  EXPECT_NEAR(axis.x(), 0.01, 0.003);
  EXPECT_NEAR(axis.y(), 0.02, 0.003);
  EXPECT_NEAR(axis.z(), 0.0, 1e-9);
  EXPECT_NEAR(axis[3], 0.035, 0.003);
  // The back of the cylinder (facing away from the camera, +y) is there.
  int back = 0;
  for (Eigen::Index i = 0; i < c.points.rows(); ++i) back += c.points(i, 1) > 0.02 + 0.03;
  EXPECT_GT(back, 50);
  expect_nothing_in_free_space(c, r.model);
}

TEST(Completion, AnLShapedBlockGetsNoPointInSeenFreeSpace) {
  const Solid solid =
      join(box({0.0, -0.015, 0}, {0.05, 0.015, 0.04}, 0.0), box({-0.035, 0.02, 0}, {0.015, 0.02, 0.07}, 0.0));
  const Rendered r = render(solid);
  const Completion c = complete_object(r.points, kTable, r.model);
  EXPECT_NE(c.kind, CompletionKind::None);
  EXPECT_FALSE(c.hypotheses.empty());
  expect_nothing_in_free_space(c, r.model);
  // No symmetry explains it (every mirror is refused), so the walls down from its outline complete it: they lie on
  // the true faces, facing out.
  EXPECT_EQ(c.kind, CompletionKind::Extrusion);
  const auto [near, aligned] = agreement(c, solid, 0.004);
  EXPECT_GT(near, 0.9);
  EXPECT_GT(aligned, 0.85);
}

TEST(Completion, AnObjectTheImageBorderCutsIsWarnedAbout) {
  const Solid solid = box({0.3, 0.0, 0}, {0.04, 0.03, 0.05}, 0.0);
  const Rendered r = render(solid);
  ASSERT_GT(r.points.rows(), 20);
  const Completion c = complete_object(r.points, kTable, r.model);
  EXPECT_NE(c.warning.find("image border"), std::string::npos) << c.warning;
  expect_nothing_in_free_space(c, r.model);
}

TEST(Completion, BadInputThrowsNamingTheCause) {
  const Rendered r = render(box({0, 0, 0}, {0.03, 0.03, 0.03}, 0.0));
  const auto throws = [&](const Vec3Array& P, const Eigen::Vector4d& plane, const VisibilityModel& m,
                          const CompletionSettings& s, const std::string& want) {
    try {
      complete_object(P, plane, m, s);
      ADD_FAILURE() << "no exception, expected " << want;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  };
  throws(Vec3Array(0, 3), kTable, r.model, {}, "points: no point");
  Vec3Array nan = r.points;
  nan(3, 1) = std::numeric_limits<double>::quiet_NaN();
  throws(nan, kTable, r.model, {}, "points: row 3 is not finite");
  throws(r.points, Eigen::Vector4d::Zero(), r.model, {}, "plane: (a, b, c) is not a unit normal");
  throws(r.points, Eigen::Vector4d(0, 0, 1, std::nan("")), r.model, {}, "plane: not finite");
  throws(r.points, Eigen::Vector4d(0, 0, -1, 0), r.model, {}, "in or below the plane");
  throws(r.points, Eigen::Vector4d(0, 0, 1, -1.0), r.model, {}, "in or below the plane");  // the camera under it
  throws(r.points, Eigen::Vector4d(0, 0, 1, -0.2), r.model, {}, "most lie below the plane");
  throws(r.points, kTable, VisibilityModel(), {}, "visibility: the model has no view");
  CompletionSettings s;
  s.spacing = 0;
  throws(r.points, kTable, r.model, s, "spacing");
  s = {};
  s.max_free_fraction = 2;
  throws(r.points, kTable, r.model, s, "max_free_fraction");
}
