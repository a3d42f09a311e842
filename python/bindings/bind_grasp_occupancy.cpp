// The occupancy map of what the cameras saw (grasp/occupancy.hpp) and the solid volume of objects on a table
// (grasp/solid_volume.hpp), both OccupancyMaps; called by bind_grasp before the collision expert that takes them.
#include <cstdint>
#include <memory>
#include <optional>

#include "common.hpp"
#include "graspmix/grasp/occupancy.hpp"
#include "graspmix/grasp/solid_volume.hpp"
#include "graspmix/perception/visibility.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

/// The occupancy map of what the cameras saw (OccupancyMap) and its settings.
void bind_occupancy_only(py::module_& m) {
  SettingsClass<OccupancySettings>(m, "OccupancySettings",
                                   "The occupancy map of a scene from its cameras' rays (OccupancyMap).")
      .field("resolution", &OccupancySettings::resolution, "m: cell size (OctoMap's resolution), > 0")
      .field("margin", &OccupancySettings::margin, "m: the objects' bounding box grown by this is the mapped region")
      .field("unknown_is_occupied", &OccupancySettings::unknown_is_occupied,
             "cells no ray reached are obstacles (space the cameras did not see is not free)")
      .field("max_cells", &OccupancySettings::max_cells, "the dense grid's largest size (cells)")
      .done();
  py::class_<OccupancyMap, std::shared_ptr<OccupancyMap>>(
      m, "OccupancyMap",
      "Free, occupied and unknown space of a scene: OctoMap's ray insertion of every point from its own viewpoint,\n"
      "baked into a dense grid over the objects' box grown by a margin (free outside it, and within one cell of\n"
      "the support plane). The rule: include/graspmix/grasp/occupancy.hpp.")
      .def(py::init([](const py::object& points, const py::object& viewpoints, const py::object& objects,
                       const py::object& plane, const py::object& settings, const py::kwargs& kw) {
             const Vec3Array P(to_matrix(points, "OccupancyMap: points", 3));
             if (viewpoints.is_none()) throw py::value_error("OccupancyMap: viewpoints are needed (the cameras' rays)");
             const Vec3Array V = Vec3Array(to_matrix(viewpoints, "OccupancyMap: viewpoints", 3, true));
             const Vec3Array O =
                 objects.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(objects, "OccupancyMap: objects", 3, true));
             std::optional<Eigen::Vector4d> pl;
             if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "OccupancyMap: plane", 4));
             const OccupancySettings s = settings_from<OccupancySettings>(settings, kw, "OccupancyMap");
             py::gil_scoped_release release;
             return std::make_shared<OccupancyMap>(P, V, O, pl, s);
           }),
           py::arg("points"), py::arg("viewpoints"), py::arg("objects") = py::none(), py::arg("plane") = py::none(),
           py::kw_only(), py::arg("settings") = py::none(),
           ("points (N, 3), the whole cloud; viewpoints (3,) or (N, 3), the camera of each point; objects (M, 3): the\n"
            "points whose box (grown by margin) is mapped (None: all points); plane [a, b, c, d] or None.\n" +
            settings_doc<OccupancySettings>())
               .c_str())
      .def_static(
          "from_visibility",
          [](const VisibilityModel& visibility, const py::object& objects, const py::object& plane,
             const py::object& settings, const py::kwargs& kw) {
            const Vec3Array O(to_matrix(objects, "OccupancyMap.from_visibility: objects", 3, true));
            std::optional<Eigen::Vector4d> pl;
            if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "OccupancyMap.from_visibility: plane", 4));
            const OccupancySettings s = settings_from<OccupancySettings>(settings, kw, "OccupancyMap.from_visibility");
            py::gil_scoped_release release;
            return std::make_shared<OccupancyMap>(visibility, O, pl, s);
          },
          py::arg("visibility"), py::arg("objects"), py::arg("plane") = py::none(), py::kw_only(),
          py::arg("settings") = py::none(),
          "The same region and rules from a VisibilityModel's views instead of OctoMap's rays: each cell by its\n"
          "centre's state (seen free -> free, surface -> occupied, unseen -> unknown). objects (M, 3): the points\n"
          "whose box, grown by margin, is mapped; plane [a, b, c, d] or None.")
      .def(
          "state",
          [](const OccupancyMap& map, const py::object& points) {
            const Vec3Array P(to_matrix(points, "state: points", 3, true));
            Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1> out(P.rows());
            for (Eigen::Index i = 0; i < P.rows(); ++i)
              out[i] = static_cast<std::uint8_t>(map.state(P.row(i).transpose()));
            return out;
          },
          py::arg("points"), "(N,) uint8 state of each point's cell: 0 free, 1 occupied, 2 unknown (free outside).")
      .def_property_readonly("resolution", &OccupancyMap::resolution)
      .def_property_readonly("region_min", &OccupancyMap::region_min, "(3,) lower corner of the mapped region (m).")
      .def_property_readonly("region_max", &OccupancyMap::region_max, "(3,) upper corner of the mapped region (m).")
      .def_property_readonly("dims", &OccupancyMap::dims, "(3,) cells along x, y, z.")
      .def_property_readonly(
          "plane",
          [](const OccupancyMap& m) -> py::object {
            return m.has_plane() ? py::cast(Eigen::Vector4d(m.plane())) : py::none();
          },
          "The support plane, normalised, its normal towards the cameras, or None.")
      .def_property_readonly("settings", [](const OccupancyMap& m) { return OccupancySettings(m.settings()); })
      .def_property_readonly(
          "stats",
          [](const OccupancyMap& m) {
            const OccupancyStats& s = m.stats();
            py::dict d;
            d["n_rays"] = s.n_rays;
            d["n_free"] = s.n_free;
            d["n_occupied"] = s.n_occupied;
            d["n_unknown"] = s.n_unknown;
            d["seconds"] = s.seconds;
            return d;
          },
          "Rays inserted (one per cell and viewpoint; 0 for a map from a visibility model), cells by state, wall time\n"
          "(s).");
}

/// The solid volume of objects standing on a plane (grasp/solid_volume.hpp), as an OccupancyMap.
void bind_solid_volume(py::module_& m) {
  m.def(
      "solid_volume",
      [](const py::object& points, const py::object& plane, double resolution, double gap) {
        const Vec3Array P(to_matrix(points, "solid_volume: points", 3, true));
        const Eigen::Vector4d pl(to_vector(plane, "solid_volume: plane", 4));
        SolidVolumeSettings s;
        s.resolution = resolution;
        s.gap = gap;
        py::gil_scoped_release release;
        return std::make_shared<OccupancyMap>(solid_volume(P, pl, s));
      },
      py::arg("points"), py::arg("plane"), py::kw_only(), py::arg("resolution") = SolidVolumeSettings{}.resolution,
      py::arg("gap") = SolidVolumeSettings{}.gap,
      "The solid columns of objects (points (N, 3)) standing on plane [a, b, c, d]: an OccupancyMap whose occupied\n"
      "cells lie under the points' tops (the rule: include/graspmix/grasp/solid_volume.hpp); resolution, gap in m.");
}

}  // namespace

void bind_occupancy(py::module_& m) {
  bind_occupancy_only(m);
  bind_solid_volume(m);
}

}  // namespace graspmix::py_bind
