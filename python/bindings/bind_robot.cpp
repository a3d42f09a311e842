// The robot layer: hands from URDF (kinematics, collision geometry) and meshes.
#include <map>
#include <memory>
#include <optional>

#include "common.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/robot/hand.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

py::array_t<double> poses_3d(const RowMatrixXd& flat, Eigen::Index n_links) {
  const py::ssize_t N = flat.rows(), L = n_links;
  py::array_t<double> out({N, L, static_cast<py::ssize_t>(7)});
  std::copy(flat.data(), flat.data() + flat.size(), out.mutable_data());
  return out;
}

const char* shape_name(ShapeType t) {
  switch (t) {
    case ShapeType::Box:
      return "box";
    case ShapeType::Cylinder:
      return "cylinder";
    case ShapeType::Sphere:
      return "sphere";
    case ShapeType::Mesh:
      return "mesh";
  }
  return "?";
}

const char* joint_type_name(JointType t) {
  switch (t) {
    case JointType::Fixed:
      return "fixed";
    case JointType::Revolute:
      return "revolute";
    case JointType::Continuous:
      return "continuous";
    case JointType::Prismatic:
      return "prismatic";
  }
  return "?";
}

}  // namespace

void bind_robot(py::module_& m) {
  m.attr("URDF_AXES_ELEMENT") = kUrdfAxesElement;  // <graspmix approach_axis="x y z" fingertips="a b"/>
  SettingsClass<HandLoadSettings>(m, "HandLoadSettings", "How a URDF's meshes are found and loaded (Hand.from_urdf).")
      .property(
          "package_dirs", [](const HandLoadSettings& s) { return s.package_dirs; },
          [](HandLoadSettings& s, const py::object& v) {
            s.package_dirs.clear();
            if (v.is_none()) return;
            if (py::isinstance<py::str>(v))
              throw py::value_error("package_dirs: expected a list of folders, got one string");
            for (const auto& d : v)
              s.package_dirs.push_back(to_path(py::reinterpret_borrow<py::object>(d), "package_dirs"));
          },
          "extra folders searched for package://name/... meshes (each holds package folders, as in ROS_PACKAGE_PATH)")
      .field("load_meshes", &HandLoadSettings::load_meshes,
             "False: mesh shapes keep only their file names (no geometry)")
      .field("approach_snap_deg", &HandLoadSettings::approach_snap_deg,
             "degrees: the inferred approach axis snaps to the nearest wrist axis within this (Hand.approach_axis)")
      .field("same_finger_deg", &HandLoadSettings::same_finger_deg,
             "degrees: two chain ends within this across the approach axis lie on one finger (Hand.fingertips)")
      .done();

  m.def(
      "load_mesh",
      [](const py::object& path, const py::object& scale) {
        const std::string p = to_path(path, "path");
        const Eigen::Vector3d sc =
            scale.is_none() ? Eigen::Vector3d::Ones() : Eigen::Vector3d(to_vector(scale, "scale", 3));
        TriangleMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = Hand::load_mesh(p, sc);
        }
        return py::make_tuple(mesh.vertices, mesh.triangles);
      },
      py::arg("path"), py::arg("scale") = py::none(),
      "(vertices (V, 3), triangles (T, 3)) of every triangle in a mesh file (STL, OBJ, ... via assimp), scaled.");
  py::class_<Hand, HandPtr>(
      m, "Hand",
      "A hand as a kinematic tree from a URDF (urdfdom): fk (eq:fk_function) and collision geometry.\n"
      "The wrist is the root link; joint_names are the independent joints (mimic joints follow\n"
      "value = multiplier * master + offset and are not listed); poses are [x, y, z, qx, qy, qz, qw]\n"
      "of the URDF link frames (not inertial frames).")
      .def_static(
          "from_urdf",
          [](const py::object& path, const py::object& package_dirs, const py::object& settings, py::kwargs kw) {
            if (!package_dirs.is_none()) kw["package_dirs"] = package_dirs;
            const HandLoadSettings s = settings_from<HandLoadSettings>(settings, kw, "Hand.from_urdf");
            const std::string p = to_path(path, "path");
            py::gil_scoped_release release;
            return std::make_shared<Hand>(Hand::from_urdf(p, s));
          },
          py::arg("path"), py::arg("package_dirs") = py::none(), py::kw_only(), py::arg("settings") = py::none(),
          ("Reads a URDF. Mesh files (STL, OBJ, ... via assimp) resolve against the URDF's folder; package://\n"
           "paths also against its parents and package_dirs. ValueError names a missing file, malformed XML,\n"
           "a URDF without links or with more than 1000, anything urdfdom complains about, and every bad number\n"
           "or shape (non-finite, lower > upper limits, zero axis, non-positive size or mesh scale) with the\n"
           "link or joint at fault, an unsupported joint or an unreadable mesh.\n" +
           settings_doc<HandLoadSettings>())
              .c_str())
      .def_static(
          "from_urdf_string",
          [](const std::string& xml, const py::object& base_dir, const py::object& package_dirs,
             const py::object& settings, py::kwargs kw) {
            if (!package_dirs.is_none()) kw["package_dirs"] = package_dirs;
            const HandLoadSettings s = settings_from<HandLoadSettings>(settings, kw, "Hand.from_urdf_string");
            const std::string dir = to_path(base_dir, "base_dir");
            py::gil_scoped_release release;
            return std::make_shared<Hand>(Hand::from_urdf_string(xml, dir, s));
          },
          py::arg("xml"), py::arg("base_dir") = ".", py::arg("package_dirs") = py::none(), py::kw_only(),
          py::arg("settings") = py::none(),
          ("A hand from URDF text; relative mesh paths resolve against base_dir.\n" + settings_doc<HandLoadSettings>())
              .c_str())
      .def_property_readonly("name", &Hand::name)
      .def_property_readonly("source", &Hand::source, "The URDF file it was read from.")
      .def_property_readonly("joint_names", &Hand::joint_names, "Independent joints, the order of joint arrays.")
      .def_property_readonly("joint_limits", &Hand::joint_limits,
                             "(n_dofs, 2) lower, upper (m or rad; +-inf if unbounded).")
      .def_property_readonly("link_names", &Hand::link_names,
                             "Every link, the wrist (root) first; the order of fk rows.")
      .def_property_readonly("root_link", [](const Hand& h) { return h.link_names().front(); })
      .def_property_readonly(
          "approach_axis", [](const Hand& h) { return Eigen::Vector3d(h.approach_axis()); },
          "(3,) unit: the approach axis in the wrist frame, from the URDF's <graspmix approach_axis> or inferred "
          "(the direction from the wrist to the fingertips, snapped to a wrist axis within approach_snap_deg)")
      .def_property_readonly(
          "fingertips",
          [](const Hand& h) {
            std::vector<std::string> out;
            for (const int l : h.fingertips()) out.push_back(h.link_names()[static_cast<size_t>(l)]);
            return out;
          },
          "The fingertip links (link_names order): from the URDF's <graspmix fingertips> or inferred (the distal "
          "link of each finger chain)")
      .def_property_readonly("grasp_axes_source", &Hand::grasp_axes_source,
                             "'urdf' (its <graspmix> element), 'inferred' or 'set' (set_grasp_axes)")
      .def(
          "set_grasp_axes",
          [](Hand& h, const py::object& approach, const std::vector<std::string>& fingertips) {
            h.set_grasp_axes(Eigen::Vector3d(to_vector(approach, "approach_axis", 3)), fingertips);
          },
          py::arg("approach_axis"), py::arg("fingertips"),
          "Gives the approach axis (3,) and fingertip links; ValueError naming a bad value.")
      .def_property_readonly("n_dofs", &Hand::n_dofs)
      .def_property_readonly("n_links", &Hand::n_links)
      .def_property_readonly(
          "mimic_joints",
          [](const Hand& h) {
            py::dict out;
            for (const auto& j : h.joints())
              if (j.mimic)
                out[py::str(j.name)] =
                    py::make_tuple(h.joint_names()[static_cast<size_t>(j.dof)], j.multiplier, j.offset);
            return out;
          },
          "name -> (independent joint, multiplier, offset): value = multiplier * joints[master] + offset.")
      .def_property_readonly(
          "joints",
          [](const Hand& h) {
            py::list out;
            for (const auto& j : h.joints()) {
              py::dict d;
              d["name"] = j.name;
              d["type"] = joint_type_name(j.type);
              d["parent"] = h.link_names()[static_cast<size_t>(j.parent_link)];
              d["child"] = h.link_names()[static_cast<size_t>(j.child_link)];
              d["origin"] = pose_to_vector(j.T_parent_joint);
              d["axis"] = j.axis;
              d["limits"] = py::make_tuple(j.lower, j.upper);
              d["mimic"] =
                  j.mimic ? py::object(py::str(h.joint_names()[static_cast<size_t>(j.dof)])) : py::object(py::none());
              out.append(d);
            }
            return out;
          },
          "Every URDF joint (fixed and mimic included) as dicts, parents before children.")
      .def("link_index", &Hand::link_index, py::arg("link"))
      .def(
          "joints_array", [](const Hand& h, const py::object& joints) { return to_configuration(h, joints, "joints"); },
          py::arg("joints"), "A configuration (mapping or array) as an array in joint_names order.")
      .def(
          "joints_dict",
          [](const Hand& h, const py::object& joints) {
            return h.joints_to_map(to_configuration(h, joints, "joints"));
          },
          py::arg("joints"), "A configuration as {joint name: value}.")
      .def(
          "all_joint_values",
          [](const Hand& h, const py::object& joints) {
            const Eigen::VectorXd v = h.all_joint_values(to_configuration(h, joints, "joints"));
            py::dict out;
            for (size_t i = 0; i < h.joints().size(); ++i)
              if (h.joints()[i].type != JointType::Fixed)
                out[py::str(h.joints()[i].name)] = v[static_cast<Eigen::Index>(i)];
            return out;
          },
          py::arg("joints"),
          "{name: value} for every movable URDF joint, mimic joints resolved (e.g. to drive a simulator).")
      .def(
          "clamp",
          [](const Hand& h, const py::object& joints) { return h.clamp(to_configuration(h, joints, "joints")); },
          py::arg("joints"), "The configuration clamped into the joint limits.")
      .def(
          "within_limits",
          [](const Hand& h, const py::object& joints, const py::object& tol) {
            const Eigen::VectorXd q = to_configuration(h, joints, "joints");
            return tol.is_none() ? h.within_limits(q) : h.within_limits(q, tol.cast<double>());
          },
          py::arg("joints"), py::arg("tolerance") = py::none(),
          "True when every joint is within its limits, up to tolerance (joint units; None: the C++ default of "
          "Hand::within_limits).")
      .def(
          "fk",
          [](const Hand& h, const py::object& T_world_wrist, const py::object& joints) {
            const Eigen::Isometry3d W = to_pose(T_world_wrist, "T_world_wrist");
            const auto poses = h.fk(W, to_configuration(h, joints, "joints"));
            RowMatrixXd out(static_cast<Eigen::Index>(poses.size()), 7);
            for (size_t i = 0; i < poses.size(); ++i)
              out.row(static_cast<Eigen::Index>(i)) = pose_to_vector(poses[i]).transpose();
            return out;
          },
          py::arg("T_world_wrist"), py::arg("joints"),
          "eq:fk_function: (n_links, 7) world poses of every link (link_names order) for a wrist pose (7,)\n"
          "and joints (mapping or array in joint_names order). Joint limits are not enforced.")
      .def(
          "fk_batch",
          [](const Hand& h, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(h, joints, "joints");
            RowMatrixXd flat;
            {
              py::gil_scoped_release release;
              flat = h.fk_batch(W, q);
            }
            return poses_3d(flat, h.n_links());
          },
          py::arg("T_world_wrist"), py::arg("joints"),
          "fk over N hands: wrists (N, 7), joints (N, n_dofs), a list of mappings, or one configuration for all\n"
          "-> (N, n_links, 7).")
      .def(
          "collision_shapes",
          [](const Hand& h, const std::string& link) {
            py::list out;
            for (const auto& s : h.links()[static_cast<size_t>(h.link_index(link))].collisions) {
              py::dict d;
              d["type"] = shape_name(s.type);
              d["origin"] = pose_to_vector(s.T_link_shape);
              switch (s.type) {
                case ShapeType::Box:
                  d["size"] = s.size;
                  break;
                case ShapeType::Cylinder:
                  d["radius"] = s.size.x();
                  d["length"] = s.size.y();
                  break;
                case ShapeType::Sphere:
                  d["radius"] = s.size.x();
                  break;
                case ShapeType::Mesh:
                  d["file"] = s.mesh_file;
                  d["scale"] = s.size;
                  if (s.mesh) {
                    d["vertices"] = s.mesh->vertices;
                    d["triangles"] = s.mesh->triangles;
                    d["hull_planes"] = *s.hull_planes;
                    d["proxy_box"] = pose_to_vector(s.T_shape_box);
                    d["proxy_half"] = s.box_half;
                    d["proxy_growth"] = s.box_growth;
                    d["proxy_inner"] = s.box_inner;
                  }
                  break;
              }
              out.append(d);
            }
            return out;
          },
          py::arg("link"),
          "The <collision> elements of a link as dicts: type (box|cylinder|sphere|mesh), origin (7,) in the link\n"
          "frame, and size (box, full sides), radius/length (cylinder, along z), radius (sphere), or file, scale,\n"
          "vertices (V, 3, scaled, in the shape frame) and triangles (T, 3) (mesh), with the mesh's convex hull as\n"
          "hull_planes (P, 4) [nx, ny, nz, offset] (n . x <= offset inside) and its proxy: an oriented box proxy_box "
          "(7,)\n"
          "in the shape frame with half extents proxy_half (3,) around the hull, and proxy_growth: every point whose\n"
          "largest n . x - offset is g >= 0 or less lies within the box grown by proxy_growth * g; proxy_inner (3,),\n"
          "the half extents of a box of the same frame inside the hull (zeros: none).")
      .def(
          "collision_mesh",
          [](const Hand& h, const std::string& link) {
            const TriangleMesh mesh = h.collision_mesh(h.link_index(link));
            return py::make_tuple(mesh.vertices, mesh.triangles);
          },
          py::arg("link"),
          "(vertices (V, 3), triangles (T, 3)) of all of a link's collision geometry in the link frame\n"
          "(cylinders and spheres tessellated).")
      .def("__repr__", [](const Hand& h) {
        return "Hand(name='" + h.name() + "', links=" + std::to_string(h.n_links()) +
               ", dofs=" + std::to_string(h.n_dofs()) + ")";
      });
}

}  // namespace graspmix::py_bind
