// The grasp bindings' conversions (grasp_convert.hpp).
#include "grasp_convert.hpp"

#include <string>

namespace graspmix::py_bind {

std::shared_ptr<py::function> held_function(const py::function& fn) {
  return std::shared_ptr<py::function>(new py::function(fn), [](py::function* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
}

ExpertList to_experts(const py::object& obj) {
  ExpertList out;
  if (obj.is_none()) return out;
  for (const py::handle& e : obj) {
    try {
      out.push_back(e.cast<std::shared_ptr<Expert>>());
    } catch (const py::cast_error&) {
      throw py::value_error("experts: every item must be a graspmix expert (got " +
                            std::string(py::str(py::type::of(e))) + ")");
    }
  }
  return out;
}

KinematicFeasibilityExpert::Reachability to_reachability(const py::object& fn) {
  if (fn.is_none()) return nullptr;
  if (!PyCallable_Check(fn.ptr())) throw py::value_error("reachable: expected a callable or None");
  const std::shared_ptr<py::function> f = held_function(fn);
  return [f](const PoseArray& w, const RowMatrixXd& q) {
    py::gil_scoped_acquire gil;
    const py::object r = (*f)(w, q);
    auto raw = py::array::ensure(r);
    if (!raw || raw.ndim() != 1 || raw.dtype().kind() != 'b') {
      throw py::value_error("reachable must return a 1-D array of booleans (one per grasp)");
    }
    auto a = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(raw);
    Eigen::Matrix<bool, Eigen::Dynamic, 1> out(a.shape(0));
    for (py::ssize_t i = 0; i < a.shape(0); ++i) out[i] = a.at(i);
    return out;
  };
}

}  // namespace graspmix::py_bind
