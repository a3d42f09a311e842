// Conversions at the Python boundary (declared in common.hpp): shapes checked, inputs named in errors.
#include <cmath>
#include <limits>
#include <map>

#include "common.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/perception/camera.hpp"

namespace graspmix::py_bind {

RowMatrixXd to_matrix(const py::handle& obj, const char* name, int cols, bool one_d_as_row) {
  if (obj.is_none()) throw py::value_error(std::string(name) + ": expected an array, got None");
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  } catch (const py::error_already_set&) {
    a = {};
  }
  if (!a) throw py::value_error(std::string(name) + ": could not be read as an array of numbers");
  Eigen::Index rows, width;
  if (a.ndim() == 2) {
    rows = a.shape(0);
    width = a.shape(1);
  } else if (a.ndim() == 1 && one_d_as_row) {
    rows = 1;
    width = a.shape(0);
  } else {
    throw py::value_error(std::string(name) + ": expected a 2-D array" +
                          (cols >= 0 ? " of shape (N, " + std::to_string(cols) + ")" : std::string()) + ", got " +
                          std::to_string(a.ndim()) + "-D");
  }
  if (cols >= 0 && width != cols) {
    throw py::value_error(std::string(name) + ": expected shape (N, " + std::to_string(cols) + "), got (" +
                          std::to_string(rows) + ", " + std::to_string(width) + ")");
  }
  return Eigen::Map<const RowMatrixXd>(a.data(), rows, width);
}

py::object int_enum(py::module_& m, const char* name, const std::vector<std::pair<const char*, int>>& members,
                    const char* doc) {
  py::tuple pairs(members.size());
  for (std::size_t i = 0; i < members.size(); ++i) pairs[i] = py::make_tuple(members[i].first, members[i].second);
  py::object e = py::module_::import("enum").attr("IntEnum")(name, pairs, py::arg("module") = m.attr("__name__"));
  e.attr("__doc__") = doc;
  m.attr(name) = e;
  return e;
}

Vec3Array to_points3(const py::object& obj, const char* name) {
  if (obj.is_none()) return Vec3Array(0, 3);
  return Vec3Array(to_matrix(obj, name, 3, true));
}

Eigen::VectorXd to_vector(const py::handle& obj, const char* name, Eigen::Index n) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a) throw py::value_error(std::string(name) + ": could not be read as an array of numbers");
  if (a.ndim() == 0) {
    Eigen::VectorXd v(1);
    v[0] = *a.data();
    if (n >= 0 && n != 1)
      throw py::value_error(std::string(name) + ": expected " + std::to_string(n) + " values, got 1");
    return v;
  }
  if (a.ndim() != 1)
    throw py::value_error(std::string(name) + ": expected a 1-D array, got " + std::to_string(a.ndim()) + "-D");
  if (n >= 0 && a.shape(0) != n) {
    throw py::value_error(std::string(name) + ": expected " + std::to_string(n) + " values, got " +
                          std::to_string(a.shape(0)));
  }
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

std::uint64_t to_seed(const py::object& seed) {
  if (seed.is_none()) return 0;
  // Checked before any cast: a float, a bool or an integer beyond 64 bits is a ValueError, not a cast error.
  if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed)) {
    throw py::value_error("seed must be a non-negative integer, got " +
                          std::string(py::str(py::type::of(seed).attr("__name__"))));
  }
  const py::int_ value = py::reinterpret_borrow<py::int_>(seed);
  if (value < py::int_(0) || value > py::int_(std::numeric_limits<std::int64_t>::max())) {
    throw py::value_error("seed must be an integer in [0, 2**63 - 1], got " + std::string(py::str(seed)).substr(0, 80));
  }
  return static_cast<std::uint64_t>(value.cast<long long>());
}

int to_count(const py::handle& obj, const char* name, long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  // Any integer (a numpy one too: operator.index), never a bool or a float.
  py::object index;
  if (!py::isinstance<py::bool_>(obj) && PyIndex_Check(obj.ptr())) {
    index = py::reinterpret_steal<py::object>(PyNumber_Index(obj.ptr()));
    if (!index) PyErr_Clear();
  }
  if (!index) {
    throw py::value_error(std::string(name) + " must be an integer in " + range + ", got " +
                          std::string(py::str(py::type::of(obj).attr("__name__"))));
  }
  const py::int_ value = py::reinterpret_borrow<py::int_>(index);
  if (value < py::int_(lo) || value > py::int_(hi)) {
    throw py::value_error(std::string(name) + " must be an integer in " + range + ", got " +
                          std::string(py::str(obj)).substr(0, 80));
  }
  return static_cast<int>(value.cast<long long>());
}

double to_number(const py::handle& obj, const char* name) {
  const auto fail = [&]() {
    return py::value_error(std::string(name) + " must be a finite number, got " +
                           std::string(py::repr(obj)).substr(0, 80));
  };
  if (py::isinstance<py::bool_>(obj)) throw fail();  // pybind11's cast would take it as 0 or 1
  double v = 0.0;
  try {
    v = obj.cast<double>();
  } catch (const py::cast_error&) {
    throw fail();
  }
  if (!std::isfinite(v)) throw fail();
  return v;
}

RowMatrixXd to_features(const py::object& obj, Eigen::Index n_rows, int n_features, const char* name) {
  if (obj.is_none()) {
    if (n_features != 0) {
      throw py::value_error(std::string(name) + ": the density was fitted with " + std::to_string(n_features) +
                            " features, so features are required");
    }
    return RowMatrixXd(n_rows, 0);
  }
  auto a = py::array::ensure(obj);
  if (a && a.ndim() == 1) {
    const Eigen::VectorXd v = to_vector(obj, name, n_features);
    return v.transpose().replicate(n_rows, 1);
  }
  RowMatrixXd f = to_matrix(obj, name, n_features);
  if (f.rows() != n_rows) {
    throw py::value_error(std::string(name) + ": " + std::to_string(f.rows()) + " feature rows for " +
                          std::to_string(n_rows) + " poses");
  }
  return f;
}

Eigen::VectorXd to_weights(const py::object& obj, const char* name) {
  return obj.is_none() ? Eigen::VectorXd() : to_vector(obj, name);
}

std::string to_path(const py::object& obj, const char* name) {
  // os.fsencode: the file system's bytes of a str, bytes or os.PathLike, so a name that is not valid UTF-8 (its
  // undecodable bytes held as lone surrogates) names its file instead of failing to convert.
  py::object encoded;
  try {
    encoded = py::module_::import("os").attr("fsencode")(obj);
  } catch (const py::error_already_set&) {
    throw py::value_error(std::string(name) + ": expected a path (str, bytes or os.PathLike), got " +
                          std::string(py::str(py::type::of(obj).attr("__name__"))));
  }
  std::string out = encoded.cast<std::string>();
  if (out.find('\0') != std::string::npos) throw py::value_error(std::string(name) + ": the path contains a NUL byte");
  return out;
}

namespace {
bool is_mapping(const py::handle& obj) {
  return py::isinstance(obj, py::module_::import("collections.abc").attr("Mapping"));
}

std::map<std::string, double> to_joint_map(const py::handle& obj, const char* what) {
  std::map<std::string, double> out;
  for (const auto& item : py::reinterpret_borrow<py::dict>(py::dict(py::reinterpret_borrow<py::object>(obj)))) {
    std::string key;
    try {
      key = item.first.cast<std::string>();
    } catch (const py::cast_error&) {
      throw py::value_error(std::string(what) + ": joint names must be strings");
    }
    try {
      out[key] = item.second.cast<double>();
    } catch (const py::cast_error&) {
      throw py::value_error(std::string(what) + ": joint '" + key + "' has a value that is not a number");
    }
  }
  return out;
}
}  // namespace

/// One configuration from a name -> value mapping or an array in joint_names() order.
Eigen::VectorXd to_configuration(const Hand& hand, const py::handle& obj, const char* what) {
  if (obj.is_none()) throw py::value_error(std::string(what) + ": expected joint values, got None");
  if (is_mapping(obj)) return hand.joints_from_map(to_joint_map(obj, what));
  const Eigen::VectorXd q = to_vector(obj, what);
  hand.check_configuration(q, what);
  return q;
}

/// N configurations: an (N, n_dofs) array, a sequence of mappings, or one configuration for all.
RowMatrixXd to_configurations(const Hand& hand, const py::handle& obj, const char* what) {
  if (obj.is_none()) throw py::value_error(std::string(what) + ": expected joint values, got None");
  if (is_mapping(obj)) return to_configuration(hand, obj, what).transpose();
  if (py::isinstance<py::sequence>(obj) && !py::isinstance<py::str>(obj) && py::len(obj) > 0 &&
      is_mapping(py::reinterpret_borrow<py::sequence>(obj)[0])) {
    const auto seq = py::reinterpret_borrow<py::sequence>(obj);
    RowMatrixXd out(static_cast<Eigen::Index>(py::len(seq)), hand.n_dofs());
    for (size_t i = 0; i < py::len(seq); ++i) {
      out.row(static_cast<Eigen::Index>(i)) = to_configuration(hand, seq[i], what).transpose();
    }
    return out;
  }
  const auto a = py::array::ensure(obj);
  if (a && a.ndim() <= 1) return to_configuration(hand, obj, what).transpose();
  return to_matrix(obj, what, hand.n_dofs());
}

Eigen::Isometry3d to_pose(const py::handle& obj, const char* name) { return pose_from_vector(to_vector(obj, name, 7)); }

Eigen::Isometry3d to_camera_pose(const py::object& obj, const char* name) {
  return camera_pose(to_vector(obj, name, 7), name);
}

Target to_target(const std::string& kind, const py::object& index, const py::object& point, const py::object& camera) {
  static const std::map<std::string, Target::Kind> kinds = {{"all", Target::Kind::All},
                                                            {"index", Target::Kind::Index},
                                                            {"point", Target::Kind::Point},
                                                            {"largest", Target::Kind::Largest},
                                                            {"nearest", Target::Kind::Nearest}};
  const auto k = kinds.find(kind);
  if (k == kinds.end())
    throw py::value_error("target: expected all, index, point, largest or nearest, got '" + kind + "'");
  Target t;
  t.kind = k->second;
  if (t.kind == Target::Kind::Index) t.index = to_int(index, "target index");
  if (t.kind == Target::Kind::Point) t.point = to_vector(point, "target point", 3);
  if (!camera.is_none()) t.camera = Eigen::Vector3d(to_vector(camera, "camera", 3));
  return t;
}

}  // namespace graspmix::py_bind
