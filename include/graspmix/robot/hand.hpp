#pragma once
// A robot hand as a kinematic tree read from a standard URDF: the paper's fk(h) (eq:fk_function)
// for a grasp h = (h_w, h_c), with h_w the wrist pose (the URDF's root link) and h_c the joint
// configuration, and every link's collision geometry (boxes, cylinders, spheres, meshes).
//
// Joint configurations:
//   * only independent, movable joints (revolute, continuous, prismatic without <mimic>) are the
//     hand's degrees of freedom; they are `joint_names()`, in the URDF's depth-first tree order;
//   * a mimic joint follows its master: value = multiplier * master + offset (chains of mimics
//     are resolved to the independent joint at their end); it is not in `joint_names()`;
//   * fk() does not clamp to the joint limits (so it agrees with simulators given the same values);
//     `clamp` and `within_limits` are there for callers that want limits enforced.
//
// Frames: every pose is the URDF *link frame* (not the inertial/centre-of-mass frame). The wrist
// pose T_world_wrist is the root link's frame.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// Triangles as rows of three vertex indices.
using TriangleArray = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A triangle mesh in its own frame (already scaled by the URDF's <mesh scale>).
struct TriangleMesh {
  Vec3Array vertices;
  TriangleArray triangles;
};

enum class ShapeType { Box, Cylinder, Sphere, Mesh };

/// One <collision> element of a link.
struct CollisionShape {
  ShapeType type = ShapeType::Box;
  Eigen::Isometry3d T_link_shape = Eigen::Isometry3d::Identity();  ///< the <origin> of the element
  /// Box: full side lengths (m). Cylinder: (radius, length, 0), axis along the shape's z.
  /// Sphere: (radius, 0, 0). Mesh: the <mesh scale>.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  std::string mesh_file;                     ///< the resolved file (meshes only)
  std::shared_ptr<const TriangleMesh> mesh;  ///< the loaded mesh, scaled (meshes only)
  /// The convex hull of the mesh as half-spaces n . x <= offset (rows [nx, ny, nz, offset]), unit n,
  /// in the shape frame (meshes only): the collision expert treats a mesh link as its hull.
  std::shared_ptr<const RowMatrixXd> hull_planes;
  std::shared_ptr<const TriangleMesh> hull;  ///< the hull's vertices and triangles (meshes only)
  /// Meshes only: the cheap proxy of the hull, made once when the hand is read (robot/hull_proxy.cpp). An oriented
  /// box (frame T_shape_box in the shape frame, half extents box_half) that holds every hull vertex, so the hull;
  /// and box_growth such that every point whose hull distance (the largest of hull_planes' n . x - offset, as the
  /// experts measure it) is at most g >= 0 lies within the box grown by box_growth * g on every side. A point outside
  /// the grown box is decided without the hull; the hull's planes are ordered largest facet first, so a point
  /// outside the hull usually fails on the first few.
  Eigen::Isometry3d T_shape_box = Eigen::Isometry3d::Identity();
  Eigen::Vector3d box_half = Eigen::Vector3d::Zero();
  double box_growth = 1.0;
  /// Half extents of the inner proxy: the box of the same frame, scaled down from box_half until it lies inside
  /// the hull (zero where none does). A point inside it is inside the hull, at least as deep.
  Eigen::Vector3d box_inner = Eigen::Vector3d::Zero();
};

enum class JointType { Fixed, Revolute, Continuous, Prismatic };

struct JointInfo {
  std::string name;
  JointType type = JointType::Fixed;
  int parent_link = -1;  ///< index into link_names()
  int child_link = -1;
  Eigen::Isometry3d T_parent_joint = Eigen::Isometry3d::Identity();  ///< the joint's <origin>
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();                   ///< unit, in the joint (= child link) frame
  double lower = 0.0, upper = 0.0;                                   ///< limits (m or rad); continuous: -inf, +inf
  int dof = -1;             ///< index into joint_names() of the independent joint that drives it (-1: fixed)
  double multiplier = 1.0;  ///< value = multiplier * q[dof] + offset (1, 0 for independent joints)
  double offset = 0.0;
  bool mimic = false;
};

struct LinkInfo {
  std::string name;
  int parent_joint = -1;  ///< index into joints(); -1 for the root
  std::vector<CollisionShape> collisions;
  /// The <inertial> element (for simulators): mass (kg; 0 if absent), its frame in the link frame,
  /// and the inertia tensor in that frame (kg m^2).
  double mass = 0.0;
  Eigen::Isometry3d T_link_inertial = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  bool has_inertial = false;
};

/// A joint's own motion for configuration q (joint_names() order): T (the child's frame at the joint's origin)
/// moved along or turned about the joint's axis by its value; nothing for a fixed joint. Hand::fk_into's step.
inline void apply_joint(const JointInfo& j, const double* q, Eigen::Isometry3d& T) {
  if (j.dof < 0) return;
  const double v = j.multiplier * q[j.dof] + j.offset;
  if (j.type == JointType::Prismatic) {
    T.translation() += T.linear() * (j.axis * v);
  } else {
    T.linear() = T.linear() * Eigen::AngleAxisd(v, j.axis).toRotationMatrix();
  }
}

/// What Hand::from_urdf reads at most; a URDF beyond these is refused with a message naming the limit.
/// Links (and joints) of one URDF: hands have tens, and deeper chains would make urdfdom's recursive
/// clean-up of its link tree a stack risk.
inline constexpr int kMaxUrdfLinks = 1000;
/// Nesting of XML elements (a URDF nests about 6 deep; TinyXML parses nesting recursively).
inline constexpr int kMaxUrdfXmlDepth = 64;
/// m: the largest |coordinate| of an <origin>, a box, cylinder or sphere size and a scaled mesh vertex
/// (anything larger is a units error, and breaks collision checks and physics in double precision).
inline constexpr double kMaxUrdfLength = 1e4;

/// How a URDF is read.
struct HandLoadSettings {
  /// Extra folders searched for `package://name/...` meshes (each holds package folders, as in
  /// ROS_PACKAGE_PATH). Relative mesh paths and `package://` paths are first resolved against the
  /// URDF's folder and its parents (see Hand::resolve_mesh_path).
  std::vector<std::string> package_dirs;
  bool load_meshes = true;  ///< false: mesh shapes keep only their file names (no geometry)
  /// How the hand's grasp axes are inferred (Hand::approach_axis, Hand::fingertips; robot/hand_axes.cpp):
  /// degrees within which the direction from the wrist to the fingertips is snapped to the nearest axis of the
  /// wrist frame (20: the PR2 gripper's fingers lie within 1 degree of +x, a hand tilted by design stays exact);
  double approach_snap_deg = 20.0;
  /// degrees within which two candidate links, seen across the approach axis from it, lie on the same finger
  /// (45: a linkage finger's knuckle and pad lie within a few degrees, three fingers 120 degrees apart).
  double same_finger_deg = 45.0;
};

/// A hand's grasp axes as a URDF may give them: `<graspmix approach_axis="x y z" fingertips="a b"/>` under
/// <robot> (urdfdom and pybullet skip the element); either attribute may be left out.
inline constexpr const char* kUrdfAxesElement = "graspmix";

class Hand {
 public:
  /// Reads a URDF file. Throws std::invalid_argument naming the file for a missing or unreadable
  /// file, malformed XML (truncated, mismatched tags, nested deeper than kMaxUrdfXmlDepth), more than
  /// kMaxUrdfLinks links or joints, anything urdfdom complains about (even where urdfdom itself would
  /// go on with a partly read link, e.g. a malformed <box> that drops the link's collision shapes), an
  /// unsupported joint type (floating, planar), a zero axis, lower > upper limits, a mimic of an
  /// unknown or fixed joint, a negative mass, a non-positive or non-finite shape size or mesh scale,
  /// a length beyond kMaxUrdfLength, or a mesh that cannot be found or loaded. Errors name the link or
  /// joint (and the collision element) at fault.
  static Hand from_urdf(const std::string& path, const HandLoadSettings& settings = {});
  /// The same from URDF text; relative mesh paths resolve against base_dir.
  static Hand from_urdf_string(const std::string& xml, const std::string& base_dir,
                               const HandLoadSettings& settings = {}, const std::string& source = "<string>");

  const std::string& name() const { return name_; }
  const std::string& source() const { return source_; }
  /// Independent joints (the hand's degrees of freedom h_c), in tree order.
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  int n_dofs() const { return static_cast<int>(joint_names_.size()); }
  /// (n_dofs, 2) lower and upper limits; continuous joints have -inf, +inf.
  RowMatrixXd joint_limits() const;
  /// Every link, root (the wrist) first, parents before children.
  const std::vector<std::string>& link_names() const { return link_names_; }
  int n_links() const { return static_cast<int>(links_.size()); }
  const std::vector<LinkInfo>& links() const { return links_; }
  /// Every movable or fixed joint of the URDF (mimic ones included), parents before children.
  const std::vector<JointInfo>& joints() const { return joints_; }
  /// Index of a link / independent joint by name; throws std::invalid_argument naming it if unknown.
  int link_index(const std::string& link) const;
  int dof_index(const std::string& joint) const;

  /// A name -> value mapping as a vector in joint_names() order. Every independent joint must be
  /// given; a mimic joint may be given if it agrees with its master (within 1e-9); any other name
  /// (unknown or fixed joint) throws std::invalid_argument naming it.
  Eigen::VectorXd joints_from_map(const std::map<std::string, double>& values) const;
  std::map<std::string, double> joints_to_map(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// Values of every URDF joint (joints() order) for a configuration: mimics resolved, fixed = 0.
  Eigen::VectorXd all_joint_values(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// Checks the length (naming `what`) and finiteness of a configuration.
  void check_configuration(const Eigen::Ref<const Eigen::VectorXd>& q, const char* what = "joints") const;
  Eigen::VectorXd clamp(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  bool within_limits(const Eigen::Ref<const Eigen::VectorXd>& q, double tolerance = 0.0) const;

  /// eq:fk_function: the world pose of every link (link_names() order) for wrist pose T_world_wrist
  /// and configuration q (joint_names() order).
  std::vector<Eigen::Isometry3d> fk(const Eigen::Isometry3d& T_world_wrist,
                                    const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// The same into caller storage of n_links() isometries (no allocation; q unchecked: the hot path).
  void fk_into(const Eigen::Isometry3d& T_world_wrist, const double* q, Eigen::Isometry3d* out) const;
  /// Batched fk over N hands: wrists (N, 7), q (N, n_dofs) (either may be one row, broadcast) ->
  /// (N, n_links * 7), row i holding the poses of hand i's links one after another. Parallel (OpenMP).
  RowMatrixXd fk_batch(const Eigen::Ref<const PoseArray>& T_world_wrist, const Eigen::Ref<const RowMatrixXd>& q) const;
  /// The batched loop under fk_batch and the collision expert: checks wrists (N, 7) and q (N, n_dofs)
  /// (either may be one row, broadcast), then calls visit(i, q_i, link poses of hand i) for every hand,
  /// spread over OpenMP threads when N >= parallel_from (visit must then be safe for distinct i).
  /// Returns N. A bad wrist row throws std::invalid_argument naming it.
  Eigen::Index fk_each(
      const Eigen::Ref<const PoseArray>& T_world_wrist, const Eigen::Ref<const RowMatrixXd>& q,
      Eigen::Index parallel_from,
      const std::function<void(Eigen::Index, const Eigen::VectorXd&, const Eigen::Isometry3d*)>& visit) const;

  /// A triangle mesh of every collision shape of a link, in the link frame (boxes exactly, cylinders
  /// and spheres tessellated, meshes as loaded), for drawing and for building simulator shapes.
  TriangleMesh collision_mesh(int link) const;

  /// How a mesh file name from a URDF is found: `file://` is stripped; an absolute path is used as
  /// is; a relative path is tried against base_dir; `package://pkg/rest` is tried as base_dir/rest,
  /// then as <dir>/pkg/rest and <dir>/rest for base_dir and each of its parents, then in each of
  /// package_dirs as <dir>/pkg/rest. Returns the first that exists; throws std::invalid_argument
  /// listing the tries otherwise.
  static std::string resolve_mesh_path(const std::string& filename, const std::string& base_dir,
                                       const std::vector<std::string>& package_dirs);
  /// Loads every triangle of an STL/OBJ (or any format assimp reads) file, scaled; throws
  /// std::invalid_argument naming the file if it cannot be read or has no triangles.
  static TriangleMesh load_mesh(const std::string& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

  /// The approach axis in the wrist frame (unit): the direction along which the hand moves onto an object, as the
  /// clear approach, the approach-axis expert and the grasp exports use it. Given by the URDF's <graspmix
  /// approach_axis> element, or inferred when the URDF is read: the direction from the wrist to the mean of the
  /// fingertips' centres (their collision vertices' boxes, joints at mid-range), snapped to the nearest axis of
  /// the wrist frame when within HandLoadSettings::approach_snap_deg of it (the WSG 50's: exactly +z).
  const Eigen::Vector3d& approach_axis() const { return approach_axis_; }
  /// The fingertip links (indices into link_names(), in that order): the links that close on an object, whose
  /// contacts contact quality scores and between which a grasp's opening is measured. Given by the URDF's
  /// <graspmix fingertips> element, or inferred: of the links a joint moves that have collision geometry and no
  /// descendant with geometry (the distal end of each chain), those that another such link outreaches along the
  /// approach (by 1 mm) on the same side of it (within same_finger_deg across the axis) are dropped, so a linkage
  /// finger's inner knuckle gives way to its pad.
  const std::vector<int>& fingertips() const { return fingertips_; }
  /// "urdf" where the URDF's <graspmix> element gave an axis or the fingertips, "inferred" otherwise, "set" after
  /// set_grasp_axes.
  const std::string& grasp_axes_source() const { return grasp_axes_source_; }
  /// Gives the grasp axes: approach (non-zero, finite; normalised), fingertips (link names, at least one, each
  /// moved by a joint and with collision geometry). Throws std::invalid_argument naming the bad value.
  void set_grasp_axes(const Eigen::Vector3d& approach, const std::vector<std::string>& fingertips);
  /// The index of a link that may be a fingertip (moved by a joint, with collision geometry); throws
  /// std::invalid_argument starting with `what` and naming the link otherwise.
  int checked_fingertip(const std::string& link, const std::string& what) const;

 private:
  std::string name_, source_;
  std::vector<std::string> joint_names_, link_names_;
  std::vector<LinkInfo> links_;
  std::vector<JointInfo> joints_;
  std::vector<int> dof_joint_;  ///< joints() index of each independent joint
  std::map<std::string, int> link_index_, dof_index_, joint_index_;
  Eigen::Vector3d approach_axis_ = Eigen::Vector3d::UnitZ();
  std::vector<int> fingertips_;
  std::string grasp_axes_source_ = "inferred";
};

}  // namespace graspmix
