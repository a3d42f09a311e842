#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "graspmix/perception/cloud_io.hpp"
#include "temp_dir.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {

using graspmix::test_support::TempDir;

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
  for (const auto& [name, enc] : std::vector<std::pair<std::string, std::string>>{{"a.pcd", "ascii"},
                                                                                  {"b.pcd", "binary"},
                                                                                  {"c.pcd", "binary_compressed"},
                                                                                  {"d.ply", "ascii"},
                                                                                  {"e.ply", "binary"}}) {
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

  write(tmp / "header.pcd",
        "VERSION 0.7\nFIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
  e = error_of(tmp / "header.pcd");
  EXPECT_NE(e.find("header.pcd"), std::string::npos) << e;
  EXPECT_NE(e.find("header"), std::string::npos) << e;

  write(tmp / "empty.pcd",
        "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA ascii\n");
  e = error_of(tmp / "empty.pcd");
  EXPECT_NE(e.find("empty"), std::string::npos) << e;

  write(tmp / "nan.pcd",
        "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\nnan "
        "nan nan\nnan 0 0\n");
  e = error_of(tmp / "nan.pcd");
  EXPECT_NE(e.find("NaN"), std::string::npos) << e;

  write(tmp / "zero.pcd", "");
  EXPECT_NE(error_of(tmp / "zero.pcd").find("empty"), std::string::npos);
  EXPECT_NE(error_of(tmp / "missing.pcd").find("no such file"), std::string::npos);
  write(tmp / "noxyz.pcd",
        "VERSION 0.7\nFIELDS a b c\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 "
        "3\n");
  EXPECT_NE(error_of(tmp / "noxyz.pcd").find("no x, y, z"), std::string::npos);
  write(tmp / "bad.ply", "plx\nformat ascii 1.0\n");
  EXPECT_NE(error_of(tmp / "bad.ply").find("PLY header"), std::string::npos);
  EXPECT_THROW(save_cloud(tmp / "x.pcd", P, {}, "zip"), std::invalid_argument);
  EXPECT_THROW(save_cloud(tmp / "x.txt", P), std::invalid_argument);
  EXPECT_THROW(save_cloud(tmp / "x.pcd", Vec3Array(0, 3)), std::invalid_argument);
}

// ---- every header is checked against the file before PCL reads (or allocates) a body ----------

namespace {

std::string pcd_header(const std::string& data, const std::string& points = "4", const std::string& fields = "x y z",
                       const std::string& size = "4 4 4", const std::string& type = "F F F") {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type + "\nWIDTH " + points +
         "\nHEIGHT 1\nPOINTS " + points + "\nDATA " + data + "\n";
}

std::string le32(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

/// The error of a file holding `text`, which must name the file and contain every one of `words`.
void expect_error(const TempDir& tmp, const std::string& name, const std::string& text,
                  std::initializer_list<const char*> words) {
  write(tmp / name, text);
  const std::string e = error_of(tmp / name);
  EXPECT_NE(e.find(name), std::string::npos) << name << ": " << e;
  for (const char* w : words) EXPECT_NE(e.find(w), std::string::npos) << name << ": wanted '" << w << "' in: " << e;
}

}  // namespace

TEST(CloudIo, PcdHeadersAreCheckedBeforeAnyAllocation) {
  TempDir tmp;
  const std::string body(48, '\0');
  // 4294967295 points of 12 bytes in a 200-byte file: an error, not a 48 GB allocation.
  expect_error(tmp, "huge.pcd", pcd_header("binary", "4294967295") + body, {"truncated", "4294967295 points"});
  expect_error(tmp, "neg.pcd", pcd_header("binary", "-1") + body, {"header", "WIDTH", "non-negative"});
  expect_error(tmp, "wh.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nHEIGHT 2\nPOINTS 4\nDATA binary\n" + body,
               {"WIDTH 3 x HEIGHT 2 != POINTS 4"});
  expect_error(tmp, "size.pcd", pcd_header("binary", "4", "x y z", "4 4") + body, {"header", "SIZE has 2 entries"});
  expect_error(tmp, "type.pcd", pcd_header("binary", "4", "x y z", "4 4 4", "F F Q") + body, {"TYPE", "'Q'"});
  expect_error(tmp, "fsize.pcd", pcd_header("binary", "4", "x y z", "4 4 2", "F F F") + body, {"F needs SIZE 4 or 8"});
  expect_error(tmp, "data.pcd", pcd_header("zip") + body, {"unknown DATA 'zip'"});
  expect_error(tmp, "magic.pcd", "ply\nformat ascii 1.0\n", {"header", "'ply' is not a PCD keyword"});
  expect_error(tmp, "order.pcd", "FIELDS x y z\nTYPE F F F\nSIZE 4 4 4\nPOINTS 1\nDATA ascii\n1 2 3\n",
               {"TYPE comes before SIZE"});
  expect_error(tmp, "nodata.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\n", {"without a DATA line"});
  expect_error(tmp, "view.pcd",
               "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nVIEWPOINT 0 0 nan 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2 3\n",
               {"VIEWPOINT value 'nan'"});
  expect_error(tmp, "count.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 0\nPOINTS 1\nDATA ascii\n1 2 3\n",
               {"COUNT of field 'z'"});
}

TEST(CloudIo, BinaryCompressedSizesAreCheckedBeforePclMapsTheBody) {
  TempDir tmp;
  const std::string h = pcd_header("binary_compressed", "1000");
  // The 100-byte file that used to segfault inside PCL: sizes claiming far more than the file holds.
  std::string crash = h + le32(5000) + le32(12000);
  crash += std::string(100 - std::min<std::size_t>(100, crash.size()), 'x');
  expect_error(tmp, "short.pcd", crash, {"truncated", "5000 compressed bytes"});
  expect_error(tmp, "nosizes.pcd", h + "ab", {"truncated", "two 4-byte sizes"});
  expect_error(tmp, "usize.pcd", h + le32(4) + le32(999) + "abcd", {"999 uncompressed bytes", "make 12000"});
  expect_error(tmp, "ratio.pcd", h + le32(4) + le32(12000) + "abcd", {"corrupt", "at most 88 times"});
  // A well-sized but garbled stream fails in PCL's (bounds-checked) decompressor.
  expect_error(tmp, "garbled.pcd", h + le32(200) + le32(12000) + std::string(200, '\xff'), {"cannot read"});
}

TEST(CloudIo, AsciiRowsAreCheckedOneByOne) {
  TempDir tmp;
  const std::string h = pcd_header("ascii", "2");
  expect_error(tmp, "short.pcd", h + "1 2 3\n4 5\n", {"line 11: 2 values, the header's fields need 3"});
  expect_error(tmp, "long.pcd", h + "1 2 3 4\n4 5 6\n", {"line 10: 4 values"});
  expect_error(tmp, "word.pcd", h + "1 2 3\n4 five 6\n", {"line 11: value 2 'five' is not a number for field 'y'"});
  expect_error(tmp, "blank.pcd", h + "1 2 3\n \n4 5 6\n", {"line 11: a blank data row"});
  expect_error(tmp, "extra.pcd", h + "1 2 3\n4 5 6\n7 8 9\n", {"line 12: more data rows than the 2 points"});
  expect_error(tmp, "cut.pcd", h + "1 2 3\n4 5", {"truncated", "2 of 3 values of point 2 of 2"});
  expect_error(tmp, "few.pcd", h + "1 2 3\n", {"truncated: 1 of 2 declared points present"});
  expect_error(tmp, "range.pcd", pcd_header("ascii", "1", "x y z c", "4 4 4 1", "F F F U") + "1 2 3 256\n",
               {"'256' is not an integer in range for field 'c' (TYPE U SIZE 1)"});
  // Valid rows load as written: padding fields, '+' signs, CRLF line ends, empty lines (PCL skips them), blank
  // lines after the last point.
  write(tmp / "ok.pcd",
        "FIELDS x _ y z\r\nSIZE 4 4 4 4\r\nTYPE F F F F\r\nCOUNT 1 2 1 1\r\nPOINTS 2\r\nDATA ascii\r\n"
        "1 9 9 2 3\r\n\n+4 9 9 -5 6e-1\r\n\r\n \n");
  const CloudData c = load_cloud(tmp / "ok.pcd");
  ASSERT_EQ(c.points.rows(), 2);
  EXPECT_EQ(c.points.row(0), Eigen::RowVector3d(1, 2, 3));
  EXPECT_NEAR(c.points(1, 2), 0.6, 1e-7);
  EXPECT_EQ(c.points(1, 1), -5);
}

TEST(CloudIo, PlyHeadersAndBodiesAreChecked) {
  TempDir tmp;
  const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
  const std::string bin = "ply\nformat binary_little_endian 1.0\n";
  expect_error(tmp, "neg.ply", bin + "element vertex -1\n" + xyz + "end_header\n",
               {"count '-1' is not a non-negative"});
  expect_error(tmp, "huge.ply", bin + "element vertex 4294967295\n" + xyz + "end_header\n" + std::string(24, '\0'),
               {"truncated", "element 'vertex'"});
  expect_error(tmp, "faces.ply",
               bin + "element vertex 1\n" + xyz + "element face 1000\nproperty list uchar int v\n" + "end_header\n" +
                   std::string(12, '\0') + "\x03" + std::string(12, '\0'),
               {"truncated", "element 'face'"});
  expect_error(tmp, "type.ply", bin + "element vertex 1\nproperty float128 x\nend_header\n", {"unknown property type"});
  expect_error(tmp, "novertex.ply", bin + "element point 1\n" + xyz + "end_header\n" + std::string(12, '\0'),
               {"no 'vertex' element"});
  expect_error(tmp, "empty.ply", bin + "element vertex 0\n" + xyz + "end_header\n", {"empty"});
  expect_error(tmp, "organised.ply",
               bin + "obj_info num_cols 100000\nobj_info num_rows 100000\nelement vertex 1\n" + xyz + "end_header\n" +
                   std::string(12, '\0'),
               {"num_cols 100000 x num_rows 100000 != 1 vertices"});
  expect_error(tmp, "noprops.ply", bin + "element vertex 1\n" + xyz + "element junk 4000000000\nend_header\n",
               {"element 'junk' has 4000000000 rows but no properties"});
  const std::string asc = "ply\nformat ascii 1.0\nelement vertex 2\n" + xyz + "end_header\n";
  expect_error(tmp, "short.ply", asc + "1 2 3\n4 5\n", {"line 9: too few values", "'z' is missing"});
  expect_error(tmp, "long.ply", asc + "1 2 3 4\n4 5 6\n", {"line 8: 4 values"});
  expect_error(tmp, "word.ply", asc + "1 2 3\n4 x 6\n", {"line 9: value 2 'x' is not a number for property 'y'"});
  expect_error(tmp, "few.ply", asc + "1 2 3\n", {"truncated", "1 of 2 declared rows"});
  expect_error(tmp, "extra.ply", asc + "1 2 3\n4 5 6\n7 8 9\n", {"line 10: more rows"});
}

TEST(CloudIo, NpyHeadersAreCheckedAgainstTheFileSize) {
  TempDir tmp;
  const auto npy = [](const std::string& dict, const std::string& data) {
    std::string h = "{" + dict + "}";
    h += std::string(63 - (10 + h.size()) % 64, ' ') + "\n";
    return std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(h.size() & 0xff) + static_cast<char>(h.size() >> 8) +
           h + data;
  };
  const std::string row(24, '\0');
  expect_error(tmp, "huge.npy", npy("'descr': '<f8', 'fortran_order': False, 'shape': (4000000000000, 3), ", row),
               {"truncated", "(4000000000000, 3)"});
  expect_error(tmp, "neg.npy", npy("'descr': '<f8', 'fortran_order': False, 'shape': (-1, 3), ", row),
               {"shape entry '-1'"});
  expect_error(tmp, "trailing.npy", npy("'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), ", row + "xx"),
               {"2 bytes after the (1, 3) array"});
  expect_error(tmp, "dtype.npy", npy("'descr': '|b1', 'fortran_order': False, 'shape': (1, 3), ", row),
               {"unsupported .npy dtype '|b1'"});
  expect_error(tmp, "nodescr.npy", npy("'fortran_order': False, 'shape': (1, 3), ", row), {"no 'descr' entry"});
  expect_error(tmp, "shape.npy", npy("'descr': '<f8', 'fortran_order': False, 'shape': (1, 3, 1), ", row),
               {"expected an (N, 3) array, got shape (1, 3, 1)"});
  expect_error(tmp, "hlen.npy", std::string("\x93NUMPY\x02\x00\xff\xff\xff\x7f", 12) + "{}", {"truncated .npy header"});
  expect_error(tmp, "version.npy", std::string("\x93NUMPY\x07\x00", 8) + "xx", {"unsupported .npy format version 7"});
  write(tmp / "ok.npy", npy("'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), ",
                            std::string("\0\0\0\0\0\0\xf0\x3f", 8) + std::string(16, '\0')));
  EXPECT_EQ(load_cloud(tmp / "ok.npy").points.row(0), Eigen::RowVector3d(1, 0, 0));
}

// ---- per-point viewpoints (PCL's PointWithViewpoint: x y z vp_x vp_y vp_z) ----------------------

namespace {

/// Four cameras on a ring and the nearest one for each point: what a merged multi-view cloud carries.
Vec3Array nearest_cameras(const Vec3Array& P) {
  Vec3Array cams(4, 3);
  cams << 1, 0, 0.5, 0, 1, 0.5, -1, 0, 0.5, 0, -1, 0.5;
  Vec3Array V(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    Eigen::Index k = 0;
    (cams.rowwise() - P.row(i)).rowwise().squaredNorm().minCoeff(&k);
    V.row(i) = cams.row(k);
  }
  return V;
}

}  // namespace

TEST(CloudIo, PerPointViewpointsRoundTripInEveryEncoding) {
  TempDir tmp;
  const Vec3Array P = random_points(300, 4);
  const Vec3Array V = nearest_cameras(P);
  const Vec3Array N = random_points(300, 5).rowwise().normalized();
  for (const std::string name : {"a.pcd", "b.pcd", "c.pcd", "d.ply", "e.ply"}) {
    const std::string enc = name[0] == 'a' || name[0] == 'd' ? "ascii"
                            : name[0] == 'c'                 ? "binary_compressed"
                                                             : "binary";
    for (const bool with_normals : {false, true}) {
      save_cloud(tmp / name, P, with_normals ? N : Vec3Array(), enc, Eigen::Matrix<double, 7, 1>::Unit(6), V);
      const CloudData c = load_cloud(tmp / name);
      ASSERT_EQ(c.viewpoints.rows(), 300) << name;
      EXPECT_EQ(c.viewpoints, V.cast<float>().cast<double>()) << name;  // exactly the float32 written
      EXPECT_LT((c.points - P).cwiseAbs().maxCoeff(), 1e-7) << name;
      EXPECT_EQ(c.normals.rows(), with_normals ? 300 : 0) << name;
      EXPECT_FALSE(c.has_viewpoint) << name;
    }
  }
  save_cloud(tmp / "none.pcd", P);
  EXPECT_EQ(load_cloud(tmp / "none.pcd").viewpoints.rows(), 0);
  EXPECT_THROW(save_cloud(tmp / "x.pcd", P, {}, "binary", Eigen::Matrix<double, 7, 1>::Unit(6), V.topRows(5)),
               std::invalid_argument);
  Vec3Array bad = V;
  bad(7, 1) = std::nan("");
  EXPECT_THROW(save_cloud(tmp / "x.pcd", P, {}, "binary", Eigen::Matrix<double, 7, 1>::Unit(6), bad),
               std::invalid_argument);
}

TEST(CloudIo, PclReadsOurViewpointsAndWeReadPcls) {
  TempDir tmp;
  const Vec3Array P = random_points(200, 6);
  const Vec3Array V = nearest_cameras(P);
  for (const std::string enc : {"ascii", "binary", "binary_compressed"}) {
    save_cloud(tmp / (enc + ".pcd"), P, {}, enc, Eigen::Matrix<double, 7, 1>::Unit(6), V);
    pcl::PointCloud<pcl::PointWithViewpoint> cloud;
    ASSERT_EQ(pcl::io::loadPCDFile(tmp / (enc + ".pcd"), cloud), 0) << enc;
    ASSERT_EQ(cloud.size(), 200u) << enc;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const auto& q = cloud[i];
      const auto r = static_cast<Eigen::Index>(i);
      ASSERT_EQ(Eigen::RowVector3d(q.x, q.y, q.z), P.row(r).cast<float>().cast<double>()) << enc << " " << i;
      ASSERT_EQ(Eigen::RowVector3d(q.vp_x, q.vp_y, q.vp_z), V.row(r)) << enc << " " << i;
    }
  }
  // PCL's writer, an organised cloud with invalid points: the viewpoints follow the points kept.
  pcl::PointCloud<pcl::PointWithViewpoint> org(3, 2);
  for (int i = 0; i < 6; ++i) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    org[i] = pcl::PointWithViewpoint(i % 2 ? nan : 0.1f * i, 0.2f, 0.3f, 10.0f + i, 20.0f, 30.0f);
  }
  org.is_dense = false;
  for (const bool binary : {false, true}) {
    pcl::io::savePCDFile(tmp / "pcl.pcd", org, binary);
    const CloudData c = load_cloud(tmp / "pcl.pcd");
    ASSERT_EQ(c.points.rows(), 3);
    EXPECT_EQ(c.n_invalid, 3u);
    EXPECT_EQ(c.viewpoints.col(0), Eigen::Vector3d(10, 12, 14));
    EXPECT_EQ(c.points.col(0), Eigen::Vector3d(0, 0.2f, 0.4f));
  }
}

TEST(CloudIo, MalformedViewpointFieldsAreRefused) {
  TempDir tmp;
  const auto header = [](const std::string& fields, const std::string& size, const std::string& type,
                         const std::string& count) {
    return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type + "\nCOUNT " + count +
           "\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n";
  };
  expect_error(tmp, "partial.pcd", header("x y z vp_x", "4 4 4 4", "F F F F", "1 1 1 1") + "1 2 3 4\n5 6 7 8\n",
               {"has only vp_x of the per-point viewpoint fields"});
  expect_error(tmp, "count.pcd",
               header("x y z vp_x vp_y vp_z", "4 4 4 4 4 4", "F F F F F F", "1 1 1 3 1 1") +
                   "1 2 3 4 4 4 5 6\n5 6 7 8 8 8 9 9\n",
               {"field vp_x has 3 entries a point (COUNT)"});
  expect_error(
      tmp, "type.pcd",
      header("x y z vp_x vp_y vp_z", "4 4 4 4 4 4", "F F F F U F", "1 1 1 1 1 1") + "1 2 3 4 5 6\n5 6 7 8 9 9\n",
      {"field vp_y is not a float"});
  expect_error(
      tmp, "nan.pcd",
      header("x y z vp_x vp_y vp_z", "4 4 4 4 4 4", "F F F F F F", "1 1 1 1 1 1") + "1 2 3 4 5 6\n5 6 7 8 nan 9\n",
      {"viewpoint (vp_x, vp_y, vp_z) of point 1 is NaN"});
  // A NaN viewpoint on an invalid (dropped) point is no error: PCL writes organised clouds so.
  write(tmp / "nanpoint.pcd", header("x y z vp_x vp_y vp_z", "4 4 4 4 4 4", "F F F F F F", "1 1 1 1 1 1") +
                                  "1 2 3 4 5 6\nnan nan nan nan nan nan\n");
  const CloudData c = load_cloud(tmp / "nanpoint.pcd");
  ASSERT_EQ(c.viewpoints.rows(), 1);
  EXPECT_EQ(c.viewpoints.row(0), Eigen::RowVector3d(4, 5, 6));
}
