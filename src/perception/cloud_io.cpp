#include "graspmix/perception/cloud_io.hpp"

#include <sys/stat.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/exceptions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "cloud_check.hpp"

namespace graspmix {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument(path + ": " + what);
}

std::string lower_extension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// Reads one scalar of a PCL field type as double.
double read_scalar(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return v;
    }
    case pcl::PCLPointField::UINT8: {
      std::uint8_t v;
      std::memcpy(&v, p, 1);
      return v;
    }
    case pcl::PCLPointField::INT16: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case pcl::PCLPointField::UINT16: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case pcl::PCLPointField::INT32: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case pcl::PCLPointField::UINT32: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case pcl::PCLPointField::FLOAT32: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case pcl::PCLPointField::FLOAT64: {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

const pcl::PCLPointField* find_field(const pcl::PCLPointCloud2& c, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (const auto& f : c.fields)
      if (f.name == n) return &f;
  return nullptr;
}

/// Column `field` of every point as doubles; any field type PCL reads (the PCL templates would
/// silently skip a float64 x, which real PLY files have).
Eigen::VectorXd column(const pcl::PCLPointCloud2& c, const pcl::PCLPointField& f, std::size_t n) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    out[static_cast<Eigen::Index>(i)] = read_scalar(&c.data[i * c.point_step + f.offset], f.datatype);
  return out;
}

/// vp_x vp_y vp_z (PCL's PointWithViewpoint) as (n, 3), 0 rows when the file has none. All three or
/// none, each one float number a point: a partial set or a malformed field would otherwise be ignored
/// and the points oriented towards a camera the file does not name.
RowMatrixXd viewpoint_columns(const pcl::PCLPointCloud2& c, std::size_t n, const std::string& path) {
  const char* names[] = {"vp_x", "vp_y", "vp_z"};
  const pcl::PCLPointField* f[3];
  std::string present;
  for (int j = 0; j < 3; ++j) {
    f[j] = find_field(c, {names[j]});
    if (f[j]) present += (present.empty() ? "" : ", ") + std::string(names[j]);
  }
  if (present.empty()) return {};
  if (!f[0] || !f[1] || !f[2]) {
    fail(path, "has only " + present + " of the per-point viewpoint fields vp_x, vp_y, vp_z (all three or none)");
  }
  RowMatrixXd V(static_cast<Eigen::Index>(n), 3);
  for (int j = 0; j < 3; ++j) {
    if (f[j]->count != 1) {
      fail(path, std::string("field ") + names[j] + " has " + std::to_string(f[j]->count) +
                     " entries a point (COUNT), a per-point viewpoint needs 1");
    }
    if (f[j]->datatype != pcl::PCLPointField::FLOAT32 && f[j]->datatype != pcl::PCLPointField::FLOAT64) {
      fail(path, std::string("field ") + names[j] + " is not a float (TYPE F, SIZE 4 or 8): a viewpoint is in metres");
    }
    V.col(j) = column(c, *f[j], n);
  }
  return V;
}

CloudData from_pcl(const pcl::PCLPointCloud2& c, const Eigen::Vector4f& origin, const Eigen::Quaternionf& orientation,
                   const std::string& path, const std::string& format) {
  CloudData out;
  out.path = path;
  out.format = format;
  out.width = c.width;
  out.height = c.height;
  for (const auto& f : c.fields) out.fields.push_back(f.name);
  const std::size_t n = static_cast<std::size_t>(c.width) * c.height;
  if (n == 0) fail(path, "the cloud is empty (0 points)");
  if (c.data.size() < n * c.point_step)
    fail(path, "the data section is shorter than the header declares (truncated file)");
  const auto* fx = find_field(c, {"x"});
  const auto* fy = find_field(c, {"y"});
  const auto* fz = find_field(c, {"z"});
  if (!fx || !fy || !fz) {
    std::string names;
    for (const auto& f : out.fields) names += (names.empty() ? "" : " ") + cloud_check::printable(f);
    fail(path, "has no x, y, z fields (fields: " + (names.empty() ? std::string("none") : names) + ")");
  }
  RowMatrixXd P(static_cast<Eigen::Index>(n), 3);
  P.col(0) = column(c, *fx, n);
  P.col(1) = column(c, *fy, n);
  P.col(2) = column(c, *fz, n);
  RowMatrixXd N;
  const auto* nx = find_field(c, {"normal_x", "nx"});
  const auto* ny = find_field(c, {"normal_y", "ny"});
  const auto* nz = find_field(c, {"normal_z", "nz"});
  if (nx && ny && nz) {
    N.resize(static_cast<Eigen::Index>(n), 3);
    N.col(0) = column(c, *nx, n);
    N.col(1) = column(c, *ny, n);
    N.col(2) = column(c, *nz, n);
  }
  CloudData arrays = cloud_from_arrays(P, N, path, viewpoint_columns(c, n, path));
  out.points = std::move(arrays.points);
  out.normals = std::move(arrays.normals);
  out.viewpoints = std::move(arrays.viewpoints);
  out.n_invalid = arrays.n_invalid;
  out.viewpoint << origin.x(), origin.y(), origin.z(), orientation.x(), orientation.y(), orientation.z(),
      orientation.w();
  if (out.viewpoint[6] < 0) out.viewpoint.tail<4>() *= -1.0;
  out.has_viewpoint = origin.head<3>().norm() > 0 || std::abs(std::abs(orientation.w()) - 1.0f) > 1e-6f;
  return out;
}

namespace {
/// PCL's readers print their own diagnostics on stderr; graspmix reports every problem as an exception
/// naming the file instead, so they are silenced while a file is read (one line on stderr, not three).
class QuietPcl {
 public:
  QuietPcl() : previous_(pcl::console::getVerbosityLevel()) { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }
  ~QuietPcl() { pcl::console::setVerbosityLevel(previous_); }
  QuietPcl(const QuietPcl&) = delete;
  QuietPcl& operator=(const QuietPcl&) = delete;

 private:
  pcl::console::VERBOSITY_LEVEL previous_;
};
}  // namespace

CloudData load_pcd(const std::string& path) {
  // Header and body are checked against each other and the file's size before PCL reads (and
  // allocates) anything: PCL trusts the header (cloud_check.hpp).
  const cloud_check::PcdHeader header = cloud_check::check_pcd(path);
  const char* encodings[] = {"ascii", "binary", "binary_compressed"};
  const std::string encoding = encodings[header.data];
  const QuietPcl quiet;
  pcl::PCDReader reader;
  pcl::PCLPointCloud2 cloud;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0;
  int rc = -1;
  try {
    rc = reader.read(path, cloud, origin, orientation, version);
  } catch (const pcl::PCLException& e) {
    fail(path, std::string("cannot read the data section (") + e.what() + ")");
  }
  if (rc < 0) fail(path, "cannot read the data section (corrupt " + encoding + " data)");
  return from_pcl(cloud, origin, orientation, path, "pcd " + encoding);
}

CloudData load_ply(const std::string& path) {
  const std::uint64_t vertices = cloud_check::check_ply(path);  // before PCL allocates what the header claims
  const QuietPcl quiet;
  pcl::PLYReader reader;
  pcl::PCLPointCloud2 cloud;
  Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  int version = 0;
  int rc = -1;
  try {
    rc = reader.read(path, cloud, origin, orientation, version);
  } catch (const pcl::PCLException& e) {
    fail(path, std::string("cannot read PLY (") + e.what() + ")");
  }
  if (rc < 0) fail(path, "cannot read PLY (a data section not matching the header)");
  // A camera element's viewport re-sizes the cloud after the vertices are read; it must still hold them all.
  const std::uint64_t n = static_cast<std::uint64_t>(cloud.width) * cloud.height;
  if (n != vertices || cloud.data.size() < n * cloud.point_step) {
    fail(path, "the cloud's organisation (" + std::to_string(cloud.width) + " x " + std::to_string(cloud.height) +
                   ", from obj_info or the camera element) does not match its " + std::to_string(vertices) +
                   " vertices");
  }
  return from_pcl(cloud, origin, orientation, path, "ply");
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
  std::uint8_t type = 0;
  int size = 0;
  if (descr.size() == 3 && (descr[0] == '<' || descr[0] == '=')) {
    size = descr[2] - '0';
    if (descr[1] == 'f' && size == 4) type = pcl::PCLPointField::FLOAT32;
    if (descr[1] == 'f' && size == 8) type = pcl::PCLPointField::FLOAT64;
    if (descr[1] == 'i' && size == 4) type = pcl::PCLPointField::INT32;
    if (descr[1] == 'i' && size == 2) type = pcl::PCLPointField::INT16;
  }
  if (type == 0) {
    fail(path,
         "unsupported .npy dtype '" + descr.substr(0, 40) + "' (use little-endian float32, float64, int16 or int32)");
  }
  const std::uint64_t n = h.shape[0], body = h.file_size - h.data_offset, row = 3 * static_cast<std::uint64_t>(size);
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
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const std::size_t k = h.fortran ? j * n + i : i * 3 + j;
      P(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = read_scalar(&data[k * size], type);
    }
  CloudData out = cloud_from_arrays(P, {}, path);
  out.format = "npy";
  out.fields = {"x", "y", "z"};
  out.width = static_cast<std::uint32_t>(n);
  out.height = 1;
  return out;
}

}  // namespace

CloudData cloud_from_arrays(const RowMatrixXd& points, const RowMatrixXd& normals, const std::string& source,
                            const RowMatrixXd& viewpoints) {
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
  std::vector<Eigen::Index> keep;
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

CloudData load_cloud(const std::string& path) {
  struct stat st{};
  if (::stat(path.c_str(), &st) != 0) fail(path, "no such file");
  if (!S_ISREG(st.st_mode)) fail(path, "not a regular file");
  if (st.st_size == 0) fail(path, "the file is empty (0 bytes)");
  const std::string ext = lower_extension(path);
  if (ext == ".pcd") return load_pcd(path);
  if (ext == ".ply") return load_ply(path);
  if (ext == ".npy") return load_npy(path);
  fail(path, "unknown cloud format '" + ext + "' (expected .pcd, .ply or .npy)");
}

namespace {

void check_save_inputs(const std::string& path, const Vec3Array& points, const Vec3Array& normals,
                       const std::string& encoding, const Eigen::Matrix<double, 7, 1>& viewpoint,
                       const Vec3Array& viewpoints) {
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
  if (!points.allFinite()) fail(path, "points: contains NaN or infinite values");
  const bool with_normals = normals.rows() > 0;
  if (with_normals && normals.rows() != n) {
    fail(path, "normals: " + std::to_string(normals.rows()) + " rows for " + std::to_string(n) + " points");
  }
  if (with_normals && !normals.allFinite()) fail(path, "normals: contains NaN or infinite values");
  if (!viewpoint.allFinite()) fail(path, "viewpoint: contains NaN or infinite values");
  if (viewpoints.rows() > 0 && viewpoints.rows() != n) {
    fail(path, "viewpoints: " + std::to_string(viewpoints.rows()) + " rows for " + std::to_string(n) + " points");
  }
  if (!viewpoints.allFinite()) fail(path, "viewpoints: contains NaN or infinite values");
}

/// The points (and normals, and per-point viewpoints) as float32 fields x y z [normal_x normal_y normal_z]
/// [vp_x vp_y vp_z]: with no normals, PCL's PointWithViewpoint layout.
pcl::PCLPointCloud2 float_cloud(const Vec3Array& points, const Vec3Array& normals, const Vec3Array& viewpoints) {
  const Eigen::Index n = points.rows();
  std::vector<const Vec3Array*> blocks{&points};
  std::vector<const char*> names{"x", "y", "z"};
  if (normals.rows() > 0) blocks.push_back(&normals), names.insert(names.end(), {"normal_x", "normal_y", "normal_z"});
  if (viewpoints.rows() > 0) blocks.push_back(&viewpoints), names.insert(names.end(), {"vp_x", "vp_y", "vp_z"});
  pcl::PCLPointCloud2 cloud;
  for (std::size_t f = 0; f < names.size(); ++f) {
    pcl::PCLPointField field;
    field.name = names[f];
    field.offset = static_cast<std::uint32_t>(4 * f);
    field.datatype = pcl::PCLPointField::FLOAT32;
    field.count = 1;
    cloud.fields.push_back(field);
  }
  cloud.width = static_cast<std::uint32_t>(n);
  cloud.height = 1;
  cloud.is_dense = true;
  cloud.point_step = static_cast<std::uint32_t>(4 * names.size());
  cloud.row_step = cloud.point_step * cloud.width;
  cloud.data.resize(static_cast<std::size_t>(cloud.row_step));
  for (Eigen::Index i = 0; i < n; ++i) {
    float v[9];
    for (std::size_t b = 0; b < blocks.size(); ++b)
      for (int j = 0; j < 3; ++j) v[3 * b + j] = static_cast<float>((*blocks[b])(i, j));
    std::memcpy(&cloud.data[static_cast<std::size_t>(i) * cloud.point_step], v, cloud.point_step);
  }
  return cloud;
}

/// PCL's ASCII PLY writer keeps 6 significant digits (1 um at 1 m); float32 needs 9. No camera element:
/// PCL writes intrinsics its own reader then complains about; PLY keeps no viewpoint.
int write_ascii_ply(const std::string& path, const pcl::PCLPointCloud2& cloud) {
  std::ofstream out(path);
  if (!out) fail(path, "cannot open for writing (is the directory there and writable?)");
  const int n_fields = static_cast<int>(cloud.fields.size());
  out << "ply\nformat ascii 1.0\ncomment graspmix\nelement vertex " << cloud.width << "\n";
  for (const auto& f : cloud.fields) {
    const bool normal = f.name.rfind("normal_", 0) == 0;  // nx ny nz, the names PLY files use
    out << "property float " << (normal ? "n" + f.name.substr(7) : f.name) << "\n";
  }
  out << "end_header\n";
  char buf[48];
  for (std::uint32_t i = 0; i < cloud.width; ++i) {
    float v[9];
    std::memcpy(v, &cloud.data[static_cast<std::size_t>(i) * cloud.point_step], cloud.point_step);
    for (int f = 0; f < n_fields; ++f) {
      std::snprintf(buf, sizeof buf, f + 1 < n_fields ? "%.9g " : "%.9g\n", static_cast<double>(v[f]));
      out << buf;
    }
  }
  return out.good() ? 0 : -1;
}

}  // namespace

void save_cloud(const std::string& path, const Vec3Array& points, const Vec3Array& normals, const std::string& encoding,
                const Eigen::Matrix<double, 7, 1>& viewpoint, const Vec3Array& viewpoints) {
  check_save_inputs(path, points, normals, encoding, viewpoint, viewpoints);
  const bool pcd = lower_extension(path) == ".pcd";
  const pcl::PCLPointCloud2 cloud = float_cloud(points, normals, viewpoints);
  const Eigen::Vector4f origin(static_cast<float>(viewpoint[0]), static_cast<float>(viewpoint[1]),
                               static_cast<float>(viewpoint[2]), 0.0f);
  Eigen::Quaternionf orientation(static_cast<float>(viewpoint[6]), static_cast<float>(viewpoint[3]),
                                 static_cast<float>(viewpoint[4]), static_cast<float>(viewpoint[5]));
  if (orientation.norm() < 1e-6f) fail(path, "viewpoint: the quaternion has zero length");
  orientation.normalize();
  int rc = -1;
  try {
    if (pcd) {
      pcl::PCDWriter w;
      if (encoding == "ascii")
        rc = w.writeASCII(path, cloud, origin, orientation, 9);
      else if (encoding == "binary")
        rc = w.writeBinary(path, cloud, origin, orientation);
      else
        rc = w.writeBinaryCompressed(path, cloud, origin, orientation);
    } else if (encoding == "binary") {
      pcl::PLYWriter w;
      rc = w.writeBinary(path, cloud, origin, orientation, false);
    } else {
      rc = write_ascii_ply(path, cloud);
    }
  } catch (const pcl::PCLException& e) {
    fail(path, std::string("cannot write (") + e.what() + ")");
  }
  if (rc < 0) fail(path, "cannot write (is the directory there and writable?)");
}

}  // namespace graspmix
