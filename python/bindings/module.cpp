#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "common.hpp"
#include "graspmix/info.hpp"

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

Eigen::VectorXd to_vector(const py::handle& obj, const char* name, Eigen::Index n) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a) throw py::value_error(std::string(name) + ": could not be read as an array of numbers");
  if (a.ndim() == 0) {
    Eigen::VectorXd v(1);
    v[0] = *a.data();
    if (n >= 0 && n != 1) throw py::value_error(std::string(name) + ": expected " + std::to_string(n) + " values, got 1");
    return v;
  }
  if (a.ndim() != 1) throw py::value_error(std::string(name) + ": expected a 1-D array, got " + std::to_string(a.ndim()) + "-D");
  if (n >= 0 && a.shape(0) != n) {
    throw py::value_error(std::string(name) + ": expected " + std::to_string(n) + " values, got " +
                          std::to_string(a.shape(0)));
  }
  return Eigen::Map<const Eigen::VectorXd>(a.data(), a.shape(0));
}

std::uint64_t to_seed(const py::object& seed) {
  if (seed.is_none()) return 0;
  const long long s = seed.cast<long long>();
  if (s < 0) throw py::value_error("seed must be a non-negative integer, got " + std::to_string(s));
  return static_cast<std::uint64_t>(s);
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

}  // namespace graspmix::py_bind

PYBIND11_MODULE(_core, m) {
  using namespace graspmix::py_bind;
  m.doc() = "graspmix C++ core: SE(3) maps, Gaussian mixtures, pose densities (GMM and KDE)";
  m.def(
      "build_info",
      [] {
        auto info = graspmix::build_info();
        info["pybind11"] = GRASPMIX_PYBIND11_VERSION;
        return info;
      },
      "Versions of graspmix and of every library it was built against.");
  bind_se3(m);
  bind_density(m);
  bind_hand(m);
  bind_surface(m);
  bind_synthesis(m);
  bind_sim(m);
}
