#include "graspmix/perception/cloud_io.hpp"

#include <sys/stat.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>

#include <Eigen/Geometry>

#include "cloud_check.hpp"
#include "cloud_write.hpp"

namespace graspmix {

namespace {

using cloud_check::fail;
using cloud_check::Field;
using cloud_check::Kind;
using cloud_check::RawCloud;

std::string lower_extension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

template <typename T>
void fill_column(const std::uint8_t* at, std::uint64_t stride, Eigen::Ref<Eigen::VectorXd> out) {
  for (Eigen::Index i = 0; i < out.size(); ++i, at += stride) {
    T v;
    std::memcpy(&v, at, sizeof v);
    out[i] = static_cast<double>(v);
  }
}

/// The first entry of `field` for `n` values starting at `at`, as doubles: any numeric type (PCL's templates would
/// silently skip a float64 x, which real PLY files have).
void read_column(const std::uint8_t* at, const Field& f, Eigen::Ref<Eigen::VectorXd> out) {
  if (f.kind == Kind::kFloat)
    return f.size == 4 ? fill_column<float>(at, f.stride, out) : fill_column<double>(at, f.stride, out);
  const bool s = f.kind == Kind::kSigned;
  switch (f.size) {
    case 1:
      return s ? fill_column<std::int8_t>(at, f.stride, out) : fill_column<std::uint8_t>(at, f.stride, out);
    case 2:
      return s ? fill_column<std::int16_t>(at, f.stride, out) : fill_column<std::uint16_t>(at, f.stride, out);
    case 4:
      return s ? fill_column<std::int32_t>(at, f.stride, out) : fill_column<std::uint32_t>(at, f.stride, out);
    default:
      return s ? fill_column<std::int64_t>(at, f.stride, out) : fill_column<std::uint64_t>(at, f.stride, out);
  }
}

const Field* find_field(const RawCloud& c, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (const auto& f : c.fields)
      if (f.name == n) return &f;
  return nullptr;
}

/// Columns `names` of every point as (n, 3), 0 rows when any is missing.
RowMatrixXd columns(const RawCloud& c, const Field* f[3], std::size_t n) {
  if (!f[0] || !f[1] || !f[2]) return {};
  RowMatrixXd M(static_cast<Eigen::Index>(n), 3);
  Eigen::VectorXd col(static_cast<Eigen::Index>(n));
  for (int j = 0; j < 3; ++j) {
    read_column(c.data.data() + f[j]->start, *f[j], col);
    M.col(j) = col;
  }
  return M;
}

/// vp_x vp_y vp_z (PCL's PointWithViewpoint) as (n, 3), 0 rows when the file has none. All three or
/// none, each one float number a point: a partial set or a malformed field would otherwise be ignored
/// and the points oriented towards a camera the file does not name.
RowMatrixXd viewpoint_columns(const RawCloud& c, std::size_t n, const std::string& path) {
  const char* names[] = {"vp_x", "vp_y", "vp_z"};
  const Field* f[3];
  std::string present;
  for (int j = 0; j < 3; ++j) {
    f[j] = find_field(c, {names[j]});
    if (f[j]) present += (present.empty() ? "" : ", ") + std::string(names[j]);
  }
  if (present.empty()) return {};
  if (!f[0] || !f[1] || !f[2]) {
    fail(path, "has only " + present + " of the per-point viewpoint fields vp_x, vp_y, vp_z (all three or none)");
  }
  for (int j = 0; j < 3; ++j) {
    if (f[j]->count != 1) {
      fail(path, std::string("field ") + names[j] + " has " + std::to_string(f[j]->count) +
                     " entries a point (COUNT), a per-point viewpoint needs 1");
    }
    if (f[j]->kind != Kind::kFloat) {
      fail(path, std::string("field ") + names[j] + " is not a float (TYPE F, SIZE 4 or 8): a viewpoint is in metres");
    }
  }
  return columns(c, f, n);
}

/// cloud_from_arrays, with the rows it kept.
CloudData keep_finite(const RowMatrixXd& points, const RowMatrixXd& normals, const std::string& source,
                      const RowMatrixXd& viewpoints, std::vector<Eigen::Index>& keep);

CloudData from_raw(const RawCloud& c, const std::string& path, const std::string& format) {
  const std::size_t n = c.width * c.height;
  if (n == 0) fail(path, "the cloud is empty (0 points)");
  const Field* xyz[3] = {find_field(c, {"x"}), find_field(c, {"y"}), find_field(c, {"z"})};
  if (!xyz[0] || !xyz[1] || !xyz[2]) {
    std::string names;
    for (const auto& f : c.names) names += (names.empty() ? "" : " ") + cloud_check::printable(f);
    fail(path, "has no x, y, z fields (fields: " + (names.empty() ? std::string("none") : names) + ")");
  }
  const Field* normal[3] = {find_field(c, {"normal_x", "nx"}), find_field(c, {"normal_y", "ny"}),
                            find_field(c, {"normal_z", "nz"})};
  std::vector<Eigen::Index> keep;
  CloudData out = keep_finite(columns(c, xyz, n), columns(c, normal, n), path, viewpoint_columns(c, n, path), keep);
  out.path = path;
  out.format = format;
  out.fields = c.names;
  out.width = static_cast<std::uint32_t>(c.width);
  out.height = static_cast<std::uint32_t>(c.height);
  if (c.height > 1)
    out.pixels = Eigen::Map<const Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>>(
                     keep.data(), static_cast<Eigen::Index>(keep.size()))
                     .cast<std::int64_t>();
  const auto& v = c.viewpoint;  // tx ty tz qw qx qy qz, as PCL reads it (floats, not normalised)
  out.viewpoint << v[0], v[1], v[2], v[4], v[5], v[6], v[3];
  if (out.viewpoint[6] < 0) out.viewpoint.tail<4>() *= -1.0;
  out.has_viewpoint = v[0] != 0 || v[1] != 0 || v[2] != 0 || std::abs(std::abs(v[3]) - 1.0f) > 1e-6f;
  return out;
}

/// The minimal .npy reader numpy's format spec needs for an (N, 3) float or int array; the header is
/// checked against the file's size before the data is allocated.
CloudData load_npy(const std::string& path) {
  const cloud_check::NpyHeader h = cloud_check::check_npy(path);
  if (h.shape.size() != 2 || h.shape[1] != 3) {
    std::string s;
    for (auto d : h.shape) s += (s.empty() ? "" : ", ") + std::to_string(d);
    fail(path, "expected an (N, 3) array, got shape (" + s + (h.shape.size() == 1 ? "," : "") + ")");
  }
  const std::string& descr = h.descr;
  Field type;
  bool ok = false;
  if (descr.size() == 3 && (descr[0] == '<' || descr[0] == '=')) {
    type.size = descr[2] - '0';
    type.kind = descr[1] == 'f' ? Kind::kFloat : Kind::kSigned;
    ok = (descr[1] == 'f' && (type.size == 4 || type.size == 8)) ||
         (descr[1] == 'i' && (type.size == 2 || type.size == 4));
  }
  if (!ok) {
    fail(path,
         "unsupported .npy dtype '" + descr.substr(0, 40) + "' (use little-endian float32, float64, int16 or int32)");
  }
  const std::uint64_t size = static_cast<std::uint64_t>(type.size);
  const std::uint64_t n = h.shape[0], body = h.file_size - h.data_offset, row = 3 * size;
  if (n == 0) fail(path, "the cloud is empty (0 points)");
  if (n > body / row) {
    fail(path, "the data section is truncated: shape (" + std::to_string(n) + ", 3) of " + descr + " needs " +
                   std::to_string(row) + " bytes a row, only " + std::to_string(body) + " bytes follow the header");
  }
  if (body != n * row) {
    fail(path, "the file has " + std::to_string(body - n * row) + " bytes after the (" + std::to_string(n) +
                   ", 3) array its header declares");
  }
  std::vector<std::uint8_t> data(n * row);
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(h.data_offset));
  if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size()))) {
    fail(path, "cannot read the data section");
  }
  RowMatrixXd P(static_cast<Eigen::Index>(n), 3);
  Eigen::VectorXd col(static_cast<Eigen::Index>(n));
  type.stride = h.fortran ? size : row;
  for (std::uint64_t j = 0; j < 3; ++j) {
    read_column(data.data() + (h.fortran ? j * n * size : j * size), type, col);
    P.col(static_cast<Eigen::Index>(j)) = col;
  }
  CloudData out = cloud_from_arrays(P, {}, path);
  out.format = "npy";
  out.fields = {"x", "y", "z"};
  out.width = static_cast<std::uint32_t>(n);
  out.height = 1;
  return out;
}

CloudData keep_finite(const RowMatrixXd& points, const RowMatrixXd& normals, const std::string& source,
                      const RowMatrixXd& viewpoints, std::vector<Eigen::Index>& keep) {
  if (points.cols() != 3) {
    throw std::invalid_argument(source + ": expected points of shape (N, 3), got (" + std::to_string(points.rows()) +
                                ", " + std::to_string(points.cols()) + ")");
  }
  const Eigen::Index n = points.rows();
  if (n == 0) throw std::invalid_argument(source + ": the cloud is empty (0 points)");
  const bool with_normals = normals.rows() > 0;
  if (with_normals && (normals.rows() != n || normals.cols() != 3)) {
    throw std::invalid_argument(source + ": normals must have shape (" + std::to_string(n) + ", 3)");
  }
  if (viewpoints.rows() > 0 && (viewpoints.rows() != n || viewpoints.cols() != 3)) {
    throw std::invalid_argument(source + ": viewpoints must have shape (" + std::to_string(n) + ", 3)");
  }
  keep.clear();
  keep.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
    if (points.row(i).allFinite()) keep.push_back(i);
  if (keep.empty()) {
    throw std::invalid_argument(source + ": no valid point: all " + std::to_string(n) + " points are NaN or infinite");
  }
  CloudData out;
  out.path = source;
  out.n_invalid = static_cast<std::size_t>(n) - keep.size();
  out.points.resize(static_cast<Eigen::Index>(keep.size()), 3);
  bool normals_ok = with_normals;
  for (std::size_t k = 0; k < keep.size(); ++k) {
    out.points.row(static_cast<Eigen::Index>(k)) = points.row(keep[k]);
    if (normals_ok && !normals.row(keep[k]).allFinite()) normals_ok = false;
  }
  if (viewpoints.rows() > 0) {
    out.viewpoints.resize(static_cast<Eigen::Index>(keep.size()), 3);
    for (std::size_t k = 0; k < keep.size(); ++k) {
      if (!viewpoints.row(keep[k]).allFinite()) {
        throw std::invalid_argument(source + ": the viewpoint (vp_x, vp_y, vp_z) of point " + std::to_string(keep[k]) +
                                    " is NaN or infinite (a valid point needs the camera that saw it)");
      }
      out.viewpoints.row(static_cast<Eigen::Index>(k)) = viewpoints.row(keep[k]);
    }
  }
  // Normals are all-or-nothing: a partial set would silently mix given and estimated normals.
  if (normals_ok) {
    out.normals.resize(static_cast<Eigen::Index>(keep.size()), 3);
    for (std::size_t k = 0; k < keep.size(); ++k) out.normals.row(static_cast<Eigen::Index>(k)) = normals.row(keep[k]);
  }
  out.width = static_cast<std::uint32_t>(n);
  out.height = 1;
  return out;
}

}  // namespace

CloudData cloud_from_arrays(const RowMatrixXd& points, const RowMatrixXd& normals, const std::string& source,
                            const RowMatrixXd& viewpoints) {
  std::vector<Eigen::Index> keep;
  return keep_finite(points, normals, source, viewpoints, keep);
}

CloudData load_cloud(const std::string& path) {
  struct stat st{};
  if (::stat(path.c_str(), &st) != 0) fail(path, "no such file");
  if (!S_ISREG(st.st_mode)) fail(path, "not a regular file");
  if (st.st_size == 0) fail(path, "the file is empty (0 bytes)");
  const std::string ext = lower_extension(path);
  if (ext == ".pcd") {
    const RawCloud c = cloud_check::read_pcd(path);
    return from_raw(c, path, "pcd " + c.encoding);
  }
  if (ext == ".ply") return from_raw(cloud_check::read_ply(path), path, "ply");
  if (ext == ".npy") return load_npy(path);
  fail(path, "unknown cloud format '" + ext + "' (expected .pcd, .ply or .npy)");
}

void organized_grid_into(const CloudData& cloud, double* out, const std::optional<Eigen::Isometry3d>& T_file_camera) {
  if (cloud.height <= 1) {
    fail(cloud.path, "not an organized cloud (height " + std::to_string(cloud.height) +
                         "): only a file with HEIGHT > 1 has an image grid");
  }
  if (cloud.pixels.size() != cloud.points.rows()) {
    fail(cloud.path, "pixels has " + std::to_string(cloud.pixels.size()) + " entries for " +
                         std::to_string(cloud.points.rows()) + " points");
  }
  const std::int64_t size = static_cast<std::int64_t>(cloud.width) * cloud.height;
  std::fill(out, out + 3 * size, std::numeric_limits<double>::quiet_NaN());
  // p_camera = R^T (p - t), as a row: (p - t) R
  const Eigen::Isometry3d T = T_file_camera.value_or(Eigen::Isometry3d::Identity());
  const Eigen::Matrix3d R = T.linear();
  const Eigen::RowVector3d t = T.translation().transpose();
  for (Eigen::Index k = 0; k < cloud.pixels.size(); ++k) {
    const std::int64_t p = cloud.pixels[k];
    if (p < 0 || p >= size) {
      fail(cloud.path, "pixel " + std::to_string(p) + " of point " + std::to_string(k) + " is outside the " +
                           std::to_string(cloud.width) + " x " + std::to_string(cloud.height) + " grid");
    }
    Eigen::Map<Eigen::RowVector3d> row(out + 3 * p);
    if (T_file_camera) {
      row = (cloud.points.row(k) - t) * R;
    } else {
      row = cloud.points.row(k);
    }
  }
}

Vec3Array organized_grid(const CloudData& cloud) {
  Vec3Array grid(static_cast<Eigen::Index>(cloud.width) * std::max<Eigen::Index>(cloud.height, 1),
                 3);  // checked as it is filled
  organized_grid_into(cloud, grid.data());
  return grid;
}

namespace {

/// A hole of an organized cloud: a point with a NaN coordinate.
bool is_hole(const Vec3Array& points, Eigen::Index i) { return points.row(i).array().isNaN().any(); }

/// Every row of `a` finite; in an organized cloud, every row but those of its holes.
void check_finite(const std::string& path, const char* what, const Vec3Array& a, const Vec3Array& points,
                  bool organized) {
  if (!organized) {
    if (!a.allFinite()) fail(path, std::string(what) + ": contains NaN or infinite values");
    return;
  }
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    if (!is_hole(points, i) && !a.row(i).allFinite()) {
      fail(path, std::string(what) + ": row " + std::to_string(i) +
                     " is not finite, and its point is not a hole (an organized cloud marks a hole with NaN)");
    }
  }
}

void check_save_inputs(const std::string& path, const Vec3Array& points, const Vec3Array& normals,
                       const std::string& encoding, const Eigen::Matrix<double, 7, 1>& viewpoint,
                       const Vec3Array& viewpoints, std::uint32_t width, std::uint32_t height) {
  const std::string ext = lower_extension(path);
  if (ext != ".pcd" && ext != ".ply") fail(path, "can only write .pcd or .ply, got '" + ext + "'");
  const bool pcd = ext == ".pcd";
  if (pcd && encoding != "ascii" && encoding != "binary" && encoding != "binary_compressed") {
    fail(path, "unknown PCD encoding '" + encoding + "' (expected ascii, binary or binary_compressed)");
  }
  if (!pcd && encoding != "ascii" && encoding != "binary") {
    fail(path, "unknown PLY encoding '" + encoding + "' (expected ascii or binary)");
  }
  const Eigen::Index n = points.rows();
  if (n == 0) fail(path, "points: the cloud is empty, nothing to write");
  if ((width != 0 || height != 0) && static_cast<std::uint64_t>(width) * height != static_cast<std::uint64_t>(n)) {
    fail(path, "width x height = " + std::to_string(width) + " x " + std::to_string(height) + " for " +
                   std::to_string(n) + " points (an organized cloud has a row of points for every pixel)");
  }
  const bool organized = height > 1;
  if (organized && !pcd) {
    fail(path, "an organized cloud (height " + std::to_string(height) +
                   ") cannot be written as PLY, which has no standard image grid: write .pcd to keep it");
  }
  check_finite(path, "points", points, points, organized);
  if (organized && points.array().isNaN().rowwise().any().all()) {
    fail(path, "points: every point is a hole (NaN), nothing to write");
  }
  const bool with_normals = normals.rows() > 0;
  if (with_normals && normals.rows() != n) {
    fail(path, "normals: " + std::to_string(normals.rows()) + " rows for " + std::to_string(n) + " points");
  }
  if (with_normals) check_finite(path, "normals", normals, points, organized);
  if (!viewpoint.allFinite()) fail(path, "viewpoint: contains NaN or infinite values");
  if (viewpoints.rows() > 0 && viewpoints.rows() != n) {
    fail(path, "viewpoints: " + std::to_string(viewpoints.rows()) + " rows for " + std::to_string(n) + " points");
  }
  check_finite(path, "viewpoints", viewpoints, points, organized);
}

/// The points (and normals, and per-point viewpoints) as float32 fields x y z [normal_x normal_y normal_z]
/// [vp_x vp_y vp_z]: with no normals, PCL's PointWithViewpoint layout.
cloud_write::FloatCloud float_cloud(const Vec3Array& points, const Vec3Array& normals, const Vec3Array& viewpoints) {
  cloud_write::FloatCloud c;
  std::vector<const Vec3Array*> blocks{&points};
  c.names = {"x", "y", "z"};
  if (normals.rows() > 0)
    blocks.push_back(&normals), c.names.insert(c.names.end(), {"normal_x", "normal_y", "normal_z"});
  if (viewpoints.rows() > 0) blocks.push_back(&viewpoints), c.names.insert(c.names.end(), {"vp_x", "vp_y", "vp_z"});
  const Eigen::Index n = points.rows();
  c.values.resize(static_cast<std::size_t>(n) * c.names.size());
  std::size_t at = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (const Vec3Array* b : blocks)
      for (int j = 0; j < 3; ++j) c.values[at++] = static_cast<float>((*b)(i, j));
  c.width = static_cast<std::uint32_t>(n);
  return c;
}

}  // namespace

void save_cloud(const std::string& path, const Vec3Array& points, const Vec3Array& normals, const std::string& encoding,
                const Eigen::Matrix<double, 7, 1>& viewpoint, const Vec3Array& viewpoints, std::uint32_t width,
                std::uint32_t height) {
  check_save_inputs(path, points, normals, encoding, viewpoint, viewpoints, width, height);
  cloud_write::FloatCloud cloud = float_cloud(points, normals, viewpoints);
  if (height > 1) cloud.width = width, cloud.height = height;
  Eigen::Quaterniond q(viewpoint[6], viewpoint[3], viewpoint[4], viewpoint[5]);
  if (q.norm() < 1e-6) fail(path, "viewpoint: the quaternion has zero length");
  q.normalize();
  if (lower_extension(path) == ".ply") return cloud_write::write_ply(path, cloud, encoding == "binary");
  const std::array<float, 7> vp = {static_cast<float>(viewpoint[0]), static_cast<float>(viewpoint[1]),
                                   static_cast<float>(viewpoint[2]), static_cast<float>(q.w()),
                                   static_cast<float>(q.x()),        static_cast<float>(q.y()),
                                   static_cast<float>(q.z())};
  cloud_write::write_pcd(path, cloud, encoding, vp);
}

}  // namespace graspmix
