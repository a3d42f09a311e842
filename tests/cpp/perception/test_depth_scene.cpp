// The scene of one depth image against exact geometry and against segment_scene on the same view's points: two
// boxes on a table ray-cast with known intrinsics, so the plane, the objects and every point's place are known in
// closed form; the organized cloud's path against the depth image's; the image-space blocks; bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error_message.hpp"
#include "graspmix/perception/depth_scene.hpp"
#include "raycast.hpp"

using namespace graspmix;
using namespace graspmix::test;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const PinholeCamera kCam(300.0, 300.0, 159.5, 119.5, 320, 240);
const Eigen::Isometry3d kPose = looking_at({0.1, -0.45, 0.4}, {0.0, 0.0, 0.03});
const Eigen::Vector3d kBoxA_lo(-0.09, -0.04, 0.0), kBoxA_hi(-0.02, 0.03, 0.08);
const Eigen::Vector3d kBoxB_lo(0.03, -0.02, 0.0), kBoxB_hi(0.09, 0.05, 0.05);

double two_boxes(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return std::min({hit_box(o, d, kBoxA_lo, kBoxA_hi), hit_box(o, d, kBoxB_lo, kBoxB_hi),
                   hit_plane(o, d, Eigen::Vector3d::UnitZ(), 0.0)});
}

const DepthImage& image() {
  static const DepthImage d = render(kCam, kPose, two_boxes);
  return d;
}

/// The world points of a depth image's returns, row by row.
Vec3Array world_points(const DepthImage& depth) {
  const Vec3Array S = kCam.back_project(depth);
  std::vector<Eigen::Vector3d> out;
  for (Eigen::Index r = 0; r < S.rows(); ++r)
    if (S.row(r).allFinite()) out.push_back(kPose * S.row(r).transpose());
  Vec3Array P(static_cast<Eigen::Index>(out.size()), 3);
  for (std::size_t i = 0; i < out.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = out[i].transpose();
  return P;
}

bool inside(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double eps) {
  return (p.array() >= lo.array() - eps).all() && (p.array() <= hi.array() + eps).all();
}

/// The rows of s's points sorted lexicographically: the same set whatever the order.
std::vector<std::vector<double>> sorted_rows(const Vec3Array& P) {
  std::vector<std::vector<double>> rows;
  for (Eigen::Index r = 0; r < P.rows(); ++r) rows.push_back({P(r, 0), P(r, 1), P(r, 2)});
  std::sort(rows.begin(), rows.end());
  return rows;
}

}  // namespace

TEST(DepthScene, TwoBoxesOnATableExactly) {
  const Segmentation s = segment_depth(image(), kCam, kPose);
  ASSERT_TRUE(s.plane_found);
  EXPECT_NEAR(s.plane[2], 1.0, 1e-9);  // the table z = 0, towards the camera (fitted in float, as PCL does)
  EXPECT_NEAR(s.plane[3], 0.0, 1e-5);
  ASSERT_EQ(s.objects.size(), 2u);
  // Every object point is a mean of points of one box's faces: inside that box (to rounding), and all the points
  // of an object are in the same box; the larger box (A) is object 0.
  for (const SceneObject& o : s.objects) {
    const Eigen::Vector3d &lo = o.index == 0 ? kBoxA_lo : kBoxB_lo, &hi = o.index == 0 ? kBoxA_hi : kBoxB_hi;
    for (Eigen::Index i = 0; i < o.rows.size(); ++i)
      EXPECT_TRUE(inside(s.points.row(o.rows[i]).transpose(), lo, hi, 1e-6)) << "object " << o.index;
  }
  EXPECT_EQ(s.n_input, static_cast<std::size_t>((image().array() < std::numeric_limits<double>::infinity()).count()));
  ASSERT_TRUE(s.visibility);
  EXPECT_EQ(s.visibility->view(0).kind, ViewKind::Pinhole);
  // Above box A's top face is seen free, its centre is unseen.
  EXPECT_EQ(s.visibility->state({-0.055, -0.005, 0.1}), SpaceState::SeenFree);
  EXPECT_EQ(s.visibility->state({-0.055, -0.005, 0.04}), SpaceState::Unseen);
}

TEST(DepthScene, SameSceneAsSegmentSceneOnTheSamePoints) {
  // With blocks of one pixel the voxel grid sees the view's own points: the plane and the objects are the ones
  // segment_scene finds on the points with the camera as their viewpoint (only the visibility model differs).
  SegmentationSettings one;
  one.image_stride = 1;
  one.plane_image_stride = 1;  // the plane searched on the same points
  const Segmentation a = segment_depth(image(), kCam, kPose, one);
  const Vec3Array camera = kPose.translation().transpose();
  const Segmentation b = segment_scene(world_points(image()), camera, one);
  EXPECT_TRUE(a.plane.isApprox(b.plane, 1e-9));
  ASSERT_EQ(a.objects.size(), b.objects.size());
  EXPECT_EQ(a.n_after_voxel, b.n_after_voxel);
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].n_points, b.objects[i].n_points);
    EXPECT_TRUE(a.objects[i].centroid.isApprox(b.objects[i].centroid, 1e-9));
  }
  const auto pa = sorted_rows(a.points), pb = sorted_rows(b.points);
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(pa[i][k], pb[i][k], 1e-9);
  // sources are pixels: each point lies within a voxel diagonal of its pixel's point.
  const Vec3Array S = kCam.back_project(image());
  for (Eigen::Index r = 0; r < a.points.rows(); ++r) {
    const Eigen::Vector3d p = kPose * S.row(a.sources[r]).transpose();
    EXPECT_LE((p - a.points.row(r).transpose()).norm(), std::sqrt(3.0) * one.voxel_size + 1e-9);
  }
}

TEST(DepthScene, ThePlaneSearchedOnCoarseBlocksGivesTheSameObjects) {
  // The support plane searched on blocks of 4 pixels, the objects made of the one-pixel blocks above it: the same
  // objects as with the plane searched on every pixel (the plane is exact either way), every point on its box; only
  // the voxels at an object's foot differ (above the table's clearance they hold no table point).
  SegmentationSettings one, two;
  one.image_stride = two.image_stride = 1;
  one.plane_image_stride = 1;
  two.plane_image_stride = 4;
  const Segmentation a = segment_depth(image(), kCam, kPose, one), b = segment_depth(image(), kCam, kPose, two);
  ASSERT_TRUE(b.plane_found);
  EXPECT_TRUE(a.plane.isApprox(b.plane, 1e-5));
  EXPECT_LT(b.n_after_voxel, a.n_after_voxel / 3);  // the table's points, from the coarse blocks only
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_NEAR(static_cast<double>(b.objects[i].n_points), static_cast<double>(a.objects[i].n_points),
                0.03 * static_cast<double>(a.objects[i].n_points));
    EXPECT_LT((a.objects[i].centroid - b.objects[i].centroid).norm(), 1e-3);
    const Eigen::Vector3d &lo = i == 0 ? kBoxA_lo : kBoxB_lo, &hi = i == 0 ? kBoxA_hi : kBoxB_hi;
    for (Eigen::Index k = 0; k < b.objects[i].rows.size(); ++k)
      EXPECT_TRUE(inside(b.points.row(b.objects[i].rows[k]).transpose(), lo, hi, 1e-6));
  }
  // A given table (upside down: turned towards the camera) takes the same way: the same objects, no search.
  const Segmentation c = segment_depth(image(), kCam, kPose, two, Eigen::Vector4d(0, 0, -2, 0));
  EXPECT_TRUE(c.plane_given && !c.plane_found && c.candidates.empty());
  EXPECT_TRUE(c.plane.isApprox(Eigen::Vector4d(0, 0, 1, 0)));
  ASSERT_EQ(c.objects.size(), b.objects.size());
  for (std::size_t i = 0; i < b.objects.size(); ++i)
    EXPECT_NEAR(static_cast<double>(c.objects[i].n_points), static_cast<double>(b.objects[i].n_points),
                0.03 * static_cast<double>(b.objects[i].n_points));
}

TEST(DepthScene, OrganizedCloudGivesTheDepthImagesScene) {
  const Vec3Array S = kCam.back_project(image());
  const Segmentation a = segment_depth(image(), kCam, kPose);
  const Segmentation b = segment_organized(S, kCam.height(), kCam.width(), kPose);
  EXPECT_TRUE(a.plane.isApprox(b.plane, 1e-9));
  ASSERT_EQ(a.objects.size(), b.objects.size());
  EXPECT_EQ(a.n_output, b.n_output);
  EXPECT_TRUE(a.points.isApprox(b.points, 1e-6));  // the fitted intrinsics reproduce the pixels' rays
  // With the intrinsics known (fitted once, as a caller that checked the cloud already has them): the same scene.
  const PinholeFit fit = fit_pinhole(S, kCam.height(), kCam.width());
  const Segmentation c = segment_organized(S, fit.camera, kPose);
  EXPECT_TRUE(c.plane.isApprox(b.plane, 0)) << c.plane.transpose() << " vs " << b.plane.transpose();
  EXPECT_TRUE(c.points.isApprox(b.points, 0));
}

TEST(DepthScene, BlocksOfTheStrideAndTheAutomaticStride) {
  // The automatic block: the largest whose side at the median depth is within half a voxel.
  std::vector<double> z;
  for (Eigen::Index v = 0; v < image().rows(); v += 4)
    for (Eigen::Index u = 0; u < image().cols(); u += 4)
      if (has_return(image()(v, u))) z.push_back(image()(v, u));
  std::nth_element(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2), z.end());
  for (const double voxel : {0.003, 0.006, 0.012}) {
    SegmentationSettings s;
    s.voxel_size = voxel;
    const int expected = std::max(1, static_cast<int>(std::floor(0.5 * voxel * 300.0 / z[z.size() / 2])));
    EXPECT_EQ(image_stride(image(), kCam, s), expected) << voxel;
  }
  SegmentationSettings coarse;
  coarse.image_stride = 3;
  EXPECT_EQ(image_stride(image(), kCam, coarse), 3);
  const Segmentation a = segment_depth(image(), kCam, kPose, coarse);
  const Segmentation full = segment_depth(image(), kCam, kPose, SegmentationSettings{});
  EXPECT_LT(a.n_after_voxel, full.n_after_voxel);
  ASSERT_EQ(a.objects.size(), 2u);
  EXPECT_NEAR(a.plane[2], 1.0, 1e-9);
  EXPECT_NEAR(a.plane[3], 0.0, 1e-5);
  for (const SceneObject& o : a.objects) {  // block means of one face's points stay on the boxes
    const Eigen::Vector3d &lo = o.index == 0 ? kBoxA_lo : kBoxB_lo, &hi = o.index == 0 ? kBoxA_hi : kBoxB_hi;
    for (Eigen::Index i = 0; i < o.rows.size(); ++i)
      EXPECT_TRUE(inside(a.points.row(o.rows[i]).transpose(), lo, hi, 1e-6));
  }
}

// A workspace around box B (and the table about it): the scene is box B alone, the object found without the crop;
// segment_scene with the same workspace is segment_scene on the points inside it, its sources rows of the whole input.
// A workspace with nothing inside, or not a box, is an error naming it.
TEST(DepthScene, TheWorkspaceCropsTheInputFirst) {
  SegmentationSettings crop;
  crop.workspace = {0.0, -0.1, -0.05, 0.2, 0.15, 0.2};
  const Segmentation whole = segment_depth(image(), kCam, kPose), cropped = segment_depth(image(), kCam, kPose, crop);
  ASSERT_TRUE(cropped.plane_found);
  EXPECT_NEAR(cropped.plane[2], 1.0, 1e-6);
  ASSERT_EQ(cropped.objects.size(), 1u);
  ASSERT_EQ(whole.objects.size(), 2u);
  const SceneObject& b = whole.objects[1];  // box B, the smaller
  // The outlier filter's statistic is the cloud's: on box B alone it keeps a few more of B's edge points.
  EXPECT_NEAR(static_cast<double>(cropped.objects[0].n_points), static_cast<double>(b.n_points), 0.01 * b.n_points);
  EXPECT_LT((cropped.objects[0].centroid - b.centroid).norm(), 0.001);
  for (Eigen::Index r = 0; r < cropped.points.rows(); ++r)
    EXPECT_TRUE(inside(cropped.points.row(r).transpose(), kBoxB_lo, kBoxB_hi, 1e-6));

  SegmentationSettings one = crop;  // the unorganized path on the view's points
  one.image_stride = 1;
  one.plane_image_stride = 1;
  const Vec3Array P = world_points(image()), camera = kPose.translation().transpose();
  const Segmentation a = segment_scene(P, camera, one);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    if ((P.row(r).transpose().array() >= Eigen::Array3d(0.0, -0.1, -0.05)).all() &&
        (P.row(r).transpose().array() <= Eigen::Array3d(0.2, 0.15, 0.2)).all())
      rows.push_back(r);
  Vec3Array inner(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) inner.row(static_cast<Eigen::Index>(i)) = P.row(rows[i]);
  one.workspace.clear();
  const Segmentation c = segment_scene(inner, camera, one);
  ASSERT_EQ(a.objects.size(), 1u);
  ASSERT_EQ(c.objects.size(), 1u);
  EXPECT_EQ(a.points, c.points);
  EXPECT_EQ(a.n_input, static_cast<std::size_t>(P.rows()));
  for (Eigen::Index r = 0; r < a.sources.size(); ++r) EXPECT_EQ(a.sources[r], rows[c.sources[r]]);

  SegmentationSettings away;
  away.workspace = {1.0, 1.0, 1.0, 2.0, 2.0, 2.0};
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, kPose, away); }).find("nothing inside the workspace"),
            std::string::npos);
  EXPECT_NE(error_message([&] { segment_scene(P, camera, away); }).find("nothing inside the workspace"),
            std::string::npos);
  away.workspace = {0.0, 0.0, 0.0, 0.0, 1.0, 1.0};
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, kPose, away); }).find("below its maximum"),
            std::string::npos);
  away.workspace = {0.0, 0.0, 1.0};
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, kPose, away); }).find("6 numbers"), std::string::npos);
}

TEST(DepthScene, TheMedianWindowKeepsLoneOutlinePixelsFromSeeingThroughAnObject) {
  // Every fourth pixel of box A's outline (a box pixel beside a table pixel 5 cm or more behind it) takes that
  // table pixel's depth, as a sensor's lateral noise or a flying pixel gives it: its ray then sees through the box's
  // edge.
  DepthImage ragged = image();
  const Eigen::Index H = ragged.rows(), W = ragged.cols();
  std::vector<std::pair<Eigen::Index, Eigen::Index>> through;
  int k = 0;
  for (Eigen::Index v = 1; v + 1 < H; ++v)
    for (Eigen::Index u = 1; u + 1 < W; ++u) {
      const Eigen::Vector3d on = kPose * kCam.back_project(u, v, image()(v, u));
      if (!inside(on, kBoxA_lo, kBoxA_hi, 1e-9) || on.z() < 0.01) continue;
      const double behind =  // the deepest of the four pixels beside it
          std::max({image()(v, u + 1), image()(v, u - 1), image()(v + 1, u), image()(v - 1, u)});
      if (behind < image()(v, u) + 0.05 || k++ % 4) continue;
      ragged(v, u) = behind;
      through.emplace_back(v, u);
    }
  ASSERT_GT(through.size(), 10u);
  SegmentationSettings median, as_is;
  median.visibility_median_window = 1;  // the default
  as_is.visibility_median_window = 0;
  const Segmentation raw = segment_depth(ragged, kCam, kPose, as_is),
                     filtered = segment_depth(ragged, kCam, kPose, median);
  // The point of box A's surface 2 mm deep along each such pixel's ray: seen free through the ragged pixel, on the
  // surface again once the median has put the pixel back on the box: wherever most of its 3 x 3 window is box
  // (along the outline's straight runs; at a silhouette's corner most of the window is table, and stays so).
  int raw_free = 0, restored = 0, boxed = 0;
  for (const auto& [v, u] : through) {
    const Eigen::Vector3d p = kPose * kCam.back_project(u, v, image()(v, u) + 0.002);
    raw_free += raw.visibility->state(p) == SpaceState::SeenFree;
    int box = 0;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du) box += std::abs(ragged(v + dv, u + du) - image()(v, u)) < 0.02;
    if (box < 5) continue;
    ++boxed;
    restored += filtered.visibility->state(p) == SpaceState::Surface;
  }
  EXPECT_EQ(raw_free, static_cast<int>(through.size()));
  EXPECT_GT(boxed, 5);
  EXPECT_EQ(restored, boxed);
  // On the clean image the median changes no pixel a plane fills (a linear ramp's median is its centre): the same
  // state everywhere but within a pixel of an edge.
  const Segmentation clean = segment_depth(image(), kCam, kPose, as_is),
                     clean_median = segment_depth(image(), kCam, kPose, median);
  int n = 0, same = 0;
  for (Eigen::Index v = 0; v < H; v += 3)
    for (Eigen::Index u = 0; u < W; u += 3)
      for (const double delta : {-0.02, -0.003, 0.003, 0.02}) {
        const Eigen::Vector3d p = kPose * kCam.back_project(u, v, image()(v, u) + delta);
        ++n;
        same += clean.visibility->state(p) == clean_median.visibility->state(p);
      }
  EXPECT_GT(static_cast<double>(same) / n, 0.97);
  SegmentationSettings bad;
  bad.visibility_median_window = 6;
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, kPose, bad); }).find("visibility_median_window"),
            std::string::npos);
}

TEST(DepthScene, BadInputNamesWhatIsWrong) {
  DepthImage small(10, 10);
  small.setConstant(0.5);
  EXPECT_NE(error_message([&] { segment_depth(small, kCam, kPose); }).find("depth"), std::string::npos);
  DepthImage negative = image();
  negative(5, 5) = -0.1;
  EXPECT_NE(error_message([&] { segment_depth(negative, kCam, kPose); }).find("negative"), std::string::npos);
  const DepthImage none = DepthImage::Constant(kCam.height(), kCam.width(), kNaN);
  EXPECT_NE(error_message([&] { segment_depth(none, kCam, kPose); }).find("no pixel has a return"), std::string::npos);
  Eigen::Isometry3d skewed = kPose;
  skewed.linear() *= 1.1;
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, skewed); }).find("T_world_camera"), std::string::npos);
  SegmentationSettings bad;
  bad.image_stride = -1;
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, kPose, bad); }).find("image_stride"), std::string::npos);
  bad.image_stride = 0;
  bad.plane_image_stride = 0;
  EXPECT_NE(error_message([&] { segment_depth(image(), kCam, kPose, bad); }).find("plane_image_stride"),
            std::string::npos);
  const Vec3Array S = kCam.back_project(image());
  EXPECT_NE(error_message([&] { segment_organized(S, kCam.height() - 1, kCam.width(), kPose); }).find("rows"),
            std::string::npos);
  Vec3Array world = S;  // the same points in the world frame: not a pinhole image in the sensor frame
  for (Eigen::Index r = 0; r < world.rows(); ++r)
    if (world.row(r).allFinite()) world.row(r) = (kPose * S.row(r).transpose()).transpose();
  EXPECT_NE(error_message([&] { segment_organized(world, kCam.height(), kCam.width(), kPose); }).find("sensor frame"),
            std::string::npos);
}
