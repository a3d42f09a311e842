// Hand (URDF kinematics and collision geometry) and the collision expert.
#include <map>
#include <memory>
#include <optional>

#include "common.hpp"
#include "graspmix/collision.hpp"
#include "graspmix/hand.hpp"
#include "graspmix/se3.hpp"

namespace graspmix::py_bind {


std::string to_path(const py::object& obj, const char* name) {
  try {
    return py::str(py::module_::import("os").attr("fspath")(obj)).cast<std::string>();
  } catch (const py::error_already_set&) {
    throw py::value_error(std::string(name) + ": expected a path (str or os.PathLike)");
  }
}

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

Eigen::Isometry3d to_pose(const py::handle& obj, const char* name) {
  return pose_from_vector(to_vector(obj, name, 7));
}

namespace {

py::array_t<double> poses_3d(const RowMatrixXd& flat, Eigen::Index n_links) {
  const py::ssize_t N = flat.rows(), L = n_links;
  py::array_t<double> out({N, L, static_cast<py::ssize_t>(7)});
  std::copy(flat.data(), flat.data() + flat.size(), out.mutable_data());
  return out;
}

const char* shape_name(ShapeType t) {
  switch (t) {
    case ShapeType::Box: return "box";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Mesh: return "mesh";
  }
  return "?";
}

const char* joint_type_name(JointType t) {
  switch (t) {
    case JointType::Fixed: return "fixed";
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Prismatic: return "prismatic";
  }
  return "?";
}

}  // namespace

void bind_hand(py::module_& m) {
  m.def(
      "load_mesh",
      [](const py::object& path, const py::object& scale) {
        const std::string p = to_path(path, "path");
        const Eigen::Vector3d sc = scale.is_none() ? Eigen::Vector3d::Ones() : Eigen::Vector3d(to_vector(scale, "scale", 3));
        TriangleMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = Hand::load_mesh(p, sc);
        }
        return py::make_tuple(mesh.vertices, mesh.triangles);
      },
      py::arg("path"), py::arg("scale") = py::none(),
      "(vertices (V, 3), triangles (T, 3)) of every triangle in a mesh file (STL, OBJ, ... via assimp), scaled.");
  py::class_<Hand, HandPtr>(m, "Hand",
                            "A hand as a kinematic tree from a URDF (urdfdom): fk (eq:fk_function) and collision geometry.\n"
                            "The wrist is the root link; joint_names are the independent joints (mimic joints follow\n"
                            "value = multiplier * master + offset and are not listed); poses are [x, y, z, qx, qy, qz, qw]\n"
                            "of the URDF link frames (not inertial frames).")
      .def_static(
          "from_urdf",
          [](const py::object& path, const py::object& package_dirs, bool load_meshes) {
            HandLoadSettings s;
            s.load_meshes = load_meshes;
            if (!package_dirs.is_none()) {
              for (const auto& d : package_dirs) s.package_dirs.push_back(to_path(py::reinterpret_borrow<py::object>(d), "package_dirs"));
            }
            const std::string p = to_path(path, "path");
            py::gil_scoped_release release;
            return std::make_shared<Hand>(Hand::from_urdf(p, s));
          },
          py::arg("path"), py::arg("package_dirs") = py::none(), py::arg("load_meshes") = true,
          "Reads a URDF. Mesh files (STL, OBJ, ... via assimp) resolve against the URDF's folder; package://\n"
          "paths also against its parents and package_dirs. ValueError names a missing file, a URDF without\n"
          "links, an unsupported joint or an unreadable mesh.")
      .def_static(
          "from_urdf_string",
          [](const std::string& xml, const py::object& base_dir, const py::object& package_dirs, bool load_meshes) {
            HandLoadSettings s;
            s.load_meshes = load_meshes;
            if (!package_dirs.is_none()) {
              for (const auto& d : package_dirs) s.package_dirs.push_back(to_path(py::reinterpret_borrow<py::object>(d), "package_dirs"));
            }
            const std::string dir = to_path(base_dir, "base_dir");
            py::gil_scoped_release release;
            return std::make_shared<Hand>(Hand::from_urdf_string(xml, dir, s));
          },
          py::arg("xml"), py::arg("base_dir") = ".", py::arg("package_dirs") = py::none(), py::arg("load_meshes") = true,
          "A hand from URDF text; relative mesh paths resolve against base_dir.")
      .def_property_readonly("name", &Hand::name)
      .def_property_readonly("source", &Hand::source, "The URDF file it was read from.")
      .def_property_readonly("joint_names", &Hand::joint_names, "Independent joints, the order of joint arrays.")
      .def_property_readonly("joint_limits", &Hand::joint_limits, "(n_dofs, 2) lower, upper (m or rad; +-inf if unbounded).")
      .def_property_readonly("link_names", &Hand::link_names, "Every link, the wrist (root) first; the order of fk rows.")
      .def_property_readonly("root_link", [](const Hand& h) { return h.link_names().front(); })
      .def_property_readonly("n_dofs", &Hand::n_dofs)
      .def_property_readonly("n_links", &Hand::n_links)
      .def_property_readonly(
          "mimic_joints",
          [](const Hand& h) {
            py::dict out;
            for (const auto& j : h.joints())
              if (j.mimic) out[py::str(j.name)] = py::make_tuple(h.joint_names()[static_cast<size_t>(j.dof)], j.multiplier, j.offset);
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
              d["mimic"] = j.mimic ? py::object(py::str(h.joint_names()[static_cast<size_t>(j.dof)])) : py::object(py::none());
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
          "joints_dict", [](const Hand& h, const py::object& joints) { return h.joints_to_map(to_configuration(h, joints, "joints")); },
          py::arg("joints"), "A configuration as {joint name: value}.")
      .def(
          "all_joint_values",
          [](const Hand& h, const py::object& joints) {
            const Eigen::VectorXd v = h.all_joint_values(to_configuration(h, joints, "joints"));
            py::dict out;
            for (size_t i = 0; i < h.joints().size(); ++i)
              if (h.joints()[i].type != JointType::Fixed) out[py::str(h.joints()[i].name)] = v[static_cast<Eigen::Index>(i)];
            return out;
          },
          py::arg("joints"), "{name: value} for every movable URDF joint, mimic joints resolved (e.g. to drive a simulator).")
      .def("clamp", [](const Hand& h, const py::object& joints) { return h.clamp(to_configuration(h, joints, "joints")); },
           py::arg("joints"), "The configuration clamped into the joint limits.")
      .def(
          "within_limits",
          [](const Hand& h, const py::object& joints, double tol) { return h.within_limits(to_configuration(h, joints, "joints"), tol); },
          py::arg("joints"), py::arg("tolerance") = 0.0)
      .def(
          "fk",
          [](const Hand& h, const py::object& T_world_wrist, const py::object& joints) {
            const Eigen::Isometry3d W = to_pose(T_world_wrist, "T_world_wrist");
            const auto poses = h.fk(W, to_configuration(h, joints, "joints"));
            RowMatrixXd out(static_cast<Eigen::Index>(poses.size()), 7);
            for (size_t i = 0; i < poses.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pose_to_vector(poses[i]).transpose();
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
                case ShapeType::Box: d["size"] = s.size; break;
                case ShapeType::Cylinder: d["radius"] = s.size.x(); d["length"] = s.size.y(); break;
                case ShapeType::Sphere: d["radius"] = s.size.x(); break;
                case ShapeType::Mesh:
                  d["file"] = s.mesh_file;
                  d["scale"] = s.size;
                  if (s.mesh) {
                    d["vertices"] = s.mesh->vertices;
                    d["triangles"] = s.mesh->triangles;
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
          "vertices (V, 3, scaled, in the shape frame) and triangles (T, 3) (mesh).")
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
        return "Hand(name='" + h.name() + "', links=" + std::to_string(h.n_links()) + ", dofs=" + std::to_string(h.n_dofs()) + ")";
      });

  py::class_<CollisionResult>(m, "CollisionResult", "The collision expert for one configuration (depths in m, per link).")
      .def_readonly("cloud_depth", &CollisionResult::cloud_depth, "(n_links,) deepest cloud point inside each link.")
      .def_readonly("plane_depth", &CollisionResult::plane_depth, "(n_links,) depth of each link below the support plane.")
      .def_readonly("points_inside", &CollisionResult::points_inside, "(n_links,) cloud points inside each link.")
      .def_readonly("total_depth", &CollisionResult::total_depth)
      .def_readonly("log_w", &CollisionResult::log_w, "log W(h) = -beta * total_depth.")
      .def_readonly("w", &CollisionResult::w, "W(h).")
      .def_readonly("collision_free", &CollisionResult::collision_free)
      .def("__repr__", [](const CollisionResult& r) {
        return "CollisionResult(total_depth=" + std::to_string(r.total_depth) + ", log_w=" + std::to_string(r.log_w) +
               ", collision_free=" + (r.collision_free ? "True" : "False") + ")";
      });

  py::class_<CollisionBatchResult>(m, "CollisionBatchResult", "The collision expert over N configurations.")
      .def_readonly("cloud_depth", &CollisionBatchResult::cloud_depth, "(N, n_links)")
      .def_readonly("plane_depth", &CollisionBatchResult::plane_depth, "(N, n_links)")
      .def_readonly("total_depth", &CollisionBatchResult::total_depth, "(N,)")
      .def_readonly("log_w", &CollisionBatchResult::log_w, "(N,)")
      .def_readonly("w", &CollisionBatchResult::w, "(N,)")
      .def_readonly("collision_free", &CollisionBatchResult::collision_free, "(N,) bool");

  py::class_<CollisionExpert, std::shared_ptr<CollisionExpert>>(
      m, "CollisionExpert",
      "W(h) = exp(-beta * total penetration) of a hand through an object's cloud and below its support plane\n"
      "(eq:opt_criterion_std_col). Cloud depth of a link: the deepest cloud point inside it (exact for boxes,\n"
      "cylinders, spheres; meshes as their convex hulls); plane depth: the deepest point of the link below the\n"
      "plane (FCL half-space). The cloud is indexed once at construction.")
      .def(py::init([](HandPtr hand, const py::object& cloud, const py::object& plane, double beta, double point_radius,
                       double plane_margin, double cell_size, bool orient_plane, double contact_tolerance,
                       double inside_weight) {
             if (!hand) throw py::value_error("hand: expected a Hand, got None");
             CollisionSettings s;
             s.beta = beta;
             s.point_radius = point_radius;
             s.plane_margin = plane_margin;
             s.cell_size = cell_size;
             s.orient_plane = orient_plane;
             s.contact_tolerance = contact_tolerance;
             s.inside_weight = inside_weight;
             const Vec3Array pts = cloud.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(cloud, "cloud", 3));
             std::optional<Eigen::Vector4d> pl;
             if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "plane", 4));
             py::gil_scoped_release release;
             return std::make_shared<CollisionExpert>(hand, pts, pl, s);
           }),
           py::arg("hand"), py::arg("cloud"), py::arg("plane") = py::none(), py::arg("beta") = 1000.0,
           py::arg("point_radius") = 0.0, py::arg("plane_margin") = 0.0, py::arg("cell_size") = 0.0,
           py::arg("orient_plane") = true, py::arg("contact_tolerance") = 1e-9, py::arg("inside_weight") = 0.0,
           "hand: Hand; cloud: (N, 3) points (world frame); plane: [a, b, c, d] of a x + b y + c z + d = 0 or None;\n"
           "beta (1/m); point_radius (m, points as balls); plane_margin (m, the plane raised by it); cell_size (m,\n"
           "0 = automatic); orient_plane: flip the plane so the cloud lies on its positive side; contact_tolerance\n"
           "(m): depths up to it count as touching, not penetrating; inside_weight (m per point): each cloud point\n"
           "inside a link adds this to the total depth.")
      .def(
          "evaluate",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const Eigen::Isometry3d W = to_pose(T_world_wrist, "T_world_wrist");
            const Eigen::VectorXd q = to_configuration(e.hand(), joints, "joints");
            return e.evaluate(W, q);
          },
          py::arg("T_world_wrist"), py::arg("joints"), "The expert for one wrist pose (7,) and configuration.")
      .def(
          "evaluate_batch",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(e.hand(), joints, "joints");
            py::gil_scoped_release release;
            return e.evaluate_batch(W, q);
          },
          py::arg("T_world_wrist"), py::arg("joints"), "The expert over wrists (N, 7) and joints (N, n_dofs) (or one for all).")
      .def(
          "log_w",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(e.hand(), joints, "joints");
            py::gil_scoped_release release;
            return Eigen::VectorXd(e.evaluate_batch(W, q).log_w);
          },
          py::arg("T_world_wrist"), py::arg("joints"), "log W(h) (N,) over wrists (N, 7) and joints.")
      .def(
          "collision_free",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(e.hand(), joints, "joints");
            py::gil_scoped_release release;
            return Eigen::Matrix<bool, Eigen::Dynamic, 1>(e.evaluate_batch(W, q).collision_free);
          },
          py::arg("T_world_wrist"), py::arg("joints"), "(N,) bool: no cloud point inside the hand and nothing below the plane.")
      .def_property_readonly("plane", [](const CollisionExpert& e) -> py::object {
        if (!e.has_plane()) return py::none();
        return py::cast(Eigen::Vector4d(e.plane()));
      }, "The normalised, oriented plane [a, b, c, d] (free side a x + b y + c z + d > 0), or None.")
      .def_property_readonly("n_points", &CollisionExpert::n_points)
      .def_property_readonly("cell_size", &CollisionExpert::cell_size, "The grid cell of the cloud index (m).")
      .def_property_readonly("beta", [](const CollisionExpert& e) { return e.settings().beta; })
      .def_property_readonly("point_radius", [](const CollisionExpert& e) { return e.settings().point_radius; })
      .def_property_readonly("plane_margin", [](const CollisionExpert& e) { return e.settings().plane_margin; });
}

}  // namespace graspmix::py_bind
