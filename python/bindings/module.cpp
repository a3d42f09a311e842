// The graspmix._core module: build information, then one binder per layer (common.hpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <exception>
#include <stdexcept>

#include "common.hpp"
#include "graspmix/core/info.hpp"

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
  // std::invalid_argument -> ValueError, as pybind11 does, except that a message quoting bytes of a bad
  // file that are not UTF-8 (a binary file given as a URDF) keeps them as \x escapes: pybind11's own
  // translation would raise a UnicodeDecodeError that names neither the file nor the problem.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::invalid_argument& e) {
      PyObject* text =
          PyUnicode_DecodeUTF8(e.what(), static_cast<Py_ssize_t>(std::strlen(e.what())), "backslashreplace");
      if (!text) {
        PyErr_Clear();
        PyErr_SetString(PyExc_ValueError, "invalid argument (the message could not be decoded)");
        return;
      }
      PyErr_SetObject(PyExc_ValueError, text);
      Py_DECREF(text);
    }
  });
  bind_core(m);
  bind_density(m);
  bind_perception(m);
  bind_robot(m);
  bind_grasp(m);
  bind_sim(m);
}
