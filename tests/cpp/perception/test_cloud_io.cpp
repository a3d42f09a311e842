#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include "graspmix/perception/cloud_io.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path dir;
  TempDir() {
    dir = fs::temp_directory_path() / ("graspmix_io_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                       "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
  }
  ~TempDir() { fs::remove_all(dir); }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

Vec3Array random_points(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Vec3Array P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng), u(rng);
  return P;
}

std::string error_of(const std::string& path) {
  try {
    load_cloud(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

}  // namespace

TEST(CloudIo, RoundTripEveryEncoding) {
  TempDir tmp;
  const Vec3Array P = random_points(500, 1);
  const Vec3Array N = random_points(500, 2).rowwise().normalized();
  Eigen::Matrix<double, 7, 1> vp;
  vp << 0.1, 0.2, 0.3, 0, 0, std::sin(0.25), std::cos(0.25);
  for (const auto& [name, enc] : std::vector<std::pair<std::string, std::string>>{
           {"a.pcd", "ascii"}, {"b.pcd", "binary"}, {"c.pcd", "binary_compressed"}, {"d.ply", "ascii"}, {"e.ply", "binary"}}) {
    save_cloud(tmp / name, P, N, enc, vp);
    const CloudData c = load_cloud(tmp / name);
    ASSERT_EQ(c.points.rows(), 500) << name;
    // float32 on disk
    EXPECT_LT((c.points - P.cast<float>().cast<double>()).cwiseAbs().maxCoeff(), 1e-7) << name;
    ASSERT_EQ(c.normals.rows(), 500) << name;
    EXPECT_LT((c.normals - N).cwiseAbs().maxCoeff(), 1e-6) << name;
    EXPECT_EQ(c.n_invalid, 0u);
    if (name.find("pcd") != std::string::npos) {
      EXPECT_EQ(c.format, "pcd " + enc);
      EXPECT_TRUE(c.has_viewpoint);
      EXPECT_LT((c.viewpoint - vp).cwiseAbs().maxCoeff(), 1e-6) << name;
    }
  }
}

TEST(CloudIo, OrganisedCloudWithNaNsExtraFieldsAndViewpoint) {
  TempDir tmp;
  write(tmp / "org.pcd",
        "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z rgb intensity\nSIZE 4 4 4 4 4\n"
        "TYPE F F F F F\nCOUNT 1 1 1 1 1\nWIDTH 3\nHEIGHT 2\nVIEWPOINT 1 2 3 1 0 0 0\nPOINTS 6\nDATA ascii\n"
        "0.1 0.2 0.3 4.2108e+06 10\nnan nan nan 0 0\n0.4 0.5 0.6 4.2108e+06 11\n"
        "nan nan nan 0 0\n0.7 0.8 0.9 4.2108e+06 12\n1 1 nan 0 0\n");
  const CloudData c = load_cloud(tmp / "org.pcd");
  ASSERT_EQ(c.points.rows(), 3);
  EXPECT_EQ(c.n_invalid, 3u);
  EXPECT_EQ(c.width, 3u);
  EXPECT_EQ(c.height, 2u);
  EXPECT_NEAR(c.points(2, 2), 0.9, 1e-6);
  EXPECT_EQ(c.fields, (std::vector<std::string>{"x", "y", "z", "rgb", "intensity"}));
  EXPECT_EQ(c.normals.rows(), 0);
  EXPECT_TRUE(c.has_viewpoint);
  EXPECT_NEAR(c.viewpoint[0], 1.0, 1e-9);
  EXPECT_NEAR(c.viewpoint[6], 1.0, 1e-9);
}

TEST(CloudIo, DoublePrecisionPly) {
  TempDir tmp;
  write(tmp / "d.ply",
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\nproperty double y\nproperty double z\n"
        "property uchar red\nend_header\n0.125 0.25 0.5 255\n1.5 2.5 3.5 0\n");
  const CloudData c = load_cloud(tmp / "d.ply");
  ASSERT_EQ(c.points.rows(), 2);
  EXPECT_DOUBLE_EQ(c.points(0, 2), 0.5);
  EXPECT_DOUBLE_EQ(c.points(1, 0), 1.5);
}

TEST(CloudIo, BrokenFilesNameTheFileAndTheProblem) {
  TempDir tmp;
  const Vec3Array P = random_points(100, 3);
  save_cloud(tmp / "ok.pcd", P, {}, "binary");
  // PCL pads binary files to whole pages; cut into the 1200 bytes of data after a ~170 byte header.
  fs::copy_file(tmp / "ok.pcd", tmp / "trunc.pcd");
  fs::resize_file(tmp / "trunc.pcd", 800);
  std::string e = error_of(tmp / "trunc.pcd");
  EXPECT_NE(e.find("trunc.pcd"), std::string::npos) << e;
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;

  save_cloud(tmp / "ok_a.pcd", P, {}, "ascii");
  std::string text;
  {
    std::ifstream in(tmp / "ok_a.pcd");
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  write(tmp / "trunc_a.pcd", text.substr(0, text.size() / 2));
  e = error_of(tmp / "trunc_a.pcd");
  EXPECT_NE(e.find("truncated"), std::string::npos) << e;

  write(tmp / "header.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
  e = error_of(tmp / "header.pcd");
  EXPECT_NE(e.find("header.pcd"), std::string::npos) << e;
  EXPECT_NE(e.find("header"), std::string::npos) << e;

  write(tmp / "empty.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA ascii\n");
  e = error_of(tmp / "empty.pcd");
  EXPECT_NE(e.find("empty"), std::string::npos) << e;

  write(tmp / "nan.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\nnan nan nan\nnan 0 0\n");
  e = error_of(tmp / "nan.pcd");
  EXPECT_NE(e.find("NaN"), std::string::npos) << e;

  write(tmp / "zero.pcd", "");
  EXPECT_NE(error_of(tmp / "zero.pcd").find("empty"), std::string::npos);
  EXPECT_NE(error_of(tmp / "missing.pcd").find("no such file"), std::string::npos);
  write(tmp / "noxyz.pcd", "VERSION 0.7\nFIELDS a b c\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
  EXPECT_NE(error_of(tmp / "noxyz.pcd").find("no x, y, z"), std::string::npos);
  write(tmp / "bad.ply", "plx\nformat ascii 1.0\n");
  EXPECT_NE(error_of(tmp / "bad.ply").find("PLY header"), std::string::npos);
  EXPECT_THROW(save_cloud(tmp / "x.pcd", P, {}, "zip"), std::invalid_argument);
  EXPECT_THROW(save_cloud(tmp / "x.txt", P), std::invalid_argument);
  EXPECT_THROW(save_cloud(tmp / "x.pcd", Vec3Array(0, 3)), std::invalid_argument);
}
