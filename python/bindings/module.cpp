// The graspmix._core module: build information, then one binder per layer (common.hpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

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
  bind_core(m);
  bind_density(m);
  bind_perception(m);
  bind_robot(m);
  bind_grasp(m);
  bind_sim(m);
}
