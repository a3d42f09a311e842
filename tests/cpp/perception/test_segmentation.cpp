#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "graspmix/perception/segmentation.hpp"

using namespace graspmix;

namespace {

struct Box {
  Eigen::Vector3d lo, hi;
  bool contains(const Eigen::Vector3d& p, double tol) const {
    return (p.array() >= lo.array() - tol).all() && (p.array() <= hi.array() + tol).all();
  }
};

/// A pinhole depth camera (45 degree vertical field of view) ray-casting a square table at z = 0 (half
/// side `table`, none when 0) and axis-aligned boxes, with the acquisition's noise model: depth read at
/// a pixel shifted by N(0, pixel_std) and back-projected through the true pixel, plus N(0, depth_std).
struct Render {
  Vec3Array points;
  std::vector<int> hit;  ///< per point: -1 the table, else the box index
};

Render render(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, const std::vector<Box>& boxes, double table,
              double pixel_std = 0, double depth_std = 0, std::uint64_t seed = 0, int w = 320, int h = 240) {
  const Eigen::Vector3d fwd = (target - eye).normalized();
  const Eigen::Vector3d right = fwd.cross(Eigen::Vector3d::UnitZ()).normalized(), up = right.cross(fwd);
  const double ty = std::tan(M_PI / 8), tx = ty * w / h;
  auto ray = [&](double u, double v) {
    return Eigen::Vector3d(fwd + (2 * (u + 0.5) / w - 1) * tx * right + (1 - 2 * (v + 0.5) / h) * ty * up);
  };
  auto cast = [&](const Eigen::Vector3d& d, int& id) {
    double best = std::numeric_limits<double>::infinity();
    id = -2;
    if (table > 0 && d.z() * eye.z() < 0) {
      const double t = -eye.z() / d.z();
      const Eigen::Vector3d p = eye + t * d;
      if (std::abs(p.x()) <= table && std::abs(p.y()) <= table) best = t, id = -1;
    }
    for (std::size_t b = 0; b < boxes.size(); ++b) {
      double t0 = 0, t1 = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        const double a = (boxes[b].lo[k] - eye[k]) / d[k], c = (boxes[b].hi[k] - eye[k]) / d[k];
        t0 = std::max(t0, std::min(a, c));
        t1 = std::min(t1, std::max(a, c));
      }
      if (t0 <= t1 && t0 < best) best = t0, id = static_cast<int>(b);
    }
    return best;
  };
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> px(0.0, pixel_std > 0 ? pixel_std : 1.0), dz(0.0, depth_std > 0 ? depth_std : 1.0);
  Render r;
  std::vector<Eigen::Vector3d> pts;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const double su = pixel_std > 0 ? std::clamp(std::round(u + px(rng)), 0.0, w - 1.0) : u;
      const double sv = pixel_std > 0 ? std::clamp(std::round(v + px(rng)), 0.0, h - 1.0) : v;
      int id = -2;
      double depth = cast(ray(su, sv), id);
      if (id == -2) continue;
      if (depth_std > 0) depth += dz(rng);
      pts.push_back(eye + depth * ray(u, v));
      r.hit.push_back(id);
    }
  }
  r.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) r.points.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return r;
}

Render concat(const std::vector<Render>& parts, Vec3Array& viewpoints, const std::vector<Eigen::Vector3d>& eyes) {
  Render all;
  Eigen::Index n = 0;
  for (const auto& p : parts) n += p.points.rows();
  all.points.resize(n, 3);
  viewpoints.resize(n, 3);
  Eigen::Index row = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    all.points.middleRows(row, parts[k].points.rows()) = parts[k].points;
    viewpoints.middleRows(row, parts[k].points.rows()).rowwise() = eyes[k].transpose();
    all.hit.insert(all.hit.end(), parts[k].hit.begin(), parts[k].hit.end());
    row += parts[k].points.rows();
  }
  return all;
}

Box box_at(double x, double y, double sx, double sy, double sz) {
  return {Eigen::Vector3d(x - sx / 2, y - sy / 2, 0), Eigen::Vector3d(x + sx / 2, y + sy / 2, sz)};
}

const std::vector<Box> kThreeBoxes = {box_at(0.0, 0.0, 0.06, 0.05, 0.10), box_at(-0.02, 0.085, 0.05, 0.05, 0.06),
                                      box_at(0.03, -0.075, 0.04, 0.04, 0.04)};
const Eigen::Vector3d kEye(0.5, 0.1, 0.45), kTarget(0, 0, 0.03);

Vec3Array one(const Eigen::Vector3d& v) { return v.transpose(); }

/// The support rule's figures, printed when an expectation on the plane fails.
std::string figures(const Segmentation& s) {
  std::string out;
  for (const auto& c : s.candidates) {
    out += "[" + std::to_string(c.plane[0]) + " " + std::to_string(c.plane[1]) + " " + std::to_string(c.plane[2]) +
           " " + std::to_string(c.plane[3]) + "] inliers " + std::to_string(c.inlier_fraction) + " camera " +
           std::to_string(c.camera_height) + " behind " + std::to_string(c.behind_fraction) + " margin " +
           std::to_string(c.margin) + " " + c.reason + "\n";
  }
  return out;
}

/// Every object's points lie in exactly one box, a different box for every object, and each box is found.
void expect_objects_are_the_boxes(const Segmentation& s, const std::vector<Box>& boxes) {
  ASSERT_EQ(s.objects.size(), boxes.size());
  std::vector<int> seen(boxes.size(), 0);
  for (const auto& o : s.objects) {
    int which = -1;
    for (std::size_t b = 0; b < boxes.size(); ++b)
      if (boxes[b].contains(o.centroid, 0.0)) which = static_cast<int>(b);
    ASSERT_GE(which, 0) << "centroid of object " << o.index << " in no box";
    ++seen[static_cast<std::size_t>(which)];
    // Lateral noise puts a few flying pixels (a neighbour's depth) at the silhouette, still attached.
    int inside = 0;
    for (Eigen::Index j = 0; j < o.rows.size(); ++j) {
      const Eigen::Vector3d p = s.points.row(o.rows[j]).transpose();
      inside += boxes[static_cast<std::size_t>(which)].contains(p, 0.006);
      EXPECT_EQ(s.labels[o.rows[j]], o.index);
    }
    EXPECT_GT(inside, 0.95 * static_cast<double>(o.rows.size())) << "object " << o.index;
  }
  for (const int n : seen) EXPECT_EQ(n, 1);
}

}  // namespace

TEST(Segmentation, TableAndThreeBoxesFromOneNoisyCamera) {
  const Render r = render(kEye, kTarget, kThreeBoxes, 1.0, 1.0, 0.001, 3);
  const Segmentation s = segment_scene(r.points, one(kEye));
  ASSERT_TRUE(s.plane_found) << figures(s);
  EXPECT_FALSE(s.plane_given);
  EXPECT_GT(s.plane[2], 0.999) << "normal up, towards the camera";
  EXPECT_NEAR(s.plane[3], 0.0, 0.002);
  expect_objects_are_the_boxes(s, kThreeBoxes);
  for (std::size_t i = 1; i < s.objects.size(); ++i) EXPECT_GE(s.objects[i - 1].n_points, s.objects[i].n_points);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {  // sources name an input point of the same voxel
    EXPECT_LT((r.points.row(s.sources[i]) - s.points.row(i)).norm(), 0.003 * std::sqrt(3.0) + 1e-9);
  }
  EXPECT_EQ(s.n_input, static_cast<std::size_t>(r.points.rows()));
  EXPECT_EQ(s.n_after_voxel, s.n_plane + s.n_outliers + s.n_small_clusters + s.n_output);
  // The points the clean-up dropped are kept aside: the outliers and the small clusters, above the table, none kept.
  EXPECT_GT(s.n_outliers, 0u);
  ASSERT_EQ(static_cast<std::size_t>(s.dropped.rows()), s.n_outliers + s.n_small_clusters);
  for (Eigen::Index i = 0; i < s.dropped.rows(); ++i) {
    EXPECT_GT(s.plane.head<3>().dot(s.dropped.row(i).transpose()) + s.plane[3], SegmentationSettings{}.table_clearance);
    EXPECT_GT((s.points.rowwise() - s.dropped.row(i)).rowwise().norm().minCoeff(), 0.0);
  }
}

TEST(Segmentation, OrientationFollowsTheCameraNotThePoints) {
  // The same scene seen from below (a glass table): the boxes hang under it, the camera is under it.
  std::vector<Box> hanging;
  for (const auto& b : kThreeBoxes)
    hanging.push_back({Eigen::Vector3d(b.lo.x(), b.lo.y(), -b.hi.z()), Eigen::Vector3d(b.hi.x(), b.hi.y(), 0)});
  const Eigen::Vector3d eye(0.5, 0.1, -0.45);
  const Render r = render(eye, Eigen::Vector3d(0, 0, -0.03), hanging, 1.0, 0.0, 0.001, 4);
  const Segmentation s = segment_scene(r.points, one(eye));
  ASSERT_TRUE(s.plane_found) << figures(s);
  EXPECT_LT(s.plane[2], -0.999);
  expect_objects_are_the_boxes(s, hanging);
}

TEST(Segmentation, WithoutViewpointsTheCameraIsAtTheOrigin) {
  // The cloud in the camera's frame: the scene shifted so that the camera is at the origin.
  const Render r = render(kEye, kTarget, kThreeBoxes, 1.0);
  const Vec3Array in_camera = r.points.rowwise() - kEye.transpose();
  const Segmentation s = segment_scene(in_camera, Vec3Array(0, 3));
  ASSERT_TRUE(s.plane_found) << figures(s);
  EXPECT_GT(s.plane[2], 0.999);
  EXPECT_NEAR(s.plane[3], kEye.z(), 0.002);  // z = -0.45 in the camera's frame, the camera on the + side
  EXPECT_EQ(s.objects.size(), kThreeBoxes.size());
}

TEST(Segmentation, ObjectOnlyCloudsHaveNoPlane) {
  const Box tall = box_at(0, 0, 0.06, 0.05, 0.10), flat = box_at(0, 0, 0.12, 0.08, 0.025),
            on_side = box_at(0, 0, 0.12, 0.025, 0.08);
  std::vector<Eigen::Vector3d> ring;
  for (int k = 0; k < 4; ++k)
    ring.emplace_back(0.5 * std::cos(M_PI / 4 + k * M_PI / 2), 0.5 * std::sin(M_PI / 4 + k * M_PI / 2), 0.35);
  for (const Box& b : {tall, flat, on_side}) {
    const Render single = render(kEye, kTarget, {b}, 0.0, 1.0, 0.001, 5);
    const Segmentation s1 = segment_scene(single.points, one(kEye));
    EXPECT_FALSE(s1.plane_found) << "a face of a " << b.hi.transpose() - b.lo.transpose() << " box, one camera";
    ASSERT_EQ(s1.objects.size(), 1u);
    EXPECT_EQ(s1.n_plane, 0u);
    std::vector<Render> views;
    for (const auto& e : ring) views.push_back(render(e, kTarget, {b}, 0.0, 1.0, 0.001, 6));
    Vec3Array vps;
    const Render all = concat(views, vps, ring);
    const Segmentation s4 = segment_scene(all.points, vps);
    EXPECT_FALSE(s4.plane_found) << "a face of a " << b.hi.transpose() - b.lo.transpose() << " box, four cameras";
    EXPECT_EQ(s4.objects.size(), 1u);
  }
}

TEST(Segmentation, PerPointViewpointsFromFourCamerasFindTheTable) {
  std::vector<Eigen::Vector3d> ring;
  for (int k = 0; k < 4; ++k) ring.emplace_back(0.5 * std::cos(k * M_PI / 2), 0.5 * std::sin(k * M_PI / 2), 0.35);
  std::vector<Render> views;
  for (const auto& e : ring) views.push_back(render(e, kTarget, kThreeBoxes, 0.4, 1.0, 0.001, 7, 160, 120));
  Vec3Array vps;
  const Render all = concat(views, vps, ring);
  const Segmentation s = segment_scene(all.points, vps);
  ASSERT_TRUE(s.plane_found) << figures(s);
  EXPECT_GT(s.plane[2], 0.999);
  expect_objects_are_the_boxes(s, kThreeBoxes);
}

TEST(Segmentation, GivenPlaneIsTurnedTowardsTheCamerasOrKeptWithoutThem) {
  const Render r = render(kEye, kTarget, kThreeBoxes, 1.0);
  const Eigen::Vector4d down(0, 0, -2, 0);  // z = 0, written with the normal down and not unit
  const Segmentation s = segment_scene(r.points, one(kEye), {}, down);
  EXPECT_TRUE(s.plane_given);
  EXPECT_FALSE(s.plane_found);
  EXPECT_TRUE(s.candidates.empty());
  EXPECT_TRUE(s.plane.isApprox(Eigen::Vector4d(0, 0, 1, 0)));
  expect_objects_are_the_boxes(s, kThreeBoxes);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) EXPECT_GT(s.points(i, 2), SegmentationSettings{}.table_clearance);
  // No viewpoint: the caller's side is kept, so the boxes are behind it and nothing is left.
  EXPECT_THROW(segment_scene(r.points, Vec3Array(0, 3), {}, down), std::invalid_argument);
  const Segmentation up = segment_scene(r.points, Vec3Array(0, 3), {}, Eigen::Vector4d(0, 0, 1, 0));
  EXPECT_EQ(up.objects.size(), kThreeBoxes.size());
}

TEST(Segmentation, SameSeedSameResult) {
  const Render r = render(kEye, kTarget, kThreeBoxes, 1.0, 1.0, 0.001, 8);
  const Segmentation a = segment_scene(r.points, one(kEye)), b = segment_scene(r.points, one(kEye));
  EXPECT_EQ(a.plane, b.plane);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.sources, b.sources);
}

TEST(Segmentation, ObbOfABoxIsTheBox) {
  std::vector<Eigen::Vector3d> ring;
  for (int k = 0; k < 4; ++k)
    ring.emplace_back(0.5 * std::cos(M_PI / 4 + k * M_PI / 2), 0.5 * std::sin(M_PI / 4 + k * M_PI / 2), 0.35);
  const Box b = box_at(0.01, 0.02, 0.12, 0.06, 0.03);
  std::vector<Render> views;
  for (const auto& e : ring) views.push_back(render(e, kTarget, {b}, 0.0));
  Vec3Array vps;
  const Render all = concat(views, vps, ring);
  SegmentationSettings st;
  st.voxel_size = 0;
  const Segmentation s = segment_scene(all.points, vps, st);
  ASSERT_EQ(s.objects.size(), 1u);
  const SceneObject& o = s.objects[0];
  EXPECT_NEAR(std::abs(o.obb_rotation(0, 0)), 1.0, 1e-3);  // longest axis along x
  EXPECT_NEAR(o.obb_rotation.determinant(), 1.0, 1e-9);
  EXPECT_NEAR(o.obb_extents[0], 0.12, 0.003);
  EXPECT_NEAR(o.obb_extents[1], 0.06, 0.003);
  EXPECT_NEAR(o.obb_extents[2], 0.03, 0.003);
  EXPECT_TRUE(o.obb_center.isApprox(Eigen::Vector3d(0.01, 0.02, 0.015), 0.003 / 0.02));
}

// The join rule (segmentation.hpp) on exact ray casting: a long low box whose middle a narrow tall box in front
// hides, so that its visible parts are two clusters 2-3 cm apart, and two boxes side by side with the table seen
// through the 2 cm slot between them.
const Box kLong = box_at(0.0, 0.10, 0.14, 0.04, 0.04), kPost = box_at(0.0, 0.035, 0.02, 0.03, 0.12);
const Eigen::Vector3d kFront(0.0, -0.55, 0.35), kFrontTarget(0.0, 0.1, 0.03);

TEST(Segmentation, AnObjectCutInTwoByANearerOnesShadowIsJoined) {
  const Render r = render(kFront, kFrontTarget, {kLong, kPost}, 1.0, 0.0, 0.0, 0, 640, 480);
  SegmentationSettings off;
  off.join_occluded = false;
  const Segmentation apart = segment_scene(r.points, one(kFront), off);
  ASSERT_EQ(apart.objects.size(), 3u) << "the long box's visible parts are two clusters without the rule";
  EXPECT_EQ(apart.n_joined, 0u);
  const Segmentation s = segment_scene(r.points, one(kFront));
  EXPECT_EQ(s.n_joined, 1u);
  expect_objects_are_the_boxes(s, {kLong, kPost});
  std::size_t long_points = 0;  // every point of the long box is in one object
  for (const auto& o : apart.objects) long_points += kLong.contains(o.centroid, 0.0) ? o.n_points : 0;
  for (const auto& o : s.objects)
    if (kLong.contains(o.centroid, 0.0)) EXPECT_EQ(o.n_points, long_points);
  EXPECT_GE(s.times.join, 0.0);
  // Without viewpoints there is no visibility model, and the rule is off.
  const Segmentation blind = segment_scene(r.points, Vec3Array(0, 3), {}, Eigen::Vector4d(0, 0, 1, 0));
  EXPECT_EQ(blind.visibility, nullptr);
  EXPECT_EQ(blind.n_joined, 0u);
  EXPECT_EQ(blind.objects.size(), 3u);
}

TEST(Segmentation, TwoBoxesWithTheTableSeenBetweenThemStayTwo) {
  const std::vector<Box> pair = {box_at(-0.035, 0.0, 0.05, 0.05, 0.05), box_at(0.035, 0.0, 0.05, 0.05, 0.05)};
  for (const Eigen::Vector3d& eye : {kFront, Eigen::Vector3d(0.1, -0.45, 0.5), Eigen::Vector3d(-0.2, -0.4, 0.3)}) {
    const Render r = render(eye, kTarget, pair, 1.0, 1.0, 0.001, 5);
    const Segmentation s = segment_scene(r.points, one(eye));
    // (a sliver of a box's face seen edge-on may come apart and be joined back: only the boxes must stay two)
    SCOPED_TRACE("eye " + std::to_string(eye.x()) + " " + std::to_string(eye.y()) + " " + std::to_string(eye.z()));
    expect_objects_are_the_boxes(s, pair);
  }
}

TEST(Segmentation, BadInputsNameTheCause) {
  const Render r = render(kEye, kTarget, kThreeBoxes, 1.0);
  auto message = [&](const Vec3Array& p, const Vec3Array& v, const SegmentationSettings& st,
                     std::optional<Eigen::Vector4d> plane = std::nullopt) {
    try {
      segment_scene(p, v, st, plane);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(Vec3Array(0, 3), Vec3Array(0, 3), {}).find("empty"), std::string::npos);
  Vec3Array nan = r.points;
  nan(3, 1) = std::nan("");
  EXPECT_NE(message(nan, Vec3Array(0, 3), {}).find("NaN"), std::string::npos);
  EXPECT_NE(message(r.points, Vec3Array(2, 3), {}).find("viewpoints"), std::string::npos);
  EXPECT_NE(message(r.points, Vec3Array::Constant(1, 3, INFINITY), {}).find("viewpoints"), std::string::npos);
  SegmentationSettings st;
  st.cluster_tolerance = 0;
  EXPECT_NE(message(r.points, one(kEye), st).find("cluster_tolerance"), std::string::npos);
  st = {};
  st.join_max_size = 0;
  EXPECT_NE(message(r.points, one(kEye), st).find("join_max_size"), std::string::npos);
  st = {};
  st.split_touching = true;
  st.split_seed_resolution = st.split_voxel_resolution;
  EXPECT_NE(message(r.points, one(kEye), st).find("split_seed_resolution"), std::string::npos);
  st = {};
  st.join_max_gap = -1;
  EXPECT_NE(message(r.points, one(kEye), st).find("join_max_gap"), std::string::npos);
  st = {};
  st.max_cluster_size = 5;
  EXPECT_NE(message(r.points, one(kEye), st).find("max_cluster_size"), std::string::npos);
  const Render table = render(kEye, kTarget, {}, 1.0, 1.0, 0.001, 9);
  EXPECT_NE(message(table.points, one(kEye), {}).find("no object above the support plane"), std::string::npos);
  EXPECT_NE(message(table.points, one(kEye), {}, Eigen::Vector4d(0, 0, 1, 0)).find("no object above"),
            std::string::npos);
  EXPECT_NE(message(r.points, one(kEye), {}, Eigen::Vector4d(0, 0, 0, 1)).find("plane"), std::string::npos);
}

/// A mug-like shape: a hollow 8 x 8 x 10 cm body, walls 6 mm thick, a handle of three bars 3 cm beyond its +x wall.
std::vector<Box> mug_boxes() {
  const double w = 0.006, x0 = -0.04, x1 = 0.04;
  return {{{x0, -0.04, 0}, {x1, -0.04 + w, 0.10}},
          {{x0, 0.04 - w, 0}, {x1, 0.04, 0.10}},
          {{x0, -0.04, 0}, {x0 + w, 0.04, 0.10}},
          {{x1 - w, -0.04, 0}, {x1, 0.04, 0.10}},
          {{x0, -0.04, 0}, {x1, 0.04, w}},
          {{x1, -0.006, 0.02}, {x1 + 0.03, 0.006, 0.032}},
          {{x1, -0.006, 0.07}, {x1 + 0.03, 0.006, 0.082}},
          {{x1 + 0.018, -0.006, 0.02}, {x1 + 0.03, 0.006, 0.082}}};
}

// The split rule (segmentation.hpp) on exact ray casting, one camera with the acquisition's noise: a tall box and a
// low, deeper one touching side by side are one Euclidean cluster 18 cm long, cut at the concave creases where the
// low box meets the tall one (not flush: coplanar faces across the contact would join them, as they would join
// LCCP's patches). Seen from straight in front (kFront) the contact shows as a convex corner and the boxes stay
// joined: the views below see the crease. One box that long has no concave crease and stays whole. A mug-like shape (a
// hollow square body 8 cm across, its walls 6 mm thick, a handle of three bars 3 cm out) is within split_max_size and
// is not tried.
TEST(Segmentation, TheSplitRuleCutsTwoTouchingBoxesAndNotOneObject) {
  const SegmentationSettings on;  // the rule is on by default
  ASSERT_TRUE(on.split_touching);
  SegmentationSettings off;
  off.split_touching = false;
  const std::vector<Box> touching = {box_at(-0.045, 0.0, 0.09, 0.06, 0.10), box_at(0.045, 0.0, 0.09, 0.10, 0.05)};
  for (const Eigen::Vector3d& eye : {kEye, Eigen::Vector3d(0.3, -0.4, 0.35), Eigen::Vector3d(-0.2, -0.4, 0.4)}) {
    SCOPED_TRACE("eye " + std::to_string(eye.x()) + " " + std::to_string(eye.y()) + " " + std::to_string(eye.z()));
    const Render r = render(eye, kTarget, touching, 1.0, 1.0, 0.001, 11, 640, 480);
    const Segmentation joined = segment_scene(r.points, one(eye), off);
    ASSERT_EQ(joined.objects.size(), 1u) << "touching boxes are one Euclidean cluster";
    EXPECT_EQ(joined.n_split, 0u);
    const Segmentation s = segment_scene(r.points, one(eye), on);
    EXPECT_EQ(s.n_split, 1u);
    expect_objects_are_the_boxes(s, touching);
    EXPECT_GE(s.times.split, 0.0);
  }
  const std::vector<Box> long_box = {box_at(0.0, 0.0, 0.18, 0.06, 0.05)};
  const std::vector<Box> mug = mug_boxes();
  for (const auto& [name, boxes] : {std::pair<std::string, std::vector<Box>>{"long box", long_box}, {"mug", mug}}) {
    for (const Eigen::Vector3d& eye : {kEye, kFront, Eigen::Vector3d(-0.2, -0.4, 0.4)}) {
      SCOPED_TRACE(name + ", eye " + std::to_string(eye.x()) + " " + std::to_string(eye.y()) + " " +
                   std::to_string(eye.z()));
      const Render r = render(eye, kTarget, boxes, 1.0, 1.0, 0.001, 13, 640, 480);
      ASSERT_EQ(segment_scene(r.points, one(eye), off).objects.size(), 1u);
      const Segmentation s = segment_scene(r.points, one(eye), on);
      EXPECT_EQ(s.n_split, 0u);
      EXPECT_EQ(s.objects.size(), 1u);
      if (name == "long box") {
        EXPECT_GT(s.objects[0].obb_extents.maxCoeff(), on.split_max_size) << "the rule was tried";
      }
    }
  }
}

// split_object_near (segmentation.hpp) on the scenes of the split test above. Two touching boxes 0.7 times as long
// and as tall are one segment within split_max_size (15 cm), which the rule leaves whole; named by a point on the
// low box, the segment is cut at split_named_max_size (12 cm) into the two boxes. One box 10 cm long is left whole;
// without viewpoints nothing is cut. The rule's limit, asserted so that a change to it shows: the mug of the test
// above (11 cm with its handle; its principal box longer than 12 cm) named by a point is cut too.
TEST(Segmentation, APointTargetsSegmentIsTriedByTheSplitRuleBelowItsSizeGate) {
  const SegmentationSettings s;
  const std::vector<Box> touching = {box_at(-0.0315, 0.0, 0.063, 0.06, 0.07), box_at(0.0315, 0.0, 0.063, 0.10, 0.035)};
  const Render r = render(kEye, kTarget, touching, 1.0, 1.0, 0.001, 11, 640, 480);
  Segmentation scene = segment_scene(r.points, one(kEye), s);
  ASSERT_EQ(scene.objects.size(), 1u) << "within the size gate: one segment";
  ASSERT_LT(scene.objects[0].obb_extents.maxCoeff(), s.split_max_size);
  const Vec3Array viewpoints = one(kEye).replicate(scene.points.rows(), 1);
  const Eigen::Vector3d low(0.0315, 0, 0.035);
  EXPECT_EQ(split_object_near(scene, Vec3Array(0, 3), low, s), 0u);
  EXPECT_EQ(split_object_near(scene, viewpoints, low, s), 1u);
  EXPECT_EQ(scene.n_split, 1u);
  expect_objects_are_the_boxes(scene, touching);
  ASSERT_EQ(scene.labels.size(), scene.points.rows());
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    EXPECT_EQ(scene.objects[k].index, static_cast<int>(k));
    for (Eigen::Index j = 0; j < scene.objects[k].rows.size(); ++j)
      EXPECT_EQ(scene.labels[scene.objects[k].rows[j]], static_cast<int>(k));
  }
  EXPECT_GE(scene.objects[0].n_points, scene.objects[1].n_points);  // ordered as segment_scene orders them
  const std::vector<Box> mug = mug_boxes();
  for (const auto& [boxes, cut] :
       {std::pair<std::vector<Box>, bool>{{box_at(0.0, 0.0, 0.10, 0.06, 0.05)}, false}, {mug, true}}) {
    const Render m = render(kEye, kTarget, boxes, 1.0, 1.0, 0.001, 13, 640, 480);
    Segmentation one_object = segment_scene(m.points, one(kEye), s);
    ASSERT_EQ(one_object.objects.size(), 1u);
    EXPECT_EQ(split_object_near(one_object, one(kEye), Eigen::Vector3d(0, 0, 0.1), s) > 0, cut);
    EXPECT_EQ(one_object.objects.size() > 1, cut);
  }
  SegmentationSettings bad = s;
  bad.split_named_max_size = 0;
  EXPECT_THROW(split_object_near(scene, viewpoints, low, bad), std::invalid_argument);
  EXPECT_THROW(split_object_near(scene, one(kEye), Eigen::Vector3d(0, std::nan(""), 0), s), std::invalid_argument);
  EXPECT_THROW(split_object_near(scene, Vec3Array::Zero(2, 3), low, s), std::invalid_argument);
}
