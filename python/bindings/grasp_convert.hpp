#pragma once
// Conversions at the Python boundary that only the grasp layer's bindings need (bind_grasp*.cpp): experts and the
// reachability test, Python callables that C++ may call, copy and free on threads without the GIL.
#include <memory>
#include <vector>

#include "common.hpp"
#include "graspmix/grasp/experts.hpp"

namespace graspmix::py_bind {

using ExpertList = std::vector<std::shared_ptr<const Expert>>;
/// The graspmix experts of an iterable (None: none); ValueError naming an item that is not one.
ExpertList to_experts(const py::object& obj);
/// A Python callable held for C++: copies of the handle only touch an atomic count, and the callable is released
/// with the GIL taken, so a std::function holding it may be copied and destroyed on any thread.
std::shared_ptr<py::function> held_function(const py::function& fn);
/// A reachability test from a Python callable fn(wrists (N, 7), joints (N, D)) -> (N,) booleans, called with the
/// GIL taken; None: no test.
KinematicFeasibilityExpert::Reachability to_reachability(const py::object& fn);

}  // namespace graspmix::py_bind
