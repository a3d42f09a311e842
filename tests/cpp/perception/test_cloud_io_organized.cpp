// Organised clouds (width x height with NaN holes) through save_cloud, load_cloud and organized_grid, and PLY
// files as PCL writes them: cross-checked against PCL's own readers and writers (pcl_io, linked by this test only).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "core/error_message.hpp"
#include "graspmix/perception/cloud_io.hpp"
#include "temp_dir.hpp"

using namespace graspmix;
using graspmix::test::error_message;

namespace {

using graspmix::test_support::TempDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A width x height view of a wavy surface, row v * width + u at pixel (u, v), with a seeded fifth of the
/// pixels holes (NaN rows); `holes` gets their indices.
Vec3Array grid_points(int width, int height, std::uint64_t seed, std::vector<Eigen::Index>& holes) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  Vec3Array P(width * height, 3);
  holes.clear();
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const int i = v * width + u;
      const double z = 1.0 + 0.05 * std::sin(u) + 0.01 * v;
      P.row(i) << (u - width / 2) * 0.01 * z, (v - height / 2) * 0.01 * z, z;
      if (u01(rng) < 0.2) P.row(i).setConstant(kNaN), holes.push_back(i);
    }
  return P;
}

/// The kept pixels of a grid: every index that is not a hole.
Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1> kept(Eigen::Index n, const std::vector<Eigen::Index>& holes) {
  std::vector<std::int64_t> out;
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::find(holes.begin(), holes.end(), i) == holes.end()) out.push_back(i);
  return Eigen::Map<Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1>>(out.data(), static_cast<Eigen::Index>(out.size()));
}

/// Equal, NaN where the other is NaN.
void expect_same_grid(const Vec3Array& a, const Vec3Array& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (int j = 0; j < 3; ++j) {
      if (std::isnan(b(i, j))) {
        ASSERT_TRUE(std::isnan(a(i, j))) << what << " row " << i;
      } else {
        ASSERT_EQ(a(i, j), b(i, j)) << what << " row " << i;
      }
    }
}

}  // namespace

TEST(CloudIoOrganized, RoundTripKeepsTheGridInEveryEncodingAndPclReadsIt) {
  TempDir tmp;
  std::vector<Eigen::Index> holes;
  const Vec3Array P = grid_points(7, 5, 1, holes);
  Vec3Array N = Vec3Array::Zero(35, 3);
  N.col(2).setOnes();
  for (const Eigen::Index h : holes) N.row(h).setConstant(kNaN);  // a hole's normal is NaN too, as PCL writes it
  const Vec3Array on_disk = P.cast<float>().cast<double>();
  for (const std::string enc : {"ascii", "binary", "binary_compressed"}) {
    const std::string path = tmp / (enc + ".pcd");
    save_cloud(path, P, N, enc, Eigen::Matrix<double, 7, 1>::Unit(6), {}, 7, 5);
    const CloudData c = load_cloud(path);
    EXPECT_EQ(c.width, 7u) << enc;
    EXPECT_EQ(c.height, 5u) << enc;
    EXPECT_EQ(c.n_invalid, holes.size()) << enc;
    EXPECT_EQ(c.pixels, kept(35, holes)) << enc;
    EXPECT_EQ(c.normals.rows(), c.points.rows()) << enc;
    expect_same_grid(organized_grid(c), on_disk, enc);
    for (Eigen::Index k = 0; k < c.points.rows(); ++k) ASSERT_EQ(c.points.row(k), on_disk.row(c.pixels[k])) << enc;

    pcl::PointCloud<pcl::PointXYZ> pc;
    ASSERT_EQ(pcl::io::loadPCDFile(path, pc), 0) << enc;
    ASSERT_EQ(pc.width, 7u) << enc;
    ASSERT_EQ(pc.height, 5u) << enc;
    Vec3Array theirs(35, 3);
    for (int i = 0; i < 35; ++i) theirs.row(i) << pc[i].x, pc[i].y, pc[i].z;
    expect_same_grid(theirs, on_disk, enc + " read by PCL");
  }
}

TEST(CloudIoOrganized, CloudsPclWritesKeepTheirPixels) {
  TempDir tmp;
  std::vector<Eigen::Index> holes;
  const Vec3Array P = grid_points(6, 4, 2, holes);
  pcl::PointCloud<pcl::PointXYZ> org(6, 4);
  for (int i = 0; i < 24; ++i) org[i] = pcl::PointXYZ(P(i, 0), P(i, 1), P(i, 2));
  org.is_dense = false;
  const Vec3Array on_disk = P.cast<float>().cast<double>();
  for (const std::string enc : {"ascii", "binary", "binary_compressed"}) {
    const std::string path = tmp / ("pcl_" + enc + ".pcd");
    if (enc == "ascii") pcl::io::savePCDFileASCII(path, org);
    if (enc == "binary") pcl::io::savePCDFileBinary(path, org);
    if (enc == "binary_compressed") pcl::io::savePCDFileBinaryCompressed(path, org);
    const CloudData c = load_cloud(path);
    EXPECT_EQ(c.format, "pcd " + enc);
    EXPECT_EQ(c.pixels, kept(24, holes)) << enc;
    expect_same_grid(organized_grid(c), on_disk, enc);
  }
}

TEST(CloudIoOrganized, PlyFilesNameTheirFieldsAsPclsReaderDoes) {
  TempDir tmp;
  pcl::PointCloud<pcl::PointXYZRGBNormal> cloud;
  for (int i = 0; i < 10; ++i) {
    pcl::PointXYZRGBNormal p;
    p.x = 0.1f * i, p.y = 0.2f, p.z = -0.3f * i, p.r = 10, p.g = 20, p.b = static_cast<std::uint8_t>(i);
    p.normal_x = 0, p.normal_y = 1, p.normal_z = 0, p.curvature = 0.5f;
    cloud.push_back(p);
  }
  // PCL's writer: obj_info lines, red green blue as uchar, nx ny nz, an empty face element.
  for (const bool binary : {false, true}) {
    const std::string path = tmp / (binary ? "b.ply" : "a.ply");
    pcl::PLYWriter().write(path, cloud, binary, false);
    pcl::PCLPointCloud2 theirs;
    ASSERT_EQ(pcl::io::loadPLYFile(path, theirs), 0);
    const CloudData c = load_cloud(path);
    std::vector<std::string> names;
    for (const auto& f : theirs.fields) names.push_back(f.name);
    EXPECT_EQ(c.fields, names) << path;
    pcl::PointCloud<pcl::PointXYZ> read;  // PCL's ASCII writer rounds: compare with what PCL reads
    pcl::fromPCLPointCloud2(theirs, read);
    ASSERT_EQ(c.points.rows(), 10);
    ASSERT_EQ(c.normals.rows(), 10);
    for (int i = 0; i < 10; ++i) {
      EXPECT_EQ(c.points.row(i), Eigen::RowVector3d(read[i].x, read[i].y, read[i].z)) << i;
      EXPECT_NEAR(c.points(i, 2), cloud[i].z, 1e-6) << i;
      EXPECT_EQ(c.normals.row(i), Eigen::RowVector3d(0, 1, 0)) << i;
    }
  }
  // A hand-written organised PLY (obj_info num_cols x num_rows, NaN holes, alpha and a vertex list): the same
  // fields and organisation as PCL's reader, and each point's pixel.
  const std::string path = tmp / "org.ply";
  std::ofstream(path) << "ply\nformat ascii 1.0\nobj_info num_cols 3\nobj_info num_rows 2\nelement vertex 6\n"
                         "property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                         "property uchar green\nproperty uchar blue\nproperty uchar alpha\n"
                         "property list uchar int ids\nend_header\n"
                         "0 0 1 1 2 3 4 1 7\nnan nan nan 0 0 0 0 1 7\n2 0 1 1 2 3 4 1 7\n"
                         "0 1 1 1 2 3 4 1 7\n1 1 1 1 2 3 4 1 7\nnan 1 1 0 0 0 0 1 7\n";
  pcl::PCLPointCloud2 theirs;
  ASSERT_EQ(pcl::io::loadPLYFile(path, theirs), 0);
  const CloudData c = load_cloud(path);
  std::vector<std::string> names;
  for (const auto& f : theirs.fields) names.push_back(f.name);
  EXPECT_EQ(c.fields, names);
  EXPECT_EQ(c.width, theirs.width);
  EXPECT_EQ(c.height, theirs.height);
  EXPECT_EQ(c.pixels, (Eigen::Matrix<std::int64_t, 4, 1>() << 0, 2, 3, 4).finished());
  EXPECT_EQ(c.points.row(3), Eigen::RowVector3d(1, 1, 1));
}

TEST(CloudIoOrganized, BadOrganisedInputsNameTheProblem) {
  TempDir tmp;
  std::vector<Eigen::Index> holes;
  Vec3Array P = grid_points(7, 5, 3, holes);
  const auto save = [&](const std::string& name, const Vec3Array& points, std::uint32_t w, std::uint32_t h,
                        const Vec3Array& normals = {}) {
    return error_message(
        [&] { save_cloud(tmp / name, points, normals, "binary", Eigen::Matrix<double, 7, 1>::Unit(6), {}, w, h); });
  };
  std::string e = save("o.ply", P, 7, 5);
  EXPECT_NE(e.find("o.ply: an organized cloud (height 5) cannot be written as PLY"), std::string::npos) << e;
  e = save("o.pcd", P, 7, 4);
  EXPECT_NE(e.find("width x height = 7 x 4 for 35 points"), std::string::npos) << e;
  const Eigen::Index seen = kept(35, holes)[0];
  Vec3Array N = Vec3Array::Zero(35, 3);
  N(seen, 1) = kNaN;  // on a point that is not a hole
  e = save("n.pcd", P, 7, 5, N);
  EXPECT_NE(e.find("normals: row " + std::to_string(seen) + " is not finite"), std::string::npos) << e;
  Vec3Array inf = P;
  inf.row(0) << 1.0, 1.0, std::numeric_limits<double>::infinity();
  e = save("i.pcd", inf, 7, 5);
  EXPECT_NE(e.find("points: row 0 is not finite"), std::string::npos) << e;
  e = save("h.pcd", Vec3Array::Constant(35, 3, kNaN), 7, 5);
  EXPECT_NE(e.find("every point is a hole"), std::string::npos) << e;
  e = save("u.pcd", P, 0, 0);  // unorganised: holes are not allowed there
  EXPECT_NE(e.find("points: contains NaN"), std::string::npos) << e;

  // One row is an unorganised cloud: no pixels, and no grid.
  Vec3Array row(3, 3);
  row << 0, 0, 1, 1, 0, 1, 2, 0, 1;
  save_cloud(tmp / "row.pcd", row, {}, "ascii", Eigen::Matrix<double, 7, 1>::Unit(6), {}, 3, 1);
  const CloudData c = load_cloud(tmp / "row.pcd");
  EXPECT_EQ(c.pixels.size(), 0);
  e = error_message([&] { organized_grid(c); });
  EXPECT_NE(e.find(tmp / "row.pcd"), std::string::npos) << e;
  EXPECT_NE(e.find("not an organized cloud (height 1)"), std::string::npos) << e;
}
